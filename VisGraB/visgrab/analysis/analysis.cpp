#include "visgrab/analysis/analysis.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <unordered_map>
#include <utility>

#include "visgrab/analysis/attempts.hpp"

namespace visgrab::analysis {

namespace {

using database::Arrangement;
using database::SceneKind;
using database::Texture;
using results::RunResults;
using results::TrialRecord;

const double kNaN = std::nan("");

/// One scene's grasps of one method, in rank order.
struct SceneTally {
  std::string key;  // "<method>|<scene id>": the scene's random stream
  std::optional<database::SceneConditions> conditions;
  std::vector<const TrialRecord*> grasps;
  int successes = 0;
};

/// The scenes of one run and method, in the run's scene order.
std::vector<SceneTally> tallyScenes(const RunResults& run, const std::string& method) {
  std::vector<SceneTally> scenes;
  std::unordered_map<std::string, std::size_t> index;
  auto addScene = [&](const std::string& id,
                      const std::optional<database::SceneConditions>& conditions) {
    const auto [it, inserted] = index.emplace(id, scenes.size());
    if (inserted) scenes.push_back({method + "|" + id, conditions, {}, 0});
    return it->second;
  };
  for (const results::RunScene& scene : run.scenes) addScene(scene.id, scene.conditions);
  for (const TrialRecord& t : run.trials) {
    if (t.method != method) continue;
    SceneTally& scene = scenes[addScene(t.sceneId, t.conditions)];
    scene.grasps.push_back(&t);
    if (results::isSuccess(t.outcome)) ++scene.successes;
  }
  for (SceneTally& scene : scenes) {
    std::stable_sort(scene.grasps.begin(), scene.grasps.end(),
                     [](const TrialRecord* a, const TrialRecord* b) {
                       return a->rank != b->rank ? a->rank < b->rank : a->graspId < b->graspId;
                     });
  }
  return scenes;
}

GroupResult analyseGroup(const std::vector<const SceneTally*>& scenes, int maxAttempts,
                         const AnalysisOptions& options) {
  GroupResult r;
  Distribution& d = r.distribution;
  FirstSuccess& f = r.firstSuccess;
  QualityMeans& q = r.quality;
  d.scenes = static_cast<int>(scenes.size());
  f.scenes = d.scenes;
  r.attempts.exact.assign(static_cast<std::size_t>(maxAttempts), 0.0);
  double qLift = 0.0;
  double qGws = 0.0;
  double qGwsUnit = 0.0;
  double gaSum = 0.0;
  double gaGivenSum = 0.0;
  std::vector<SceneOutcomes> outcomes;
  for (const SceneTally* scene : scenes) {
    const int n = static_cast<int>(scene->grasps.size());
    SceneOutcomes& o = outcomes.emplace_back();
    o.key = scene->key;
    if (n == 0) {
      ++d.scenesWithoutGrasps;
      continue;
    }
    int firstGiven = 0;
    for (int i = 0; i < n; ++i) {
      const TrialRecord& t = *scene->grasps[static_cast<std::size_t>(i)];
      const auto outcome = static_cast<std::size_t>(t.outcome);
      ++d.counts[outcome];
      d.share[outcome] += 1.0 / n;
      const bool success = results::isSuccess(t.outcome);
      o.success.push_back(success);
      if (!success) continue;
      ++q.successes;
      qLift += t.qLift;
      qGws += t.qGws;  // NaN (not computed) makes the mean NaN: shown as undefined
      qGwsUnit += t.qGwsUnit;
      if (firstGiven == 0) firstGiven = i + 1;
    }
    d.grasps += n;
    for (int k = 1; k <= maxAttempts; ++k) {
      r.attempts.exact[static_cast<std::size_t>(k - 1)] +=
          successWithinAttempts(n, scene->successes, k);
    }
    if (scene->successes > 0) {
      ++f.scenesWithSuccess;
      gaSum += expectedAttemptsToFirstSuccess(n, scene->successes);
      gaGivenSum += firstGiven;
    }
  }
  if (d.scenes > 0) {
    for (double& s : d.share) s /= d.scenes;
    d.noGraspShare = static_cast<double>(d.scenesWithoutGrasps) / d.scenes;
    for (double& e : r.attempts.exact) e /= d.scenes;
  }
  q.meanQLift = q.successes > 0 ? qLift / q.successes : kNaN;
  q.meanQGws = q.successes > 0 ? qGws / q.successes : kNaN;
  q.meanQGwsUnit = q.successes > 0 ? qGwsUnit / q.successes : kNaN;
  f.p = f.scenes > 0 ? static_cast<double>(f.scenesWithSuccess) / f.scenes : kNaN;
  f.ga = f.scenesWithSuccess > 0 ? gaSum / f.scenesWithSuccess : kNaN;
  f.gaGivenOrder = f.scenesWithSuccess > 0 ? gaGivenSum / f.scenesWithSuccess : kNaN;
  const RandomizedAttempts randomized =
      randomizedAttempts(outcomes, maxAttempts, options.randomTrials, options.seed);
  r.attempts.randomized = randomized.rate;
  f.gaRandomized = randomized.meanFirstSuccess;
  return r;
}

void tallyObjects(const std::vector<SceneTally>& scenes, std::array<ObjectTable, 2>& tables) {
  for (const SceneTally& scene : scenes) {
    if (!scene.conditions || !database::validate(*scene.conditions).empty()) continue;
    const database::SceneConditions& c = *scene.conditions;
    ObjectTable& table = tables[c.texture == Texture::kTextured ? 0 : 1];
    const Arrangement a = c.arrangement();
    SuccessCount* count = nullptr;
    std::optional<database::ObjectPair> pair;
    if (c.kind == SceneKind::kSingle) {
      count = &table.single[static_cast<std::size_t>(c.objects[0] - 1)]
                           [a == Arrangement::kStanding ? 0 : 1];
    } else {
      pair = c.pair();
      count = &table.pairs[static_cast<std::size_t>(pair->letter - 'a')]
                          [a == Arrangement::kApart ? 0 : 1];
    }
    for (const TrialRecord* t : scene.grasps) {
      ++count->grasps;
      if (!results::isSuccess(t->outcome)) continue;
      ++count->successes;
      if (pair && t->object == pair->first) ++count->byObject[0];
      if (pair && t->object == pair->second) ++count->byObject[1];
    }
  }
}

}  // namespace

bool ConditionGroup::contains(const std::optional<database::SceneConditions>& conditions) const {
  if (!texture && !kind && !arrangement) return true;
  if (!conditions) return false;
  if (texture && conditions->texture != *texture) return false;
  if (kind && conditions->kind != *kind) return false;
  if (arrangement && conditions->arrangement() != *arrangement) return false;
  return true;
}

std::vector<ConditionGroup> conditionGroups() {
  std::vector<ConditionGroup> groups;
  for (const Texture texture : {Texture::kTextured, Texture::kPlain}) {
    const std::string t(database::toString(texture));
    auto add = [&](std::optional<SceneKind> kind, std::optional<Arrangement> arrangement) {
      ConditionGroup g;
      g.texture = texture;
      g.kind = kind;
      g.arrangement = arrangement;
      g.key = t;
      g.name = t;
      if (kind) {
        g.key += "-" + std::string(database::toString(*kind));
        g.name += ", " + std::string(database::toString(*kind));
      }
      const std::string a = arrangement ? std::string(database::toString(*arrangement)) : "all";
      g.key += "-" + a;
      g.name += ", " + a;
      groups.push_back(std::move(g));
    };
    add(SceneKind::kSingle, Arrangement::kStanding);
    add(SceneKind::kSingle, Arrangement::kLying);
    add(SceneKind::kSingle, std::nullopt);
    add(SceneKind::kDouble, Arrangement::kApart);
    add(SceneKind::kDouble, Arrangement::kClose);
    add(SceneKind::kDouble, std::nullopt);
    add(std::nullopt, std::nullopt);
  }
  ConditionGroup overall;
  overall.key = "overall";
  overall.name = "overall";
  groups.push_back(overall);
  return groups;
}

double SuccessCount::percent() const { return grasps > 0 ? 100.0 * successes / grasps : kNaN; }

double SuccessCount::percentOf(int i) const {
  return grasps > 0 ? 100.0 * byObject[static_cast<std::size_t>(i)] / grasps : kNaN;
}

Analysis analyze(const std::vector<RunResults>& runs, const AnalysisOptions& options) {
  if (options.randomTrials < 1) throw std::invalid_argument("randomTrials must be at least 1");
  if (options.maxAttempts < 0) throw std::invalid_argument("maxAttempts must not be negative");
  Analysis a;
  a.options = options;
  a.groups = conditionGroups();
  std::map<std::string, int> methodUses;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    a.runLabels.push_back(runs[r].label.empty() ? "run " + std::to_string(r + 1) : runs[r].label);
    for (const std::string& m : runs[r].methods) ++methodUses[m];
  }
  // Columns and their scene tallies.
  std::vector<std::vector<SceneTally>> tallies;
  int largest = 1;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    std::vector<std::string> methods = runs[r].methods;
    for (const TrialRecord& t : runs[r].trials) {
      if (std::find(methods.begin(), methods.end(), t.method) == methods.end()) {
        methods.push_back(t.method);
        ++methodUses[t.method];
      }
    }
    int unknown = 0;
    for (const results::RunScene& s : runs[r].scenes) unknown += s.conditions ? 0 : 1;
    a.unknownScenes.push_back(unknown);
    for (const std::string& m : methods) {
      MethodColumn column;
      column.run = r;
      column.method = m;
      column.label = methodUses[m] > 1 ? a.runLabels[r] + ": " + m : m;
      for (const auto& [name, count] : runs[r].rejected) column.rejected += name == m ? count : 0;
      for (const TrialRecord& t : runs[r].trials) {
        column.closingCapped += t.method == m && t.closingCapped ? 1 : 0;
      }
      a.columns.push_back(column);
      tallies.push_back(tallyScenes(runs[r], m));
      for (const SceneTally& s : tallies.back()) {
        largest = std::max(largest, static_cast<int>(s.grasps.size()));
      }
    }
  }
  a.maxAttempts = options.maxAttempts > 0 ? options.maxAttempts : largest;
  for (const ConditionGroup& group : a.groups) {
    std::vector<GroupResult>& row = a.results.emplace_back();
    for (const std::vector<SceneTally>& scenes : tallies) {
      std::vector<const SceneTally*> members;
      for (const SceneTally& s : scenes) {
        if (group.contains(s.conditions)) members.push_back(&s);
      }
      row.push_back(analyseGroup(members, a.maxAttempts, options));
    }
  }
  for (const std::vector<SceneTally>& scenes : tallies) {
    std::array<ObjectTable, 2> tables{};
    tallyObjects(scenes, tables);
    a.objectTables[0].push_back(tables[0]);
    a.objectTables[1].push_back(tables[1]);
  }
  return a;
}

}  // namespace visgrab::analysis
