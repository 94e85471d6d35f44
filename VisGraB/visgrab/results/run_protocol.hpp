#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "rwsim/trial/trial_protocol.hpp"
#include "visgrab/results/trial_record.hpp"

/// The trial protocol a run's trials ran, found again for the replays that draw them (`visgrab
/// render --results`, the report's pictures, the viewer; docs/protocols.md, "Replays").
namespace visgrab::results {

/// The run recorded a protocol (name and hash) that is neither given nor a protocol of that
/// name and hash in the data folder, nor the file the run recorded. what() says so and asks for
/// `--protocol FILE`.
class ProtocolNotFoundError : public std::runtime_error {
 public:
  /// `name` and `hash` as run.csv records them; `reason` why the data folder's file does not do.
  ProtocolNotFoundError(std::string name, std::string hash, std::string reason);
  /// The recorded protocol's name.
  const std::string& name() const { return name_; }
  /// The recorded protocol's hash (rwsim::trial::protocolHash).
  const std::string& hash() const { return hash_; }
  /// Why the data folder's protocol of that name does not do: "DATA/protocols/NAME.xml does
  /// not exist", "... has hash H (another protocol of that name)", "... does not load: ...";
  /// for a run that recorded its protocol file, followed by why that does not do either (",
  /// and the run's protocol file F does not exist", "... has hash H (changed since the run)").
  const std::string& reason() const { return reason_; }

 private:
  std::string name_;
  std::string hash_;
  std::string reason_;
};

/// Where a protocol named `name` lives in the data folder `data`: `data`/protocols/`name`.xml
/// (`--protocol NAME`, Python's run(protocol=NAME) and the replays all look there).
std::filesystem::path namedProtocolFile(const std::filesystem::path& data, const std::string& name);

/// The names of the protocols in `data`/protocols (its `*.xml` files without the extension),
/// sorted; none when the folder is missing.
std::vector<std::string> knownProtocols(const std::filesystem::path& data);

/// The hash of the protocol `sources` records: its protocol_hash, or for a run without a
/// protocol record (the default) the lift's.
std::string recordedProtocolHash(const RunSources& sources);

/// The protocol to replay the trials of a run with `sources` (the one the trials ran):
///  - `given` (`--protocol`, a file) when its rwsim::trial::protocolHash is the recorded one;
///  - without `given`: the lift for a run that recorded no protocol; else namedProtocolFile(
///    `data`, NAME) (NAME the recorded name: a named protocol, as `--protocol NAME` finds it) when
///    its hash is the recorded one; else the file the run recorded (RunSources::protocolFile,
///    the `--protocol FILE` it was given) when it still has that hash.
/// @throws std::runtime_error naming the file and both hashes when `given` has another hash;
/// ProtocolNotFoundError when the recorded protocol is not found; rw::common::LoadError when
/// `given` does not load.
rwsim::trial::TrialProtocol replayProtocol(
    const RunSources& sources, const std::filesystem::path& data,
    const std::optional<std::filesystem::path>& given = std::nullopt);

}  // namespace visgrab::results
