#include "visgrab/session/grasp_order.hpp"

#include <algorithm>
#include <charconv>
#include <map>
#include <stdexcept>
#include <utility>

#include "visgrab/session/scene_selection.hpp"

namespace visgrab::session {

GraspOrder benchmarkOrder(const database::Database& db,
                          const std::vector<const database::SceneEntry*>& selected,
                          const std::vector<grasp::GraspRequest>& requests) {
  GraspOrder order;
  std::map<std::string, std::size_t> position;
  for (const auto* entry : selected) {
    position.emplace(entry->id, order.scenes.size());
    order.scenes.push_back(SceneGraspList{entry, {}});
  }
  std::map<std::pair<std::string, std::string>, int> ranks;
  for (const auto& r : requests) {
    if (!db.contains(r.sceneId)) {
      order.unknownScene.push_back(&r);
      continue;
    }
    const std::string& id = db.scene(r.sceneId).id;
    const auto it = position.find(id);
    if (it == position.end()) continue;  // not selected
    if (std::find(order.methods.begin(), order.methods.end(), r.method) == order.methods.end()) {
      order.methods.push_back(r.method);
    }
    order.scenes[it->second].grasps.push_back(RankedGrasp{&r, ranks[{id, r.method}]++});
  }
  const auto methodIndex = [&](const RankedGrasp& g) {
    return std::find(order.methods.begin(), order.methods.end(), g.request->method) -
           order.methods.begin();
  };
  for (auto& scene : order.scenes) {
    std::stable_sort(scene.grasps.begin(), scene.grasps.end(),
                     [&](const RankedGrasp& a, const RankedGrasp& b) {
                       return methodIndex(a) < methodIndex(b);
                     });
  }
  return order;
}

std::vector<SceneGrasp> sceneGrasps(const database::Database& db, const database::SceneEntry& entry,
                                    const taskio::GraspFileContents& grasps,
                                    const results::RunResults* results) {
  std::vector<const database::SceneEntry*> selected;
  if (results != nullptr) {
    for (const auto& s : results->scenes) {
      if (db.contains(s.id)) selected.push_back(&db.scene(s.id));
    }
  } else {
    selected = selectScenes(db, "");
  }
  if (std::none_of(selected.begin(), selected.end(),
                   [&](const database::SceneEntry* s) { return s->id == entry.id; })) {
    selected.push_back(&entry);
  }
  const GraspOrder order = benchmarkOrder(db, selected, grasps.requests);
  std::vector<SceneGrasp> out;
  for (const auto& scene : order.scenes) {
    if (scene.entry->id != entry.id) continue;
    for (const auto& g : scene.grasps) out.push_back(SceneGrasp{*g.request, g.rank, std::nullopt});
  }
  if (results != nullptr) {
    std::map<std::pair<std::string, std::string>, const results::TrialRecord*> byKey;
    for (const auto& t : results->trials) {
      // The unperturbed trial of a run with repeats (the one a plain run has).
      if (t.sceneId == entry.id && t.repeat == 0) {
        byKey.emplace(std::make_pair(t.method, t.graspId), &t);
      }
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

}  // namespace visgrab::session
