// Which settings a saved session must share with the configuration that resumes, localises in
// or merges it (slam/config/config_fingerprint.h), as settings are added over time.
#include "slam/config/config_fingerprint.h"

#include <gtest/gtest.h>

#include <string>

namespace uwbsar {
namespace {

/// `fingerprint` without the line of `key`: a session saved before the key existed.
std::string Without(const std::string& fingerprint, const std::string& key) {
  const std::size_t at = fingerprint.find(key + ": ");
  EXPECT_NE(at, std::string::npos) << key;
  return fingerprint.substr(0, at) + fingerprint.substr(fingerprint.find('\n', at) + 1);
}

TEST(ConfigFingerprintTest, ASettingAddedLaterCountsAsItsDefaultInOlderSessions) {
  SystemConfig config;
  const std::string older = Without(ConfigFingerprint(config), "imaging.coherent_oversampling");
  EXPECT_EQ(FingerprintDifference(older, config), "");
  config.imaging.coherent_oversampling = 8;  // tiles an older session was not made with
  EXPECT_NE(FingerprintDifference(older, config).find("imaging.coherent_oversampling"),
            std::string::npos);
}

TEST(ConfigFingerprintTest, SessionsOfEitherImagingMethodAreReadUnderTheOther) {
  // A session saved while direct was the default, with the ffbp settings of that time, is
  // read under today's defaults (ffbp), and the other way round.
  SystemConfig saved, now;
  saved.imaging.method = ImagingMethod::kDirect;
  saved.imaging.ffbp.levels = 3;
  saved.imaging.ffbp.base_scans = 8;
  now.imaging.method = ImagingMethod::kFfbp;
  EXPECT_EQ(FingerprintDifference(ConfigFingerprint(saved), now), "");
  EXPECT_EQ(FingerprintDifference(ConfigFingerprint(now), saved), "");
  const std::string older_text =
      ConfigFingerprint(saved) + "imaging.method: direct\nimaging.ffbp.angular_oversampling: 12\n";
  EXPECT_EQ(FingerprintDifference(older_text, now), "");
  // What does change tiles still counts.
  now.imaging.pixel_size_m = 0.01;
  EXPECT_NE(FingerprintDifference(ConfigFingerprint(saved), now).find("imaging.pixel_size_m"),
            std::string::npos);
}

}  // namespace
}  // namespace uwbsar
