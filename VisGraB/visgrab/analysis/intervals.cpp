#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "visgrab/analysis/attempts.hpp"
#include "visgrab/analysis/detail/scene_tally.hpp"

namespace visgrab::analysis::detail {

namespace {

/// Estimates that are ratios of sums over units (scenes): with unit u drawn c_u times, estimate
/// e is sum_u c_u x_u[num(e)] / sum_u c_u x_u[den(e)] (NaN when the denominator is 0). Each
/// unit's values are computed once, so a resample costs one pass over the units.
class RatioEstimates {
 public:
  explicit RatioEstimates(std::size_t features) : features_(features) {}

  /// Adds a unit's values (one per feature).
  void addUnit(const std::vector<double>& values) {
    values_.insert(values_.end(), values.begin(), values.end());
    ++units_;
  }

  /// Adds estimate sum(numerator) / sum(denominator); returns its index.
  std::size_t addRatio(std::size_t numerator, std::size_t denominator) {
    ratios_.emplace_back(numerator, denominator);
    return ratios_.size() - 1;
  }

  /// The percentile intervals of the estimates (undefined without units).
  std::vector<results::Interval> intervals(const results::BootstrapOptions& options) const {
    if (units_ == 0) return std::vector<results::Interval>(ratios_.size(), kUndefinedInterval);
    return results::bootstrapIntervals(
        units_, ratios_.size(),
        [this](const std::vector<int>& counts, std::vector<double>& out) { evaluate(counts, out); },
        options);
  }

 private:
  void evaluate(const std::vector<int>& counts, std::vector<double>& out) const {
    std::vector<double> sums(features_, 0.0);
    for (std::size_t u = 0; u < units_; ++u) {
      const int c = counts[u];
      if (c == 0) continue;  // never 0 * NaN
      const double* x = values_.data() + u * features_;
      for (std::size_t f = 0; f < features_; ++f) sums[f] += c * x[f];
    }
    for (std::size_t e = 0; e < ratios_.size(); ++e) {
      const double den = sums[ratios_[e].second];
      out[e] = den > 0.0 ? sums[ratios_[e].first] / den : kUndefinedValue;
    }
  }

  std::size_t features_;
  std::size_t units_ = 0;
  std::vector<double> values_;  // units x features, row by row
  std::vector<std::pair<std::size_t, std::size_t>> ratios_;
};

/// An interval, undefined where its estimate is.
results::Interval unless(double estimate, const results::Interval& interval) {
  return std::isnan(estimate) ? kUndefinedInterval : interval;
}

// The features of a scene in the group bootstrap.
enum GroupFeature : std::size_t {
  kOne,                                // 1: the scene
  kShares,                             // count_o / n per outcome (0 without grasps)
  kNoGrasp = kShares + kOutcomeCount,  // 1 without grasps
  kGrasps,                             // n
  kSuccesses,                          // k
  kQLift,                              // sum of Q_lift over the successes
  kQGws,                               // of Q_GWS (NaN where one lacks it)
  kQGwsUnit,                           // of Q_GWS,unit
  kHasSuccess,                         // 1 if k > 0
  kGa,                                 // (n + 1) / (k + 1) if k > 0, else 0
  kGaGiven,                            // rank of the first success if k > 0, else 0
  kCurve,                              // successWithinAttempts(n, k, 1..maxAttempts)
};

}  // namespace

results::BootstrapOptions bootstrapOptions(const AnalysisOptions& options, const std::string& key) {
  results::BootstrapOptions b;
  b.resamples = options.bootstrapResamples;
  b.level = options.ciLevel;
  b.seed = results::deriveSeed(options.bootstrapSeed, key);
  b.threads = 1;
  return b;
}

void addGroupIntervals(const std::vector<const SceneTally*>& scenes, int maxAttempts,
                       const results::BootstrapOptions& options, GroupResult& result) {
  const auto attempts = static_cast<std::size_t>(maxAttempts);
  RatioEstimates estimates(kCurve + attempts);
  for (const SceneTally* scene : scenes) {
    std::vector<double> x(kCurve + attempts, 0.0);
    const int n = static_cast<int>(scene->grasps.size());
    const int k = scene->successes;
    x[kOne] = 1.0;
    x[kNoGrasp] = n == 0 ? 1.0 : 0.0;
    x[kGrasps] = n;
    x[kSuccesses] = k;
    int firstGiven = 0;
    for (int i = 0; i < n; ++i) {
      const results::TrialRecord& t = *scene->grasps[static_cast<std::size_t>(i)];
      x[kShares + static_cast<std::size_t>(t.outcome)] += 1.0 / n;
      if (!results::isSuccess(t.outcome)) continue;
      x[kQLift] += t.qLift;
      x[kQGws] += t.qGws;
      x[kQGwsUnit] += t.qGwsUnit;
      if (firstGiven == 0) firstGiven = i + 1;
    }
    if (k > 0) {
      x[kHasSuccess] = 1.0;
      x[kGa] = expectedAttemptsToFirstSuccess(n, k);
      x[kGaGiven] = firstGiven;
    }
    for (std::size_t m = 0; m < attempts; ++m) {
      x[kCurve + m] = n > 0 ? successWithinAttempts(n, k, static_cast<int>(m) + 1) : 0.0;
    }
    estimates.addUnit(x);
  }
  // The estimates in the order of the ratios added.
  for (std::size_t o = 0; o < kOutcomeCount; ++o) estimates.addRatio(kShares + o, kOne);
  estimates.addRatio(kNoGrasp, kOne);
  estimates.addRatio(kSuccesses, kGrasps);
  estimates.addRatio(kQLift, kSuccesses);
  estimates.addRatio(kQGws, kSuccesses);
  estimates.addRatio(kQGwsUnit, kSuccesses);
  estimates.addRatio(kHasSuccess, kOne);
  estimates.addRatio(kGa, kHasSuccess);
  estimates.addRatio(kGaGiven, kHasSuccess);
  for (std::size_t m = 0; m < attempts; ++m) estimates.addRatio(kCurve + m, kOne);
  const std::vector<results::Interval> ci = estimates.intervals(options);

  std::size_t e = 0;
  Distribution& d = result.distribution;
  for (std::size_t o = 0; o < kOutcomeCount; ++o) d.shareCi[o] = unless(d.share[o], ci[e++]);
  d.noGraspShareCi = unless(d.noGraspShare, ci[e++]);
  result.success.rateCi = unless(result.success.rate, ci[e++]);
  QualityMeans& q = result.quality;
  q.meanQLiftCi = unless(q.meanQLift, ci[e++]);
  q.meanQGwsCi = unless(q.meanQGws, ci[e++]);
  q.meanQGwsUnitCi = unless(q.meanQGwsUnit, ci[e++]);
  FirstSuccess& f = result.firstSuccess;
  f.pCi = unless(f.p, ci[e++]);
  f.gaCi = unless(f.ga, ci[e++]);
  f.gaGivenOrderCi = unless(f.gaGivenOrder, ci[e++]);
  result.attempts.exactCi.clear();
  for (std::size_t m = 0; m < attempts; ++m) {
    const double exact =
        m < result.attempts.exact.size() ? result.attempts.exact[m] : kUndefinedValue;
    result.attempts.exactCi.push_back(unless(exact, ci[e++]));
  }
}

results::Interval percentInterval(const std::vector<const SceneTally*>& scenes,
                                  const results::BootstrapOptions& options) {
  RatioEstimates estimates(2);
  int grasps = 0;
  for (const SceneTally* scene : scenes) {
    const auto n = static_cast<double>(scene->grasps.size());
    grasps += static_cast<int>(scene->grasps.size());
    estimates.addUnit({n, 100.0 * scene->successes});
  }
  estimates.addRatio(1, 0);
  if (grasps == 0) return kUndefinedInterval;
  return estimates.intervals(options)[0];
}

RobustRate robustRate(const std::vector<const SceneTally*>& scenes,
                      const results::BootstrapOptions* options) {
  RobustRate r;
  RatioEstimates estimates(3);  // grasps, sum of P, borderline grasps
  double sumP = 0.0;
  int borderline = 0;
  for (const SceneTally* scene : scenes) {
    std::vector<double> x(3, 0.0);
    for (const GraspRepeats& g : scene->repeats) {
      const double p = static_cast<double>(g.held) / g.trials;
      const bool isBorderline = g.held > 0 && g.held < g.trials;
      x[0] += 1.0;
      x[1] += p;
      x[2] += isBorderline ? 1.0 : 0.0;
      ++r.grasps;
      r.trials += g.trials;
      sumP += p;
      borderline += isBorderline ? 1 : 0;
    }
    estimates.addUnit(x);
  }
  r.rate = r.grasps > 0 ? sumP / r.grasps : kUndefinedValue;
  r.borderlineShare = r.grasps > 0 ? static_cast<double>(borderline) / r.grasps : kUndefinedValue;
  if (options != nullptr && r.grasps > 0) {
    estimates.addRatio(1, 0);
    estimates.addRatio(2, 0);
    const std::vector<results::Interval> ci = estimates.intervals(*options);
    r.rateCi = ci[0];
    r.borderlineShareCi = ci[1];
  }
  return r;
}

}  // namespace visgrab::analysis::detail
