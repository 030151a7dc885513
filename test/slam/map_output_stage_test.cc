// slam::MapOutputStage::CommitWritten (the outputs of `map --resume` and `merge`): the files a
// writer stages are committed as one set; a writer that fails leaves the folder as it was.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>

#include "slam/outputs/map_outputs.h"

namespace uwbsar::tools {
namespace {

namespace fs = std::filesystem;

void Write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

/// Every entry of `dir` with its contents ("<dir>" for folders).
std::map<std::string, std::string> Listing(const std::string& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().filename() == kFolderLockName) continue;  // the folder's lock, not an output
    std::ostringstream text;
    if (e.is_directory()) {
      text << "<dir>";
    } else {
      text << std::ifstream(e.path()).rdbuf();
    }
    out[e.path().filename().string()] = text.str();
  }
  return out;
}

class MapOutputStageTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = (fs::temp_directory_path() /
            ("uwbsar_stage_" + std::to_string(::getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name()))
               .string();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // An earlier plain `map` run's outputs, a stale joined run and a user's file.
    for (const char* name : {"trajectory.tum", "odometry.tum", "loops.csv", "map.png",
                             "session.uwbsar", "trajectory_7.tum", "summary.json"}) {
      Write(dir_ + "/" + name, std::string("old ") + name);
    }
    Write(dir_ + "/notes.txt", "mine");
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string dir_;
};

TEST_F(MapOutputStageTest, AWriterThatFailsLeavesTheFolderAsItWas) {
  const auto before = Listing(dir_);
  {
    slam::MapOutputStage stage(dir_);
    EXPECT_THROW(stage.CommitWritten([](const std::string& stage_dir) -> std::vector<std::string> {
      Write(stage_dir + "/map.png", "new");
      Write(stage_dir + "/trajectory_0.tum", "new");
      throw std::runtime_error("disk full");
    }),
                 std::runtime_error);
  }
  EXPECT_EQ(Listing(dir_), before);  // the staging folder is gone too
}

TEST_F(MapOutputStageTest, CommittedFilesReplaceAnEarlierRunsOutputsAsOneSet) {
  std::vector<std::string> files;
  {
    slam::MapOutputStage stage(dir_);
    files = stage.CommitWritten([](const std::string& stage_dir) {
      for (const char* name :
           {"map.png", "trajectory_0.tum", "trajectory_1.tum", "session.uwbsar", "summary.json"}) {
        Write(stage_dir + "/" + name, std::string("new ") + name);
      }
      return std::vector<std::string>{"map.png", "trajectory_0.tum", "trajectory_1.tum",
                                      "session.uwbsar", "summary.json"};
    });
  }
  ASSERT_EQ(files.size(), 5u);
  EXPECT_EQ(fs::path(files.back()).filename(), "summary.json");
  const std::map<std::string, std::string> expected = {{"map.png", "new map.png"},
                                                       {"trajectory_0.tum", "new trajectory_0.tum"},
                                                       {"trajectory_1.tum", "new trajectory_1.tum"},
                                                       {"session.uwbsar", "new session.uwbsar"},
                                                       {"summary.json", "new summary.json"},
                                                       {"notes.txt", "mine"}};
  EXPECT_EQ(Listing(dir_), expected);
}

}  // namespace
}  // namespace uwbsar::tools
