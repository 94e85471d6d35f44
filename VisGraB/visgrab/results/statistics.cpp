#include "visgrab/results/statistics.hpp"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "rw/common/task_pool.hpp"

namespace visgrab::results {

namespace {

/// SplitMix64's output function (a bijective mix of 64 bits).
std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30U)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27U)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31U);
}

constexpr std::uint64_t kGoldenGamma = 0x9e3779b97f4a7c15ULL;

}  // namespace

bool Interval::defined() const { return !std::isnan(low) && !std::isnan(high); }

std::uint64_t SeededRandom::next() {
  state_ += kGoldenGamma;
  return mix64(state_);
}

double SeededRandom::uniform() { return static_cast<double>(next() >> 11U) * 0x1.0p-53; }

std::uint64_t SeededRandom::below(std::uint64_t n) {
  // Rejection of the top partial block keeps every value equally likely.
  const std::uint64_t limit = UINT64_MAX - UINT64_MAX % n;
  std::uint64_t x = next();
  while (x >= limit) x = next();
  return x % n;
}

double SeededRandom::normal() {
  if (hasSpare_) {
    hasSpare_ = false;
    return spare_;
  }
  double u = 0.0;
  double v = 0.0;
  double s = 0.0;
  do {
    u = 2.0 * uniform() - 1.0;
    v = 2.0 * uniform() - 1.0;
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double factor = std::sqrt(-2.0 * std::log(s) / s);
  spare_ = v * factor;
  hasSpare_ = true;
  return u * factor;
}

std::uint64_t deriveSeed(std::uint64_t base, std::uint64_t key) {
  return mix64(mix64(base + kGoldenGamma) ^ (key * kGoldenGamma + 0x632be59bd9b4e019ULL));
}

std::uint64_t deriveSeed(std::uint64_t base, std::string_view key) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;  // FNV-1a 64
  for (const char c : key) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 0x100000001b3ULL;
  }
  return deriveSeed(base, hash);
}

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// `what` followed by `value`, for an error message.
std::string statisticsMessage(const std::string& what, double value) {
  std::ostringstream text;
  text.precision(17);
  text << what << value;
  return text.str();
}

/// Throws unless 0 < level < 1 (NaN fails too).
void checkStatisticsLevel(const char* function, double level) {
  if (!(level > 0.0 && level < 1.0)) {
    throw std::invalid_argument(statisticsMessage(
        std::string(function) + ": confidence level must be in (0, 1), got ", level));
  }
}

/// c[0] + c[1] x + ... + c[7] x^7 (Horner).
double polynomial8(const std::array<double, 8>& c, double x) {
  double value = c[7];
  for (int i = 6; i >= 0; --i) value = value * x + c[static_cast<std::size_t>(i)];
  return value;
}

// AS 241 (Wichura 1988, PPND16): rational approximations in r = 0.180625 - q^2 for |q| <= 0.425,
// then in sqrt(-log(min(p, 1 - p))) - 1.6 up to 5, and - 5 beyond.
constexpr std::array<double, 8> kAs241A = {3.3871328727963666080e0, 1.3314166789178437745e2,
                                           1.9715909503065514427e3, 1.3731693765509461125e4,
                                           4.5921953931549871457e4, 6.7265770927008700853e4,
                                           3.3430575583588128105e4, 2.5090809287301226727e3};
constexpr std::array<double, 8> kAs241B = {1.0,
                                           4.2313330701600911252e1,
                                           6.8718700749205790830e2,
                                           5.3941960214247511077e3,
                                           2.1213794301586595867e4,
                                           3.9307895800092710610e4,
                                           2.8729085735721942674e4,
                                           5.2264952788528545610e3};
constexpr std::array<double, 8> kAs241C = {1.42343711074968357734e0,  4.63033784615654529590e0,
                                           5.76949722146069140550e0,  3.64784832476320460504e0,
                                           1.27045825245236838258e0,  2.41780725177450611770e-1,
                                           2.27238449892691845833e-2, 7.74545014278341407640e-4};
constexpr std::array<double, 8> kAs241D = {1.0,
                                           2.05319162663775882187e0,
                                           1.67638483018380384940e0,
                                           6.89767334985100004550e-1,
                                           1.48103976427480074590e-1,
                                           1.51986665636164571966e-2,
                                           5.47593808499534494600e-4,
                                           1.05075007164441684324e-9};
constexpr std::array<double, 8> kAs241E = {6.65790464350110377720e0,  5.46378491116411436990e0,
                                           1.78482653991729133580e0,  2.96560571828504891230e-1,
                                           2.65321895265761230930e-2, 1.24266094738807843860e-3,
                                           2.71155556874348757815e-5, 2.01033439929228813265e-7};
constexpr std::array<double, 8> kAs241F = {1.0,
                                           5.99832206555887937690e-1,
                                           1.36929880922735805310e-1,
                                           1.48753612908506148525e-2,
                                           7.86869131145613259100e-4,
                                           1.84631831751005468180e-5,
                                           1.42151175831644588870e-7,
                                           2.04426310338993978564e-15};

/// The two-sided critical value z = Phi^-1((1 + level) / 2).
double criticalValue(double level) { return normalQuantile(0.5 * (1.0 + level)); }

/// Throws unless 0 <= successes <= trials and 0 < level < 1.
void checkBinomial(const char* function, int successes, int trials, double level) {
  if (successes < 0 || successes > trials) {
    throw std::invalid_argument(std::string(function) + ": need 0 <= successes <= trials, got " +
                                std::to_string(successes) + " of " + std::to_string(trials));
  }
  checkStatisticsLevel(function, level);
}

/// The non-NaN values, sorted.
std::vector<double> sortedNumbers(std::vector<double> values) {
  values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return std::isnan(v); }),
               values.end());
  std::sort(values.begin(), values.end());
  return values;
}

/// Hyndman-Fan type 7 on sorted values without NaN (NaN when empty).
double sortedQuantile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return kNaN;
  const double h = static_cast<double>(sorted.size() - 1) * q;
  const double below = std::floor(h);
  const auto lo = static_cast<std::size_t>(below);
  const double fraction = h - below;
  if (fraction == 0.0 || lo + 1 >= sorted.size()) return sorted[lo];
  return sorted[lo] + fraction * (sorted[lo + 1] - sorted[lo]);
}

/// Throws unless 0 <= q <= 1.
void checkProbability(const char* function, double q) {
  if (!(q >= 0.0 && q <= 1.0)) {
    throw std::invalid_argument(
        statisticsMessage(std::string(function) + ": q must be in [0, 1], got ", q));
  }
}

/// Writes resample `replicate`'s counts of counts.size() units into `counts` (resampleCounts
/// without the allocation, so that a bootstrap worker reuses one buffer).
void drawResampleCounts(std::uint64_t seed, int replicate, std::vector<int>& counts) {
  std::fill(counts.begin(), counts.end(), 0);
  const std::uint64_t units = counts.size();
  if (units == 0) return;
  SeededRandom random(deriveSeed(seed, static_cast<std::uint64_t>(replicate)));
  int* const count = counts.data();
  for (std::uint64_t i = 0; i < units; ++i) ++count[random.below(units)];
}

/// pooledDifference with unit i counted weight(i) times.
template <typename Weight>
double weightedPooledDifference(const std::vector<PairedUnit>& units, Weight weight) {
  double successesA = 0.0;
  double trialsA = 0.0;
  double successesB = 0.0;
  double trialsB = 0.0;
  for (std::size_t i = 0; i < units.size(); ++i) {
    const double w = weight(i);
    successesA += w * units[i].successesA;
    trialsA += w * units[i].trialsA;
    successesB += w * units[i].successesB;
    trialsB += w * units[i].trialsB;
  }
  if (!(trialsA > 0.0) || !(trialsB > 0.0)) return kNaN;
  return successesA / trialsA - successesB / trialsB;
}

}  // namespace

double normalQuantile(double p) {
  if (!(p > 0.0 && p < 1.0)) {
    throw std::invalid_argument(statisticsMessage("normalQuantile: p must be in (0, 1), got ", p));
  }
  const double q = p - 0.5;
  if (std::abs(q) <= 0.425) {
    const double r = 0.180625 - q * q;
    return q * polynomial8(kAs241A, r) / polynomial8(kAs241B, r);
  }
  double r = std::sqrt(-std::log(q < 0.0 ? p : 1.0 - p));
  double value = 0.0;
  if (r <= 5.0) {
    r -= 1.6;
    value = polynomial8(kAs241C, r) / polynomial8(kAs241D, r);
  } else {
    r -= 5.0;
    value = polynomial8(kAs241E, r) / polynomial8(kAs241F, r);
  }
  return q < 0.0 ? -value : value;
}

Interval wilsonInterval(int successes, int trials, double level) {
  checkBinomial("wilsonInterval", successes, trials, level);
  if (trials == 0) return {kNaN, kNaN};
  const double n = trials;
  const double rate = successes / n;
  const double z = criticalValue(level);
  const double z2 = z * z;
  const double scale = 1.0 + z2 / n;
  const double centre = (rate + z2 / (2.0 * n)) / scale;
  const double half = z / scale * std::sqrt(rate * (1.0 - rate) / n + z2 / (4.0 * n * n));
  // The ends are exactly 0 at no success and 1 at all, which rounding would miss by an ulp.
  return {successes == 0 ? 0.0 : std::clamp(centre - half, 0.0, 1.0),
          successes == trials ? 1.0 : std::clamp(centre + half, 0.0, 1.0)};
}

Interval waldInterval(int successes, int trials, double level) {
  checkBinomial("waldInterval", successes, trials, level);
  if (trials == 0) return {kNaN, kNaN};
  const double n = trials;
  const double rate = successes / n;
  const double half = criticalValue(level) * std::sqrt(rate * (1.0 - rate) / n);
  return {std::clamp(rate - half, 0.0, 1.0), std::clamp(rate + half, 0.0, 1.0)};
}

double quantile(std::vector<double> values, double q) {
  checkProbability("quantile", q);
  return sortedQuantile(sortedNumbers(std::move(values)), q);
}

Interval percentileInterval(const std::vector<double>& replicates, double level) {
  checkStatisticsLevel("percentileInterval", level);
  const std::vector<double> sorted = sortedNumbers(replicates);
  return {sortedQuantile(sorted, 0.5 * (1.0 - level)), sortedQuantile(sorted, 0.5 * (1.0 + level))};
}

std::vector<int> resampleCounts(std::size_t units, std::uint64_t seed, int replicate) {
  std::vector<int> counts(units, 0);
  drawResampleCounts(seed, replicate, counts);
  return counts;
}

std::vector<Interval> bootstrapIntervals(std::size_t units, std::size_t estimates,
                                         const ResampleStatistic& statistic,
                                         const BootstrapOptions& options) {
  if (options.resamples < 1) {
    throw std::invalid_argument("bootstrapIntervals: need at least 1 resample, got " +
                                std::to_string(options.resamples));
  }
  checkStatisticsLevel("bootstrapIntervals", options.level);
  if (options.threads < 1) {
    throw std::invalid_argument("bootstrapIntervals: need at least 1 thread, got " +
                                std::to_string(options.threads));
  }
  if (units == 0) return std::vector<Interval>(estimates, Interval{kNaN, kNaN});
  const auto resamples = static_cast<std::size_t>(options.resamples);
  // replicates[e * resamples + b]: estimate e of resample b; each task writes its own slots.
  std::vector<double> replicates(estimates * resamples, kNaN);
  const rw::common::TaskPool pool(std::min(options.threads, options.resamples));
  struct WorkerBuffers {
    std::vector<int> counts;
    std::vector<double> out;
  };
  std::vector<WorkerBuffers> buffers(static_cast<std::size_t>(pool.threads()),
                                     {std::vector<int>(units), std::vector<double>(estimates)});
  pool.run(resamples, [&](std::size_t b, int worker) {
    WorkerBuffers& buffer = buffers[static_cast<std::size_t>(worker)];
    drawResampleCounts(options.seed, static_cast<int>(b), buffer.counts);
    std::fill(buffer.out.begin(), buffer.out.end(), kNaN);
    statistic(buffer.counts, buffer.out);
    for (std::size_t e = 0; e < estimates; ++e) replicates[e * resamples + b] = buffer.out[e];
  });
  std::vector<Interval> intervals;
  intervals.reserve(estimates);
  std::vector<double> column(resamples);
  for (std::size_t e = 0; e < estimates; ++e) {
    std::copy_n(replicates.begin() + static_cast<std::ptrdiff_t>(e * resamples), resamples,
                column.begin());
    intervals.push_back(percentileInterval(column, options.level));
  }
  return intervals;
}

double pooledDifference(const std::vector<PairedUnit>& units) {
  return weightedPooledDifference(units, [](std::size_t) { return 1.0; });
}

Interval pairedBootstrapInterval(const std::vector<PairedUnit>& units,
                                 const BootstrapOptions& options) {
  const ResampleStatistic difference = [&units](const std::vector<int>& counts,
                                                std::vector<double>& out) {
    out[0] = weightedPooledDifference(units, [&counts](std::size_t i) { return counts[i]; });
  };
  return bootstrapIntervals(units.size(), 1, difference, options).front();
}

double pairedPermutationPValue(const std::vector<PairedUnit>& units, int permutations,
                               std::uint64_t seed) {
  if (permutations < 1) {
    throw std::invalid_argument("pairedPermutationPValue: need at least 1 permutation, got " +
                                std::to_string(permutations));
  }
  const double observed = pooledDifference(units);
  if (std::isnan(observed)) return kNaN;
  // Differences equal to the observed one but for rounding count as ties (as large).
  const double threshold = std::abs(observed) * (1.0 - 1e-12);
  std::vector<PairedUnit> swapped(units.size());
  int asLarge = 0;
  for (int k = 0; k < permutations; ++k) {
    SeededRandom random(deriveSeed(seed, static_cast<std::uint64_t>(k)));
    for (std::size_t i = 0; i < units.size(); ++i) {
      const PairedUnit& u = units[i];
      const bool swap = (random.next() >> 63U) != 0;
      swapped[i] = swap ? PairedUnit{u.successesB, u.trialsB, u.successesA, u.trialsA} : u;
    }
    if (std::abs(pooledDifference(swapped)) >= threshold) ++asLarge;
  }
  return (1.0 + asLarge) / (1.0 + permutations);
}

int repeatsToDecide(double alpha, double margin) {
  if (!(alpha > 0.0 && alpha < 1.0)) {
    throw std::invalid_argument(
        statisticsMessage("repeatsToDecide: alpha must be in (0, 1), got ", alpha));
  }
  if (!(margin > 0.0 && margin < 1.0)) {
    throw std::invalid_argument(
        statisticsMessage("repeatsToDecide: margin must be in (0, 1), got ", margin));
  }
  // First guess from logarithms (log1p keeps small margins exact), then the exact rule on powers.
  const double guess = std::ceil(std::log(alpha) / std::log1p(-margin));
  if (!(guess <= static_cast<double>(INT_MAX - 1))) {
    throw std::invalid_argument(
        statisticsMessage("repeatsToDecide: more than INT_MAX repeats for margin ", margin));
  }
  int k = std::max(2, static_cast<int>(guess));
  const auto enough = [&](int n) { return std::pow(1.0 - margin, n) <= alpha; };
  while (k > 2 && enough(k - 1)) --k;
  while (!enough(k)) ++k;
  return k;
}

}  // namespace visgrab::results
