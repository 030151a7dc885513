// place_recognition.validation.detectors (issue 27): the paper's AKAZE+ORB by default; any two
// distinct detectors this build has, else a ConfigError naming the key (and for an unknown name
// its index and the allowed names).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "app/app_config_io.h"
#include "slam/app_config.h"

namespace uwbsar {
namespace {

/// The message of the ConfigError that loading `yaml` throws ("" when none).
std::string ConfigErrorOf(const std::string& yaml) {
  try {
    LoadConfigFromString(yaml, "pair.yaml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(PlaceRecognitionDetectorPairTest, DefaultIsThePapersAkazeAndOrb) {
  const Config c;
  const std::vector<DetectorKind> paper = {DetectorKind::kAkaze, DetectorKind::kOrb};
  EXPECT_EQ(c.place_recognition.validation.detectors, paper);
}

TEST(PlaceRecognitionDetectorPairTest, TheKeyNeedsTwoDistinctKnownDetectors) {
  const std::string key = "place_recognition.validation.detectors";
  auto yaml = [](const std::string& list) {
    return "place_recognition:\n  validation:\n    detectors: " + list + "\n";
  };
  EXPECT_EQ(ConfigErrorOf(yaml("[brisk, orb]")), "");
  EXPECT_NE(ConfigErrorOf(yaml("[akaze]")).find(key), std::string::npos);
  EXPECT_NE(ConfigErrorOf(yaml("[akaze, orb, brisk]")).find(key), std::string::npos);
  EXPECT_NE(ConfigErrorOf(yaml("[orb, orb]")).find(key), std::string::npos);
  const std::string unknown = ConfigErrorOf(yaml("[akaze, kaze]"));
  EXPECT_NE(unknown.find(key + "[1]"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("sift, surf, brisk, akaze, orb"), std::string::npos) << unknown;
}

}  // namespace
}  // namespace uwbsar
