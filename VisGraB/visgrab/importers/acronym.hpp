#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rw/math/types.hpp"
#include "visgrab/importers/nd_array.hpp"

namespace visgrab::importers {

/// The object of an ACRONYM grasp file (its `object/...` datasets), as ACRONYM's FleX
/// simulation used it.
struct AcronymObject {
  /// `object/file`: the mesh, relative to ACRONYM's mesh folder (e.g. "meshes/Table/x.obj").
  std::string file;
  /// `object/scale`: the factor the mesh file's coordinates were multiplied by (> 0).
  double scale = 1.0;
  /// `object/density`, kg/m^3 (> 0).
  double density = 0.0;
  /// `object/friction`: Coulomb coefficient (>= 0).
  double friction = 0.0;
  /// `object/mass`, kg (> 0).
  double mass = 0.0;
  /// `object/com`: centre of mass in the scaled mesh's frame, m.
  rw::math::Vector3D com = rw::math::Vector3D::Zero();
  /// `object/inertia`: inertia tensor about the centre of mass, kg m^2 (symmetric 3x3).
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  /// `object/volume` of the scaled mesh, m^3, when the file has it.
  std::optional<double> volume;
};

/// Reads the object fields of an ACRONYM `.h5` file.
/// @throws ImportError naming the file and the dataset: missing, another shape, a value out of
/// range (non-finite, scale/density/mass <= 0, friction < 0, an inertia that is not symmetric).
AcronymObject readAcronymObject(const std::filesystem::path& file);

/// The grasps' labels of an ACRONYM `.h5` (`grasps/qualities/flex/object_in_gripper`) or a
/// GraspGen `.json` (`grasps.object_in_gripper`): 1 held, 0 not, in grasp order.
/// @throws ImportError naming the file and the key: missing, not one value per grasp (N, as
/// the transforms), a value other than 0 and 1.
std::vector<int> readAcronymLabels(const std::filesystem::path& file);

/// The grasps' transforms (N x 4 x 4, the Panda hand's base frame in the scaled mesh's frame) of
/// an ACRONYM `.h5` (`grasps/transforms`) or a GraspGen `.json` (`grasps.transforms`), told
/// apart by the file's first byte ('{' is JSON). @throws ImportError naming the file and key.
NdArray readAcronymTransforms(const std::filesystem::path& file);

}  // namespace visgrab::importers
