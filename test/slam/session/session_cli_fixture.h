// The session CLI tests' fixture: three short simulated runs in the bundled seed_hall room
// (a: depart 3 m and return; b: a revisit of a's corridor from another start; c: another
// scene, which no loop connects to a) and each mapped once into map_<name>.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "test/cli_runner.h"

namespace uwbsar::testing {

namespace fs = std::filesystem;

inline nlohmann::json Json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

inline int Lines(const std::string& text) {
  int n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

/// A copy of the folder `from` (a saved map) at `to`, replacing what was there; returns `to`.
inline std::string CopyOf(const std::string& from, const std::string& to) {
  fs::remove_all(to);
  fs::copy(from, to, fs::copy_options::recursive);
  return to;
}

class SessionCliTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new std::string(
        (fs::temp_directory_path() / ("uwbsar_session_cli_" + std::to_string(::getpid())))
            .string());
    fs::remove_all(*dir_);
    fs::create_directories(*dir_);
    const std::string hall =
        std::string(UWBSAR_SOURCE_DIR) + "/config/maps/seed_hall/seed_hall.yaml";
    std::ofstream(*dir_ + "/a.yaml") << "simulator:\n  route:\n    depart_distance_m: 3.0\n";
    std::ofstream(*dir_ + "/b.yaml")
        << "simulator:\n  route:\n    depart_distance_m: 2.0\n    start_x_m: 1.0\n"
           "    start_yaw_deg: 15.0\n";
    for (const auto& [name, args] : std::vector<std::pair<std::string, std::string>>{
             {"a", "--config " + *dir_ + "/a.yaml simulate --seed 1"},
             {"b", "--config " + *dir_ + "/b.yaml simulate --scene-seed 1 --seed 2"},
             {"c", "--config " + *dir_ + "/a.yaml simulate --scene-seed 7 --seed 3"}}) {
      const CliRun r =
          Uwbsar(args + " --map " + hall + " --route depart-return --out " + Bag(name));
      ASSERT_EQ(r.exit_code, 0) << r.output;
    }
    for (const std::string name : {"a", "b", "c"}) {
      const CliRun r = Uwbsar("-q map " + Bag(name) + " --out " + *dir_ + "/map_" + name);
      ASSERT_EQ(r.exit_code, 0) << r.output;
    }
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
    dir_ = nullptr;
  }
  static std::string Bag(const std::string& name) { return *dir_ + "/bag_" + name; }
  static std::string Map(const std::string& name) { return *dir_ + "/map_" + name; }
  static std::string* dir_;
};
inline std::string* SessionCliTest::dir_ = nullptr;

}  // namespace uwbsar::testing
