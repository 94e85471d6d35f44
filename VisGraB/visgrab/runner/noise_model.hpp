#pragma once

#include <cstdint>
#include <filesystem>
#include <numbers>
#include <string>
#include <string_view>

#include "rw/math/types.hpp"

/// The noise model of robust verdicts (`visgrab run --repeats N [--noise FILE]`,
/// docs/noise-model.md): repeat 0 of a grasp runs unperturbed, repeats 1..N-1 under seeded
/// perturbations of the hand's pose, the objects' pose, the friction coefficients and the
/// objects' mass.
namespace visgrab::runner {

/// Smallest factor a friction or mass perturbation applies (the factor 1 + N(0, sigma) is
/// floored here, so that no coefficient or mass becomes zero or negative).
inline constexpr double kNoiseScaleFloor = 0.05;
/// Largest translation sigma a model may give, metres (a guard against millimetres written as
/// metres).
inline constexpr double kMaxTranslationSigma = 0.05;
/// Largest rotation sigma a model may give, radians (pi/4; a guard against degrees written as
/// radians).
inline constexpr double kMaxRotationSigma = std::numbers::pi / 4.0;
/// Largest relative sigma (friction, mass) a model may give: beyond it the floor, not the
/// Gaussian, shapes the factors' distribution.
inline constexpr double kMaxRelativeSigma = 0.5;

/// Standard deviations of the zero-mean Gaussian perturbations; 0 switches a part off.
/// Default-constructed it is the documented default model (defaultNoiseModel()).
struct NoiseModel {
  /// Hand translation, metres, per axis of the TCP frame.
  double handTranslation = 0.002;
  /// Hand rotation, radians, per component of a rotation vector in the TCP frame.
  double handRotation = rw::math::kDeg2Rad;
  /// Object translation, metres, per horizontal world axis (x, y): the objects stay on the table.
  double objectTranslation = 0.002;
  /// Object rotation, radians, about the world vertical through the mean of the objects' origins.
  double objectRotation = rw::math::kDeg2Rad;
  /// Friction, relative: every friction coefficient times max(kNoiseScaleFloor, 1 + N(0, sigma)).
  double friction = 0.1;
  /// Mass, relative: every object's mass and inertia times max(kNoiseScaleFloor,
  /// 1 + N(0, sigma)).
  double mass = 0.1;

  /// Field-wise equality.
  friend bool operator==(const NoiseModel&, const NoiseModel&) = default;
};

/// One repeat's perturbation, drawn by samplePerturbation. Default-constructed it is the
/// identity (no perturbation).
struct Perturbation {
  /// The hand's TCP offset: X_W_tcp' = X_W_tcp * X_tcp_perturbed.
  rw::math::Transform3D X_tcp_perturbed = rw::math::Transform3D::Identity();
  /// Planar motion of all objects together: world x offset, metres.
  double objectDx = 0.0;
  /// Planar motion of all objects together: world y offset, metres.
  double objectDy = 0.0;
  /// Planar motion of all objects together: turn about the world vertical through the mean of
  /// the objects' origins, radians (applied before the offset).
  double objectYaw = 0.0;
  /// Factor on every friction coefficient (>= kNoiseScaleFloor).
  double frictionScale = 1.0;
  /// Factor on every object's mass and inertia (>= kNoiseScaleFloor).
  double massScale = 1.0;
};

/// The documented defaults (docs/noise-model.md, "Defaults"; scenes/noise/default.noise.xml):
/// hand and objects 2 mm and 1 degree, friction and mass 10 %.
NoiseModel defaultNoiseModel();

/// Reads a noise model from XML text (schema xml/noise-model.xsd); `file` names it in messages.
/// Parts left out keep their defaults. @throws rw::common::LoadError with every problem as
/// `file:line:column: error: ...` (malformed XML, wrong root, unknown or repeated element,
/// unknown or missing attribute, a value that is not a finite number or is out of range).
NoiseModel parseNoiseModel(std::string_view xml, const std::filesystem::path& file);

/// Reads a noise model file. @throws rw::common::LoadError as parseNoiseModel, or naming the
/// file when it cannot be read.
NoiseModel loadNoiseModel(const std::filesystem::path& file);

/// One line that tells models apart (every sigma in shortest exact form, SI units), for run.csv:
/// "hand 0.002 m 0.017453292519943295 rad; object 0.002 m 0.017453292519943295 rad;
/// friction 0.1; mass 0.1".
std::string describe(const NoiseModel& model);

/// Checks every sigma: finite, >= 0 and at most its bound (kMaxTranslationSigma,
/// kMaxRotationSigma, kMaxRelativeSigma). @throws std::invalid_argument naming the first bad one.
void checkNoiseModel(const NoiseModel& model);

/// The perturbation of `seed`: 11 standard normals drawn from results::SeededRandom(seed) in a
/// fixed order (hand translation x y z, hand rotation vector x y z, object x y, object yaw,
/// friction, mass), all of them whatever sigmas are zero, so that a part's draws do not depend
/// on the other parts. A zero sigma gives that part's identity exactly.
/// @throws std::invalid_argument for a model checkNoiseModel rejects.
Perturbation samplePerturbation(const NoiseModel& model, std::uint64_t seed);

/// The text of xml/noise-model.xsd, which parseNoiseModel validates against.
std::string_view noiseModelSchema();

}  // namespace visgrab::runner
