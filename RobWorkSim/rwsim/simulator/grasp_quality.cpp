#include "rwsim/simulator/grasp_quality.hpp"

namespace rwsim::simulator {

GwsQualities gwsQualities(const std::vector<TrialContact>& contacts, const rw::math::Vector3D& cog,
                          double r, const GwsQualityOptions& options) {
  namespace gp = rw::graspplanning;
  GwsQualities q;
  if (contacts.empty() || !(r > 0.0)) return q;
  std::vector<gp::Contact3D> c3;
  c3.reserve(contacts.size());
  for (const TrialContact& c : contacts) {
    gp::Contact3D x;
    x.position = c.position;
    x.normal = c.normal;
    x.mu = c.mu;
    x.normalForce = c.normalForce;
    x.force = c.force;
    c3.push_back(x);
  }
  gp::GwsOptions paper;
  paper.coneEdges = options.coneEdges;
  paper.force = gp::GwsForce::kMeasuredForce;
  paper.duplicateBelow = options.duplicateBelow;
  paper.hull = options.hull;
  q.qGws = gp::gwsEpsilon(c3, cog, r, paper).epsilon;
  gp::GwsOptions unit;
  unit.coneEdges = options.coneEdges;
  unit.force = gp::GwsForce::kUnitNormal;
  unit.hull = options.hull;
  q.qGwsUnit = gp::gwsEpsilon(c3, cog, r, unit).epsilon;
  return q;
}

}  // namespace rwsim::simulator
