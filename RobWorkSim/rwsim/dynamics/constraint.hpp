#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rw/math/types.hpp"
#include "rwsim/dynamics/ids.hpp"

namespace rwsim::dynamics {

/// The kinds of RobWorkSim's body-to-body `<Constraint>`. The free DOF are measured in the
/// constraint frame (see Constraint::X_parent_constraint), linear ones first.
enum class ConstraintType {
  kFixed,               ///< no free DOF (a weld)
  kPrismatic,           ///< translation along z
  kRevolute,            ///< rotation about z
  kUniversal,           ///< rotation about x, then y
  kSpherical,           ///< rotation about the origin (3 angular DOF)
  kPiston,              ///< translation along z, rotation about z
  kPrismaticRotoid,     ///< translation along z, rotation about x
  kPrismaticUniversal,  ///< translation along z, rotation about x, then y
  kFree,                ///< all 6 DOF free (only a spring would act)
};

/// How many DOF of a constraint type are free.
struct ConstraintDof {
  /// Free translations.
  std::size_t linear = 0;
  /// Free rotations.
  std::size_t angular = 0;
  /// All free DOF.
  std::size_t total() const { return linear + angular; }
};

/// The free DOF of `type` (RobWorkSim's counts: Fixed 0, Prismatic 1+0, Revolute 0+1,
/// Universal 0+2, Spherical 0+3, Piston 1+1, PrismaticRotoid 1+1, PrismaticUniversal 1+2,
/// Free 3+3).
ConstraintDof constraintDof(ConstraintType type);
/// The type's name as RobWorkSim writes it ("Revolute").
std::string_view constraintTypeName(ConstraintType type);
/// The type named `name`, in any case; none for an unknown name.
std::optional<ConstraintType> constraintTypeFromName(std::string_view name);
/// The free DOF of `type` in order, for messages ("translation along z, rotation about x").
std::string_view constraintDofText(ConstraintType type);
/// Every type name, comma-separated ("Fixed, Prismatic, ..., Free"), for messages.
std::string constraintTypeNames();

/// Stops of one free DOF of a constraint, in m or rad, measured from the configuration the
/// simulation starts in; an infinite bound is no stop.
struct ConstraintLimit {
  /// Lower stop.
  double low = -std::numeric_limits<double>::infinity();
  /// Upper stop.
  double high = std::numeric_limits<double>::infinity();
};

/// A linear spring-damper on a constraint's free DOF (RobWorkSim's Constraint::SpringParams).
/// Read and checked, not yet simulated.
struct ConstraintSpring {
  /// Compliance, DOF x DOF (m/N, rad/(N m)).
  Eigen::MatrixXd compliance;
  /// Damping, DOF x DOF (N s/m, N m s/rad).
  Eigen::MatrixXd damping;
};

/// A joint between two bodies that no device describes (RobWorkSim's `<Constraint>`).
struct Constraint {
  /// Unique name.
  std::string name;
  /// What it leaves free.
  ConstraintType type = ConstraintType::kFixed;
  /// The body the constraint frame is fixed to.
  BodyId parent;
  /// The body it holds.
  BodyId child;
  /// The constraint frame in the parent's body frame (Prismatic, Revolute and Piston move
  /// along or about its z axis).
  rw::math::Transform3D X_parent_constraint = rw::math::Transform3D::Identity();
  /// Empty, or one entry per free DOF, linear DOF first, in the order of ConstraintType's
  /// comments.
  std::vector<ConstraintLimit> limits;
  /// A spring on the free DOF, if given.
  std::optional<ConstraintSpring> spring;
};

}  // namespace rwsim::dynamics
