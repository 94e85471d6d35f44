#include "slurm_commands.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <iostream>
#include <map>
#include <set>
#include <stdexcept>
#include <string>

#include "cli_common/data_folder.hpp"
#include "protocol_option.hpp"
#include "repeat_options.hpp"
#include "visgrab/database/atomic_file.hpp"

namespace visgrab::app {

namespace {

namespace fs = std::filesystem;

/// `text` in single quotes for bash.
std::string quoted(const std::string& text) {
  std::string out = "'";
  for (const char c : text) {
    if (c == '\'') {
      out += "'\\''";
    } else {
      out += c;
    }
  }
  return out + "'";
}

std::string quoted(const fs::path& path) { return quoted(path.string()); }

fs::path slurmDir(const SlurmPlan& plan) { return plan.out / "slurm"; }

/// The #SBATCH lines every job gets.
std::string commonHeader(const SlurmPlan& plan) {
  std::string out = "#SBATCH --cpus-per-task=" + std::to_string(plan.cpusPerTask) + "\n";
  for (const auto& o : plan.sbatchOptions) out += "#SBATCH " + o + "\n";
  return out;
}

/// The hand's short name: its folder's name (scenes/hands/sdh/sdh.grasp.xml: sdh).
std::string handName(const fs::path& hand) {
  const fs::path folder = hand.has_extension() ? hand.parent_path() : hand;
  return folder.filename().string();
}

/// A name safe in file names and shell words: letters, digits, '-', '_', '.'.
std::string safeName(std::string name) {
  for (char& c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '-' || c == '_' || c == '.';
    if (!ok) c = '_';
  }
  return name.empty() || name.front() == '.' ? "run" + name : name;
}

/// The result folder of `run` (the merge writes it, analyze reads it).
fs::path resultsDir(const SlurmPlan& plan, const SlurmRun& run) {
  return plan.out / "results" / run.name;
}

}  // namespace

std::vector<SlurmRun> slurmRuns(const SlurmPlan& plan) {
  std::vector<SlurmRun> runs;
  std::set<std::string> names;
  for (const auto& g : plan.grasps) {
    for (const auto& h : plan.hands) {
      std::string base = g.stem().string();
      if (plan.hands.size() > 1) base += "-" + handName(h);
      base = safeName(base);
      std::string name = base;
      for (int i = 2; names.contains(name); ++i) name = base + "-" + std::to_string(i);
      names.insert(name);
      runs.push_back({name, g, h});
    }
  }
  return runs;
}

std::string trialsScript(const SlurmPlan& plan) {
  const auto runs = slurmRuns(plan);
  const std::size_t tasks = runs.size() * static_cast<std::size_t>(plan.shards);
  std::string s = "#!/bin/bash\n";
  s += "# The trials of " + std::to_string(runs.size()) + " run(s) x " +
       std::to_string(plan.shards) + " shard(s), written by `visgrab slurm` (docs/cluster.md).\n";
  s += "# Array task T runs shard T % " + std::to_string(plan.shards) + " + 1 of run T / " +
       std::to_string(plan.shards) +
       " with --resume: a requeued or resubmitted task\n# (sbatch --array=3,7 " +
       (slurmDir(plan) / "trials.sbatch").string() + ") continues its shard.\n";
  s += "#SBATCH --job-name=visgrab-trials\n";
  s += "#SBATCH --array=0-" + std::to_string(tasks - 1) + "\n";
  s += "#SBATCH --output=" + (slurmDir(plan) / "logs" / "trials-%A_%a.out").string() + "\n";
  s += commonHeader(plan);
  s += "set -euo pipefail\n";
  s += "shards=" + std::to_string(plan.shards) + "\n";
  s += "task=${SLURM_ARRAY_TASK_ID:?not started as a task of a Slurm job array}\n";
  s += "run=$((task / shards))\n";
  s += "shard=$((task % shards + 1))\n";
  s += "case $run in\n";
  for (std::size_t i = 0; i < runs.size(); ++i) {
    s += "  " + std::to_string(i) + ") name=" + quoted(runs[i].name) +
         "; grasps=" + quoted(runs[i].grasps) + "; hand=" + quoted(runs[i].hand) + " ;;\n";
  }
  s += "  *) echo \"array task $task is beyond the " + std::to_string(tasks) +
       " tasks of this job\" >&2; exit 2 ;;\n";
  s += "esac\n";
  s +=
      R"(echo "run $name, shard $shard of $shards on $(hostname), restart ${SLURM_RESTART_COUNT:-0}")"
      "\n";
  s += "exec " + quoted(plan.visgrab) + " run --db " + quoted(plan.database) +
       R"( --grasps "$grasps" --hand "$hand")";
  if (!plan.scenes.empty()) s += " --scenes " + quoted(plan.scenes);
  for (const std::string& word : plan.runArguments) s += " " + quoted(word);
  s += " \\\n  --shard \"$shard\" --of \"$shards\" --threads " + std::to_string(plan.cpusPerTask) +
       " --resume --quiet \\\n  --out " + quoted(plan.out / "shards") +
       "/\"$name\"/shard-\"$shard\"\n";
  return s;
}

std::string mergeScript(const SlurmPlan& plan) {
  const auto runs = slurmRuns(plan);
  std::string s = "#!/bin/bash\n";
  s += "# Merges the shards of each run (visgrab merge) and analyzes the runs side by side, "
       "written by\n# `visgrab slurm` (docs/cluster.md); submitted with "
       "--dependency=afterok:<the trials job>.\n";
  s += "#SBATCH --job-name=visgrab-merge\n";
  s += "#SBATCH --output=" + (slurmDir(plan) / "logs" / "merge-%j.out").string() + "\n";
  s += commonHeader(plan);
  s += "set -euo pipefail\n";
  s += "shards=" + std::to_string(plan.shards) + "\n";
  s += "for name in";
  for (const auto& r : runs) s += " " + quoted(r.name);
  s += "; do\n";
  s += "  dirs=()\n";
  s += "  for ((k = 1; k <= shards; ++k)); do dirs+=(" + quoted(plan.out / "shards") +
       "/\"$name\"/shard-$k); done\n";
  s += "  " + quoted(plan.visgrab) + " merge \"${dirs[@]}\" --out " + quoted(plan.out / "results") +
       "/\"$name\"\n";
  s += "done\n";
  if (plan.analyze) {
    s += quoted(plan.visgrab) + " analyze";
    for (const auto& r : runs) s += " " + quoted(resultsDir(plan, r));
    s += " --out " + quoted(plan.out / "report") + " --threads " +
         std::to_string(plan.cpusPerTask) + (plan.pictures ? "" : " --no-pictures") + " --quiet\n";
  }
  return s;
}

std::string submitScript(const SlurmPlan& plan) {
  const fs::path dir = slurmDir(plan);
  std::string s = "#!/bin/bash\n";
  s += "# Submits the trials array and the merge job that waits for it (written by `visgrab "
       "slurm`).\n";
  s += "set -euo pipefail\n";
  s += "trials=$(sbatch --parsable " + quoted(dir / "trials.sbatch") + ")\n";
  s += "trials=${trials%%;*}\n";
  s += "merge=$(sbatch --parsable --dependency=afterok:\"$trials\" " +
       quoted(dir / "merge.sbatch") + ")\n";
  s += "echo \"trials job $trials, merge job ${merge%%;*}\"\n";
  return s;
}

namespace {

/// Runs `argv` (searched in PATH), its stdout captured, stderr passed on. Returns stdout;
/// throws naming the command when it cannot start or fails.
std::string runCaptured(const std::vector<std::string>& argv) {
  int pipeFds[2];
  if (::pipe(pipeFds) != 0) throw std::runtime_error("cannot make a pipe for " + argv[0]);
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("cannot start " + argv[0] + ": " + std::strerror(errno));
  if (pid == 0) {
    ::dup2(pipeFds[1], STDOUT_FILENO);
    ::close(pipeFds[0]);
    ::close(pipeFds[1]);
    std::vector<char*> args;
    args.reserve(argv.size() + 1);
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    ::execvp(args[0], args.data());
    const std::string message = "cannot run " + argv[0] + ": " + std::strerror(errno) + "\n";
    [[maybe_unused]] const auto n = ::write(STDERR_FILENO, message.data(), message.size());
    ::_exit(127);
  }
  ::close(pipeFds[1]);
  std::string output;
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(pipeFds[0], buffer, sizeof buffer);
    if (n > 0) {
      output.append(buffer, static_cast<std::size_t>(n));
    } else if (n == 0 || errno != EINTR) {
      break;
    }
  }
  ::close(pipeFds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  std::string command;
  for (const auto& a : argv) command += (command.empty() ? "" : " ") + a;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw std::runtime_error("`" + command + "` failed (" +
                             (WIFEXITED(status) ? "exit code " + std::to_string(WEXITSTATUS(status))
                                                : std::string("killed by a signal")) +
                             ")");
  }
  return output;
}

/// The job id in `sbatch --parsable` output ("<id>" or "<id>;<cluster>").
std::string parsableJobId(const std::string& output, const std::string& command) {
  std::string id = output.substr(0, output.find_first_of(";\n"));
  while (!id.empty() && (id.back() == '\r' || id.back() == ' ')) id.pop_back();
  if (id.empty() ||
      !std::all_of(id.begin(), id.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    throw std::runtime_error("`" + command + "` printed \"" + output +
                             "\", expected a job id (sbatch --parsable)");
  }
  return id;
}

/// An sbatch option's value: one line.
std::string sbatchValue(const std::string& option, const std::string& value) {
  if (value.empty() || value.find_first_of("\n\r") != std::string::npos) {
    throw UsageError(option + ": expected a value on one line");
  }
  return value;
}

int runSlurm(const Arguments& a) {
  SlurmPlan plan;
  const auto abs = [](const std::string& p) { return fs::absolute(p).lexically_normal(); };
  plan.visgrab = a.option("visgrab") ? abs(*a.option("visgrab"))
                                     : fs::read_symlink("/proc/self/exe").lexically_normal();
  plan.database = abs(a.option("db").value());
  for (const auto& g : a.values("grasps")) plan.grasps.push_back(abs(g));
  for (const auto& h : a.values("hand")) {
    plan.hands.push_back(abs(handOptionPath(h, dataFolder(a)).string()));
  }
  if (plan.hands.empty())
    plan.hands.push_back(abs((dataFolder(a) / "hands/sdh/sdh.grasp.xml").string()));
  plan.scenes = scenesFilter(a);
  plan.runArguments = repeatArguments(a);
  if (const auto protocol = protocolOption(a)) {
    plan.runArguments.insert(plan.runArguments.end(),
                             {"--protocol", abs(protocol->string()).string()});
  }
  plan.shards = integerOption(a, "shards", 1, 1);
  plan.cpusPerTask = integerOption(a, "cpus-per-task", 1, 1);
  plan.out = abs(a.option("out").value());
  for (const char* name : {"partition", "time", "account", "mem"}) {
    if (const auto v = a.option(name)) {
      plan.sbatchOptions.push_back(std::string("--") + name + "=" +
                                   sbatchValue(std::string("--") + name, *v));
    }
  }
  for (const auto& o : a.values("sbatch-option")) {
    plan.sbatchOptions.push_back(sbatchValue("--sbatch-option", o));
  }
  plan.analyze = !a.flag("no-analyze");
  plan.pictures = !a.flag("no-pictures");
  if (a.flag("dry-run") && a.flag("submit"))
    throw UsageError("--dry-run and --submit exclude each other");
  if (!fs::exists(plan.database)) {
    throw std::runtime_error("--db " + plan.database.string() + " does not exist");
  }
  for (const auto& p : plan.grasps) {
    if (!fs::exists(p)) throw std::runtime_error("--grasps " + p.string() + " does not exist");
  }
  for (const auto& p : plan.hands) {
    if (!fs::exists(p)) throw std::runtime_error("--hand " + p.string() + " does not exist");
  }
  const std::size_t tasks = slurmRuns(plan).size() * static_cast<std::size_t>(plan.shards);
  if (tasks > 1001) {
    std::cerr << "visgrab slurm: warning: " << tasks
              << " array tasks; a cluster's MaxArraySize (default 1001) limits the indices: use "
                 "fewer shards or split the sweep (docs/cluster.md)\n";
  }
  const fs::path dir = slurmDir(plan);
  const std::vector<std::pair<fs::path, std::string>> files{
      {dir / "trials.sbatch", trialsScript(plan)},
      {dir / "merge.sbatch", mergeScript(plan)},
      {dir / "submit.sh", submitScript(plan)}};
  if (a.flag("dry-run")) {
    for (const auto& [file, text] : files) {
      std::cout << "#### " << file.string() << "\n" << text;
    }
    return 0;
  }
  fs::create_directories(dir / "logs");
  for (const auto& [file, text] : files) {
    database::writeFileAtomically(file, text);
    fs::permissions(file, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                    fs::perm_options::add);
  }
  std::cout << "wrote " << (dir / "trials.sbatch").string() << " (" << tasks << " array tasks) and "
            << (dir / "merge.sbatch").string() << "\n";
  if (!a.flag("submit")) {
    std::cout << "submit them with " << (dir / "submit.sh").string()
              << " (or visgrab slurm ... --submit)\n";
    return 0;
  }
  const std::string sbatch = a.option("sbatch").value_or("sbatch");
  const std::vector<std::string> trialsCommand{sbatch, "--parsable",
                                               (dir / "trials.sbatch").string()};
  const std::string trials = parsableJobId(runCaptured(trialsCommand), sbatch + " --parsable");
  const std::vector<std::string> mergeCommand{
      sbatch, "--parsable", "--dependency=afterok:" + trials, (dir / "merge.sbatch").string()};
  const std::string merge = parsableJobId(runCaptured(mergeCommand), sbatch + " --parsable");
  std::cout << "submitted: trials job " << trials << ", merge job " << merge << " (after " << trials
            << " succeeds)\n";
  std::cout << "results in " << (plan.out / "results").string() << ", report in "
            << (plan.out / "report").string() << "\n";
  return 0;
}

}  // namespace

void addSlurmCommands(CommandLine& cli) {
  CLI::App& slurm = cli.addCommand(
      nullptr, "slurm",
      "Write (and with --submit submit) the Slurm jobs of a benchmark: a job array whose tasks "
      "each run one shard of one run (`visgrab run --shard K --of N --resume`; one run per "
      "--grasps set and --hand) and a merge job, after the array succeeded, that merges each "
      "run's shards (`visgrab merge`) and analyzes the runs. Scripts in OUT/slurm (logs in "
      "OUT/slurm/logs), shards in OUT/shards, results in OUT/results, report in OUT/report "
      "(docs/cluster.md).",
      guarded(runSlurm));
  slurm
      .add_option("--db",
                  "The database (a generated folder or manifest) on a file system the "
                  "nodes share")
      ->required()
      ->type_name("DIR|MANIFEST");
  slurm
      .add_option("--grasps",
                  "A method's grasp file or folder: one run per --grasps and --hand; repeatable")
      ->required()
      ->type_name("FILE|DIR")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  slurm
      .add_option("--hand",
                  "A hand (name in DATA/hands, folder or grasp description; default: the SDH): "
                  "every --grasps "
                  "runs with every --hand; repeatable")
      ->type_name("DIR|GRASP.xml")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  slurm
      .add_option("--shards", "Shards per run (array tasks per run); size them to 2-5 minutes each")
      ->required()
      ->type_name("N")
      ->check(integerAtLeast(1));
  slurm.add_option("--out", "The folder of scripts, shards, results and report")
      ->required()
      ->type_name("OUT");
  slurm
      .add_option("--cpus-per-task",
                  "CPUs per array task (sbatch --cpus-per-task), used as visgrab's --threads")
      ->type_name("N")
      ->default_str("1")
      ->check(integerAtLeast(1));
  slurm.add_option("--partition", "sbatch --partition of every job")->type_name("NAME");
  slurm.add_option("--time", "sbatch --time of every job (a task's limit)")->type_name("TIME");
  slurm.add_option("--account", "sbatch --account of every job")->type_name("NAME");
  slurm.add_option("--mem", "sbatch --mem of every job")->type_name("SIZE");
  slurm
      .add_option("--sbatch-option",
                  "Another sbatch option for every job, as written after #SBATCH "
                  "(e.g. --qos=long); repeatable")
      ->type_name("OPTION")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  addFlag(slurm, "--dry-run", "Print the scripts; write and submit nothing");
  addFlag(slurm, "--submit", "Submit the jobs (sbatch --parsable) after writing them");
  addFlag(slurm, "--no-analyze", "The merge job only merges (no report)");
  addFlag(slurm, "--no-pictures", "The report without its pictures");
  slurm.add_option("--visgrab", "The visgrab binary the jobs run (default: this one)")
      ->type_name("FILE");
  slurm.add_option("--sbatch", "The sbatch command for --submit")
      ->type_name("FILE")
      ->default_str("sbatch");
  addScenesOption(slurm);
  addRepeatOptions(slurm);
  addProtocolOption(slurm);
  addDataOption(slurm);
}

}  // namespace visgrab::app
