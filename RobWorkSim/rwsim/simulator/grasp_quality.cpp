#include "rwsim/simulator/grasp_quality.hpp"

namespace rwsim::simulator {

std::vector<rw::graspplanning::Contact3D> toContacts3D(const std::vector<TrialContact>& contacts) {
  std::vector<rw::graspplanning::Contact3D> c3;
  c3.reserve(contacts.size());
  for (const TrialContact& c : contacts) {
    rw::graspplanning::Contact3D x;
    x.position = c.position;
    x.normal = c.normal;
    x.mu = c.mu;
    x.normalForce = c.normalForce;
    x.force = c.force;
    c3.push_back(x);
  }
  return c3;
}

GwsQualities gwsQualities(const std::vector<TrialContact>& contacts, const rw::math::Vector3D& cog,
                          double r, const GwsQualityOptions& options) {
  namespace gp = rw::graspplanning;
  GwsQualities q;
  if (contacts.empty() || !(r > 0.0)) return q;
  const std::vector<gp::Contact3D> c3 = toContacts3D(contacts);
  gp::GwsOptions unit;
  unit.coneEdges = options.coneEdges;
  unit.force = gp::GwsForce::kUnitNormal;
  unit.hull = options.hull;
  gp::GwsOptions paper = unit;
  paper.force = gp::GwsForce::kMeasuredForce;
  paper.duplicateBelow = options.duplicateBelow;
  q.qGws = gp::gwsEpsilon(c3, cog, r, paper).epsilon;
  q.qGwsUnit = gp::gwsEpsilon(c3, cog, r, unit).epsilon;
  return q;
}

}  // namespace rwsim::simulator
