#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "command_line.hpp"

int main(int argc, char** argv) {
  try {
    const auto cli = visgrab::app::makeCommandLine();
    return cli->run(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const std::exception& e) {
    std::cerr << "visgrab: error: " << e.what() << "\n";
    return 1;
  }
}
