#include "visgrab/results/run_protocol.hpp"

#include <algorithm>
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

/// The protocol in `file` when it exists, loads and has hash `recorded`; else nothing, and
/// `reason` says which it is not ("F does not exist", "F does not load: ...", "F has hash H
/// (`otherHash`)").
std::optional<TrialProtocol> loadWithHash(const fs::path& file, const std::string& recorded,
                                          const std::string& otherHash, std::string& reason) {
  std::error_code error;
  if (!fs::is_regular_file(file, error)) {
    reason = file.string() + " does not exist";
    return std::nullopt;
  }
  TrialProtocol protocol;
  try {
    protocol = rwsim::trial::loadTrialProtocol(file);
  } catch (const std::exception& e) {
    reason = file.string() + " does not load: " + e.what();
    return std::nullopt;
  }
  if (const std::string hash = rwsim::trial::protocolHash(protocol); hash != recorded) {
    reason = file.string() + " has hash " + hash + " (" + otherHash + ")";
    return std::nullopt;
  }
  return protocol;
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

fs::path namedProtocolFile(const fs::path& data, const std::string& name) {
  return data / "protocols" / (name + ".xml");
}

std::vector<std::string> knownProtocols(const fs::path& data) {
  std::vector<std::string> names;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(data / "protocols", error)) {
    if (entry.path().extension() == ".xml") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
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
  // The data folder's protocol of the recorded name first (where `--protocol NAME` found it),
  // then the file the run was given.
  std::string reason;
  if (plainName(sources.protocol)) {
    const fs::path file = namedProtocolFile(data, sources.protocol);
    if (auto protocol = loadWithHash(file, recorded, "another protocol of that name", reason)) {
      return *protocol;
    }
  } else {
    reason = "its name is not a file name of " + (data / "protocols").string();
  }
  if (!sources.protocolFile.empty()) {
    std::string fileReason;
    if (auto protocol =
            loadWithHash(sources.protocolFile, recorded, "changed since the run", fileReason)) {
      return *protocol;
    }
    reason += ", and the run's protocol file " + fileReason;
  }
  throw ProtocolNotFoundError(sources.protocol, sources.protocolHash, reason);
}

}  // namespace visgrab::results
