#pragma once

#include <optional>
#include <string_view>

#include <Eigen/Geometry>

#include "visgrab/render/camera.hpp"
#include "visgrab/render/scene.hpp"

namespace visgrab::view {

/// Where a picture looks from, around the table frame (z up; the database's stereo rig looks
/// from -y towards +y).
enum class ViewPreset {
  kOblique,  ///< from the front left, 35 degrees up (the default)
  kFront,    ///< from -y, as the stereo rig, 30 degrees up
  kSide,     ///< from +x, 25 degrees up
  kTop,      ///< from straight above
};

/// Lower-case name of a preset ("oblique", "front", "side", "top").
std::string_view viewPresetName(ViewPreset preset);
/// The preset with this name, if any.
std::optional<ViewPreset> viewPresetFromName(std::string_view name);

/// An orbit view: the camera `distance` metres from `target`, at `azimuthDeg` about the world z
/// axis (0: on +x, 90: on +y) and `elevationDeg` above the x-y plane (clamped to +-89.5), looking
/// at the target with the image's up towards world +z; vertical field of view `fovYDeg`.
struct Orbit {
  /// The point looked at, world frame.
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  /// Azimuth, degrees.
  double azimuthDeg = -125.0;
  /// Elevation, degrees.
  double elevationDeg = 35.0;
  /// Distance from the target, m (> 0).
  double distance = 1.0;
  /// Vertical field of view, degrees (in (0, 180)).
  double fovYDeg = 35.0;
};

/// The orbit of a preset.
Orbit presetOrbit(ViewPreset preset);

/// The pinhole camera of an orbit for an image of width x height (square pixels, principal
/// point at the centre); near and far planes bracket the target by the distance.
/// @throws std::invalid_argument for a non-positive size or distance, or a bad field of view.
render::PinholeCamera orbitCamera(const Orbit& orbit, int width, int height);

/// `orbit` moved to look at the centre of `box` from as far as makes the box's bounding sphere
/// fill the smaller field of view with `margin` (> 1 leaves space around it).
Orbit framed(Orbit orbit, const Eigen::AlignedBox3d& box, int width, int height,
             double margin = 1.15);

/// The lighting of all pictures: a key light from the front left above (casting shadows), a
/// fill light from the right and a soft ambient term.
render::Lighting studioLighting();

/// The background colour of the pictures (linear RGB): a light grey-blue.
Eigen::Vector3f studioBackground();

}  // namespace visgrab::view
