#include "visgrab/results/statistics.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace visgrab::results {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---------------------------------------------------------------------------------------------
// SeededRandom and deriveSeed

TEST(SeededRandomTest, MatchesSplitMix64Reference) {
  // Reference outputs from an independent SplitMix64 written in Python 3 (state += 0x9e37...7c15;
  // z = (z ^ z >> 30) * 0xbf58...e5b9; z = (z ^ z >> 27) * 0x94d0...11eb; z ^ z >> 31, all mod
  // 2^64), run in the shell.
  SeededRandom zero(0);
  EXPECT_EQ(zero.next(), 0xe220a8397b1dcdafULL);
  EXPECT_EQ(zero.next(), 0x6e789e6aa1b965f4ULL);
  EXPECT_EQ(zero.next(), 0x06c45d188009454fULL);
  SeededRandom other(1234567);
  EXPECT_EQ(other.next(), 0x599ed017fb08fc85ULL);
  EXPECT_EQ(other.next(), 0x2c73f08458540fa5ULL);
  EXPECT_EQ(other.next(), 0x883ebce5a3f27c77ULL);
}

TEST(SeededRandomTest, UniformIsTheTop53BitsInUnitInterval) {
  // (0xe220a8397b1dcdaf >> 11) * 2^-53 in Python.
  SeededRandom first(0);
  EXPECT_DOUBLE_EQ(first.uniform(), 0.8833108082136426);

  SeededRandom random(7);
  const int draws = 100000;
  double sum = 0.0;
  for (int i = 0; i < draws; ++i) {
    const double u = random.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
  }
  // The mean's standard deviation is sqrt(1/12 / 1e5) = 0.00091: 0.005 is 5.5 of them.
  EXPECT_NEAR(sum / draws, 0.5, 0.005);
}

TEST(SeededRandomTest, BelowIsInRangeAndUniform) {
  SeededRandom random(11);
  const int n = 7;
  const int draws = 70000;
  std::vector<int> counts(n, 0);
  for (int i = 0; i < draws; ++i) {
    const std::uint64_t x = random.below(n);
    ASSERT_LT(x, static_cast<std::uint64_t>(n));
    ++counts[x];
  }
  // Each count is Binomial(70000, 1/7): mean 10000, standard deviation 92.6; 500 is 5.4 of them.
  for (const int count : counts) EXPECT_NEAR(count, 10000.0, 500.0);

  EXPECT_EQ(random.below(1), 0U);
  // A bound just above 2^63 rejects almost half of the raw values: still always in range.
  const std::uint64_t big = (1ULL << 63U) + 1;
  for (int i = 0; i < 1000; ++i) ASSERT_LT(random.below(big), big);
}

TEST(SeededRandomTest, NormalHasStandardMoments) {
  SeededRandom random(2012);
  const int draws = 100000;
  double sum = 0.0;
  double squares = 0.0;
  int inside = 0;
  for (int i = 0; i < draws; ++i) {
    const double x = random.normal();
    sum += x;
    squares += x * x;
    if (std::abs(x) < 1.959963984540054) ++inside;
  }
  const double mean = sum / draws;
  const double variance = squares / draws - mean * mean;
  // Standard deviations on 1e5 draws: mean 0.0032, variance sqrt(2/1e5) = 0.0045, the 95 %
  // fraction sqrt(0.95 * 0.05 / 1e5) = 0.00069; the bounds are 4.5 to 6 of them.
  EXPECT_NEAR(mean, 0.0, 0.015);
  EXPECT_NEAR(variance, 1.0, 0.025);
  EXPECT_NEAR(static_cast<double>(inside) / draws, 0.95, 0.004);
}

TEST(DeriveSeedTest, IsDeterministicAndDiffersByKey) {
  EXPECT_EQ(deriveSeed(5, 17), deriveSeed(5, 17));
  EXPECT_NE(deriveSeed(5, 17), deriveSeed(5, 18));
  EXPECT_NE(deriveSeed(5, 17), deriveSeed(6, 17));
  std::set<std::uint64_t> seeds;
  for (std::uint64_t key = 0; key < 1000; ++key) seeds.insert(deriveSeed(20120601, key));
  EXPECT_EQ(seeds.size(), 1000U);
  // Neighbouring keys give unrelated streams: their first outputs differ in about 32 bits.
  SeededRandom a(deriveSeed(1, 0));
  SeededRandom b(deriveSeed(1, 1));
  const int differing = std::popcount(a.next() ^ b.next());
  EXPECT_GT(differing, 12);
  EXPECT_LT(differing, 52);
}

TEST(DeriveSeedTest, TextKeyIsItsFnv1aHash) {
  // FNV-1a 64 of "a" is the published 0xaf63dc4c8601ec8c; of "scene_017" from Python.
  EXPECT_EQ(deriveSeed(9, "a"), deriveSeed(9, 0xaf63dc4c8601ec8cULL));
  EXPECT_EQ(deriveSeed(9, "scene_017"), deriveSeed(9, 0x6b6f7c4de7f85d00ULL));
  EXPECT_NE(deriveSeed(9, "scene_017"), deriveSeed(9, "scene_018"));
}

// ---------------------------------------------------------------------------------------------
// normalQuantile

TEST(NormalQuantileTest, MatchesHighPrecisionValues) {
  // Exact quantiles from mpmath at 50 digits (findroot of ncdf(x) - p), rounded to 17 digits;
  // statistics.NormalDist().inv_cdf agrees to the last digit or two.
  struct Case {
    double p;
    double x;
  };
  const Case cases[] = {
      {0.975, 1.9599639845400539},          {0.025, -1.9599639845400542},
      {0.999, 3.0902323061678133},          {0.3, -0.52440051270804082},
      {0.8, 0.84162123357291436},           {1e-10, -6.3613409024040562},
      {0.999999999999, 7.0344869100478352}, {1e-300, -37.047096299361199},
  };
  for (const Case& c : cases) {
    EXPECT_NEAR(normalQuantile(c.p), c.x, 1e-15 * std::abs(c.x)) << "p = " << c.p;
  }
  EXPECT_EQ(normalQuantile(0.5), 0.0);
  EXPECT_NEAR(normalQuantile(0.1), -normalQuantile(0.9), 1e-15);
}

TEST(NormalQuantileTest, RejectsOutsideOpenUnitInterval) {
  for (const double p : {0.0, 1.0, -0.1, 1.5, kNaN}) {
    EXPECT_THROW(normalQuantile(p), std::invalid_argument) << "p = " << p;
  }
}

// ---------------------------------------------------------------------------------------------
// Binomial intervals

struct BinomialCase {
  int successes;
  int trials;
  double level;
  double low;
  double high;
};

TEST(WilsonIntervalTest, MatchesWorkedValues) {
  // (p + z^2/2n -+ z sqrt(p(1-p)/n + z^2/4n^2)) / (1 + z^2/n) in mpmath at 50 digits; 0/10 has
  // high end z^2/(n + z^2) = 3.8415/13.8415 and 10/10 low end n/(n + z^2), as by hand.
  const BinomialCase cases[] = {
      {9, 10, 0.95, 0.59584997320476157, 0.98212378690492709},
      {0, 10, 0.95, 0.0, 0.27753279986288917},
      {10, 10, 0.95, 0.72246720013711083, 1.0},
      {45, 50, 0.95, 0.78639768562520346, 0.95652423506810958},
      {3, 7, 0.9, 0.18644319036395604, 0.71052290898640712},
  };
  for (const BinomialCase& c : cases) {
    const Interval i = wilsonInterval(c.successes, c.trials, c.level);
    EXPECT_NEAR(i.low, c.low, 1e-14) << c.successes << "/" << c.trials;
    EXPECT_NEAR(i.high, c.high, 1e-14) << c.successes << "/" << c.trials;
    EXPECT_TRUE(i.defined());
  }
  EXPECT_EQ(wilsonInterval(0, 10, 0.95).low, 0.0);
  EXPECT_EQ(wilsonInterval(10, 10, 0.95).high, 1.0);
}

TEST(WaldIntervalTest, MatchesWorkedValues) {
  // p -+ z sqrt(p(1-p)/n) clipped to [0, 1], mpmath at 50 digits; 9/10: 0.9 -+ 1.96 * 0.0949.
  const BinomialCase cases[] = {
      {9, 10, 0.95, 0.71406149030863155, 1.0},
      {0, 10, 0.95, 0.0, 0.0},
      {10, 10, 0.95, 1.0, 1.0},
      {45, 50, 0.95, 0.81684577053901934, 0.98315422946098066},
      {3, 7, 0.9, 0.12091158152539685, 0.73623127561746029},
  };
  for (const BinomialCase& c : cases) {
    const Interval i = waldInterval(c.successes, c.trials, c.level);
    EXPECT_NEAR(i.low, c.low, 1e-14) << c.successes << "/" << c.trials;
    EXPECT_NEAR(i.high, c.high, 1e-14) << c.successes << "/" << c.trials;
  }
}

TEST(BinomialIntervalTest, NoTrialsIsUndefined) {
  for (const Interval& i : {wilsonInterval(0, 0, 0.95), waldInterval(0, 0, 0.95)}) {
    EXPECT_TRUE(std::isnan(i.low));
    EXPECT_TRUE(std::isnan(i.high));
    EXPECT_FALSE(i.defined());
  }
}

TEST(BinomialIntervalTest, RejectsBadArguments) {
  for (const auto& interval : {&wilsonInterval, &waldInterval}) {
    EXPECT_THROW(interval(-1, 10, 0.95), std::invalid_argument);
    EXPECT_THROW(interval(11, 10, 0.95), std::invalid_argument);
    EXPECT_THROW(interval(0, -1, 0.95), std::invalid_argument);
    EXPECT_THROW(interval(5, 10, 0.0), std::invalid_argument);
    EXPECT_THROW(interval(5, 10, 1.0), std::invalid_argument);
    EXPECT_THROW(interval(5, 10, kNaN), std::invalid_argument);
  }
}

// ---------------------------------------------------------------------------------------------
// Quantiles

TEST(QuantileTest, MatchesNumpy) {
  // numpy 1.24.2: numpy.quantile([3.5, -1, 7.25, 2, 10, 0.5, 4], q) (default method "linear").
  const std::vector<double> values = {3.5, -1.0, 7.25, 2.0, 10.0, 0.5, 4.0};
  const std::pair<double, double> cases[] = {
      {0.0, -1.0},
      {0.025, -0.7749999999999999},
      {0.1, -0.09999999999999987},
      {0.25, 1.25},
      {0.5, 3.5},
      {0.9, 8.350000000000001},
      {0.975, 9.5875},
      {1.0, 10.0},
  };
  for (const auto& [q, expected] : cases) EXPECT_NEAR(quantile(values, q), expected, 1e-12) << q;
  EXPECT_EQ(quantile({42.0}, 0.3), 42.0);
}

TEST(QuantileTest, IgnoresNaN) {
  // numpy.nanquantile([1, nan, 4, 2, nan], q).
  const std::vector<double> values = {1.0, kNaN, 4.0, 2.0, kNaN};
  EXPECT_DOUBLE_EQ(quantile(values, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(quantile(values, 0.3), 1.6);
  EXPECT_DOUBLE_EQ(quantile(values, 0.5), 2.0);
  EXPECT_DOUBLE_EQ(quantile(values, 1.0), 4.0);
  EXPECT_TRUE(std::isnan(quantile({kNaN, kNaN}, 0.5)));
  EXPECT_TRUE(std::isnan(quantile({}, 0.5)));
}

TEST(QuantileTest, RejectsQOutsideUnitInterval) {
  EXPECT_THROW(quantile({1.0, 2.0}, -0.01), std::invalid_argument);
  EXPECT_THROW(quantile({1.0, 2.0}, 1.01), std::invalid_argument);
  EXPECT_THROW(quantile({1.0, 2.0}, kNaN), std::invalid_argument);
}

TEST(PercentileIntervalTest, MatchesNumpy) {
  // r = numpy.arange(1, 21)**2 / 7: numpy.quantile(r, [0.025, 0.975]) and [0.1, 0.9].
  std::vector<double> replicates;
  for (int k = 20; k >= 1; --k) replicates.push_back(k * k / 7.0);  // order must not matter
  const Interval i95 = percentileInterval(replicates, 0.95);
  EXPECT_NEAR(i95.low, 0.3464285714285714, 1e-12);
  EXPECT_NEAR(i95.high, 54.49642857142857, 1e-12);
  const Interval i80 = percentileInterval(replicates, 0.8);
  EXPECT_NEAR(i80.low, 1.2142857142857144, 1e-12);
  EXPECT_NEAR(i80.high, 46.814285714285724, 1e-12);

  replicates.push_back(kNaN);
  replicates.insert(replicates.begin(), kNaN);
  const Interval withNaN = percentileInterval(replicates, 0.95);
  EXPECT_DOUBLE_EQ(withNaN.low, i95.low);
  EXPECT_DOUBLE_EQ(withNaN.high, i95.high);

  EXPECT_FALSE(percentileInterval({kNaN, kNaN}, 0.95).defined());
  EXPECT_THROW(percentileInterval(replicates, 0.0), std::invalid_argument);
  EXPECT_THROW(percentileInterval(replicates, 1.0), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// Scene bootstrap

/// Per-unit successes and trials; the statistic is their pooled rate over a resample.
struct RateUnits {
  std::vector<double> successes;
  std::vector<double> trials;
};

/// The pooled rate sum(c_i s_i) / sum(c_i n_i) of a resample (through data(): the coverage test
/// calls it two million times, also in the unoptimised sanitizer build).
ResampleStatistic pooledRate(const RateUnits& units) {
  return [&units](const std::vector<int>& counts, std::vector<double>& out) {
    const int* const c = counts.data();
    const double* const successes = units.successes.data();
    const double* const trials = units.trials.data();
    double s = 0.0;
    double n = 0.0;
    for (std::size_t i = 0; i < counts.size(); ++i) {
      s += c[i] * successes[i];
      n += c[i] * trials[i];
    }
    out[0] = n > 0.0 ? s / n : kNaN;
  };
}

TEST(ResampleCountsTest, DrawsUnitsWithReplacement) {
  EXPECT_TRUE(resampleCounts(0, 1, 0).empty());
  const std::size_t units = 50;
  std::vector<double> total(units, 0.0);
  const int replicates = 2000;
  for (int b = 0; b < replicates; ++b) {
    const std::vector<int> counts = resampleCounts(units, 99, b);
    ASSERT_EQ(counts.size(), units);
    int sum = 0;
    for (std::size_t i = 0; i < units; ++i) {
      ASSERT_GE(counts[i], 0);
      sum += counts[i];
      total[i] += counts[i];
    }
    ASSERT_EQ(sum, static_cast<int>(units));
  }
  EXPECT_EQ(resampleCounts(units, 99, 5), resampleCounts(units, 99, 5));
  EXPECT_NE(resampleCounts(units, 99, 5), resampleCounts(units, 99, 6));
  EXPECT_NE(resampleCounts(units, 99, 5), resampleCounts(units, 100, 5));
  // A unit's count is Binomial(50, 1/50): mean 1, variance 0.98; its average over 2000
  // replicates has standard deviation 0.022, and 0.12 is 5.4 of them.
  for (const double t : total) EXPECT_NEAR(t / replicates, 1.0, 0.12);
}

TEST(BootstrapIntervalsTest, SameIntervalsForAnyThreadCount) {
  RateUnits units;
  SeededRandom random(3);
  for (int i = 0; i < 30; ++i) {
    units.trials.push_back(static_cast<double>(1 + random.below(20)));
    units.successes.push_back(std::floor(random.uniform() * (units.trials.back() + 1)));
  }
  const ResampleStatistic rate = pooledRate(units);
  // Two estimates: the pooled rate and the largest drawn unit's trials.
  const ResampleStatistic both = [&](const std::vector<int>& counts, std::vector<double>& out) {
    std::vector<double> one(1);
    rate(counts, one);
    out[0] = one[0];
    out[1] = 0.0;
    for (std::size_t i = 0; i < counts.size(); ++i) {
      if (counts[i] > 0) out[1] = std::max(out[1], units.trials[i]);
    }
  };
  BootstrapOptions options;
  options.resamples = 500;
  options.threads = 1;
  const std::vector<Interval> serial = bootstrapIntervals(30, 2, both, options);
  options.threads = 3;
  const std::vector<Interval> parallel = bootstrapIntervals(30, 2, both, options);
  ASSERT_EQ(serial.size(), 2U);
  ASSERT_EQ(parallel.size(), 2U);
  for (std::size_t e = 0; e < 2; ++e) {
    EXPECT_EQ(serial[e].low, parallel[e].low);
    EXPECT_EQ(serial[e].high, parallel[e].high);
    EXPECT_LT(serial[e].low, serial[e].high);
  }
}

TEST(BootstrapIntervalsTest, ReplicateBUsesResampleCountsOfB) {
  RateUnits units{{1, 0, 4, 2, 5, 3, 0, 1}, {2, 3, 5, 2, 6, 7, 1, 4}};
  BootstrapOptions options;
  options.resamples = 301;
  options.level = 0.9;
  options.seed = 777;
  options.threads = 2;
  const Interval got = bootstrapIntervals(8, 1, pooledRate(units), options).front();
  // The same replicates made here from resampleCounts, one at a time.
  std::vector<double> replicates;
  for (int b = 0; b < options.resamples; ++b) {
    const std::vector<int> counts = resampleCounts(8, options.seed, b);
    double s = 0.0;
    double n = 0.0;
    for (std::size_t i = 0; i < 8; ++i) {
      s += counts[i] * units.successes[i];
      n += counts[i] * units.trials[i];
    }
    replicates.push_back(s / n);
  }
  const Interval expected = percentileInterval(replicates, 0.9);
  EXPECT_DOUBLE_EQ(got.low, expected.low);
  EXPECT_DOUBLE_EQ(got.high, expected.high);
}

TEST(BootstrapIntervalsTest, IdenticalUnitsGiveTheirValue) {
  // Every unit 3 of 5: every resample's pooled rate is 3m / 5m = 0.6.
  const RateUnits units{std::vector<double>(10, 3.0), std::vector<double>(10, 5.0)};
  const Interval i = bootstrapIntervals(10, 1, pooledRate(units), {}).front();
  EXPECT_DOUBLE_EQ(i.low, 0.6);
  EXPECT_DOUBLE_EQ(i.high, 0.6);
}

TEST(BootstrapIntervalsTest, TwoUnitsSpanBothValues) {
  // Units of rate 0 and 1 with one trial each: a resample's rate is 0, 1/2 or 1 with probability
  // 1/4, 1/2, 1/4, so the 2.5 % and 97.5 % quantiles of 2000 replicates are 0 and 1 unless fewer
  // than 50 of the 2000 are 0 (or 1): probability below 1e-100.
  const RateUnits units{{0.0, 1.0}, {1.0, 1.0}};
  const Interval i = bootstrapIntervals(2, 1, pooledRate(units), {}).front();
  EXPECT_EQ(i.low, 0.0);
  EXPECT_EQ(i.high, 1.0);
}

TEST(BootstrapIntervalsTest, UndefinedStatisticsAndNoUnits) {
  const ResampleStatistic partly = [](const std::vector<int>& counts, std::vector<double>& out) {
    out[0] = counts[0];  // out[1] left as it came: NaN
  };
  const std::vector<Interval> intervals = bootstrapIntervals(4, 2, partly, {});
  EXPECT_TRUE(intervals[0].defined());
  EXPECT_FALSE(intervals[1].defined());

  int calls = 0;
  const ResampleStatistic counting = [&calls](const std::vector<int>&, std::vector<double>& out) {
    ++calls;
    out[0] = 1.0;
  };
  const std::vector<Interval> none = bootstrapIntervals(0, 3, counting, {});
  ASSERT_EQ(none.size(), 3U);
  for (const Interval& i : none) EXPECT_FALSE(i.defined());
  EXPECT_EQ(calls, 0);
}

TEST(BootstrapIntervalsTest, RejectsBadOptionsAndPassesOnStatisticErrors) {
  const RateUnits units{{1.0, 2.0}, {2.0, 2.0}};
  const ResampleStatistic rate = pooledRate(units);
  BootstrapOptions bad;
  bad.resamples = 0;
  EXPECT_THROW(bootstrapIntervals(2, 1, rate, bad), std::invalid_argument);
  for (const double level : {0.0, 1.0, -0.5, kNaN}) {
    bad = {};
    bad.level = level;
    EXPECT_THROW(bootstrapIntervals(2, 1, rate, bad), std::invalid_argument) << level;
  }
  bad = {};
  bad.threads = 0;
  EXPECT_THROW(bootstrapIntervals(2, 1, rate, bad), std::invalid_argument);

  const ResampleStatistic failing = [](const std::vector<int>&, std::vector<double>&) {
    throw std::runtime_error("statistic failed");
  };
  BootstrapOptions two;
  two.threads = 2;
  EXPECT_THROW(bootstrapIntervals(2, 1, failing, two), std::runtime_error);
}

/// A Gamma(shape, 1) variate for shape >= 1 (Marsaglia and Tsang, ACM TOMS 26(3), 2000).
double gammaVariate(SeededRandom& random, double shape) {
  const double d = shape - 1.0 / 3.0;
  const double c = 1.0 / std::sqrt(9.0 * d);
  for (;;) {
    double x = 0.0;
    double v = 0.0;
    do {
      x = random.normal();
      v = 1.0 + c * x;
    } while (v <= 0.0);
    v = v * v * v;
    const double u = random.uniform();
    if (u < 1.0 - 0.0331 * x * x * x * x) return d * v;
    if (std::log(u) < 0.5 * x * x + d * (1.0 - v + std::log(v))) return d * v;
  }
}

/// A Beta(a, b) variate as X / (X + Y), X ~ Gamma(a), Y ~ Gamma(b).
double betaVariate(SeededRandom& random, double a, double b) {
  const double x = gammaVariate(random, a);
  return x / (x + gammaVariate(random, b));
}

// Scene success rates ~ Beta(3, 2): mean 0.6, variance ab / ((a+b)^2 (a+b+1)) = 0.04, so the
// grasps of one scene are correlated (intra-class correlation 1 / (a+b+1) = 1/6).
constexpr double kBetaA = 3.0;
constexpr double kBetaB = 2.0;
constexpr double kTrueRate = kBetaA / (kBetaA + kBetaB);

TEST(ClusteredCoverageTest, BetaSamplerHasItsMoments) {
  SeededRandom random(4);
  const int draws = 20000;
  double sum = 0.0;
  double squares = 0.0;
  for (int i = 0; i < draws; ++i) {
    const double x = betaVariate(random, kBetaA, kBetaB);
    ASSERT_GT(x, 0.0);
    ASSERT_LT(x, 1.0);
    sum += x;
    squares += x * x;
  }
  const double mean = sum / draws;
  // Standard deviations on 2e4 draws: mean 0.2 / sqrt(2e4) = 0.0014, variance about 0.0003.
  EXPECT_NEAR(mean, 0.6, 0.007);
  EXPECT_NEAR(squares / draws - mean * mean, 0.04, 0.002);
}

TEST(ClusteredCoverageTest, SceneBootstrapCoversTheTruthAndWaldDoesNot) {
  // 1,000 synthetic benchmarks of 100 scenes each: a scene's success rate is drawn from Beta(3, 2)
  // and its grasp count uniformly from 5..40 independently of it, so the pooled rate
  // sum(s_i) / sum(n_i) estimates exactly the Beta mean 0.6. The scene bootstrap of the pooled
  // rate (2,000 resamples, 95 %) must cover 0.6 in about 95 % of the benchmarks; the naive Wald
  // interval on all grasps ignores the clustering (design effect about 1 + (22.5 - 1) / 6 = 4.6)
  // and covers far less often.
  const int datasets = 1000;
  const std::size_t scenes = 100;
  int bootstrapCovers = 0;
  int waldCovers = 0;
  for (int d = 0; d < datasets; ++d) {
    SeededRandom random(deriveSeed(20240601, static_cast<std::uint64_t>(d)));
    RateUnits units;
    int successes = 0;
    int trials = 0;
    for (std::size_t i = 0; i < scenes; ++i) {
      const int n = 5 + static_cast<int>(random.below(36));
      const double rate = betaVariate(random, kBetaA, kBetaB);
      int s = 0;
      for (int g = 0; g < n; ++g) s += random.uniform() < rate ? 1 : 0;
      units.successes.push_back(s);
      units.trials.push_back(n);
      successes += s;
      trials += n;
    }
    BootstrapOptions options;
    options.resamples = 2000;
    options.level = 0.95;
    options.seed = deriveSeed(19700101, static_cast<std::uint64_t>(d));
    options.threads = 2;
    const Interval boot = bootstrapIntervals(scenes, 1, pooledRate(units), options).front();
    const Interval wald = waldInterval(successes, trials, 0.95);
    if (boot.low <= kTrueRate && kTrueRate <= boot.high) ++bootstrapCovers;
    if (wald.low <= kTrueRate && kTrueRate <= wald.high) ++waldCovers;
  }
  const double bootstrapCoverage = static_cast<double>(bootstrapCovers) / datasets;
  const double waldCoverage = static_cast<double>(waldCovers) / datasets;
  std::cout << "coverage of the true rate 0.6 over " << datasets
            << " clustered data sets: scene bootstrap " << bootstrapCoverage << ", Wald "
            << waldCoverage << "\n";
  RecordProperty("bootstrap_coverage", std::to_string(bootstrapCoverage));
  RecordProperty("wald_coverage", std::to_string(waldCoverage));
  // A coverage estimate from 1,000 sets has standard deviation sqrt(0.95 * 0.05 / 1000) = 0.007:
  // [0.93, 0.97] is about 3 of them either side of 0.95.
  EXPECT_GE(bootstrapCoverage, 0.93);
  EXPECT_LE(bootstrapCoverage, 0.97);
  EXPECT_LT(waldCoverage, 0.85);
}

// ---------------------------------------------------------------------------------------------
// Paired comparisons

TEST(PooledDifferenceTest, HandMadePair) {
  // A: 3 + 5 + 0 = 8 of 4 + 6 + 2 = 12; B: 1 + 2 + 1 = 4 of 12: 2/3 - 1/3 = 1/3.
  const std::vector<PairedUnit> units = {{3, 4, 1, 4}, {5, 6, 2, 6}, {0, 2, 1, 2}};
  EXPECT_NEAR(pooledDifference(units), 1.0 / 3.0, 1e-15);
  EXPECT_TRUE(std::isnan(pooledDifference({})));
  EXPECT_TRUE(std::isnan(pooledDifference({{1, 2, 0, 0}})));
  EXPECT_TRUE(std::isnan(pooledDifference({{0, 0, 1, 2}})));
}

/// Twelve scenes where A does better than B by about 0.25.
std::vector<PairedUnit> betterA() {
  std::vector<PairedUnit> units;
  SeededRandom random(8);
  for (int i = 0; i < 12; ++i) {
    const auto n = static_cast<double>(6 + random.below(10));
    const double base = random.uniform() * 0.6;
    units.push_back({std::round(n * (base + 0.3)), n, std::round(n * base), n});
  }
  return units;
}

TEST(PairedBootstrapIntervalTest, ContainsTheDifferenceAndIsDeterministic) {
  const std::vector<PairedUnit> units = betterA();
  const double d = pooledDifference(units);
  BootstrapOptions options;
  options.threads = 1;
  const Interval i = pairedBootstrapInterval(units, options);
  EXPECT_LT(i.low, d);
  EXPECT_GT(i.high, d);
  EXPECT_GT(i.low, 0.0);  // every scene favours A
  options.threads = 2;
  const Interval again = pairedBootstrapInterval(units, options);
  EXPECT_EQ(again.low, i.low);
  EXPECT_EQ(again.high, i.high);

  // The same replicates made here: resampleCounts as weights of both sides' sums.
  std::vector<double> replicates;
  for (int b = 0; b < options.resamples; ++b) {
    const std::vector<int> counts = resampleCounts(units.size(), options.seed, b);
    double sA = 0.0;
    double nA = 0.0;
    double sB = 0.0;
    double nB = 0.0;
    for (std::size_t u = 0; u < units.size(); ++u) {
      sA += counts[u] * units[u].successesA;
      nA += counts[u] * units[u].trialsA;
      sB += counts[u] * units[u].successesB;
      nB += counts[u] * units[u].trialsB;
    }
    replicates.push_back(sA / nA - sB / nB);
  }
  const Interval expected = percentileInterval(replicates, options.level);
  EXPECT_NEAR(i.low, expected.low, 1e-12);
  EXPECT_NEAR(i.high, expected.high, 1e-12);

  EXPECT_FALSE(pairedBootstrapInterval({}, options).defined());
}

TEST(PairedPermutationPValueTest, IdenticalSidesGiveOne) {
  const std::vector<PairedUnit> units = {{3, 5, 3, 5}, {1, 4, 1, 4}, {6, 6, 6, 6}};
  EXPECT_DOUBLE_EQ(pairedPermutationPValue(units, 500, 1), 1.0);
}

/// The exact two-sided permutation p-value over all 2^n swaps, compared in integers:
/// |sA/nA - sB/nB| >= |d| as |sA nB - sB nA| * N >= D * nA nB, with d = D / N.
double exactPermutationPValue(const std::vector<PairedUnit>& units) {
  using Int = long long;
  const auto difference = [&](unsigned mask, Int& numerator, Int& denominator) {
    Int sA = 0;
    Int nA = 0;
    Int sB = 0;
    Int nB = 0;
    for (std::size_t i = 0; i < units.size(); ++i) {
      const PairedUnit& u = units[i];
      const bool swap = ((mask >> i) & 1U) != 0;
      sA += static_cast<Int>(swap ? u.successesB : u.successesA);
      nA += static_cast<Int>(swap ? u.trialsB : u.trialsA);
      sB += static_cast<Int>(swap ? u.successesA : u.successesB);
      nB += static_cast<Int>(swap ? u.trialsA : u.trialsB);
    }
    numerator = std::llabs(sA * nB - sB * nA);
    denominator = nA * nB;
  };
  Int observedNumerator = 0;
  Int observedDenominator = 0;
  difference(0, observedNumerator, observedDenominator);
  const unsigned masks = 1U << units.size();
  unsigned asLarge = 0;
  for (unsigned mask = 0; mask < masks; ++mask) {
    Int numerator = 0;
    Int denominator = 0;
    difference(mask, numerator, denominator);
    if (numerator * observedDenominator >= observedNumerator * denominator) ++asLarge;
  }
  return static_cast<double>(asLarge) / masks;
}

TEST(PairedPermutationPValueTest, MatchesExactEnumeration) {
  // Eight scenes, unequal trial counts on the two sides, a moderate difference.
  const std::vector<PairedUnit> units = {{4, 6, 3, 6}, {2, 5, 2, 4}, {7, 9, 4, 8},  {1, 3, 2, 3},
                                         {5, 8, 3, 7}, {3, 4, 3, 5}, {6, 10, 5, 9}, {2, 6, 1, 6}};
  const double exact = exactPermutationPValue(units);
  const int permutations = 20000;
  const double p = pairedPermutationPValue(units, permutations, 31);
  std::cout << "exact permutation p-value " << exact << ", Monte Carlo " << p << "\n";
  ASSERT_GT(exact, 0.05);  // the case is meant to be moderate, not extreme
  ASSERT_LT(exact, 0.6);
  // The count b of permutations as extreme is Binomial(m, exact), and p = (1 + b) / (1 + m):
  // its standard deviation is at most sqrt(0.25 / m) = 0.0035 and its bias below 1 / (1 + m).
  // 4.5 standard deviations plus the bias bound.
  const double tolerance =
      4.5 * std::sqrt(exact * (1.0 - exact) / permutations) + 1.0 / (1.0 + permutations);
  EXPECT_NEAR(p, exact, tolerance);
}

TEST(PairedPermutationPValueTest, ClearlyDifferentSidesGiveSmallP) {
  // Twenty scenes of 9/10 against 2/10: only the identity and the full swap are as extreme
  // (probability 2^-19), so b is almost surely 0 and p = 1 / 1000, never 0.
  const std::vector<PairedUnit> units(20, PairedUnit{9, 10, 2, 10});
  const double p = pairedPermutationPValue(units, 999, 5);
  EXPECT_GE(p, 1.0 / 1000.0);
  EXPECT_LE(p, 2.0 / 1000.0);
}

TEST(PairedPermutationPValueTest, UndefinedDifferenceAndBadCount) {
  EXPECT_TRUE(std::isnan(pairedPermutationPValue({{1, 2, 0, 0}}, 100, 1)));
  EXPECT_TRUE(std::isnan(pairedPermutationPValue({}, 100, 1)));
  EXPECT_THROW(pairedPermutationPValue({{1, 2, 1, 2}}, 0, 1), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// Adaptive repeats

TEST(RepeatsToDecideTest, HandValues) {
  EXPECT_EQ(repeatsToDecide(0.05, 0.5), 5);    // 0.5^4 = 0.0625 > 0.05 >= 0.5^5 = 0.03125
  EXPECT_EQ(repeatsToDecide(0.05, 0.632), 3);  // 0.368^2 = 0.135 > 0.05 >= 0.368^3 = 0.0498
  EXPECT_EQ(repeatsToDecide(0.5, 0.9), 2);     // 0.1^1 would do: at least 2
  EXPECT_EQ(repeatsToDecide(0.25, 0.5), 2);    // 0.5^2 = 0.25 exactly: <= holds
  EXPECT_EQ(repeatsToDecide(0.125, 0.5), 3);   // 0.5^3 = 0.125 exactly
  EXPECT_EQ(repeatsToDecide(0.01, 0.1), 44);   // 0.9^43 = 0.01078, 0.9^44 = 0.00970
  EXPECT_EQ(repeatsToDecide(0.05, 0.05), 59);  // 0.95^58 = 0.0510, 0.95^59 = 0.0485
  EXPECT_EQ(repeatsToDecide(0.001, 0.99), 2);  // 0.01^2 = 1e-4
}

TEST(RepeatsToDecideTest, RejectsBadArguments) {
  for (const double bad : {0.0, 1.0, -0.1, 1.1, kNaN}) {
    EXPECT_THROW(repeatsToDecide(bad, 0.5), std::invalid_argument) << bad;
    EXPECT_THROW(repeatsToDecide(0.05, bad), std::invalid_argument) << bad;
  }
  EXPECT_THROW(repeatsToDecide(0.05, 1e-12), std::invalid_argument);  // ~3e12 repeats
}

}  // namespace
}  // namespace visgrab::results
