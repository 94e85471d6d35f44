#include "visgrab/runner/shard_merge.hpp"

#include <algorithm>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>

#include "rw/common/text_file.hpp"
#include "rw/common/write_error.hpp"
#include "visgrab/results/grasp_summary.hpp"
#include "visgrab/results/results_file.hpp"
#include "visgrab/runner/shard_record.hpp"

namespace visgrab::runner {

namespace {

namespace fs = std::filesystem;

/// A shard folder that passed its own checks.
struct CheckedShard {
  fs::path dir;
  ShardRecord record;
};

std::runtime_error shardError(const fs::path& dir, const std::string& message) {
  return std::runtime_error("shard folder " + dir.string() + ": " + message);
}

/// Checks that `file` of a finished shard is complete and unchanged since the shard finished.
void checkFinishedFile(const fs::path& dir, std::string_view name, const std::string& hash) {
  const fs::path file = dir / name;
  if (!fs::exists(file)) throw shardError(dir, std::string(name) + " is missing");
  const std::string bytes = rw::common::readTextFileOrThrow(file);
  if (name == results::kTrialsFileName) {
    const results::TrialsFile parsed = results::parseTrials(bytes, file.string());
    if (parsed.tornLastLine) {
      throw shardError(dir, std::string(name) +
                                " ends in a torn line (a write cut off): the shard's results "
                                "are incomplete; run the shard again with --resume");
    }
  }
  if (contentHash(bytes) != hash) {
    throw shardError(dir, std::string(name) +
                              " has changed since the shard finished (its hash does not match "
                              "shard.txt); run the shard again with --resume");
  }
}

/// Reads and checks one shard folder on its own.
CheckedShard checkShard(const fs::path& dir) {
  if (!fs::is_directory(dir)) throw shardError(dir, "not a folder");
  CheckedShard shard{dir, readShardRecord(dir)};
  if (!shard.record.finished) {
    throw shardError(dir, describe(shard.record.shard) +
                              " has not finished (shard.txt says running: the task was killed, "
                              "stopped or still runs); run it again with --resume");
  }
  checkFinishedFile(dir, results::kTrialsFileName, shard.record.trialsHash);
  checkFinishedFile(dir, results::kRunFileName, shard.record.runHash);
  return shard;
}

/// Checks that the shards are 1..N of one run, each once; returns them in shard order.
std::vector<CheckedShard> checkOneRun(std::vector<CheckedShard> shards) {
  const CheckedShard& first = shards.front();
  const int count = first.record.shard.count;
  std::map<int, const CheckedShard*> byIndex;
  for (const CheckedShard& s : shards) {
    if (s.record.shard.count != count) {
      throw std::runtime_error("shard folders " + first.dir.string() + " (" +
                               describe(first.record.shard) + ") and " + s.dir.string() + " (" +
                               describe(s.record.shard) +
                               ") are not shards of one run: they cut it into different numbers "
                               "of shards");
    }
    const std::string difference = describeDifference(first.record.inputs, s.record.inputs);
    if (!difference.empty()) {
      throw std::runtime_error("shard folders " + first.dir.string() + " and " + s.dir.string() +
                               " are shards of different runs: " + difference + " differ");
    }
    const auto [it, inserted] = byIndex.emplace(s.record.shard.index, &s);
    if (!inserted) {
      throw std::runtime_error("shard folders " + it->second->dir.string() + " and " +
                               s.dir.string() + " are both " + describe(s.record.shard) +
                               " (a shard given twice)");
    }
  }
  std::string missing;
  for (int k = 1; k <= count; ++k) {
    if (!byIndex.contains(k)) missing += (missing.empty() ? "" : ", ") + std::to_string(k);
  }
  if (!missing.empty()) {
    throw std::runtime_error(
        "shard" + std::string(missing.find(',') == std::string::npos ? " " : "s ") + missing +
        " of " + std::to_string(count) + " missing: give the folders of all " +
        std::to_string(count) + " shards");
  }
  std::sort(shards.begin(), shards.end(), [](const CheckedShard& a, const CheckedShard& b) {
    return a.record.shard.index < b.record.shard.index;
  });
  return shards;
}

/// What differs between the engine records of two shards' run.csv (a record without an engine is
/// ODE's); empty if nothing.
std::string engineDifference(const results::RunSources& a, const results::RunSources& b) {
  const std::string engineA = a.engine.empty() ? "ode" : a.engine;
  const std::string engineB = b.engine.empty() ? "ode" : b.engine;
  if (engineA != engineB) {
    return "ran on different engines: " + engineA + " and " + engineB +
           "; a run's shards must all run on one engine";
  }
  if (a.engineSettings == b.engineSettings) return {};
  const auto settings = [](const std::string& s) {
    return s.empty() ? std::string("none (no engine_settings record in run.csv)") : '"' + s + '"';
  };
  return "ran " + engineA + " with different engine settings: " + settings(a.engineSettings) +
         " and " + settings(b.engineSettings) +
         "; a run's shards must all run with one setting (a shard without an engine_settings "
         "record was written by an older visgrab: run it again with --resume)";
}

/// Refuses an output folder that holds results already (trials.csv, run.csv or grasps.csv), as
/// `visgrab run` does: writing over them would leave files of the old results beside the new.
void checkOutputHoldsNoResults(const fs::path& out) {
  for (const std::string_view name :
       {results::kTrialsFileName, results::kRunFileName, results::kGraspsFileName}) {
    if (fs::exists(out / name)) {
      throw std::runtime_error(out.string() + " already holds results (" + std::string(name) +
                               "); merge into another folder (--out) or remove it first");
    }
  }
}

bool sameFolder(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  return fs::exists(a) && fs::exists(b) && fs::equivalent(a, b, ec);
}

}  // namespace

MergeSummary mergeShards(const std::vector<fs::path>& shardDirs, const fs::path& out) {
  if (shardDirs.empty()) throw std::runtime_error("no shard folders to merge");
  std::vector<CheckedShard> checked;
  for (const fs::path& dir : shardDirs) {
    if (sameFolder(dir, out)) {
      throw shardError(dir, "is also the output folder (--out): merge into another folder");
    }
  }
  checkOutputHoldsNoResults(out);
  for (const fs::path& dir : shardDirs) checked.push_back(checkShard(dir));
  const std::vector<CheckedShard> shards = checkOneRun(std::move(checked));

  results::RunResults merged;
  std::map<std::string, int> rejected;
  for (const CheckedShard& s : shards) {
    results::RunResults part = results::readResults(s.dir);
    if (part.trials.size() != s.record.trials) {
      throw shardError(s.dir, "trials.csv holds " + std::to_string(part.trials.size()) +
                                  " trials, shard.txt says " + std::to_string(s.record.trials));
    }
    if (&s == &shards.front()) {
      merged.methods = part.methods;
      merged.sources = part.sources;
      merged.repeats = part.repeats;
    } else if (part.repeats != merged.repeats) {
      throw std::runtime_error("shard folders " + shards.front().dir.string() + " and " +
                               s.dir.string() +
                               " are shards of different runs: their run.csv records other "
                               "repeats, noise or adaptive rule");
    } else if (part.methods != merged.methods) {
      throw std::runtime_error("shard folders " + shards.front().dir.string() + " and " +
                               s.dir.string() +
                               " are shards of different runs: their run.csv lists other methods");
    } else if (const std::string difference = engineDifference(merged.sources, part.sources);
               !difference.empty()) {
      throw std::runtime_error("shard folders " + shards.front().dir.string() + " and " +
                               s.dir.string() + " " + difference);
    } else if (part.sources.protocol != merged.sources.protocol ||
               part.sources.protocolHash != merged.sources.protocolHash) {
      throw std::runtime_error("shard folders " + shards.front().dir.string() + " and " +
                               s.dir.string() +
                               " ran other trial protocols (run.csv's protocol records differ); "
                               "run every shard with the same --protocol");
    } else if (part.sources.database != merged.sources.database ||
               part.sources.databaseHash != merged.sources.databaseHash ||
               part.sources.grasps != merged.sources.grasps ||
               part.sources.hand != merged.sources.hand ||
               part.sources.protocolFile != merged.sources.protocolFile) {
      throw std::runtime_error("shard folders " + shards.front().dir.string() + " and " +
                               s.dir.string() +
                               " name other input paths in run.csv (database, grasps, hand or "
                               "protocol file); "
                               "run every shard with the same paths");
    }
    merged.scenes.insert(merged.scenes.end(), part.scenes.begin(), part.scenes.end());
    for (auto& t : part.trials) merged.trials.push_back(std::move(t));
    for (const auto& [method, n] : part.rejected) rejected[method] += n;
  }
  for (const auto& [method, n] : rejected) merged.rejected.emplace_back(method, n);
  // As a run writes its folder: marked unfinished until its last file is there, so a merge
  // killed between its files leaves a folder the analyses refuse, not part of a run.
  std::error_code made;
  fs::create_directories(out, made);
  if (made) throw rw::common::WriteError(out, made);
  results::markUnfinished(out);
  results::writeResults(out, merged);
  if (merged.repeats.repeated()) results::writeGraspSummary(out, merged);
  results::markFinished(out);

  MergeSummary summary;
  summary.shards = static_cast<int>(shards.size());
  summary.scenes = static_cast<int>(merged.scenes.size());
  summary.methods = static_cast<int>(merged.methods.size());
  summary.trials = merged.trials.size();
  return summary;
}

}  // namespace visgrab::runner
