#include "protocol_option.hpp"

#include <stdexcept>

#include "cli_common/data_folder.hpp"
#include "rwsim/trial/trial_protocol.hpp"

namespace visgrab::app {

CLI::Option* addProtocolOption(CLI::App& command) {
  return command
      .add_option("--protocol",
                  "The trial protocol: lift (the paper's, default), shake (ACRONYM's: no "
                  "gravity, close to a force, shake, held by two fingers) or a protocol file "
                  "(xml/protocol.xsd, docs/protocols.md); recorded in run.csv unless it is the "
                  "lift")
      ->type_name("lift|shake|FILE");
}

std::optional<std::filesystem::path> protocolOption(const Arguments& a) {
  const auto text = a.option("protocol");
  if (!text) return std::nullopt;
  std::filesystem::path file;
  try {
    file = cli::protocolPath(*text, dataFolder(a));
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--protocol: ") + e.what());
  }
  rwsim::trial::checkProtocol(rwsim::trial::loadTrialProtocol(file));
  return file;
}

}  // namespace visgrab::app
