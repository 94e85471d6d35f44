// The `slurm_cluster` test's driver: makes sure the shared test database exists, writes grasps
// on every one of its 20 scenes and runs slurm_cluster_test.py (a real one-node Slurm cluster)
// on them; its exit code is the test's (77: skipped, with the reason printed).
#include <sys/wait.h>

#include <cstdlib>
#include <exception>
#include <iostream>
#include <string>
#include <string_view>
#include <vector>

#include "shard_test_grasps.hpp"
#include "support/test_database.hpp"
#include "support/test_support.hpp"
#include "visgrab/taskio/grasp_list.hpp"

int main() {
  try {
    const visgrab::test::TempDir work;
    const std::vector<std::string_view> scenes(visgrab::test::kTestSceneIds.begin(),
                                               visgrab::test::kTestSceneIds.end());
    const auto grasps = work.path() / "top.txt";
    visgrab::taskio::writeGraspList(visgrab::test::cylinderGrasps(scenes, 2, "top"), grasps);
    using visgrab::test::shellQuoted;
    const std::string command =
        shellQuoted(VISGRAB_PYTHON3) + " " + shellQuoted(VISGRAB_SLURM_TEST_SCRIPT) + " " +
        shellQuoted(VISGRAB_BINARY) + " " + shellQuoted(visgrab::test::testDatabasePath()) + " " +
        shellQuoted(grasps) + " " + shellQuoted(visgrab::test::sdhHandFile()) + " " +
        shellQuoted(work.path());
    std::cout << command << std::endl;
    const int status = std::system(command.c_str());
    if (status == -1 || !WIFEXITED(status)) {
      std::cout << "FAILED: the test script did not exit normally\n";
      return 1;
    }
    return WEXITSTATUS(status);
  } catch (const std::exception& e) {
    std::cout << "FAILED: " << e.what() << "\n";
    return 1;
  }
}
