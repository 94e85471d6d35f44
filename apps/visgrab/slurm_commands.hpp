#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "command_line.hpp"

namespace visgrab::app {

/// What `visgrab slurm` writes: the job array over (run, shard) and the merge-and-analyze job.
struct SlurmPlan {
  /// The `visgrab` binary the jobs run (absolute).
  std::filesystem::path visgrab;
  /// The database (absolute; on a file system every node sees).
  std::filesystem::path database;
  /// One run per (grasp set, hand): its grasp file or folder.
  std::vector<std::filesystem::path> grasps;
  /// The hands (absolute).
  std::vector<std::filesystem::path> hands;
  /// The scene filter (empty: all scenes).
  std::string scenes;
  /// Shards per run.
  int shards = 1;
  /// CPUs per array task, passed on as --threads.
  int cpusPerTask = 1;
  /// The folder of everything (absolute): slurm/, shards/, results/, report/.
  std::filesystem::path out;
  /// sbatch options for every job (--partition, --time, ... as "name=value").
  std::vector<std::string> sbatchOptions;
  /// The merge job also writes the report (visgrab analyze), without pictures if set.
  bool analyze = true;
  /// See analyze.
  bool pictures = true;
  /// `visgrab run`'s repeat options, passed on to every shard (repeatArguments; empty: none).
  std::vector<std::string> runArguments;
};

/// A run of the sweep: its name (its folder under shards/ and results/), grasp set and hand.
struct SlurmRun {
  /// See SlurmRun.
  std::string name;
  /// See SlurmRun.
  std::filesystem::path grasps;
  /// See SlurmRun.
  std::filesystem::path hand;
};

/// The runs of `plan`: every grasp set with every hand (grasp sets outer), named after the
/// grasp file (and the hand's folder when there are several hands), made unique.
std::vector<SlurmRun> slurmRuns(const SlurmPlan& plan);

/// The array job's script: task T (0-based, `--array=0-(runs x shards - 1)`) runs shard
/// T % shards + 1 of run T / shards with --resume.
std::string trialsScript(const SlurmPlan& plan);

/// The merge-and-analyze job's script (submitted with --dependency=afterok on the array).
std::string mergeScript(const SlurmPlan& plan);

/// A script that submits both jobs with sbatch (for resubmitting by hand).
std::string submitScript(const SlurmPlan& plan);

/// `visgrab slurm`: writes (and submits) the job array of a benchmark on a Slurm cluster.
void addSlurmCommands(CommandLine& cli);

}  // namespace visgrab::app
