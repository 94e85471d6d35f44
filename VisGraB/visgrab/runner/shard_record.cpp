#include "visgrab/runner/shard_record.hpp"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <map>
#include <sstream>

#include "rw/common/diagnostic.hpp"
#include "rw/common/strings.hpp"
#include "rw/common/text_file.hpp"
#include "visgrab/database/atomic_file.hpp"
#include "visgrab/database/database.hpp"

namespace visgrab::runner {

namespace {

namespace fs = std::filesystem;

constexpr std::string_view kFirstLine = "visgrab shard 1";

/// 64-bit FNV-1a, continued over several pieces.
class Fnv1a {
 public:
  void add(std::string_view bytes) { state_ = rw::common::fnv1a(bytes, state_); }
  /// A piece with its length first, so that ("ab", "c") and ("a", "bc") differ.
  void addField(std::string_view bytes) {
    add(std::to_string(bytes.size()));
    add(":");
    add(bytes);
  }
  std::string hex() const { return rw::common::hex64(state_); }

 private:
  std::uint64_t state_ = rw::common::kFnv1aBasis;
};

rw::common::LoadError loadError(const std::string& file, int line, const std::string& message) {
  rw::common::Diagnostic d;
  d.file = file;
  d.line = line;
  d.message = message;
  return rw::common::LoadError({d});
}

/// The regular files of `folder` whose names do not start with '.', by name.
std::vector<fs::path> folderFiles(const fs::path& folder) {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(folder)) {
    if (e.is_regular_file() && !e.path().filename().string().starts_with('.')) {
      files.push_back(e.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

void addFile(Fnv1a& hash, const fs::path& file, const std::string& name) {
  hash.addField(name);
  hash.addField(rw::common::readTextFileOrThrow(file));
}

}  // namespace

std::string contentHash(std::string_view bytes) {
  Fnv1a hash;
  hash.add(bytes);
  return hash.hex();
}

RunFingerprint fingerprintRun(const fs::path& database, const std::vector<fs::path>& grasps,
                              const fs::path& hand, const std::string& scenes) {
  RunFingerprint out;
  out.database = database::indexHash(database);
  {
    Fnv1a hash;
    for (const fs::path& source : grasps) {
      if (fs::is_directory(source)) {
        for (const fs::path& f : folderFiles(source)) {
          addFile(hash, f, f.filename().string());
        }
      } else {
        addFile(hash, source, source.filename().string());
      }
    }
    out.grasps = hash.hex();
  }
  {
    Fnv1a hash;
    if (fs::is_directory(hand)) {
      for (const fs::path& f : folderFiles(hand)) addFile(hash, f, f.filename().string());
    } else {
      addFile(hash, hand, hand.filename().string());
    }
    out.hand = hash.hex();
  }
  out.scenes = scenes;
  return out;
}

std::string formatShardRecord(const ShardRecord& r) {
  std::ostringstream out;
  out << kFirstLine << "\n"
      << "shard " << r.shard.index << " of " << r.shard.count << "\n"
      << "state " << (r.finished ? "finished" : "running") << "\n"
      << "database " << r.inputs.database << "\n"
      << "grasps " << r.inputs.grasps << "\n"
      << "hand " << r.inputs.hand << "\n"
      << "scenes " << r.inputs.scenes << "\n";
  if (r.finished) {
    out << "trials " << r.trials << "\n"
        << "trials.csv " << r.trialsHash << "\n"
        << "run.csv " << r.runHash << "\n";
  }
  return out.str();
}

namespace {

bool isHash(std::string_view v) {
  return v.size() == 16 && std::all_of(v.begin(), v.end(), [](char c) {
           return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
         });
}

template <typename T>
bool parseNumber(std::string_view text, T& value) {
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end == text.data() + text.size();
}

}  // namespace

ShardRecord parseShardRecord(std::string_view text, const std::string& file) {
  ShardRecord r;
  std::map<std::string, int> seen;
  int lineNo = 0;
  std::size_t pos = 0;
  if (text.empty())
    throw loadError(file, 1, "empty file, expected \"" + std::string(kFirstLine) + "\"");
  if (text.back() != '\n') {
    throw loadError(file, static_cast<int>(std::count(text.begin(), text.end(), '\n')) + 1,
                    "the last line is cut off (no line break): the record is incomplete");
  }
  while (pos < text.size()) {
    const std::size_t eol = text.find('\n', pos);
    const std::string_view line = text.substr(pos, eol - pos);
    pos = eol + 1;
    ++lineNo;
    if (lineNo == 1) {
      if (line != kFirstLine) {
        throw loadError(
            file, 1,
            "expected \"" + std::string(kFirstLine) + "\", found \"" + std::string(line) + "\"");
      }
      continue;
    }
    const std::size_t space = line.find(' ');
    const std::string key(line.substr(0, space));
    const std::string_view value =
        space == std::string_view::npos ? std::string_view() : line.substr(space + 1);
    if (seen.contains(key)) {
      throw loadError(
          file, lineNo,
          "\"" + key + "\" given twice (first on line " + std::to_string(seen[key]) + ")");
    }
    seen[key] = lineNo;
    const auto bad = [&](const std::string& expected) {
      return loadError(
          file, lineNo,
          "\"" + key + "\": expected " + expected + ", found \"" + std::string(value) + "\"");
    };
    if (key == "shard") {
      const std::size_t of = value.find(" of ");
      if (of == std::string_view::npos || !parseNumber(value.substr(0, of), r.shard.index) ||
          !parseNumber(value.substr(of + 4), r.shard.count) || r.shard.count < 1 ||
          r.shard.index < 1 || r.shard.index > r.shard.count) {
        throw bad("\"K of N\" with 1 <= K <= N");
      }
    } else if (key == "state") {
      if (value != "running" && value != "finished") throw bad("running or finished");
      r.finished = value == "finished";
    } else if (key == "database" || key == "grasps" || key == "hand" || key == "trials.csv" ||
               key == "run.csv") {
      if (!isHash(value)) throw bad("16 hex digits");
      std::string& field = key == "database"     ? r.inputs.database
                           : key == "grasps"     ? r.inputs.grasps
                           : key == "hand"       ? r.inputs.hand
                           : key == "trials.csv" ? r.trialsHash
                                                 : r.runHash;
      field = value;
    } else if (key == "scenes") {
      r.inputs.scenes = value;
    } else if (key == "trials") {
      if (!parseNumber(value, r.trials)) throw bad("a number of trials");
    } else {
      throw loadError(file, lineNo, "unknown key \"" + key + "\"");
    }
  }
  std::vector<std::string> required{"shard", "state", "database", "grasps", "hand", "scenes"};
  if (r.finished) {
    for (const char* k : {"trials", "trials.csv", "run.csv"}) required.emplace_back(k);
  }
  for (const auto& k : required) {
    if (!seen.contains(k)) throw loadError(file, lineNo, "no \"" + k + "\" line");
  }
  return r;
}

ShardRecord readShardRecord(const fs::path& dir) {
  const fs::path file = dir / kShardRecordFileName;
  if (!fs::exists(file)) {
    throw loadError(file.string(), 0,
                    "missing: " + dir.string() +
                        " is not the result folder of a shard (visgrab run --shard K --of N)");
  }
  return parseShardRecord(rw::common::readTextFileOrThrow(file), file.string());
}

void writeShardRecord(const fs::path& dir, const ShardRecord& record) {
  database::writeFileAtomically(dir / kShardRecordFileName, formatShardRecord(record));
}

std::string describeDifference(const RunFingerprint& a, const RunFingerprint& b) {
  std::vector<std::string> parts;
  if (a.database != b.database) parts.emplace_back("the database (index)");
  if (a.grasps != b.grasps) parts.emplace_back("the grasp files");
  if (a.hand != b.hand) parts.emplace_back("the hand");
  if (a.scenes != b.scenes) {
    parts.emplace_back("the scene filter (\"" + a.scenes + "\" vs \"" + b.scenes + "\")");
  }
  std::string out;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    out += (i == 0 ? "" : ", ") + parts[i];
  }
  return out;
}

}  // namespace visgrab::runner
