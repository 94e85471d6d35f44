#include "visgrab/grasp/contact_ik.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <numeric>
#include <stdexcept>

#include <Eigen/Cholesky>

#include "rw/kinematics/frame_tree.hpp"
#include "rw/models/parallel_kinematics.hpp"
#include "visgrab/grasp/detail/normal_equations.hpp"

namespace visgrab::grasp {

namespace {

using rw::kinematics::FrameId;
using rw::kinematics::FrameType;
using rw::math::Q;
using rw::math::Rotation3D;
using rw::math::Transform3D;
using rw::math::Vector3D;

constexpr double kRegularisation = 1e-5;  // m per rad (or m per m) towards the seed
constexpr int kMaxIterations = 200;
// Refits (placement candidates) start from a solution a few millimetres away: a smaller bound
// keeps unreachable candidates (fingers too short after a back-off) from iterating long.
constexpr int kMaxRefitIterations = 40;
constexpr double kErrorPenalty = 10.0;        // m of clearance per m of position error
constexpr double kBasinDirectionGain = 10.0;  // direction weight of the first phase / described
constexpr double kMaxRotationStep = 0.5;      // rad
constexpr double kMaxTranslationStep = 0.1;   // m
constexpr double kMaxJointStep = 0.5;         // rad or m
// Step of the central differences that give a parallel device's joint columns (rad or m): the
// closure solver's 1e-12 tolerance over it is a relative error of about 1e-6 in a column.
constexpr double kParallelJointStep = 1e-6;

Rotation3D skew(const Vector3D& v) {
  Rotation3D S;
  S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return S;
}

double angleBetween(const Vector3D& a, const Vector3D& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// A joint on the path from a fingertip to the base: its frame, the DOF it follows and the gain.
struct ChainJoint {
  FrameId frame;
  int dof = 0;
  double gain = 1.0;
  bool revolute = true;
};

// One target of the solver: a fingertip and where its pad should be, pushing along `direction`.
struct Target {
  int fingertip = 0;
  Vector3D position = Vector3D::Zero();
  Vector3D direction = Vector3D::UnitZ();
};

// The world poses the solver needs: the frames on the paths from WORLD to the fingertips,
// computed exactly as rw::kinematics::FKTable computes them (parent's world pose times the
// local transform, in id order; a frame attached below a later frame walks up to WORLD), so
// the doubles are the same. A frame is recomputed only when its local transform's inputs (its
// joint value or its movable transform) or its parent's pose changed since it was last
// computed, and only when a fingertip that needs it is asked for.
class ChainKinematics {
 public:
  ChainKinematics(const rw::kinematics::FrameTree& tree, const rw::kinematics::State& state,
                  const std::vector<FrameId>& tips)
      : tree_(tree) {
    std::vector<int> slotOf(tree.size(), -1);
    // Every frame on a path to a tip, in id order (FKTable's order).
    std::vector<char> needed(tree.size(), 0);
    for (const FrameId tip : tips) {
      for (FrameId f = tip; f.index > 0; f = state.parentOf(f)) {
        needed[static_cast<std::size_t>(f.index)] = 1;
      }
    }
    std::vector<char> done(tree.size(), 0);
    done[0] = 1;
    for (std::size_t i = 1; i < tree.size(); ++i) {
      const FrameId id{static_cast<std::int32_t>(i)};
      const FrameId parent = state.parentOf(id);
      const auto p = static_cast<std::size_t>(parent.index);
      const bool direct = p < i && done[p];
      done[i] = direct ? 1 : 0;
      if (!needed[i]) continue;
      Slot slot;
      slot.frame = id;
      slot.parent = parent.index > 0 ? slotOf[p] : -1;
      slot.walk = !direct;
      slotOf[i] = static_cast<int>(slots_.size());
      slots_.push_back(slot);
    }
    world_.assign(slots_.size(), Transform3D::Identity());
    for (const FrameId tip : tips) {
      std::vector<int> path;
      for (FrameId f = tip; f.index > 0; f = state.parentOf(f)) {
        path.push_back(slotOf[static_cast<std::size_t>(f.index)]);
      }
      std::sort(path.begin(), path.end());
      paths_.push_back(std::move(path));
      tipSlot_.push_back(slotOf[static_cast<std::size_t>(tip.index)]);
    }
    slotOf_ = std::move(slotOf);
  }

  // Brings the poses on fingertip `tip`'s path up to date with `state`.
  void update(const rw::kinematics::State& state, int tip) {
    for (const int s : paths_[static_cast<std::size_t>(tip)]) refresh(state, s);
  }

  // X_W_f of a frame on an updated path.
  const Transform3D& world(FrameId f) const {
    return pose(slotOf_[static_cast<std::size_t>(f.index)]);
  }
  // X_W of fingertip `tip`'s frame (after update(state, tip)).
  const Transform3D& tipWorld(int tip) const {
    return pose(tipSlot_[static_cast<std::size_t>(tip)]);
  }

 private:
  struct Slot {
    FrameId frame;
    int parent = -1;    // slot of the parent; -1 for WORLD
    bool walk = false;  // FKTable's second pass: the pose by walking up to WORLD
    bool valid = false;
    std::uint64_t parentVersion = 0;
    std::uint64_t version = 0;
    std::array<double, 7> inputs{};  // the local transform's state values (joint or movable)
  };

  // The pose of a slot; WORLD (no slot) is the identity.
  const Transform3D& pose(int slot) const {
    return slot < 0 ? worldPose_ : world_[static_cast<std::size_t>(slot)];
  }

  // The state values a frame's local transform reads, bit for bit.
  bool sameInputs(const Slot& slot, const rw::kinematics::State& state) const {
    const auto& frame = tree_.frame(slot.frame);
    if (frame.type() == FrameType::kMovable) {
      return std::memcmp(slot.inputs.data(), state.values().data() + frame.stateOffset(),
                         7 * sizeof(double)) == 0;
    }
    if (frame.isJoint()) {
      const double q = frame.jointValue(state);
      return std::memcmp(slot.inputs.data(), &q, sizeof(double)) == 0;
    }
    return true;
  }

  void keepInputs(Slot& slot, const rw::kinematics::State& state) const {
    const auto& frame = tree_.frame(slot.frame);
    if (frame.type() == FrameType::kMovable) {
      std::memcpy(slot.inputs.data(), state.values().data() + frame.stateOffset(),
                  7 * sizeof(double));
    } else if (frame.isJoint()) {
      slot.inputs[0] = frame.jointValue(state);
    }
  }

  void refresh(const rw::kinematics::State& state, int index) {
    Slot& slot = slots_[static_cast<std::size_t>(index)];
    auto& X = world_[static_cast<std::size_t>(index)];
    if (slot.walk) {
      X = rw::kinematics::worldTransform(tree_, state, slot.frame);
      ++slot.version;
      return;
    }
    const std::uint64_t parentVersion =
        slot.parent < 0 ? 0 : slots_[static_cast<std::size_t>(slot.parent)].version;
    if (slot.valid && slot.parentVersion == parentVersion && sameInputs(slot, state)) return;
    const Transform3D& parent =
        slot.parent < 0 ? worldPose_ : world_[static_cast<std::size_t>(slot.parent)];
    X = parent * tree_.frame(slot.frame).localTransform(state);
    keepInputs(slot, state);
    slot.parentVersion = parentVersion;
    slot.valid = true;
    ++slot.version;
  }

  const rw::kinematics::FrameTree& tree_;
  const Transform3D worldPose_ = Transform3D::Identity();
  std::vector<Slot> slots_;
  std::vector<Transform3D> world_;
  std::vector<std::vector<int>> paths_;
  std::vector<int> tipSlot_;
  std::vector<int> slotOf_;
};

std::vector<FrameId> fingertipFrames(const ContactIkSettings& ik) {
  std::vector<FrameId> out;
  for (const Fingertip& tip : ik.fingertips) out.push_back(tip.frame);
  return out;
}

// The hand's kinematics for the solver: sets the base pose and q, evaluates the residuals. For
// a serial or tree hand the joint columns of the Jacobian are the joint axes on the paths to
// the fingertips; for a parallel hand (closed loops) a joint moves passive joints on other
// paths as well, so its columns are central differences through the closure solver.
class HandModel {
 public:
  explicit HandModel(const HandGraspSetup& setup)
      : setup_(setup),
        ik_(*setup.contactIk()),
        state_(setup.defaultState()),
        directionWeight_(ik_.directionWeight),
        fk_(setup.workcell().frames(), state_, fingertipFrames(ik_)),
        parallel_(setup.device().parallel() != nullptr) {
    const auto& tree = setup.workcell().frames();
    const FrameId base = setup.placementFrame();
    X_W_parent_ = rw::kinematics::worldTransform(tree, state_, tree.frame(base).parent());
    const auto& active = setup.device().activeJoints();
    for (const Fingertip& tip : ik_.fingertips) {
      std::vector<ChainJoint> chain;
      for (FrameId f = tip.frame; f.valid() && f != base; f = tree.frame(f).parent()) {
        const auto& frame = tree.frame(f);
        if (!frame.isJoint() || frame.isPassive()) continue;
        const FrameId owner = frame.isDependent() ? frame.dependency()->owner : f;
        const auto it = std::find(active.begin(), active.end(), owner);
        if (it == active.end()) continue;
        chain.push_back({f, static_cast<int>(it - active.begin()),
                         frame.isDependent() ? frame.dependency()->gain : 1.0,
                         frame.type() == FrameType::kRevolute});
      }
      chains_.push_back(std::move(chain));
    }
  }

  // Residuals at the base pose and q (see solveContactIk); keeps the poses for jacobian().
  // Infinite when a parallel hand's loops cannot close at q (a step the solver then rejects).
  double residuals(const Transform3D& X_W_base, const Q& q, const std::vector<Target>& targets,
                   const std::vector<int>& free, const Q& qRef, bool moveBase,
                   const Vector3D& approach, Eigen::VectorXd& r) {
    const auto& tree = setup_.workcell().frames();
    tree.frame(setup_.placementFrame())
        .setMovableTransform(state_, X_W_parent_.inverse() * X_W_base);
    if (!setQ(q)) {
      r.setZero(6 * static_cast<int>(targets.size()) + (moveBase ? 3 : 0) +
                static_cast<int>(free.size()));
      return std::numeric_limits<double>::infinity();
    }
    lastQ_ = q;
    const int nFree = static_cast<int>(free.size());
    const int rows = 6 * static_cast<int>(targets.size()) + (moveBase ? 3 : 0) + nFree;
    r.setZero(rows);
    const double wd = directionWeight_;
    int row = 0;
    for (const Target& t : targets) {
      const Fingertip& tip = ik_.fingertips[static_cast<std::size_t>(t.fingertip)];
      fk_.update(state_, t.fingertip);
      const Transform3D& X = fk_.tipWorld(t.fingertip);
      const Vector3D p = X * tip.point;
      const Vector3D n = X.linear() * tip.normal;
      r.segment<3>(row) = p - t.position;
      r.segment<3>(row + 3) = wd * (n - t.direction);
      row += 6;
    }
    if (moveBase) {
      const Vector3D a = X_W_base.linear() * ik_.approachAxisInBase;
      r.segment<3>(row) = ik_.approachWeight * (a - approach);
      row += 3;
    }
    for (int k = 0; k < nFree; ++k) {
      const auto j = static_cast<Eigen::Index>(free[static_cast<std::size_t>(k)]);
      r[row + k] = kRegularisation * (q[j] - qRef[j]);
    }
    return 0.5 * r.squaredNorm();
  }

  // Jacobian of the residuals at the pose of the last residuals() call (columns: base v, base
  // w if moveBase, then the free joints).
  void jacobian(const Transform3D& X_W_base, const std::vector<Target>& targets,
                const std::vector<int>& free, bool moveBase, Eigen::MatrixXd& J) {
    const int nBase = moveBase ? 6 : 0;
    const int nFree = static_cast<int>(free.size());
    const int rows = 6 * static_cast<int>(targets.size()) + (moveBase ? 3 : 0) + nFree;
    J.setZero(rows, nBase + nFree);
    const double wd = directionWeight_;
    int row = 0;
    for (const Target& t : targets) {
      const Fingertip& tip = ik_.fingertips[static_cast<std::size_t>(t.fingertip)];
      const Transform3D& X = fk_.tipWorld(t.fingertip);
      const Vector3D p = X * tip.point;
      const Vector3D n = X.linear() * tip.normal;
      if (moveBase) {
        J.block<3, 3>(row, 0).setIdentity();
        J.block<3, 3>(row, 3) = -skew(p - X_W_base.translation());
        J.block<3, 3>(row + 3, 3) = -wd * skew(n);
      }
      if (parallel_) {
        row += 6;
        continue;
      }
      for (const ChainJoint& c : chains_[static_cast<std::size_t>(t.fingertip)]) {
        const auto col = std::find(free.begin(), free.end(), c.dof);
        if (col == free.end()) continue;
        const int k = nBase + static_cast<int>(col - free.begin());
        const Transform3D& XJ = fk_.world(c.frame);
        const Vector3D z = XJ.linear().col(2);
        if (c.revolute) {
          J.block<3, 1>(row, k) += c.gain * z.cross(p - XJ.translation());
          J.block<3, 1>(row + 3, k) += wd * c.gain * z.cross(n);
        } else {
          J.block<3, 1>(row, k) += c.gain * z;
        }
      }
      row += 6;
    }
    if (moveBase) {
      const Vector3D a = X_W_base.linear() * ik_.approachAxisInBase;
      J.block<3, 3>(row, 3) = -ik_.approachWeight * skew(a);
      row += 3;
    }
    for (int k = 0; k < nFree; ++k) J(row + k, nBase + k) = kRegularisation;
    if (parallel_) parallelJointColumns(targets, free, nBase, J);
  }

  // Sets the weight of the direction residuals.
  void setDirectionWeight(double w) { directionWeight_ = w; }

  // Pad point and push direction of a fingertip, world frame.
  void fingertipAt(const Transform3D& X_W_base, const Q& q, int fingertip, Vector3D& p,
                   Vector3D& n) {
    const auto& tree = setup_.workcell().frames();
    tree.frame(setup_.placementFrame())
        .setMovableTransform(state_, X_W_parent_.inverse() * X_W_base);
    setup_.device().setQ(q, state_);  // a solution's q: its loops closed when it was found
    const Fingertip& tip = ik_.fingertips[static_cast<std::size_t>(fingertip)];
    const Transform3D X = rw::kinematics::worldTransform(tree, state_, tip.frame);
    p = X * tip.point;
    n = X.linear() * tip.normal;
  }

 private:
  // Sets q; false when a parallel hand's loops cannot close there (the state is then as before).
  bool setQ(const Q& q) {
    try {
      setup_.device().setQ(q, state_);
    } catch (const rw::models::ClosureError&) {
      return false;
    }
    return true;
  }

  // Pad point and push direction of every target's fingertip at q (base as set).
  bool tipsAt(const Q& q, const std::vector<Target>& targets, std::vector<Vector3D>& p,
              std::vector<Vector3D>& n) {
    if (!setQ(q)) return false;
    p.clear();
    n.clear();
    for (const Target& t : targets) {
      const Fingertip& tip = ik_.fingertips[static_cast<std::size_t>(t.fingertip)];
      fk_.update(state_, t.fingertip);
      const Transform3D& X = fk_.tipWorld(t.fingertip);
      p.push_back(X * tip.point);
      n.push_back(X.linear() * tip.normal);
    }
    return true;
  }

  // The joint columns of a parallel hand: central differences of the pad points and directions
  // (one-sided where a side cannot close or leaves the limits), then the state back at lastQ_.
  void parallelJointColumns(const std::vector<Target>& targets, const std::vector<int>& free,
                            int nBase, Eigen::MatrixXd& J) {
    const double wd = directionWeight_;
    const Q& lower = setup_.device().lowerLimits();
    const Q& upper = setup_.device().upperLimits();
    std::vector<Vector3D> p0, n0, pPlus, nPlus, pMinus, nMinus;
    tipsAt(lastQ_, targets, p0, n0);
    for (std::size_t k = 0; k < free.size(); ++k) {
      const auto j = static_cast<Eigen::Index>(free[k]);
      Q plus = lastQ_;
      Q minus = lastQ_;
      plus[j] = std::min(plus[j] + kParallelJointStep, upper[j]);
      minus[j] = std::max(minus[j] - kParallelJointStep, lower[j]);
      const bool up = plus[j] > lastQ_[j] && tipsAt(plus, targets, pPlus, nPlus);
      const bool down = minus[j] < lastQ_[j] && tipsAt(minus, targets, pMinus, nMinus);
      if (!up) {
        plus = lastQ_;
        pPlus = p0;
        nPlus = n0;
      }
      if (!down) {
        minus = lastQ_;
        pMinus = p0;
        nMinus = n0;
      }
      const double span = plus[j] - minus[j];
      if (span <= 0.0) continue;  // pinned: the column stays zero
      const auto col = static_cast<Eigen::Index>(nBase) + static_cast<Eigen::Index>(k);
      for (std::size_t t = 0; t < targets.size(); ++t) {
        const auto row = static_cast<Eigen::Index>(6 * t);
        J.block<3, 1>(row, col) = (pPlus[t] - pMinus[t]) / span;
        J.block<3, 1>(row + 3, col) = wd * (nPlus[t] - nMinus[t]) / span;
      }
    }
    tipsAt(lastQ_, targets, p0, n0);
  }

  const HandGraspSetup& setup_;
  const ContactIkSettings& ik_;
  rw::kinematics::State state_;
  Transform3D X_W_parent_ = Transform3D::Identity();
  double directionWeight_;
  ChainKinematics fk_;
  bool parallel_ = false;
  Q lastQ_;
  std::vector<std::vector<ChainJoint>> chains_;
};

// Levenberg-Marquardt over the base pose (if moveBase) and the free joints. The buffers are
// kept between runs; a rejected step reuses the normal equations of the current point.
class Solver {
 public:
  Solver(HandModel& model, const HandGraspSetup& setup, const Vector3D& approach)
      : model_(model),
        lower_(setup.device().lowerLimits()),
        upper_(setup.device().upperLimits()),
        approach_(approach) {}

  double solve(Transform3D& X_W_base, Q& q, const std::vector<Target>& targets,
               const std::vector<int>& free, bool moveBase, int maxIterations = kMaxIterations) {
    qRef_ = q;
    double cost = model_.residuals(X_W_base, q, targets, free, qRef_, moveBase, approach_, r_);
    model_.jacobian(X_W_base, targets, free, moveBase, J_);
    bool fresh = true;
    double lambda = 1e-3;
    for (int it = 0; it < maxIterations && cost > 1e-16; ++it) {
      if (fresh) {
        detail::gramMatrix(J_, A_);
        detail::gradient(J_, r_, g_);
        fresh = false;
      }
      damped_ = A_;
      damped_.diagonal() += lambda * (A_.diagonal().array() + 1e-9).matrix();
      ldlt_.compute(damped_);
      step_ = ldlt_.solve(-g_);
      limitStep(step_, moveBase);
      Transform3D X_try = X_W_base;
      qTry_ = q;
      apply(step_, free, moveBase, X_try, qTry_);
      const double tryCost =
          model_.residuals(X_try, qTry_, targets, free, qRef_, moveBase, approach_, rTry_);
      if (tryCost < cost) {
        const double gain = cost - tryCost;
        X_W_base = X_try;
        q = qTry_;
        std::swap(r_, rTry_);
        model_.jacobian(X_W_base, targets, free, moveBase, J_);
        fresh = true;
        cost = tryCost;
        lambda = std::max(lambda / 3.0, 1e-9);
        if (gain < 1e-14 && step_.norm() < 1e-9) break;
      } else {
        lambda *= 4.0;
        if (lambda > 1e8) break;
      }
    }
    return cost;
  }

 private:
  static void limitStep(Eigen::VectorXd& step, bool moveBase) {
    double scale = 1.0;
    const int nBase = moveBase ? 6 : 0;
    if (moveBase) {
      const double v = step.head<3>().norm();
      const double w = step.segment<3>(3).norm();
      if (v > kMaxTranslationStep) scale = std::min(scale, kMaxTranslationStep / v);
      if (w > kMaxRotationStep) scale = std::min(scale, kMaxRotationStep / w);
    }
    const double joints = step.tail(step.size() - nBase).cwiseAbs().maxCoeff();
    if (step.size() > nBase && joints > kMaxJointStep)
      scale = std::min(scale, kMaxJointStep / joints);
    step *= scale;
  }

  void apply(const Eigen::VectorXd& step, const std::vector<int>& free, bool moveBase,
             Transform3D& X, Q& q) const {
    const int nBase = moveBase ? 6 : 0;
    if (moveBase) {
      const Vector3D w = step.segment<3>(3);
      const double angle = w.norm();
      Rotation3D R = X.linear();
      if (angle > 0.0) R = Eigen::AngleAxisd(angle, w / angle).toRotationMatrix() * R;
      // Re-orthonormalise to keep rounding from accumulating.
      X.linear() = Eigen::Quaterniond(R).normalized().toRotationMatrix();
      X.translation() += step.head<3>();
    }
    for (std::size_t k = 0; k < free.size(); ++k) {
      const auto j = static_cast<Eigen::Index>(free[k]);
      q[j] = std::clamp(q[j] + step[nBase + static_cast<Eigen::Index>(k)], lower_[j], upper_[j]);
    }
  }

  HandModel& model_;
  Q lower_;
  Q upper_;
  Vector3D approach_;
  Q qRef_;
  Q qTry_;
  Eigen::VectorXd r_;
  Eigen::VectorXd rTry_;
  Eigen::MatrixXd J_;
  Eigen::MatrixXd A_;
  Eigen::VectorXd g_;
  Eigen::MatrixXd damped_;
  Eigen::LDLT<Eigen::MatrixXd> ldlt_;
  Eigen::VectorXd step_;
};

// The errors of a solution against its targets.
struct Errors {
  double position = 0.0;
  double direction = 0.0;
  double approach = 0.0;
};

Errors measure(HandModel& model, const ContactIkSettings& ik, const Transform3D& X_W_base,
               const Q& q, const std::vector<Target>& targets, const Vector3D& approach) {
  Errors e;
  for (const Target& t : targets) {
    Vector3D p;
    Vector3D n;
    model.fingertipAt(X_W_base, q, t.fingertip, p, n);
    e.position = std::max(e.position, (p - t.position).norm());
    e.direction = std::max(e.direction, angleBetween(n, t.direction));
  }
  e.approach = angleBetween(X_W_base.linear() * ik.approachAxisInBase, approach);
  return e;
}

// The seed base pose: approach axis along `approach`, the fingertips' centroid (at q, base at
// identity) on the targets' centroid, turned about the approach to fit the fingertips to
// their targets.
Transform3D seedPose(HandModel& model, const ContactIkSettings& ik, const Q& q,
                     const std::vector<Target>& targets, const Vector3D& approach) {
  std::vector<Vector3D> tips;
  Vector3D tipMean = Vector3D::Zero();
  Vector3D targetMean = Vector3D::Zero();
  for (const Target& t : targets) {
    Vector3D p;
    Vector3D n;
    model.fingertipAt(Transform3D::Identity(), q, t.fingertip, p, n);
    tips.push_back(p);
    tipMean += p;
    targetMean += t.position;
  }
  tipMean /= static_cast<double>(targets.size());
  targetMean /= static_cast<double>(targets.size());
  const Rotation3D R0 =
      Eigen::Quaterniond::FromTwoVectors(ik.approachAxisInBase, approach).toRotationMatrix();
  double s = 0.0;
  double c = 0.0;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    Vector3D m = R0 * (tips[i] - tipMean);
    Vector3D d = targets[i].position - targetMean;
    m -= m.dot(approach) * approach;
    d -= d.dot(approach) * approach;
    s += approach.dot(m.cross(d));
    c += m.dot(d);
  }
  const double theta = (s == 0.0 && c == 0.0) ? 0.0 : std::atan2(s, c);
  const Rotation3D R = Eigen::AngleAxisd(theta, approach).toRotationMatrix() * R0;
  return rw::math::makeTransform(R, targetMean - R * tipMean);
}

struct Attempt {
  bool valid = false;
  double cost = 0.0;
  // How far the base is behind the contacts' centroid along the approach, less a penalty of
  // kErrorPenalty per metre of position error: valid attempts with more are preferred.
  double clearance = 0.0;
  Errors errors;
  Transform3D X_W_base = Transform3D::Identity();
  Q q;
  int grasp = -1;
  std::vector<Target> targets;
  std::vector<int> fingerOfContact;
};

// One solver run from a seed: two phases, the directions weighted up to find the right basin
// (finger posture), then as described.
Attempt runAttempt(HandModel& model, Solver& solver, const ContactIkSettings& ik, const Q& seed,
                   const std::vector<Target>& targets, const std::vector<int>& joints,
                   const Vector3D& approach, const Vector3D& centroid) {
  Attempt at;
  at.q = seed;
  at.X_W_base = seedPose(model, ik, seed, targets, approach);
  model.setDirectionWeight(kBasinDirectionGain * ik.directionWeight);
  solver.solve(at.X_W_base, at.q, targets, joints, true);
  model.setDirectionWeight(ik.directionWeight);
  at.cost = solver.solve(at.X_W_base, at.q, targets, joints, true);
  at.errors = measure(model, ik, at.X_W_base, at.q, targets, approach);
  at.valid = at.errors.position <= ik.maxPositionError &&
             at.errors.direction <= ik.maxDirectionError &&
             at.errors.approach <= ik.maxApproachError;
  at.clearance =
      (centroid - at.X_W_base.translation()).dot(approach) - kErrorPenalty * at.errors.position;
  at.targets = targets;
  return at;
}

bool better(const Attempt& a, const Attempt& best) {
  if (best.grasp < 0) return true;
  if (a.valid != best.valid) return a.valid;
  return a.valid ? a.clearance > best.clearance : a.errors.position < best.errors.position;
}

std::string describeFailure(const Attempt& a, const ContactIkSettings& ik) {
  char buffer[256];
  std::snprintf(buffer, sizeof(buffer),
                "no hand configuration reaches the contacts: best fingertip deviation %.1f mm "
                "(limit %.1f mm), direction %.1f deg (limit %.1f), approach %.1f deg (limit %.1f)",
                a.errors.position * 1e3, ik.maxPositionError * 1e3,
                a.errors.direction * rw::math::kRad2Deg, ik.maxDirectionError * rw::math::kRad2Deg,
                a.errors.approach * rw::math::kRad2Deg, ik.maxApproachError * rw::math::kRad2Deg);
  return buffer;
}

void checkInput(const HandGraspSetup& setup, const std::vector<DesiredContact>& contacts,
                const Vector3D& approach) {
  const ContactIkSettings* ik = setup.contactIk();
  if (ik == nullptr) {
    throw std::invalid_argument("hand \"" + setup.deviceName() +
                                "\" has no contact IK in its grasp description");
  }
  const auto n = static_cast<int>(contacts.size());
  if (std::none_of(ik->grasps.begin(), ik->grasps.end(),
                   [&](const IkGrasp& g) { return g.contacts == n; })) {
    throw std::invalid_argument("hand \"" + setup.deviceName() + "\" cannot solve a grasp with " +
                                std::to_string(n) + " contacts (see its <ContactIK> <Grasp>s)");
  }
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    if (!contacts[i].position.allFinite() || !(contacts[i].direction.norm() > 1e-9)) {
      throw std::invalid_argument("contact " + std::to_string(i + 1) +
                                  " has a zero or non-finite direction or position");
    }
  }
  if (!(approach.norm() > 1e-9)) throw std::invalid_argument("the approach direction is zero");
}

// Two attempts that land on the same solution (base within 1 mm and 1 degree, joints within
// 0.01 rad or 1 mm, same contact assignment).
bool sameSolution(const Attempt& a, const Attempt& b) {
  if (a.grasp != b.grasp || a.fingerOfContact != b.fingerOfContact) return false;
  const Transform3D d = a.X_W_base.inverse(Eigen::Isometry) * b.X_W_base;
  const double angle = Eigen::AngleAxisd(d.linear()).angle();
  return d.translation().norm() < 1e-3 && angle < rw::math::kDeg2Rad &&
         (a.q - b.q).cwiseAbs().maxCoeff() < 1e-2;
}

std::vector<Target> targetsOf(const std::vector<DesiredContact>& contacts,
                              const std::vector<int>& fingerOfContact) {
  std::vector<Target> targets;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    targets.push_back(
        {fingerOfContact[k], contacts[k].position, contacts[k].direction.normalized()});
  }
  return targets;
}

// The result for the fingers at `qContact` with the base at X_W_base: errors, then qOpen with
// the fingertips `backoff` short of the contacts (same base), qClosed and tauMax.
ContactIkResult finishResult(HandModel& model, Solver& solver, const HandGraspSetup& setup,
                             const std::vector<Target>& targets, const Vector3D& approach,
                             int grasp, const Transform3D& X_W_base, const Q& qContact,
                             double backoff, int maxIterations = kMaxIterations) {
  const ContactIkSettings& ik = *setup.contactIk();
  const IkGrasp& g = ik.grasps[static_cast<std::size_t>(grasp)];
  const Errors e = measure(model, ik, X_W_base, qContact, targets, approach);
  ContactIkResult result;
  result.valid = e.position <= ik.maxPositionError && e.direction <= ik.maxDirectionError &&
                 e.approach <= ik.maxApproachError;
  result.X_W_base = X_W_base;
  result.X_W_tcp = X_W_base * setup.X_base_tcp();
  result.qContact = qContact;
  result.positionError = e.position;
  result.directionError = e.direction;
  result.approachError = e.approach;
  result.grasp = grasp;
  for (const Target& t : targets) result.fingerOfContact.push_back(t.fingertip);
  std::vector<Target> backed = targets;
  for (Target& t : backed) t.position -= backoff * t.direction;
  Transform3D X = X_W_base;
  result.qOpen = qContact;
  if (backoff > 0.0) solver.solve(X, result.qOpen, backed, g.joints, false, maxIterations);
  result.qClosed = result.qOpen + g.closeOffset;
  result.tauMax = setup.tauRule().evaluate(result.qOpen);
  return result;
}

}  // namespace

std::vector<ContactIkResult> contactIkSolutions(const HandGraspSetup& setup,
                                                const std::vector<DesiredContact>& contacts,
                                                const Vector3D& approach, int maxSolutions) {
  checkInput(setup, contacts, approach);
  const ContactIkSettings& ik = *setup.contactIk();
  const Vector3D a = approach.normalized();
  HandModel model(setup);
  Solver solver(model, setup, a);
  std::vector<Attempt> attempts;
  const auto n = static_cast<int>(contacts.size());
  Vector3D centroid = Vector3D::Zero();
  for (const DesiredContact& c : contacts) centroid += c.position / static_cast<double>(n);
  int tried = 0;
  for (std::size_t gi = 0; gi < ik.grasps.size(); ++gi) {
    const IkGrasp& g = ik.grasps[gi];
    if (g.contacts != n) continue;
    std::vector<int> order(static_cast<std::size_t>(n));
    std::iota(order.begin(), order.end(), 0);
    do {
      std::vector<int> fingerOf(static_cast<std::size_t>(n));
      for (std::size_t k = 0; k < order.size(); ++k) {
        fingerOf[static_cast<std::size_t>(order[k])] = g.fingers[k];
      }
      const std::vector<Target> targets = targetsOf(contacts, fingerOf);
      for (const Q& seed : g.seeds) {
        Attempt at = runAttempt(model, solver, ik, seed, targets, g.joints, a, centroid);
        at.grasp = static_cast<int>(gi);
        at.fingerOfContact = fingerOf;
        ++tried;
        attempts.push_back(std::move(at));
      }
    } while (std::next_permutation(order.begin(), order.end()));
  }
  // Best first (stable: ties keep the order of attempts), then distinct valid solutions only,
  // or the single best attempt when none is valid.
  std::stable_sort(attempts.begin(), attempts.end(),
                   [](const Attempt& x, const Attempt& y) { return better(x, y); });
  std::vector<const Attempt*> chosen;
  for (const Attempt& at : attempts) {
    if (!chosen.empty() && !at.valid) break;
    if (std::any_of(chosen.begin(), chosen.end(),
                    [&](const Attempt* c) { return sameSolution(*c, at); })) {
      continue;
    }
    chosen.push_back(&at);
    if (!at.valid || static_cast<int>(chosen.size()) >= std::max(1, maxSolutions)) break;
  }
  std::vector<ContactIkResult> results;
  for (const Attempt* at : chosen) {
    ContactIkResult r = finishResult(model, solver, setup, at->targets, a, at->grasp, at->X_W_base,
                                     at->q, ik.backoff);
    r.attempts = tried;
    if (!r.valid) r.reason = describeFailure(*at, ik);
    results.push_back(std::move(r));
  }
  return results;
}

ContactIkResult solveContactIk(const HandGraspSetup& setup,
                               const std::vector<DesiredContact>& contacts,
                               const Vector3D& approach) {
  return contactIkSolutions(setup, contacts, approach, 1).front();
}

namespace {

void describeRefit(ContactIkResult& r) {
  if (r.valid) return;
  char buffer[160];
  std::snprintf(buffer, sizeof(buffer),
                "refitted fingers miss the contacts: fingertip deviation %.1f mm, direction "
                "%.1f deg, approach %.1f deg",
                r.positionError * 1e3, r.directionError * rw::math::kRad2Deg,
                r.approachError * rw::math::kRad2Deg);
  r.reason = buffer;
}

const IkGrasp& checkSolution(const HandGraspSetup& setup,
                             const std::vector<DesiredContact>& contacts, const Vector3D& approach,
                             const ContactIkResult& solution) {
  checkInput(setup, contacts, approach);
  const ContactIkSettings& ik = *setup.contactIk();
  if (solution.grasp < 0 || static_cast<std::size_t>(solution.grasp) >= ik.grasps.size() ||
      solution.fingerOfContact.size() != contacts.size()) {
    throw std::invalid_argument("refitContactIk: the solution does not belong to these contacts");
  }
  return ik.grasps[static_cast<std::size_t>(solution.grasp)];
}

}  // namespace

ContactIkResult refitContactIk(const HandGraspSetup& setup,
                               const std::vector<DesiredContact>& contacts,
                               const Vector3D& approach, const ContactIkResult& solution,
                               const Transform3D& X_W_base, double backoff) {
  const IkGrasp& g = checkSolution(setup, contacts, approach, solution);
  const Vector3D a = approach.normalized();
  HandModel model(setup);
  Solver solver(model, setup, a);
  const std::vector<Target> targets = targetsOf(contacts, solution.fingerOfContact);
  Transform3D X = X_W_base;
  Q q = solution.qContact;
  solver.solve(X, q, targets, g.joints, false, kMaxRefitIterations);
  ContactIkResult r = finishResult(model, solver, setup, targets, a, solution.grasp, X_W_base, q,
                                   backoff, kMaxRefitIterations);
  r.attempts = 1;
  describeRefit(r);
  return r;
}

ContactIkResult reopenContactIk(const HandGraspSetup& setup,
                                const std::vector<DesiredContact>& contacts,
                                const Vector3D& approach, const ContactIkResult& refitted,
                                double backoff) {
  checkSolution(setup, contacts, approach, refitted);
  const Vector3D a = approach.normalized();
  HandModel model(setup);
  Solver solver(model, setup, a);
  const std::vector<Target> targets = targetsOf(contacts, refitted.fingerOfContact);
  ContactIkResult r =
      finishResult(model, solver, setup, targets, a, refitted.grasp, refitted.X_W_base,
                   refitted.qContact, backoff, kMaxRefitIterations);
  r.attempts = 1;
  describeRefit(r);
  return r;
}

}  // namespace visgrab::grasp
