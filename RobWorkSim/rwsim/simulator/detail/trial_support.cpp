#include "rwsim/simulator/detail/trial_support.hpp"

#include <algorithm>

#include "rw/graspplanning/grasp_wrench_space.hpp"
#include "rw/kinematics/frame_tree.hpp"

namespace rwsim::simulator::detail {

namespace {

bool isHand(const std::vector<bool>& isHandBody, dynamics::BodyId body) {
  return body.valid() && body.index() < isHandBody.size() && isHandBody[body.index()];
}

// The load of a solved point on `object`: its normal force, the normal pointing into the object
// and the whole force on it (world frame).
struct Load {
  double normalForce = 0.0;
  rw::math::Vector3D normal;
  rw::math::Vector3D force;
};

Load loadOn(const SolvedContact& c, bool objectIsB) {
  const rw::math::Vector3D n = objectIsB ? c.point.normal : rw::math::Vector3D(-c.point.normal);
  const rw::math::Vector3D forceOnObject = objectIsB ? c.force : rw::math::Vector3D(-c.force);
  return {forceOnObject.dot(n), n, forceOnObject};
}

// Calls visit(body index, normal force) for each point between a hand body and another body
// whose normal force on that other body exceeds `threshold`, in the contacts' order.
template <class Visit>
void forEachLoadedHandPoint(const std::vector<SolvedBodyContact>& contacts,
                            const std::vector<bool>& isHandBody, double threshold, Visit visit) {
  for (const auto& bc : contacts) {
    const bool handA = isHand(isHandBody, bc.bodyA);
    const bool handB = isHand(isHandBody, bc.bodyB);
    if (handA == handB) continue;
    const dynamics::BodyId other = handA ? bc.bodyB : bc.bodyA;
    for (const auto& p : bc.points) {
      const double f = loadOn(p, handA).normalForce;
      if (f > threshold) visit(other.index(), f);
    }
  }
}

}  // namespace

std::vector<int> handContactCounts(const std::vector<SolvedBodyContact>& contacts,
                                   const std::vector<bool>& isHandBody, double threshold) {
  std::vector<int> counts(isHandBody.size(), 0);
  forEachLoadedHandPoint(contacts, isHandBody, threshold,
                         [&](std::size_t body, double) { ++counts[body]; });
  return counts;
}

std::vector<double> handNormalForces(const std::vector<SolvedBodyContact>& contacts,
                                     const std::vector<bool>& isHandBody, double threshold) {
  std::vector<double> forces(isHandBody.size(), 0.0);
  forEachLoadedHandPoint(contacts, isHandBody, threshold,
                         [&](std::size_t body, double f) { forces[body] += f; });
  return forces;
}

std::vector<TrialContact> objectContacts(const dynamics::DynamicWorkCell& dwc,
                                         const std::vector<SolvedBodyContact>& contacts,
                                         const std::vector<bool>& isHandBody,
                                         dynamics::BodyId object,
                                         const rw::math::Transform3D& X_W_object, double threshold,
                                         double frictionScale) {
  std::vector<TrialContact> out;
  const rw::math::Transform3D X_object_W = X_W_object.inverse();
  for (const auto& bc : contacts) {
    const bool objectIsB = bc.bodyB == object;
    if (!(objectIsB || bc.bodyA == object)) continue;
    const dynamics::BodyId other = objectIsB ? bc.bodyA : bc.bodyB;
    if (!isHand(isHandBody, other)) continue;
    double mu = dwc.materials().mu(dwc.body(object).material, dwc.body(other).material);
    if (frictionScale != 1.0) mu *= frictionScale;  // the identity keeps the dwc's mu exactly
    for (const auto& p : bc.points) {
      const Load load = loadOn(p, objectIsB);
      if (load.normalForce <= threshold) continue;
      TrialContact c;
      c.position = X_object_W * p.point.position;
      c.normal = X_object_W.linear() * load.normal;
      c.normalForce = load.normalForce;
      c.mu = mu;
      c.force = X_object_W.linear() * load.force;
      c.handBody = other;
      out.push_back(c);
    }
  }
  return out;
}

double maxRadiusFromCog(const dynamics::DynamicWorkCell& dwc, dynamics::BodyId body) {
  const auto& b = dwc.body(body);
  const auto& wc = dwc.workcell();
  const rw::kinematics::State state = wc.defaultState();
  double r = 0.0;
  for (const auto frame : b.geometryFrames) {
    const auto* object = wc.findObject(frame);
    if (object == nullptr) continue;
    const rw::math::Transform3D X_body_frame =
        rw::kinematics::relativeTransform(wc.frames(), state, b.frame, frame);
    for (const auto& g : object->collision) {
      const rw::math::Transform3D X = X_body_frame * g.X_frame_geometry;
      for (const auto& v : g.geometry->triangles().vertices) {
        r = std::max(r, (X * v - b.mass.cog).norm());
      }
    }
  }
  return r;
}

}  // namespace rwsim::simulator::detail
