#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string_view>
#include <vector>

/// Interval estimates, tests and seeded random streams behind the benchmark's error bars
/// (docs/report.md, "Error bars"): the scene bootstrap, Wilson intervals of per-grasp success
/// probabilities, paired permutation tests, and the adaptive repeats' stopping rule. Pure
/// arithmetic: no file, no simulator.
namespace visgrab::results {

/// A two-sided interval; both ends NaN when it is undefined (no data).
struct Interval {
  /// Lower end.
  double low = 0.0;
  /// Upper end.
  double high = 0.0;
  /// True when both ends are numbers.
  bool defined() const;
};

/// A deterministic stream of random numbers (SplitMix64: Steele, Lea and Flood, OOPSLA 2014), so
/// that a seed gives the same numbers with every compiler and standard library (the standard
/// distributions are implementation-defined).
class SeededRandom {
 public:
  /// The stream of `seed`.
  explicit SeededRandom(std::uint64_t seed) : state_(seed) {}
  /// The next 64 random bits.
  std::uint64_t next();
  /// Uniform in [0, 1) (53 random bits).
  double uniform();
  /// Uniform integer in [0, n), without modulo bias. Precondition: n > 0.
  std::uint64_t below(std::uint64_t n);
  /// Standard normal (Marsaglia's polar method; the spare value is kept for the next call).
  double normal();

 private:
  std::uint64_t state_;
  double spare_ = 0.0;
  bool hasSpare_ = false;
};

/// A seed derived from `base` and a key, well mixed (SplitMix64's finaliser over both), so that
/// streams of different keys are independent and any worker can make the stream of any key.
std::uint64_t deriveSeed(std::uint64_t base, std::uint64_t key);
/// Same, for a text key (its FNV-1a 64-bit hash as the key).
std::uint64_t deriveSeed(std::uint64_t base, std::string_view key);

/// The standard normal quantile Phi^-1(p) (Wichura's AS 241, relative error about 1e-16).
/// @throws std::invalid_argument unless 0 < p < 1.
double normalQuantile(double p);

/// The Wilson score interval (Wilson 1927) of a binomial proportion: `successes` of `trials` at
/// confidence `level` (e.g. 0.95). Undefined (NaN) for trials == 0.
/// @throws std::invalid_argument unless 0 <= successes <= trials and 0 < level < 1.
Interval wilsonInterval(int successes, int trials, double level);

/// The naive ("Wald") binomial interval p +- z sqrt(p (1 - p) / n), clipped to [0, 1]: what one
/// gets by treating every grasp as independent (it under-covers on clustered data). Undefined for
/// trials == 0. @throws std::invalid_argument like wilsonInterval.
Interval waldInterval(int successes, int trials, double level);

/// The q-quantile of `values` with linear interpolation between order statistics (Hyndman and
/// Fan's type 7, numpy.quantile's default). NaN values are ignored; NaN when none is left.
/// @throws std::invalid_argument unless 0 <= q <= 1.
double quantile(std::vector<double> values, double q);

/// The percentile interval of bootstrap replicates: their (1 - level) / 2 and (1 + level) / 2
/// quantiles (quantile()). NaN replicates (a statistic undefined on a resample) are ignored.
/// @throws std::invalid_argument unless 0 < level < 1.
Interval percentileInterval(const std::vector<double>& replicates, double level);

/// Settings of a bootstrap.
struct BootstrapOptions {
  /// Resamples (replicates).
  int resamples = 2000;
  /// Confidence level of the intervals.
  double level = 0.95;
  /// Seed: resample b draws from SeededRandom(deriveSeed(seed, b)).
  std::uint64_t seed = 20120601;
  /// Worker threads (the intervals do not depend on the count).
  int threads = 1;
};

/// How often each of `units` units is drawn in resample `replicate` of a bootstrap (units draws
/// with replacement, from SeededRandom(deriveSeed(seed, replicate))): the counts add up to
/// `units`. Replicate b is the same whichever thread computes it.
std::vector<int> resampleCounts(std::size_t units, std::uint64_t seed, int replicate);

/// A statistic of a resample: gets each unit's count (resampleCounts) and writes one value per
/// estimate into `out` (already sized; NaN where undefined).
using ResampleStatistic =
    std::function<void(const std::vector<int>& counts, std::vector<double>& out)>;

/// The cluster ("scene") bootstrap of `estimates` statistics of `units` units: each resample
/// draws the units with replacement (resampleCounts) and evaluates `statistic`; returns the
/// percentile interval of each estimate. Zero units give undefined intervals (the statistic is
/// not called). The counts given to `statistic` are valid only during the call. Deterministic
/// whatever options.threads.
/// @throws std::invalid_argument for resamples < 1, a level outside (0, 1) or threads < 1; what
/// `statistic` throws.
std::vector<Interval> bootstrapIntervals(std::size_t units, std::size_t estimates,
                                         const ResampleStatistic& statistic,
                                         const BootstrapOptions& options);

/// One unit (scene) of a paired comparison: A's and B's successes and trials in it.
struct PairedUnit {
  /// A's successes.
  double successesA = 0.0;
  /// A's trials.
  double trialsA = 0.0;
  /// B's successes.
  double successesB = 0.0;
  /// B's trials.
  double trialsB = 0.0;
};

/// The pooled rate difference sum(successesA) / sum(trialsA) - sum(successesB) / sum(trialsB)
/// (NaN when either side has no trials).
double pooledDifference(const std::vector<PairedUnit>& units);

/// The paired bootstrap interval of pooledDifference over the units (resampled together, so both
/// sides see the same scenes). @throws std::invalid_argument for options bootstrapIntervals
/// rejects.
Interval pairedBootstrapInterval(const std::vector<PairedUnit>& units,
                                 const BootstrapOptions& options);

/// The two-sided paired permutation p-value of pooledDifference: permutation k swaps A and B
/// within each unit with probability 1/2 (SeededRandom(deriveSeed(seed, k))); p = (1 + #{k :
/// |d_k| >= |d| (1 - 1e-12)}) / (1 + permutations) (Phipson and Smyth 2010: never 0). NaN when the
/// difference is undefined. @throws std::invalid_argument for permutations < 1.
double pairedPermutationPValue(const std::vector<PairedUnit>& units, int permutations,
                               std::uint64_t seed);

/// The adaptive repeats' stopping rule: a grasp whose unperturbed trial (repeat 0) and first k
/// perturbed trials all agree (all held or all not held) is declared decided (P = 1 or P = 0), k
/// the smallest integer >= 2 with (1 - margin)^k <= alpha. Its stated error rate, one-sided, over
/// the perturbed trials (repeat 0 is no random draw, so it does not count): a grasp whose P over
/// perturbations is at most 1 - margin is declared always held with probability at most alpha
/// (P^k <= (1 - margin)^k), and likewise one whose P is at least margin declared never held.
/// Returns k.
int repeatsToDecide(double alpha, double margin);

/// The most repeats a run takes (`--repeats`, Python repeats=): a per-grasp P to within about
/// 0.01 (the 95 % Wilson half-width at P = 0.5 is 0.0098), finer than the simulator's own error
/// (a time step moves verdicts by several per cent: docs/report.md), and the run's trial count
/// stays far from the integers' limits.
inline constexpr int kMaxRepeats = 10000;

/// The fewest repeats with which the rule can stop a grasp early: repeat 0, the k agreeing
/// perturbed trials of repeatsToDecide, and one more (with fewer, every grasp runs them all).
/// What the runner, the command line and Python check `--repeats` against.
inline int minimumAdaptiveRepeats(double alpha, double margin) {
  return repeatsToDecide(alpha, margin) + 2;
}

}  // namespace visgrab::results
