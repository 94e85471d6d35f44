#include "visgrab/analysis/showcase.hpp"

#include <algorithm>
#include <array>
#include <cstdio>

#include "visgrab/analysis/detail/format.hpp"

namespace visgrab::analysis {

namespace {

using database::SceneKind;
using database::Texture;

/// The four groups pictures are chosen for, in report order.
std::vector<ConditionGroup> pictureGroups() {
  std::vector<ConditionGroup> out;
  for (const Texture texture : {Texture::kTextured, Texture::kPlain}) {
    for (const SceneKind kind : {SceneKind::kSingle, SceneKind::kDouble}) {
      for (const ConditionGroup& g : conditionGroups()) {
        if (g.texture == texture && g.kind == kind && !g.arrangement) out.push_back(g);
      }
    }
  }
  return out;
}

}  // namespace

std::vector<Showcase> chooseShowcases(const Analysis& analysis,
                                      const std::vector<results::RunResults>& runs) {
  std::vector<Showcase> out;
  const auto groups = pictureGroups();
  for (std::size_t c = 0; c < analysis.columns.size(); ++c) {
    const MethodColumn& column = analysis.columns[c];
    if (column.run >= runs.size()) continue;
    const results::RunResults& run = runs[column.run];
    for (const ConditionGroup& group : groups) {
      std::vector<const results::TrialRecord*> held, failed;
      for (const results::TrialRecord& t : run.trials) {
        // The unperturbed trials only (repeat 0), as the analyses read them.
        if (t.method != column.method || t.repeat != 0 || !t.conditions ||
            !group.contains(t.conditions)) {
          continue;
        }
        (results::isSuccess(t.outcome) ? held : failed).push_back(&t);
      }
      auto add = [&](const char* role, const results::TrialRecord& t) {
        Showcase s;
        s.column = c;
        s.run = column.run;
        s.groupKey = group.key;
        s.groupName = group.name;
        s.role = role;
        s.trial = t;
        out.push_back(std::move(s));
      };
      const results::TrialRecord* best = nullptr;
      for (const auto* t : held) {
        if (best == nullptr || t->qLift > best->qLift ||
            (t->qLift == best->qLift && t->qGws > best->qGws)) {
          best = t;
        }
      }
      if (best != nullptr) add("best", *best);
      if (held.size() > 1) {
        std::vector<const results::TrialRecord*> others;
        for (const auto* t : held) {
          if (t != best) others.push_back(t);
        }
        std::stable_sort(others.begin(), others.end(),
                         [](const auto* a, const auto* b) { return a->qLift < b->qLift; });
        add("typical", *others[(others.size() - 1) / 2]);
      }
      if (!failed.empty()) {
        std::array<int, kOutcomeCount> counts{};
        for (const auto* t : failed) ++counts[static_cast<std::size_t>(t->outcome)];
        const auto most = static_cast<std::size_t>(std::max_element(counts.begin(), counts.end()) -
                                                   counts.begin());
        for (const auto* t : failed) {
          if (static_cast<std::size_t>(t->outcome) == most) {
            add("failure", *t);
            break;
          }
        }
      }
    }
  }
  return out;
}

std::string showcaseCaption(const Showcase& showcase) {
  const results::TrialRecord& t = showcase.trial;
  std::string text = showcase.role + ": " + t.sceneId + " " + t.graspId + " (rank " +
                     std::to_string(t.rank + 1) + "), " +
                     std::string(rwsim::trial::outcomeName(t.outcome));
  if (results::isSuccess(t.outcome)) {
    char q[40];
    std::snprintf(q, sizeof q, ", Q_lift %.3f", t.qLift);
    text += q;
    text += ", Q_GWS " + detail::fixed(t.qGws, 4) + ", Q_GWS,unit " + detail::fixed(t.qGwsUnit, 4);
  }
  return text;
}

}  // namespace visgrab::analysis
