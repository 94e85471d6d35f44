#include "visgrab/analysis/analysis.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

#include "rw/common/number_text.hpp"
#include "rw/common/task_pool.hpp"
#include "visgrab/analysis/attempts.hpp"
#include "visgrab/analysis/detail/scene_tally.hpp"

namespace visgrab::analysis {

namespace detail {

std::vector<SceneTally> tallyScenes(const results::RunResults& run, const std::string& method) {
  using results::TrialRecord;
  std::vector<SceneTally> scenes;
  std::unordered_map<std::string, std::size_t> index;
  auto addScene = [&](const std::string& id,
                      const std::optional<database::SceneConditions>& conditions) {
    const auto [it, inserted] = index.emplace(id, scenes.size());
    if (inserted) scenes.push_back({id, method + "|" + id, conditions, {}, {}, 0});
    return it->second;
  };
  for (const results::RunScene& scene : run.scenes) addScene(scene.id, scene.conditions);
  // The grasps are the unperturbed trials; the perturbed repeats only count in `repeats`.
  for (const TrialRecord& t : run.trials) {
    if (t.method != method || t.repeat != 0) continue;
    SceneTally& scene = scenes[addScene(t.sceneId, t.conditions)];
    scene.grasps.push_back(&t);
    if (results::isSuccess(t.outcome)) ++scene.successes;
  }
  for (SceneTally& scene : scenes) {
    std::stable_sort(scene.grasps.begin(), scene.grasps.end(),
                     [](const TrialRecord* a, const TrialRecord* b) {
                       return a->rank != b->rank ? a->rank < b->rank : a->graspId < b->graspId;
                     });
    scene.repeats.assign(scene.grasps.size(), GraspRepeats{});
  }
  // Every trial of a grasp, by (scene, grasp id); a repeat whose grasp has no repeat 0 is not a
  // grasp of the analyses and is left out.
  std::unordered_map<std::string, GraspRepeats*> byGrasp;
  for (SceneTally& scene : scenes) {
    for (std::size_t i = 0; i < scene.grasps.size(); ++i) {
      byGrasp.emplace(scene.id + '\n' + scene.grasps[i]->graspId, &scene.repeats[i]);
    }
  }
  for (const TrialRecord& t : run.trials) {
    if (t.method != method) continue;
    const auto it = byGrasp.find(t.sceneId + '\n' + t.graspId);
    if (it == byGrasp.end()) continue;
    ++it->second->trials;
    it->second->held += results::isSuccess(t.outcome) ? 1 : 0;
  }
  return scenes;
}

}  // namespace detail

namespace {

using database::Arrangement;
using database::SceneKind;
using database::Texture;
using detail::SceneTally;
using results::RunResults;
using results::TrialRecord;

const double kNaN = std::nan("");

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
  r.success.grasps = d.grasps;
  r.success.successes = q.successes;
  r.success.rate = d.grasps > 0 ? static_cast<double>(q.successes) / d.grasps : kNaN;
  return r;
}

/// The index of a pair or single object's SuccessCount in an ObjectTable and its scenes' key.
struct ObjectCell {
  std::size_t table = 0;        // 0 textured, 1 plain
  bool single = true;           // single object or pair
  std::size_t subject = 0;      // object - 1 or pair index
  std::size_t arrangement = 0;  // 0 standing/apart, 1 lying/close
};

/// The object table cell a scene counts in, if its conditions are known and valid.
std::optional<ObjectCell> objectCell(const SceneTally& scene) {
  if (!scene.conditions || !database::validate(*scene.conditions).empty()) return std::nullopt;
  const database::SceneConditions& c = *scene.conditions;
  ObjectCell cell;
  cell.table = c.texture == Texture::kTextured ? 0 : 1;
  const Arrangement a = c.arrangement();
  if (c.kind == SceneKind::kSingle) {
    cell.subject = static_cast<std::size_t>(c.objects[0] - 1);
    cell.arrangement = a == Arrangement::kStanding ? 0 : 1;
  } else {
    cell.single = false;
    cell.subject = static_cast<std::size_t>(c.pair()->letter - 'a');
    cell.arrangement = a == Arrangement::kApart ? 0 : 1;
  }
  return cell;
}

void tallyObjects(const std::vector<SceneTally>& scenes, std::array<ObjectTable, 2>& tables) {
  for (const SceneTally& scene : scenes) {
    const auto cell = objectCell(scene);
    if (!cell) continue;
    ObjectTable& table = tables[cell->table];
    SuccessCount& count = cell->single ? table.single[cell->subject][cell->arrangement]
                                       : table.pairs[cell->subject][cell->arrangement];
    std::optional<database::ObjectPair> pair;
    if (!cell->single) pair = scene.conditions->pair();
    for (const TrialRecord* t : scene.grasps) {
      ++count.grasps;
      if (!results::isSuccess(t->outcome)) continue;
      ++count.successes;
      if (pair && t->object == pair->first) ++count.byObject[0];
      if (pair && t->object == pair->second) ++count.byObject[1];
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

std::optional<OptionProblem> checkOptions(const AnalysisOptions& options) {
  auto problem = [](std::string field, std::string cli, std::string python, std::string what) {
    return OptionProblem{std::move(field), std::move(cli), std::move(python), std::move(what)};
  };
  if (options.randomTrials < 1) {
    return problem("randomTrials", "", "",
                   "must be at least 1, got " + std::to_string(options.randomTrials));
  }
  if (options.maxAttempts < 0) {
    return problem("maxAttempts", "", "",
                   "must not be negative, got " + std::to_string(options.maxAttempts));
  }
  if (!(options.ciLevel > 0.0 && options.ciLevel < 1.0)) {
    return problem(
        "ciLevel", "--ci-level", "ci_level",
        "must be between 0 and 1 (exclusive), got " + rw::common::shortestText(options.ciLevel));
  }
  if (options.bootstrapResamples != 0 && options.bootstrapResamples < kMinBootstrapResamples) {
    return problem("bootstrapResamples", "--bootstrap", "bootstrap",
                   "must be 0 (no intervals) or at least " +
                       std::to_string(kMinBootstrapResamples) + ", got " +
                       std::to_string(options.bootstrapResamples) +
                       (options.bootstrapResamples > 0
                            ? " (the interval's ends would be the extremes of a few resamples, "
                              "which need not contain the estimate)"
                            : ""));
  }
  if (options.permutations < 1) {
    return problem("permutations", "", "",
                   "must be at least 1, got " + std::to_string(options.permutations));
  }
  if (options.threads < 1) {
    return problem("threads", "--threads", "threads",
                   "must be at least 1, got " + std::to_string(options.threads));
  }
  return std::nullopt;
}

namespace {

/// The members of `group` among `scenes`.
std::vector<const SceneTally*> members(const ConditionGroup& group,
                                       const std::vector<SceneTally>& scenes) {
  std::vector<const SceneTally*> out;
  for (const SceneTally& s : scenes) {
    if (group.contains(s.conditions)) out.push_back(&s);
  }
  return out;
}

/// A column's stream key: its run's label and its method.
std::string columnKey(const Analysis& a, std::size_t column) {
  return a.runLabels[a.columns[column].run] + "|" + a.columns[column].method;
}

using Tasks = std::vector<std::function<void()>>;

/// The task that fills the intervals of Tables 3 and 4 for column `c`: per object (or pair) and
/// arrangement, a bootstrap over its scenes.
std::function<void()> objectIntervalsTask(Analysis& a,
                                          const std::vector<std::vector<SceneTally>>& tallies,
                                          std::size_t c) {
  return [&a, &tallies, c] {
    std::map<std::tuple<std::size_t, bool, std::size_t, std::size_t>,
             std::vector<const SceneTally*>>
        cells;
    for (const SceneTally& s : tallies[c]) {
      if (const auto cell = objectCell(s)) {
        cells[{cell->table, cell->single, cell->subject, cell->arrangement}].push_back(&s);
      }
    }
    for (const auto& [where, scenes] : cells) {
      const auto [table, single, subject, arrangement] = where;
      ObjectTable& t = a.objectTables[table][c];
      SuccessCount& count = single ? t.single[subject][arrangement] : t.pairs[subject][arrangement];
      const std::string key = "objects|" + std::to_string(table) + "|" +
                              (single ? "single|" : "double|") + std::to_string(subject) + "|" +
                              std::to_string(arrangement) + "|" + columnKey(a, c);
      count.percentCi = detail::percentInterval(scenes, detail::bootstrapOptions(a.options, key));
    }
  };
}

/// Adds a Comparison (and the task that fills it) for every pair of columns with shared scenes
/// in each group.
void planComparisons(Analysis& a, const std::vector<RunResults>& runs,
                     const std::vector<std::vector<SceneTally>>& tallies, Tasks& tasks) {
  const std::size_t columns = a.columns.size();
  for (std::size_t g = 0; g < a.groups.size(); ++g) {
    for (std::size_t i = 0; i < columns; ++i) {
      for (std::size_t j = i + 1; j < columns; ++j) {
        std::vector<const SceneTally*> sa;
        std::vector<const SceneTally*> sb;
        std::unordered_map<std::string, const SceneTally*> inB;
        for (const SceneTally* s : members(a.groups[g], tallies[j])) inB.emplace(s->id, s);
        for (const SceneTally* s : members(a.groups[g], tallies[i])) {
          const auto it = inB.find(s->id);
          if (it == inB.end()) continue;
          sa.push_back(s);
          sb.push_back(it->second);
        }
        if (sa.empty()) continue;
        const std::size_t slot = a.comparisons.size();
        Comparison& comparison = a.comparisons.emplace_back();
        comparison.group = g;
        comparison.columnA = i;
        comparison.columnB = j;
        const std::size_t runA = a.columns[i].run;
        const std::size_t runB = a.columns[j].run;
        if (runA != runB) {
          comparison.runDifferences = differingSources(runs[runA].sources, runs[runB].sources);
        }
        const std::string key = a.groups[g].key + "|" + columnKey(a, i) + "|" + columnKey(a, j);
        tasks.emplace_back([sa = std::move(sa), sb = std::move(sb), &a, slot, key] {
          detail::compareColumns(sa, sb, a.options, key, a.comparisons[slot]);
        });
      }
    }
  }
}

/// The intervals, comparisons and robust rates (the work that resamples), as numbered tasks on
/// options.threads workers; each task writes its own slot, so the result does not depend on the
/// thread count.
void addStatistics(Analysis& a, const std::vector<RunResults>& runs,
                   const std::vector<std::vector<SceneTally>>& tallies,
                   const std::vector<bool>& repeated) {
  Tasks tasks;
  for (std::size_t g = 0; g < a.groups.size(); ++g) {
    for (std::size_t c = 0; c < a.columns.size(); ++c) {
      const std::string key = a.groups[g].key + "|" + columnKey(a, c);
      if (a.intervals) {
        tasks.emplace_back([&a, &tallies, g, c, key] {
          detail::addGroupIntervals(members(a.groups[g], tallies[c]), a.maxAttempts,
                                    detail::bootstrapOptions(a.options, "group|" + key),
                                    a.results[g][c]);
        });
      }
      if (repeated[a.columns[c].run]) {
        const std::size_t slot = a.robust.size();
        a.robust.emplace_back();
        tasks.emplace_back([&a, &tallies, slot, g, c, key] {
          const results::BootstrapOptions b = detail::bootstrapOptions(a.options, "robust|" + key);
          RobustRate& r = a.robust[slot];
          r = detail::robustRate(members(a.groups[g], tallies[c]), a.intervals ? &b : nullptr);
          r.group = g;
          r.column = c;
        });
      }
    }
  }
  if (a.intervals) {
    for (std::size_t c = 0; c < a.columns.size(); ++c) {
      tasks.push_back(objectIntervalsTask(a, tallies, c));
    }
    planComparisons(a, runs, tallies, tasks);
  }
  rw::common::TaskPool pool(a.options.threads);
  pool.run(tasks.size(), [&tasks](std::size_t task, int) { tasks[task](); });
}

}  // namespace

Analysis analyze(const std::vector<RunResults>& runs, const AnalysisOptions& options) {
  if (const auto problem = checkOptions(options)) {
    throw std::invalid_argument(problem->field + " " + problem->problem);
  }
  Analysis a;
  a.options = options;
  a.groups = conditionGroups();
  std::map<std::string, int> methodUses;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    a.runLabels.push_back(runs[r].label.empty() ? "run " + std::to_string(r + 1) : runs[r].label);
    if (!runs[r].finished) a.unfinishedRuns.push_back(a.runLabels.back());
    for (const std::string& m : runs[r].methods) ++methodUses[m];
    // The label names the run's columns and keys its bootstrap streams: two runs of one label
    // would show as one and draw the same resamples.
    for (std::size_t q = 0; q < r; ++q) {
      if (a.runLabels[q] == a.runLabels[r]) {
        throw std::invalid_argument("runs " + std::to_string(q + 1) + " and " +
                                    std::to_string(r + 1) + " have the same label '" +
                                    a.runLabels[r] +
                                    "' (results::readResultFolders labels folders apart)");
      }
    }
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
        column.closingCapped += t.method == m && t.repeat == 0 && t.closingCapped ? 1 : 0;
      }
      a.columns.push_back(column);
      tallies.push_back(detail::tallyScenes(runs[r], m));
      for (const SceneTally& s : tallies.back()) {
        largest = std::max(largest, static_cast<int>(s.grasps.size()));
      }
    }
  }
  a.maxAttempts = options.maxAttempts > 0 ? options.maxAttempts : largest;
  for (const ConditionGroup& group : a.groups) {
    std::vector<GroupResult>& row = a.results.emplace_back();
    for (const std::vector<SceneTally>& scenes : tallies) {
      row.push_back(analyseGroup(members(group, scenes), a.maxAttempts, options));
    }
  }
  for (const std::vector<SceneTally>& scenes : tallies) {
    std::array<ObjectTable, 2> tables{};
    tallyObjects(scenes, tables);
    a.objectTables[0].push_back(tables[0]);
    a.objectTables[1].push_back(tables[1]);
  }
  a.intervals = options.bootstrapResamples > 0;
  std::vector<bool> repeated;
  for (const RunResults& run : runs) {
    repeated.push_back(std::any_of(run.trials.begin(), run.trials.end(),
                                   [](const TrialRecord& t) { return t.repeat > 0; }));
  }
  addStatistics(a, runs, tallies, repeated);
  return a;
}

}  // namespace visgrab::analysis
