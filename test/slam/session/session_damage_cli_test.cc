// A saved map whose file was damaged or edited is refused by every command that reads it,
// naming the file, table, row and column, and stays byte for byte as it was (issue 45): a run's
// fingerprint emptied (the join would count the recording twice), bytes flipped inside a
// tile's zstd body (the map would be silently wrong).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "test/cli_runner.h"
#include "test/slam/session/session_cli_fixture.h"
#include "test/slam/session/sqlite_edit.h"

namespace uwbsar {
namespace {

namespace fs = std::filesystem;
using testing::CliRun;
using testing::CopyOf;
using testing::RunCommand;
using testing::SessionCliTest;
using testing::Uwbsar;

/// sha256sum of every file of the map folder `dir` (not its hidden lock file).
std::string Sha256s(const std::string& dir) {
  return RunCommand("cd '" + dir + "' && sha256sum *").output;
}

/// `command` is refused (exit 3, one line holding `expected`) and leaves `map` as it was.
void ExpectRefusedAndUnchanged(const std::string& command, const std::string& map,
                               const std::string& expected) {
  const std::string before = Sha256s(map);
  ASSERT_NE(before.find("session.uwbsar"), std::string::npos) << before;
  const CliRun r = Uwbsar(command);
  EXPECT_EQ(r.exit_code, 3) << command << "\n" << r.output;
  EXPECT_NE(r.output.find(expected), std::string::npos) << command << "\n" << r.output;
  EXPECT_EQ(testing::Lines(r.output), 1) << r.output;
  EXPECT_EQ(Sha256s(map), before) << command;
}

TEST_F(SessionCliTest, ARunWithoutItsFingerprintRefusesTheJoinNamingTheRow) {
  for (const std::string value : {"NULL", "''"}) {
    const std::string map = CopyOf(Map("a"), *dir_ + "/no_fingerprint");
    const std::string session = map + "/session.uwbsar";
    testing::RunSql(session, "UPDATE trajectories SET fingerprint = " + value);
    const std::string where = session + ": trajectories row 1: fingerprint is ";
    const std::string what = value == "NULL" ? "NULL" : "empty";
    // The same recording again: without its fingerprint it would count as a new run.
    ExpectRefusedAndUnchanged("map " + Bag("a") + " --resume " + map + " --out " + map, map,
                              where + what);
    ExpectRefusedAndUnchanged("merge " + map + " " + Map("a") + " --out " + *dir_ + "/nf_merge",
                              map, where + what);
    EXPECT_FALSE(fs::exists(*dir_ + "/nf_merge/summary.json"));
  }
}

TEST_F(SessionCliTest, BytesFlippedInATileAreRefusedNamingTheKeyframe) {
  const std::string map = CopyOf(Map("a"), *dir_ + "/flipped_tile");
  const std::string session = map + "/session.uwbsar";
  const std::string id = testing::SqlText(session, "SELECT min(id) FROM keyframes");
  ASSERT_FALSE(id.empty());
  testing::FlipBlobBytes(session, "keyframes", "tile", std::stoll(id), 10);
  const std::string expected = session + ": keyframes row 1: tile of keyframe " + id +
                               " does not match its checksum tile_xxh3";
  ExpectRefusedAndUnchanged(
      "localize " + Bag("b") + " --map " + map + " --out " + *dir_ + "/flipped_loc", map, expected);
  ExpectRefusedAndUnchanged("merge " + Map("b") + " " + map + " --out " + *dir_ + "/flipped_m", map,
                            expected);
  EXPECT_FALSE(fs::exists(*dir_ + "/flipped_m/summary.json"));
}

}  // namespace
}  // namespace uwbsar
