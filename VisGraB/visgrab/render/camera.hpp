#pragma once

#include <Eigen/Core>

#include "rw/math/types.hpp"

namespace visgrab::render {

/// A pinhole camera in OpenCV's convention, placed in the world.
///
/// Camera frame C: x right, y down, z forward along the optical axis (the camera looks along +z).
/// A point p_C = (x, y, z) with z > 0 projects to the pixel coordinates
///   u = fx * x / z + skew * y / z + cx,   v = fy * y / z + cy,
/// where, as in OpenCV, the centre of the pixel in row i (counted from the top) and column j
/// (counted from the left) is at (u, v) = (j, i); pixel (i, j) covers [j - 0.5, j + 0.5] x
/// [i - 0.5, i + 0.5]. The renderer samples depth and instance ids exactly at these centres.
/// K = [fx skew cx; 0 fy cy; 0 0 1] is OpenCV's camera matrix for an image of width x height.
struct PinholeCamera {
  /// Focal length along x, pixels.
  double fx = 500.0;
  /// Focal length along y, pixels.
  double fy = 500.0;
  /// Principal point, pixels (OpenCV convention: pixel centres at integers).
  double cx = 319.5;
  /// Principal point, pixels.
  double cy = 239.5;
  /// Skew K(0, 1), usually 0.
  double skew = 0.0;
  /// Image width in pixels.
  int width = 640;
  /// Image height in pixels.
  int height = 480;
  /// Near clipping distance along the optical axis, metres (> 0).
  double near = 0.05;
  /// Far clipping distance along the optical axis, metres (> near).
  double far = 20.0;
  /// The camera's pose in the world.
  rw::math::Transform3D X_WC = rw::math::Transform3D::Identity();

  /// The 3x3 camera matrix K.
  Eigen::Matrix3d K() const;

  /// Projects a world point with OpenCV's formula; returns (u, v) in pixels.
  /// @pre the point is in front of the camera (camera z > 0).
  Eigen::Vector2d project(const rw::math::Vector3D& p_W) const;

  /// Checks the parameters.
  /// @throws std::invalid_argument naming the bad parameter (size <= 0, fx or fy <= 0,
  ///   near <= 0 or far <= near, a non-finite value).
  void validate() const;
};

/// The OpenGL projection matrix (clip from camera frame C) that rasterises a point exactly where
/// PinholeCamera::project puts it, for a viewport of width x height whose window y runs upwards
/// (OpenGL's convention, so image row i is window row height - 1 - i). Clip w is the camera z;
/// camera z in [near, far] maps to normalised depth [-1, 1].
Eigen::Matrix4d glProjection(const PinholeCamera& camera);

}  // namespace visgrab::render
