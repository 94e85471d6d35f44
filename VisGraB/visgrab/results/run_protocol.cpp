#include "visgrab/results/run_protocol.hpp"

#include <exception>
#include <system_error>
#include <utility>

namespace visgrab::results {

namespace {

namespace fs = std::filesystem;
using rwsim::trial::TrialProtocol;

/// "the protocol "shake" (hash H)", or the lift's description for a run without a record.
std::string recordedProtocol(const RunSources& sources) {
  if (sources.protocol.empty()) {
    return "the lift protocol (the default: run.csv records no protocol; hash " +
           recordedProtocolHash(sources) + ")";
  }
  return "the protocol \"" + sources.protocol + "\" (hash " + sources.protocolHash + ")";
}

/// A name that names a file of DATA/protocols (no folder, no "." or "..").
bool plainName(const std::string& name) {
  return !name.empty() && name != "." && name != ".." && name.find('/') == std::string::npos &&
         name.find('\\') == std::string::npos;
}

}  // namespace

ProtocolNotFoundError::ProtocolNotFoundError(std::string name, std::string hash, std::string reason)
    : std::runtime_error("the run's trials ran the protocol \"" + name + "\" (hash " + hash +
                         "), which cannot be found: " + reason +
                         "; pass --protocol FILE with the protocol file the run used"),
      name_(std::move(name)),
      hash_(std::move(hash)),
      reason_(std::move(reason)) {}

std::string recordedProtocolHash(const RunSources& sources) {
  if (sources.protocol.empty()) return rwsim::trial::protocolHash(TrialProtocol::lift());
  return sources.protocolHash;
}

TrialProtocol replayProtocol(const RunSources& sources, const fs::path& data,
                             const std::optional<fs::path>& given) {
  const std::string recorded = recordedProtocolHash(sources);
  if (given) {
    TrialProtocol protocol = rwsim::trial::loadTrialProtocol(*given);
    const std::string hash = rwsim::trial::protocolHash(protocol);
    if (hash != recorded) {
      throw std::runtime_error(given->string() + ": the protocol \"" + protocol.name +
                               "\" has hash " + hash + ", but the run's trials ran " +
                               recordedProtocol(sources) +
                               "; replaying with it would draw other trials than the run's");
    }
    return protocol;
  }
  if (sources.protocol.empty()) return TrialProtocol::lift();
  if (sources.protocolHash.empty()) {
    throw ProtocolNotFoundError(sources.protocol, "unknown",
                                "run.csv records its name without its protocol_hash");
  }
  if (!plainName(sources.protocol)) {
    throw ProtocolNotFoundError(sources.protocol, sources.protocolHash,
                                "its name is not a file name of " + (data / "protocols").string());
  }
  const fs::path file = data / "protocols" / (sources.protocol + ".xml");
  std::error_code error;
  if (!fs::is_regular_file(file, error)) {
    throw ProtocolNotFoundError(sources.protocol, sources.protocolHash,
                                file.string() + " does not exist");
  }
  TrialProtocol protocol;
  try {
    protocol = rwsim::trial::loadTrialProtocol(file);
  } catch (const std::exception& e) {
    throw ProtocolNotFoundError(sources.protocol, sources.protocolHash,
                                file.string() + " does not load: " + e.what());
  }
  if (const std::string hash = rwsim::trial::protocolHash(protocol); hash != recorded) {
    throw ProtocolNotFoundError(
        sources.protocol, sources.protocolHash,
        file.string() + " has hash " + hash + " (another protocol of that name)");
  }
  return protocol;
}

}  // namespace visgrab::results
