#include "visgrab/grasp/grasp_resolver.hpp"

#include <cstdio>
#include <stdexcept>
#include <utility>

namespace visgrab::grasp {

namespace {

using rw::math::Q;

std::string where(const GraspRequest& r) {
  std::string out;
  if (!r.sourceFile.empty()) {
    out = r.sourceFile + (r.sourceLine > 0 ? ":" + std::to_string(r.sourceLine) : "") + ": ";
  }
  return out + "grasp " + (r.id.empty() ? "(no id)" : "\"" + r.id + "\"") + ": ";
}

ResolvedGrasp inputError(const GraspRequest& r, const std::string& what) {
  ResolvedGrasp out;
  out.status = ResolveStatus::kInputError;
  out.reason = what;
  out.message = where(r) + what;
  return out;
}

// Empty if `q` has one finite value per DOF, else what is wrong.
std::string checkQ(const Q& q, std::string_view name, const HandGraspSetup& setup) {
  if (q.size() != setup.dof()) {
    return std::string(name) + " has " + std::to_string(q.size()) + " values, but hand \"" +
           setup.deviceName() + "\" has " + std::to_string(setup.dof()) + " DOF";
  }
  if (!q.allFinite()) return std::string(name) + " has a non-finite value";
  return {};
}

ResolvedGrasp ok(rwsim::simulator::GraspParameters parameters) {
  ResolvedGrasp out;
  out.status = ResolveStatus::kOk;
  out.parameters = std::move(parameters);
  return out;
}

ResolvedGrasp ok(const rw::math::Transform3D& X_W_tcp, Q qOpen, Q qClosed, Q tauMax) {
  return ok({X_W_tcp, std::move(qOpen), std::move(qClosed), std::move(tauMax)});
}

ResolvedGrasp resolveContacts(const GraspRequest& r, const HandGraspSetup& setup,
                              const PlacementTest* scene, const PlacementOptions& options) {
  std::vector<ContactIkResult> solutions;
  try {
    solutions = contactIkSolutions(setup, r.contacts, r.approach,
                                   scene != nullptr ? options.maxSolutions : 1);
  } catch (const std::invalid_argument& e) {
    return inputError(r, e.what());
  }
  ContactIkResult& ik = solutions.front();
  if (!ik.valid || scene == nullptr) {
    ResolvedGrasp out = ok(ik.parameters());
    if (!ik.valid) {
      out.status = ResolveStatus::kInvalidContacts;
      out.reason = ik.reason;
      out.message = where(r) + ik.reason;
    }
    out.ik = std::move(ik);
    return out;
  }
  Placement placement =
      placeContactGrasp(setup, r.contacts, r.approach, solutions, *scene, options);
  ResolvedGrasp out = ok(placement.ik.parameters());
  if (!placement.found) {
    char buffer[128];
    std::snprintf(buffer, sizeof(buffer),
                  "no collision-free placement among %d candidates (contact slack %.0f mm); "
                  "least penetration %.1f mm: ",
                  placement.candidates, options.contactSlack * 1e3,
                  placement.check.penetration * 1e3);
    out.status = ResolveStatus::kInCollision;
    out.reason = buffer + placement.check.detail;
    out.message = where(r) + out.reason;
  }
  out.ik = placement.ik;
  out.placement = std::move(placement);
  return out;
}

// A parallel-jaw grasp through the hand's jaw frame: X_W_tcp = X_W_jaw * X_tcp_jaw^-1, the
// configuration of the jaw frame's pre-shape.
ResolvedGrasp resolveJaw(const GraspRequest& r, const HandGraspSetup& setup) {
  const JawFrame* jaw = setup.jawFrame();
  if (jaw == nullptr) {
    return inputError(r, "hand \"" + setup.deviceName() +
                             "\" declares no jaw frame (<JawFrame> in its grasp description), "
                             "which parallel-jaw grasps need");
  }
  if (!r.X_W_jaw.matrix().allFinite()) return inputError(r, "the jaw pose has a non-finite value");
  if (!std::isfinite(r.width) || r.width < 0.0 || r.width > jaw->stroke) {
    char buffer[160];
    std::snprintf(buffer, sizeof(buffer),
                  "width %.4g m is outside what hand \"%s\" opens to (0 to its stroke %.4g m)",
                  r.width, setup.deviceName().c_str(), jaw->stroke);
    return inputError(r, buffer);
  }
  const PreShape& p = setup.preshapes()[jaw->preshape];
  return ok(r.X_W_jaw * jaw->X_tcp_jaw.inverse(), p.qOpen, p.qClosed, p.tauMax);
}

ResolvedGrasp resolveRequest(const GraspRequest& r, const HandGraspSetup& setup,
                             const PlacementTest* scene, const PlacementOptions& options) {
  if (r.kind != GraspKind::kContacts && !r.X_W_tcp.matrix().allFinite()) {
    return inputError(r, "the hand pose has a non-finite value");
  }
  switch (r.kind) {
    case GraspKind::kRaw: {
      for (const auto& [q, name] : {std::pair{&r.qOpen, "q_open"}, {&r.qClosed, "q_closed"}}) {
        if (const std::string e = checkQ(*q, name, setup); !e.empty()) return inputError(r, e);
      }
      if (r.tauMax.size() == 0) {
        return ok(r.X_W_tcp, r.qOpen, r.qClosed, setup.tauRule().evaluate(r.qOpen));
      }
      if (const std::string e = checkQ(r.tauMax, "tau_max", setup); !e.empty()) {
        return inputError(r, e);
      }
      if ((r.tauMax.array() < 0.0).any()) return inputError(r, "tau_max has a negative value");
      return ok(r.X_W_tcp, r.qOpen, r.qClosed, r.tauMax);
    }
    case GraspKind::kPreshape: {
      const PreShape* p = setup.findPreshape(r.preshape);
      if (p == nullptr) {
        std::string known;
        for (const PreShape& s : setup.preshapes()) known += (known.empty() ? "" : ", ") + s.name;
        return inputError(r, "unknown pre-shape \"" + r.preshape + "\" for hand \"" +
                                 setup.deviceName() + "\" (known: " + known + ")");
      }
      return ok(r.X_W_tcp * p->X_shapeTcp_tcp, p->qOpen, p->qClosed, p->tauMax);
    }
    case GraspKind::kPoseAndQ: {
      if (!setup.hasClosingRule()) {
        return inputError(r, "hand \"" + setup.deviceName() +
                                 "\" has no closing rule (no <Closing> in its grasp description), "
                                 "which pose + q grasps need; use a pre-shape or raw grasp");
      }
      if (const std::string e = checkQ(r.qOpen, "q", setup); !e.empty()) return inputError(r, e);
      return ok(r.X_W_tcp, r.qOpen, r.qOpen + setup.closeOffset(),
                setup.tauRule().evaluate(r.qOpen));
    }
    case GraspKind::kContacts:
      return resolveContacts(r, setup, scene, options);
    case GraspKind::kJaw:
      return resolveJaw(r, setup);
  }
  return inputError(r, "unknown grasp kind");
}

}  // namespace

ResolvedGrasp resolve(const GraspRequest& r, const HandGraspSetup& setup) {
  return resolveRequest(r, setup, nullptr, {});
}

ResolvedGrasp resolve(const GraspRequest& r, const HandGraspSetup& setup,
                      const PlacementTest& scene, const PlacementOptions& options) {
  return resolveRequest(r, setup, &scene, options);
}

const char* resolveStatusName(ResolveStatus status) {
  switch (status) {
    case ResolveStatus::kOk:
      return "ok";
    case ResolveStatus::kInvalidContacts:
      return "invalid_contacts";
    case ResolveStatus::kInputError:
      return "input_error";
    case ResolveStatus::kInCollision:
      return "in_collision";
  }
  return "input_error";
}

}  // namespace visgrab::grasp
