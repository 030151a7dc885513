// Test helpers for the rosbag suite: the fixture content of
// test/data/bags/fixture_data.py in C++, a checker that a bag holds exactly that
// content, a writer that records it with our BagWriter, and the Python venv.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/types.h"
#include "drivers/rosbag/bag_writer.h"
#include "drivers/rosbag/ros_messages.h"

namespace uwbsar::rosbag::testing {

inline constexpr TimestampNs kT0 = 1700000000000000000;
inline constexpr int kNumScans = 8, kNumSamples = 64, kNumOdom = 10, kNumGroundTruth = 5;
inline constexpr int kNumLaser = 2, kNumTf = 2, kNumChatter = 3;
inline constexpr int kNumMessages =
    2 * kNumScans + kNumOdom + kNumGroundTruth + kNumLaser + kNumTf + kNumChatter;

TimestampNs RadarTime(int sensor, int k);
std::vector<float> RadarSamples(int sensor, int k);
TimestampNs OdomTime(int i);
Pose2 OdomPose(int i);
TimestampNs GroundTruthTime(int j);
Pose2 GroundTruthPose(int j);

std::string SourceDir();
std::string FixtureDir();  ///< test/data/bags
/// A fresh empty folder under the system temp dir, removed by the destructor.
struct TempDir {
  TempDir();
  ~TempDir();
  std::string path;
};

/// Checks with gtest expectations that the bag at `path` decodes to exactly the
/// fixture content (every float and pose bit for bit, order, counts, skipped types).
void ExpectFixtureContent(const std::string& path);
/// Writes the fixture content with our BagWriter.
void WriteFixtureBag(const std::string& dir, const BagWriterOptions& options);

/// $UWBSAR_VENV/bin/python, or empty when UWBSAR_VENV is unset.
std::string VenvPython();
/// Runs a command, returning its exit status and (in `output`) stdout+stderr.
int RunCommand(const std::string& command, std::string* output);

}  // namespace uwbsar::rosbag::testing
