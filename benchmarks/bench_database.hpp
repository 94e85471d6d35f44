#pragma once

// The scene database a benchmark reads: $VISGRAB_BENCH_DB when it holds the scenes asked for
// (the shared test database has the default ones: VISGRAB_BENCH_DB=build/tests/test-database),
// else those scenes generated into a temporary folder at start-up and removed at exit.

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "visgrab/database/database.hpp"
#include "visgrab/database/scene_set.hpp"
#include "visgrab/generator/generator.hpp"

namespace visgrab::bench {

class BenchDatabase {
 public:
  explicit BenchDatabase(const std::vector<std::string>& ids) {
    if (const char* env = std::getenv("VISGRAB_BENCH_DB"); env != nullptr && *env != '\0') {
      db_.emplace(database::Database::open(env));
      bool all = true;
      for (const auto& id : ids) all = all && db_->contains(id);
      if (all) return;
      std::fprintf(stderr, "%s lacks a scene the benchmark needs; generating them\n", env);
      db_.reset();
    }
    temp_ =
        std::filesystem::temp_directory_path() / ("visgrab-bench-" + std::to_string(::getpid()));
    generator::GeneratorOptions options;
    options.out = temp_;
    const std::filesystem::path scenes = std::filesystem::path(VISGRAB_SOURCE_DIR) / "scenes";
    options.objectSpec = scenes / "objects/objects.xml";
    options.handFolder = scenes / "hands/sdh";
    options.materials = scenes / "materials.xml";
    options.threads = 2;
    std::vector<database::SceneConditions> conditions;
    for (const auto& id : ids) conditions.push_back(*database::parseSceneId(id));
    const auto report = generator::generateDatabase(conditions, options);
    if (!report.failures.empty()) throw std::runtime_error(report.failures.front());
    db_.emplace(database::Database::open(temp_));
  }
  ~BenchDatabase() {
    std::error_code ignored;
    if (!temp_.empty()) std::filesystem::remove_all(temp_, ignored);
  }
  BenchDatabase(const BenchDatabase&) = delete;
  BenchDatabase& operator=(const BenchDatabase&) = delete;

  const database::Database& db() const { return *db_; }

 private:
  std::filesystem::path temp_;
  std::optional<database::Database> db_;
};

}  // namespace visgrab::bench
