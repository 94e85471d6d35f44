#include <exception>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "baseline_commands.hpp"
#include "command_line.hpp"
#include "db_commands.hpp"
#include "render_commands.hpp"
#include "run_commands.hpp"
#include "sim_commands.hpp"
#include "wc_commands.hpp"

int main(int argc, char** argv) {
  try {
    std::vector<visgrab::app::Command> commands = visgrab::app::workcellCommands();
    for (auto& c : visgrab::app::simulationCommands()) commands.push_back(std::move(c));
    for (auto& c : visgrab::app::databaseCommands()) commands.push_back(std::move(c));
    for (auto& c : visgrab::app::runCommands()) commands.push_back(std::move(c));
    for (auto& c : visgrab::app::baselineCommands()) commands.push_back(std::move(c));
    for (auto& c : visgrab::app::renderCommands()) commands.push_back(std::move(c));
    const std::vector<std::string> args(argv + 1, argv + argc);
    return visgrab::app::dispatch(commands, args);
  } catch (const std::exception& e) {
    std::cerr << "visgrab: error: " << e.what() << "\n";
    return 1;
  }
}
