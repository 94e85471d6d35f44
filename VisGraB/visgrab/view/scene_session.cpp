#include "visgrab/view/scene_session.hpp"

#include <algorithm>
#include <charconv>
#include <map>
#include <stdexcept>
#include <string>

#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "visgrab/runner/benchmark_runner.hpp"

namespace visgrab::view {

SceneSession::SceneSession(const database::SceneEntry& entry, const grasp::HandGraspSetup& hand)
    : entry_(entry), hand_(&hand) {
  dwc_ = runner::loadSceneWithHand(entry, hand);
  trial_ = std::make_unique<rwsim::simulator::GraspTrial>(*dwc_, runner::trialSetup(hand, *dwc_));
  initial_ = dwc_->workcell().defaultState();
  const auto& bodies = dwc_->bodies();
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (bodies[b].kind != rwsim::dynamics::BodyKind::kRigid) continue;
    if (trial_->isHandBody(rwsim::dynamics::BodyId(b))) continue;
    for (const auto frame : bodies[b].geometryFrames) objectFrames_.push_back(frame);
  }
}

grasp::ResolvedGrasp SceneSession::resolve(const grasp::GraspRequest& request) const {
  return grasp::resolve(request, *hand_, [this](const rwsim::simulator::GraspParameters& g) {
    return trial_->checkPlacement(g, initial_);
  });
}

std::vector<SceneGrasp> sceneGrasps(const database::Database& db, const database::SceneEntry& entry,
                                    const taskio::GraspFileContents& grasps,
                                    const results::RunResults* results) {
  std::vector<std::string> methods;
  if (results != nullptr) methods = results->methods;
  std::vector<SceneGrasp> out;
  for (const auto& r : grasps.requests) {
    if (!db.contains(r.sceneId) || db.scene(r.sceneId).id != entry.id) continue;
    if (std::find(methods.begin(), methods.end(), r.method) == methods.end()) {
      methods.push_back(r.method);
    }
    out.push_back(SceneGrasp{r, std::nullopt});
  }
  std::stable_sort(out.begin(), out.end(), [&](const SceneGrasp& a, const SceneGrasp& b) {
    return std::find(methods.begin(), methods.end(), a.request.method) <
           std::find(methods.begin(), methods.end(), b.request.method);
  });
  if (results != nullptr) {
    std::map<std::pair<std::string, std::string>, const results::TrialRecord*> byKey;
    for (const auto& t : results->trials) {
      if (t.sceneId == entry.id) byKey.emplace(std::make_pair(t.method, t.graspId), &t);
    }
    for (auto& g : out) {
      const auto it = byKey.find({g.request.method, g.request.id});
      if (it != byKey.end()) g.record = *it->second;
    }
  }
  return out;
}

const SceneGrasp& selectGrasp(const std::vector<SceneGrasp>& grasps, std::string_view spec,
                              std::string_view method) {
  std::vector<const SceneGrasp*> pool;
  for (const auto& g : grasps) {
    if (method.empty() || g.request.method == method) pool.push_back(&g);
  }
  const std::string where =
      method.empty() ? std::string("the scene") : "method '" + std::string(method) + "'";
  if (pool.empty()) throw std::invalid_argument(where + " has no grasps in the grasp files");
  std::vector<const SceneGrasp*> byId;
  for (const auto* g : pool) {
    if (g->request.id == spec) byId.push_back(g);
  }
  if (byId.size() == 1) return *byId.front();
  if (byId.size() > 1) {
    std::string methods;
    for (const auto* g : byId) methods += (methods.empty() ? "" : ", ") + g->request.method;
    throw std::invalid_argument("grasp id '" + std::string(spec) + "' is used by the methods " +
                                methods + "; choose one with --method");
  }
  int n = 0;
  const auto [end, ec] = std::from_chars(spec.data(), spec.data() + spec.size(), n);
  if (ec == std::errc() && end == spec.data() + spec.size()) {
    if (n >= 1 && static_cast<std::size_t>(n) <= pool.size()) {
      return *pool[static_cast<std::size_t>(n - 1)];
    }
    throw std::invalid_argument("grasp number " + std::string(spec) + " is out of range: " + where +
                                " has grasps 1.." + std::to_string(pool.size()));
  }
  std::string ids;
  for (std::size_t i = 0; i < pool.size() && i < 8; ++i) {
    ids += (i ? ", " : "") + pool[i]->request.id;
  }
  if (pool.size() > 8) ids += ", ...";
  throw std::invalid_argument("no grasp '" + std::string(spec) + "' in " + where +
                              " (give an id, e.g. " + ids + ", or a number 1.." +
                              std::to_string(pool.size()) + ")");
}

}  // namespace visgrab::view
