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
  const std::string older = Without(ConfigFingerprint(config), "imaging.method");
  EXPECT_EQ(FingerprintDifference(older, config), "");
  config.imaging.method = ImagingMethod::kFfbp;  // tiles an older session was not made with
  EXPECT_NE(FingerprintDifference(older, config).find("imaging.method"), std::string::npos);
}

TEST(ConfigFingerprintTest, FfbpSettingsMatterOnlyWhenFfbpMakesTheTiles) {
  SystemConfig saved, now;
  now.imaging.ffbp.levels = 2;
  EXPECT_EQ(FingerprintDifference(ConfigFingerprint(saved), now), "");
  saved.imaging.method = now.imaging.method = ImagingMethod::kFfbp;
  EXPECT_NE(FingerprintDifference(ConfigFingerprint(saved), now).find("imaging.ffbp.levels"),
            std::string::npos);
  now.imaging.method = ImagingMethod::kDirect;
  EXPECT_NE(FingerprintDifference(ConfigFingerprint(saved), now).find("imaging.method"),
            std::string::npos);
}

}  // namespace
}  // namespace uwbsar
