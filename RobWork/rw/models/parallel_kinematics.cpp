#include "rw/models/parallel_kinematics.hpp"

#include <Eigen/Geometry>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <utility>

#include "rw/models/joint_values.hpp"

namespace rw::models {

using rw::kinematics::Frame;
using rw::kinematics::FrameId;
using rw::kinematics::FrameTree;
using rw::kinematics::FrameType;
using rw::kinematics::State;
using rw::math::Q;
using rw::math::Rotation3D;
using rw::math::Transform3D;
using rw::math::Vector3D;

struct ParallelKinematics::Evaluation {
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  std::vector<JunctionResidual> junctions;
};

namespace {

// The rotation vector (axis times angle in [0, pi]) of R, accurate for small angles.
Vector3D rotationVector(const Rotation3D& R) {
  Eigen::Quaterniond q(R);
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();
  const double n = q.vec().norm();
  if (n == 0.0) return Vector3D::Zero();
  return q.vec() * (2.0 * std::atan2(n, q.w()) / n);
}

std::string legName(const ParallelLeg& leg, std::size_t index) {
  if (leg.chains.empty()) return "leg " + std::to_string(index + 1);
  std::string name;
  for (const std::string& c : leg.chains) name += (name.empty() ? "" : " ") + c;
  return "leg \"" + name + "\"";
}

std::string number(double v) {
  std::ostringstream out;
  out << std::setprecision(3) << v;
  return out.str();
}

}  // namespace

ParallelKinematics::ParallelKinematics(const FrameTree& tree, ParallelStructure structure,
                                       std::string name)
    : tree_(&tree), structure_(std::move(structure)), name_(std::move(name)) {
  classifyJoints();
  buildPaths();
}

void ParallelKinematics::classifyJoints() {
  for (const FrameId f : structure_.frames) {
    const Frame& frame = tree_->frame(f);
    if (!frame.isJoint()) continue;
    all_.push_back(f);
    if (frame.isDependent()) {
      dependent_.push_back(f);
      if (!frame.isPassive() && tree_->frame(frame.dependency()->owner).isActiveJoint()) {
        actuated_.push_back(f);
      }
      continue;
    }
    full_.push_back(f);
    (frame.isPassive() ? passive_ : actuated_).push_back(f);
  }
}

void ParallelKinematics::buildPaths() {
  std::vector<int> unknownOf(tree_->size(), -1);
  for (std::size_t k = 0; k < passive_.size(); ++k) {
    unknownOf[static_cast<std::size_t>(passive_[k].index)] = static_cast<int>(k);
  }
  std::vector<char> determined(passive_.size(), 0);
  const std::string device = "device \"" + name_ + "\": ";
  for (std::size_t j = 0; j < structure_.junctions.size(); ++j) {
    const Junction& junction = structure_.junctions[j];
    const std::string where = device + "junction " + std::to_string(j + 1) + ": ";
    if (junction.legs.size() < 2) {
      throw std::invalid_argument(where + "a junction needs at least two legs");
    }
    std::vector<LegPath> paths;
    for (std::size_t i = 0; i < junction.legs.size(); ++i) {
      const ParallelLeg& leg = junction.legs[i];
      const std::string what = where + legName(leg, i);
      if (leg.start != junction.legs.front().start) {
        throw std::invalid_argument(what + " starts at \"" + tree_->frame(leg.start).name() +
                                    "\", the first leg at \"" +
                                    tree_->frame(junction.legs.front().start).name() +
                                    "\"; the legs of a junction start at one frame");
      }
      for (std::size_t k = 0; k < i; ++k) {
        if (junction.legs[k].end == leg.end) {
          throw std::invalid_argument(what + " ends at \"" + tree_->frame(leg.end).name() +
                                      "\" like " + legName(junction.legs[k], k) +
                                      "; the legs of a junction end at different frames");
        }
      }
      LegPath path = makePath(leg, what, unknownOf);
      for (const Column& c : path.columns) determined[static_cast<std::size_t>(c.unknown)] = 1;
      paths.push_back(std::move(path));
    }
    paths_.push_back(std::move(paths));
  }
  for (std::size_t k = 0; k < passive_.size(); ++k) {
    if (!determined[k]) {
      throw std::invalid_argument(device + "passive joint \"" + tree_->frame(passive_[k]).name() +
                                  "\" is on no leg of a junction, so nothing determines its value");
    }
  }
}

// The frames below a leg's start down to its end, and the joints among them that move with the
// unknowns (a dependent joint moves with its owner, times its gain).
ParallelKinematics::LegPath ParallelKinematics::makePath(const ParallelLeg& leg,
                                                         const std::string& what,
                                                         const std::vector<int>& unknownOf) const {
  LegPath path;
  for (FrameId f = leg.end; f != leg.start; f = tree_->frame(f).parent()) {
    if (!f.valid() || f == FrameTree::kWorld) {
      throw std::invalid_argument(what + ": its end \"" + tree_->frame(leg.end).name() +
                                  "\" is not below its start \"" + tree_->frame(leg.start).name() +
                                  "\"");
    }
    path.frames.push_back(f);
  }
  if (path.frames.empty()) throw std::invalid_argument(what + " has no frames");
  std::reverse(path.frames.begin(), path.frames.end());
  for (std::size_t p = 0; p < path.frames.size(); ++p) {
    const Frame& frame = tree_->frame(path.frames[p]);
    if (!frame.isJoint()) continue;
    double gain = 1.0;
    FrameId moved = frame.id();
    if (frame.isDependent()) {
      gain = frame.dependency()->gain;
      moved = frame.dependency()->owner;
    }
    const int unknown = unknownOf[static_cast<std::size_t>(moved.index)];
    if (unknown >= 0)
      path.columns.push_back(Column{frame.id(), static_cast<int>(p), unknown, gain});
  }
  return path;
}

Q ParallelKinematics::getFullQ(const State& state) const {
  return jointValues(*tree_, full_, state);
}

void ParallelKinematics::setFullQ(const Q& q, State& state) const {
  if (q.size() != fullDof()) {
    throw std::invalid_argument("device \"" + name_ + "\" has " + std::to_string(fullDof()) +
                                " joint values in its full configuration, got " +
                                std::to_string(q.size()));
  }
  setJointValues(*tree_, full_, q, state);
}

Q ParallelKinematics::fullLowerLimits() const {
  return jointLimits(*tree_, full_, [](const auto& l) { return l.lower; });
}

Q ParallelKinematics::fullUpperLimits() const {
  return jointLimits(*tree_, full_, [](const auto& l) { return l.upper; });
}

// Residual (and Jacobian) of every junction: for each leg i > 0, the position of its end minus
// leg 0's and the rotation vector of R_i R_0^T, all in the junction's start frame.
void ParallelKinematics::evaluate(const State& state, bool withJacobian, Evaluation& out) const {
  const auto n = static_cast<Eigen::Index>(passive_.size());
  Eigen::Index rows = 0;
  for (const auto& legs : paths_) rows += 6 * static_cast<Eigen::Index>(legs.size() - 1);
  out.r.resize(rows);
  if (withJacobian) out.J.setZero(rows, n);
  out.junctions.assign(paths_.size(), JunctionResidual{});
  std::vector<Transform3D> poses;
  const auto legPose = [&](const LegPath& leg, Eigen::MatrixXd& J) {
    poses.clear();
    Transform3D X = Transform3D::Identity();
    for (const FrameId f : leg.frames) {
      X = X * tree_->frame(f).localTransform(state);
      poses.push_back(X);
    }
    if (!withJacobian) return X;
    J.setZero(6, n);
    for (const Column& c : leg.columns) {
      const Transform3D& Xf = poses[static_cast<std::size_t>(c.position)];
      const Vector3D z = Xf.linear().col(2);
      if (tree_->frame(c.joint).type() == FrameType::kRevolute) {
        J.col(c.unknown).head<3>() += c.gain * z.cross(X.translation() - Xf.translation());
        J.col(c.unknown).tail<3>() += c.gain * z;
      } else {
        J.col(c.unknown).head<3>() += c.gain * z;
      }
    }
    return X;
  };
  Eigen::MatrixXd J0;
  Eigen::MatrixXd Ji;
  Eigen::Index row = 0;
  for (std::size_t j = 0; j < paths_.size(); ++j) {
    const Transform3D X0 = legPose(paths_[j].front(), J0);
    JunctionResidual& residual = out.junctions[j];
    for (std::size_t i = 1; i < paths_[j].size(); ++i) {
      const Transform3D Xi = legPose(paths_[j][i], Ji);
      const Vector3D dp = Xi.translation() - X0.translation();
      const Vector3D dr = rotationVector(Xi.linear() * X0.linear().transpose());
      out.r.segment<3>(row) = dp;
      out.r.segment<3>(row + 3) = dr;
      residual.position = std::max(residual.position, dp.norm());
      residual.angle = std::max(residual.angle, dr.norm());
      if (withJacobian) out.J.middleRows(row, 6) = Ji - J0;
      row += 6;
    }
  }
}

JunctionResidual ParallelKinematics::residual(std::size_t junction, const State& state) const {
  Evaluation e;
  evaluate(state, false, e);
  return e.junctions.at(junction);
}

void ParallelKinematics::setUnknowns(const Q& x, State& state) const {
  setJointValues(*tree_, passive_, x, state);
}

int ParallelKinematics::close(State& state) const {
  State current = state;
  double norm = 0.0;
  const int iterations = iterate(current, norm);
  if (norm > ClosureSolver::kStallTolerance) fail(current, iterations);
  state = std::move(current);
  return iterations;
}

bool ParallelKinematics::tryClose(State& state) const {
  State current = state;
  double norm = 0.0;
  iterate(current, norm);
  if (!(norm <= ClosureSolver::kStallTolerance)) return false;
  state = std::move(current);
  return true;
}

int ParallelKinematics::iterate(State& current, double& norm) const {
  Q x = jointValues(*tree_, passive_, current);
  Evaluation e;
  Evaluation trialEval;
  evaluate(current, true, e);
  norm = e.r.norm();
  int iteration = 0;
  for (; norm > ClosureSolver::kTolerance && iteration < ClosureSolver::kMaxIterations;
       ++iteration) {
    const Q step = -e.J.completeOrthogonalDecomposition().solve(e.r);
    double scale = 1.0;
    bool accepted = false;
    State trial = current;
    for (int h = 0; h < ClosureSolver::kMaxHalvings && !accepted; ++h, scale *= 0.5) {
      const Q candidate = x + scale * step;
      setUnknowns(candidate, trial);
      evaluate(trial, false, trialEval);
      if (trialEval.r.norm() < norm) {
        accepted = true;
        x = candidate;
      }
    }
    if (!accepted) break;
    current = std::move(trial);
    evaluate(current, true, e);
    norm = e.r.norm();
  }
  return iteration;
}

void ParallelKinematics::fail(const State& best, int iterations) const {
  Evaluation e;
  evaluate(best, false, e);
  std::size_t worst = 0;
  for (std::size_t j = 1; j < e.junctions.size(); ++j) {
    const auto size = [](const JunctionResidual& r) { return r.position + r.angle; };
    if (size(e.junctions[j]) > size(e.junctions[worst])) worst = j;
  }
  const JunctionResidual r = e.junctions.empty() ? JunctionResidual{} : e.junctions[worst];
  std::string legs;
  const auto& junctionLegs = structure_.junctions[worst].legs;
  for (std::size_t i = 0; i < junctionLegs.size(); ++i) {
    legs += (i == 0 ? "" : ", ") + legName(junctionLegs[i], i);
  }
  throw ClosureError("device \"" + name_ + "\": junction " + std::to_string(worst + 1) + " (" +
                         legs + ") cannot be closed: residual " + number(r.position) + " m, " +
                         number(r.angle) + " rad after " + std::to_string(iterations) +
                         " iterations",
                     worst, r);
}

}  // namespace rw::models
