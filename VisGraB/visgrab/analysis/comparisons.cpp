#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "visgrab/analysis/detail/scene_tally.hpp"

namespace visgrab::analysis {

std::vector<std::string> differingSources(const results::RunSources& a,
                                          const results::RunSources& b) {
  const auto engine = [](const results::RunSources& s) {
    return s.engine.empty() ? std::string("ode") : s.engine;
  };
  std::vector<std::string> out;
  if (a.hand != b.hand) out.emplace_back("hand");
  if (engine(a) != engine(b)) out.emplace_back("engine");
  if (a.engineSettings != b.engineSettings) out.emplace_back("engine settings");
  if (a.protocol != b.protocol || a.protocolHash != b.protocolHash) out.emplace_back("protocol");
  if (a.databaseHash != b.databaseHash) out.emplace_back("database");
  return out;
}

namespace detail {

namespace {

/// One estimate of both columns, its paired bootstrap interval and permutation p-value.
PairedDifference pairedDifference(const std::vector<results::PairedUnit>& units,
                                  const AnalysisOptions& options, const std::string& key) {
  PairedDifference d;
  double successesA = 0.0;
  double trialsA = 0.0;
  double successesB = 0.0;
  double trialsB = 0.0;
  for (const results::PairedUnit& u : units) {
    successesA += u.successesA;
    trialsA += u.trialsA;
    successesB += u.successesB;
    trialsB += u.trialsB;
  }
  d.a = trialsA > 0.0 ? successesA / trialsA : kUndefinedValue;
  d.b = trialsB > 0.0 ? successesB / trialsB : kUndefinedValue;
  d.difference = results::pooledDifference(units);
  if (std::isnan(d.difference)) {
    d.pValue = kUndefinedValue;
    return d;
  }
  d.differenceCi =
      results::pairedBootstrapInterval(units, bootstrapOptions(options, "bootstrap|" + key));
  d.pValue = results::pairedPermutationPValue(
      units, options.permutations, results::deriveSeed(options.bootstrapSeed, "permute|" + key));
  return d;
}

}  // namespace

void compareColumns(const std::vector<const SceneTally*>& a,
                    const std::vector<const SceneTally*>& b, const AnalysisOptions& options,
                    const std::string& key, Comparison& comparison) {
  std::vector<results::PairedUnit> rate;
  std::vector<results::PairedUnit> p;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const SceneTally& sa = *a[i];
    const SceneTally& sb = *b[i];
    rate.push_back({static_cast<double>(sa.successes), static_cast<double>(sa.grasps.size()),
                    static_cast<double>(sb.successes), static_cast<double>(sb.grasps.size())});
    p.push_back({sa.successes > 0 ? 1.0 : 0.0, 1.0, sb.successes > 0 ? 1.0 : 0.0, 1.0});
  }
  comparison.scenes = static_cast<int>(a.size());
  comparison.rate = pairedDifference(rate, options, "rate|" + key);
  comparison.p = pairedDifference(p, options, "p|" + key);
}

}  // namespace detail

}  // namespace visgrab::analysis
