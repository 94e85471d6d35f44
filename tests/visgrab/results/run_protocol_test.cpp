// replayProtocol: the protocol a run's trials ran, found again for a replay. A lift run replays
// the lift; a run that recorded another protocol replays the data folder's protocol of that name
// when its hash is the recorded one, else the file the run recorded, or a given file with that
// hash; anything else is an error that names the protocol, the hashes and the files.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "rw/common/diagnostic.hpp"
#include "rw/common/text_file.hpp"
#include "support/test_support.hpp"
#include "visgrab/results/run_protocol.hpp"

namespace {

namespace fs = std::filesystem;
using rwsim::trial::protocolHash;
using rwsim::trial::TrialProtocol;
using visgrab::results::ProtocolNotFoundError;
using visgrab::results::replayProtocol;
using visgrab::results::RunSources;

fs::path projectProtocol(const std::string& name) {
  return visgrab::test::sourceDir() / "scenes/protocols" / (name + ".xml");
}

// `text` with its first `from` replaced by `to` (which must be there).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// The sources of a run made with `protocol` (as the runner records it: nothing for the lift).
RunSources ranWith(const TrialProtocol& protocol) {
  RunSources s;
  if (!protocol.isLift()) {
    s.protocol = protocol.name;
    s.protocolHash = protocolHash(protocol);
  }
  return s;
}

// A data folder with the project's protocols and a shake whose shake is 3 cm ("myshake", only
// outside it, as a file of its own).
class RunProtocol : public ::testing::Test {
 protected:
  void SetUp() override {
    data_ = dir_.path() / "data";
    for (const char* name : {"lift", "shake"}) {
      fs::create_directories(data_ / "protocols");
      fs::copy_file(projectProtocol(name), data_ / "protocols" / (std::string(name) + ".xml"));
    }
    custom_ = visgrab::test::writeFile(
        dir_.path() / "elsewhere/my-shake.xml",
        replaced(replaced(rw::common::readTextFileOrThrow(projectProtocol("shake")),
                          "name=\"shake\"", "name=\"myshake\""),
                 "amplitude=\"0.02\"", "amplitude=\"0.03\""));
  }

  visgrab::test::TempDir dir_;
  fs::path data_;
  fs::path custom_;
};

TEST_F(RunProtocol, ALiftRunReplaysTheLiftAndAcceptsOnlyTheLift) {
  const RunSources lift;
  EXPECT_TRUE(replayProtocol(lift, data_).isLift());
  EXPECT_EQ(visgrab::results::recordedProtocolHash(lift), protocolHash(TrialProtocol::lift()));
  // --protocol lift (the data folder's file) is the lift.
  EXPECT_TRUE(replayProtocol(lift, data_, data_ / "protocols/lift.xml").isLift());
  // Another protocol for a lift run: refused, naming the file and both hashes.
  const fs::path shake = data_ / "protocols/shake.xml";
  try {
    replayProtocol(lift, data_, shake);
    ADD_FAILURE() << "a lift run was replayed with the shake";
  } catch (const std::runtime_error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(shake.string()), std::string::npos) << m;
    EXPECT_NE(m.find(protocolHash(rwsim::trial::loadTrialProtocol(shake))), std::string::npos) << m;
    EXPECT_NE(m.find(protocolHash(TrialProtocol::lift())), std::string::npos) << m;
    EXPECT_NE(m.find("the lift protocol"), std::string::npos) << m;
  }
}

TEST_F(RunProtocol, ANamedProtocolIsFoundInTheDataFolderByItsNameAndHash) {
  const TrialProtocol shake = rwsim::trial::loadTrialProtocol(projectProtocol("shake"));
  const RunSources run = ranWith(shake);
  ASSERT_EQ(run.protocol, "shake");
  const TrialProtocol found = replayProtocol(run, data_);
  EXPECT_EQ(found, shake);
  EXPECT_FALSE(found.gravity);
  // Given, with the same hash: a renamed copy of the file does as well.
  const fs::path copy = visgrab::test::writeFile(
      dir_.path() / "copy.xml", rw::common::readTextFileOrThrow(projectProtocol("shake")));
  EXPECT_EQ(replayProtocol(run, data_, copy), shake);
}

TEST_F(RunProtocol, AGivenFileWithAnotherHashIsRefusedNamingBothHashesAndTheFile) {
  const TrialProtocol shake = rwsim::trial::loadTrialProtocol(projectProtocol("shake"));
  const RunSources run = ranWith(shake);
  for (const fs::path& given : {custom_, data_ / "protocols/lift.xml"}) {
    SCOPED_TRACE(given.string());
    try {
      replayProtocol(run, data_, given);
      ADD_FAILURE() << "replayed with another protocol";
    } catch (const std::runtime_error& e) {
      const std::string m = e.what();
      EXPECT_EQ(m.find(given.string() + ": "), 0u) << m;
      EXPECT_NE(m.find("has hash " + protocolHash(rwsim::trial::loadTrialProtocol(given))),
                std::string::npos)
          << m;
      EXPECT_NE(m.find("the protocol \"shake\" (hash " + run.protocolHash + ")"), std::string::npos)
          << m;
      EXPECT_NE(m.find("other trials than the run's"), std::string::npos) << m;
    }
  }
  // A file that does not load is its loader's error (file:line).
  const fs::path broken = visgrab::test::writeFile(dir_.path() / "broken.xml", "<TrialProtocol>");
  EXPECT_THROW(replayProtocol(run, data_, broken), rw::common::LoadError);
}

TEST_F(RunProtocol, ACustomProtocolNeedsItsFile) {
  const TrialProtocol custom = rwsim::trial::loadTrialProtocol(custom_);
  const RunSources run = ranWith(custom);
  ASSERT_EQ(run.protocol, "myshake");
  // Not in the data folder: the error names the protocol and its hash and asks for the file.
  try {
    replayProtocol(run, data_);
    ADD_FAILURE() << "a protocol that is nowhere was found";
  } catch (const ProtocolNotFoundError& e) {
    const std::string m = e.what();
    EXPECT_EQ(e.name(), "myshake");
    EXPECT_EQ(e.hash(), run.protocolHash);
    EXPECT_NE(m.find("\"myshake\" (hash " + run.protocolHash + "), which cannot be found"),
              std::string::npos)
        << m;
    EXPECT_NE(m.find((data_ / "protocols/myshake.xml").string() + " does not exist"),
              std::string::npos)
        << m;
    EXPECT_NE(m.find("pass --protocol FILE"), std::string::npos) << m;
  }
  // Given: found.
  EXPECT_EQ(replayProtocol(run, data_, custom_), custom);

  // In the data folder under its name but with one value changed since: not found, with the
  // file's hash.
  const fs::path changed = visgrab::test::writeFile(
      data_ / "protocols/myshake.xml",
      replaced(rw::common::readTextFileOrThrow(custom_), "cycles=\"2\"", "cycles=\"3\""));
  const std::string changedHash = protocolHash(rwsim::trial::loadTrialProtocol(changed));
  try {
    replayProtocol(run, data_);
    ADD_FAILURE() << "a changed protocol was taken for the run's";
  } catch (const ProtocolNotFoundError& e) {
    EXPECT_EQ(e.reason(),
              changed.string() + " has hash " + changedHash + " (another protocol of that name)");
  }
  // The same values back under that name: found.
  fs::copy_file(custom_, changed, fs::copy_options::overwrite_existing);
  EXPECT_EQ(replayProtocol(run, data_), custom);
}

// A run made with a file of its own outside the data folder records it (protocol_file): the
// replays find the protocol there while the file keeps its values, and say why not otherwise.
TEST_F(RunProtocol, ACustomProtocolIsFoundByTheFileTheRunRecorded) {
  const TrialProtocol custom = rwsim::trial::loadTrialProtocol(custom_);
  RunSources run = ranWith(custom);
  run.protocolFile = custom_;
  EXPECT_EQ(replayProtocol(run, data_), custom);
  // Even when the record's name is no file name of the data folder.
  RunSources odd = run;
  odd.protocol = "../myshake";
  EXPECT_EQ(replayProtocol(odd, data_), custom);

  // The file changed since the run: not found, with both files' reasons.
  const std::string original = rw::common::readTextFileOrThrow(custom_);
  visgrab::test::writeFile(custom_, replaced(original, "cycles=\"2\"", "cycles=\"3\""));
  const std::string changedHash = protocolHash(rwsim::trial::loadTrialProtocol(custom_));
  try {
    replayProtocol(run, data_);
    ADD_FAILURE() << "a changed protocol file was taken for the run's";
  } catch (const ProtocolNotFoundError& e) {
    EXPECT_EQ(e.reason(), (data_ / "protocols/myshake.xml").string() +
                              " does not exist, and the run's protocol file " + custom_.string() +
                              " has hash " + changedHash + " (changed since the run)");
    EXPECT_NE(std::string(e.what()).find("pass --protocol FILE"), std::string::npos) << e.what();
  }
  // Gone: not found either.
  fs::remove(custom_);
  try {
    replayProtocol(run, data_);
    ADD_FAILURE() << "a removed protocol file was found";
  } catch (const ProtocolNotFoundError& e) {
    EXPECT_NE(
        e.reason().find(", and the run's protocol file " + custom_.string() + " does not exist"),
        std::string::npos)
        << e.reason();
  }
  // A copy in the data folder under the recorded name does.
  visgrab::test::writeFile(data_ / "protocols/myshake.xml", original);
  EXPECT_EQ(replayProtocol(run, data_), custom);
}

// The data folder's protocols by name: the rule `--protocol NAME` and the replays share.
TEST_F(RunProtocol, NamedProtocolsAreTheDataFoldersXmlFiles) {
  EXPECT_EQ(visgrab::results::namedProtocolFile(data_, "shake"), data_ / "protocols/shake.xml");
  visgrab::test::writeFile(data_ / "protocols/notes.txt", "not a protocol");
  EXPECT_EQ(visgrab::results::knownProtocols(data_), (std::vector<std::string>{"lift", "shake"}));
  EXPECT_TRUE(visgrab::results::knownProtocols(dir_.path() / "nowhere").empty());
}

TEST_F(RunProtocol, ARecordThatNamesNoFileOfTheDataFolderIsNotFound) {
  RunSources run;
  run.protocol = "../protocols/shake";
  run.protocolHash = protocolHash(rwsim::trial::loadTrialProtocol(projectProtocol("shake")));
  EXPECT_THROW(replayProtocol(run, data_), ProtocolNotFoundError);
  run.protocol = "shake";
  run.protocolHash.clear();
  try {
    replayProtocol(run, data_);
    ADD_FAILURE() << "a record without its hash was trusted";
  } catch (const ProtocolNotFoundError& e) {
    EXPECT_NE(std::string(e.what()).find("without its protocol_hash"), std::string::npos)
        << e.what();
  }
}

}  // namespace
