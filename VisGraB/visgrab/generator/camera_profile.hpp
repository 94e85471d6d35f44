#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "visgrab/generator/stereo_rig.hpp"
#include "visgrab/objects/object_spec.hpp"

namespace visgrab::generator {

/// One camera of a profile: how it differs from the ideal pinhole of the rig.
struct CameraSensorSpec {
  /// Principal point offset from the image centre ((width - 1) / 2, (height - 1) / 2), pixels.
  std::array<double, 2> principalOffset{0.0, 0.0};
  /// fy / fx (fx is the rig's focal length).
  double focalRatio = 1.0;
  /// Lens distortion, OpenCV's order and meaning: k1 k2 p1 p2 k3.
  std::array<double, 5> distortion{0.0, 0.0, 0.0, 0.0, 0.0};
  /// Exposure multiplier of the signal (1: as rendered).
  double exposure = 1.0;
  /// Analog gain: multiplies the exposed signal and its noise (1: none).
  double gain = 1.0;
};

/// Specular finish of a material class in a profile (replaces the objects' own specularity).
struct MaterialFinish {
  /// The material class (metal, glass or plastic surfaces of the objects).
  objects::SurfaceMaterial material = objects::SurfaceMaterial::kMetal;
  /// Blinn-Phong specular strength.
  float specular = 0.5f;
  /// Blinn-Phong exponent.
  float shininess = 32.0f;
};

/// A light a profile adds to the scene's lighting (directional, without shadows): e.g. a lamp
/// behind the objects whose reflections on lids and glossy sides the cameras see.
struct ExtraLight {
  /// Direction the light travels, table frame (need not be unit).
  std::array<double, 3> direction{0.0, 0.0, -1.0};
  /// Linear RGB intensity.
  std::array<double, 3> colour{0.2, 0.2, 0.2};
};

/// Colour filter layout of the raw images.
enum class BayerPattern {
  /// No mosaic: the raw images are colour (3 channels).
  kNone,
  /// Rows alternate R G R G ... / G B G B ... starting at the top-left pixel.
  kRggb,
};

/// A camera profile (scenes/cameras/*.xml, schema xml/camera-profile.xsd): the rig's geometry
/// and every effect of the cameras. Default-constructed it is the "ideal" profile: two
/// identical parallel pinhole cameras without distortion, rendered already rectified with
/// today's blur and noise and the objects' own matte finish.
struct CameraProfile {
  /// The profile's name (the file's `name` attribute).
  std::string name = "ideal";
  /// Rig geometry, image size, read noise (noiseSigma) and optical blur (blurSigma).
  StereoRigSpec rig;
  /// The left and right camera.
  std::array<CameraSensorSpec, 2> cameras;
  /// Rotation of the right camera about its own axes relative to the ideal parallel rig,
  /// RobWork RPY in degrees (R = Rz(first) Ry(second) Rx(third)).
  std::array<double, 3> misalignmentRpy{0.0, 0.0, 0.0};
  /// Offset of the right camera's optical centre from the ideal one, in the left camera's
  /// axes, metres.
  std::array<double, 3> misalignmentOffset{0.0, 0.0, 0.0};
  /// Vignetting: relative loss of signal at the image corners (0: none), falling off as cos^4
  /// of an effective field angle.
  double vignetting = 0.0;
  /// Shot noise: standard deviation shotNoise * sqrt(signal) grey levels (signal in grey
  /// levels before gain).
  double shotNoise = 0.0;
  /// The raw images' colour filter mosaic.
  BayerPattern bayer = BayerPattern::kNone;
  /// Supersampling of the pinhole render that the lens distortion warps (>= 1).
  double supersampling = 1.5;
  /// Finishes replacing the objects' own for these material classes.
  std::vector<MaterialFinish> materials;
  /// Lights added to the generator's key and fill lights.
  std::vector<ExtraLight> lights;

  /// True when the raw cameras are the rectified ones (no distortion, no misalignment, equal
  /// centred intrinsics): the images are then rendered directly, without warping.
  bool alreadyRectified() const;
};

/// Reads a camera profile. Errors name the file and line (schema, then meaning: positive
/// sizes and focal length, exposure and gain > 0, vignetting in [0, 1), misalignment under 5
/// degrees, a material named twice).
/// @throws rw::common::LoadError.
CameraProfile loadCameraProfile(const std::filesystem::path& file);

/// Same as loadCameraProfile from text; `virtualFile` names it in messages.
/// @throws rw::common::LoadError.
CameraProfile loadCameraProfileFromString(std::string_view xml,
                                          const std::filesystem::path& virtualFile);

/// The names of the profiles in `folder` (its *.xml files without extension), sorted.
std::vector<std::string> knownCameraProfiles(const std::filesystem::path& folder);

/// The profile `nameOrFile`: a path to an XML file (contains '/' or ends in ".xml"), or the
/// name of a file `folder`/NAME.xml.
/// @throws std::invalid_argument for an unknown name, listing the known ones;
///   rw::common::LoadError for a bad file.
CameraProfile findCameraProfile(std::string_view nameOrFile, const std::filesystem::path& folder);

}  // namespace visgrab::generator
