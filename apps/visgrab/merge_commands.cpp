#include "merge_commands.hpp"

#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "visgrab/runner/shard_merge.hpp"

namespace visgrab::app {

namespace {

namespace fs = std::filesystem;

int runMerge(const Arguments& a) {
  std::vector<fs::path> shards;
  for (const auto& dir : a.positionals()) shards.emplace_back(dir);
  const fs::path out = a.option("out").value();
  const runner::MergeSummary summary = runner::mergeShards(shards, out);
  std::cout << summary.shards << " shards merged: " << summary.trials << " trials, "
            << summary.scenes << " scenes, " << summary.methods << " methods; results in "
            << out.string() << "\n";
  return 0;
}

}  // namespace

void addMergeCommands(CommandLine& cli) {
  CLI::App& merge = cli.addCommand(
      nullptr, "merge",
      "Join the result folders of a run's shards (`visgrab run --shard K --of N`) into the "
      "run's result folder: the same trials.csv and run.csv as one `visgrab run` of the whole "
      "work. Every shard 1..N must be given once, finished, unchanged and of the same run "
      "(database, grasp files, hand, scene filter); docs/cluster.md.",
      guarded(runMerge));
  merge.add_option("SHARD_DIR", "The shards' result folders, in any order")
      ->required()
      ->expected(1, CLI::detail::expected_max_vector_size)
      ->allow_extra_args()
      ->type_name("");
  merge
      .add_option("--out",
                  "The result folder to write (trials.csv, run.csv); one that already holds "
                  "results is refused, as by `visgrab run`")
      ->required()
      ->type_name("RESULTS");
}

}  // namespace visgrab::app
