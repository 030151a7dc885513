// The string modes of the configuration (imaging.mode, backend.robust_loss,
// backend.initialization, compare.align) are enums read and written by their YAML
// names; any other name is refused with the key and the allowed names.
#include <gtest/gtest.h>

#include "app/app_config_io.h"

namespace uwbsar {
namespace {

std::string LoadError(const std::string& yaml) {
  try {
    LoadConfigFromString(yaml, "robot.yaml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ConfigEnumsTest, EachModeIsReadByItsName) {
  const AppConfig c = LoadConfigFromString(
      "imaging:\n  mode: coherent\nbackend:\n  robust_loss: huber\n  initialization: chordal\n"
      "compare:\n  align: origin\n",
      "robot.yaml");
  EXPECT_EQ(c.imaging.mode, ImagingMode::kCoherent);
  EXPECT_TRUE(c.imaging.coherent());
  EXPECT_EQ(c.backend.robust_loss, RobustLoss::kHuber);
  EXPECT_EQ(c.backend.initialization, GraphInitialization::kChordal);
  EXPECT_EQ(c.compare.align, CompareAlign::kOrigin);
  EXPECT_EQ(LoadConfigFromString("backend:\n  robust_loss: none\n", "t.yaml").backend.robust_loss,
            RobustLoss::kNone);
}

TEST(ConfigEnumsTest, DefaultsAreThePaperModes) {
  const AppConfig c;
  EXPECT_EQ(c.imaging.mode, ImagingMode::kPaper);
  EXPECT_EQ(c.backend.robust_loss, RobustLoss::kCauchy);
  EXPECT_EQ(c.backend.initialization, GraphInitialization::kGuess);
  EXPECT_EQ(c.compare.align, CompareAlign::kIcp);
}

TEST(ConfigEnumsTest, AnUnknownNameIsRefusedNamingTheKeyLineAndAllowedNames) {
  const std::string imaging = LoadError("imaging:\n  mode: sharp\n");
  EXPECT_NE(imaging.find("robot.yaml:2"), std::string::npos) << imaging;
  EXPECT_NE(imaging.find("'imaging.mode' must be one of paper, coherent, got 'sharp'"),
            std::string::npos)
      << imaging;
  const std::string loss = LoadError("backend:\n  robust_loss: Cauchy\n");  // names are exact
  EXPECT_NE(loss.find("'backend.robust_loss' must be one of cauchy, huber, none"),
            std::string::npos)
      << loss;
  const std::string init = LoadError("backend:\n  initialization: 1\n");
  EXPECT_NE(init.find("'backend.initialization' must be one of guess, chordal"), std::string::npos)
      << init;
  const std::string align = LoadError("compare:\n  align: [icp]\n");
  EXPECT_NE(align.find("'compare.align' must be one of icp, origin"), std::string::npos) << align;
}

TEST(ConfigEnumsTest, WrittenConfigKeepsTheNamesAndReadsBack) {
  AppConfig c;
  c.imaging.mode = ImagingMode::kCoherent;
  c.backend.robust_loss = RobustLoss::kNone;
  c.backend.initialization = GraphInitialization::kChordal;
  c.compare.align = CompareAlign::kOrigin;
  const std::string yaml = ConfigToYaml(c);
  EXPECT_NE(yaml.find("mode: coherent"), std::string::npos);
  EXPECT_NE(yaml.find("robust_loss: none"), std::string::npos);
  EXPECT_NE(yaml.find("initialization: chordal"), std::string::npos);
  EXPECT_NE(yaml.find("align: origin"), std::string::npos);
  EXPECT_EQ(ConfigToYaml(LoadConfigFromString(yaml, "written.yaml")), yaml);
}

TEST(ConfigEnumsTest, NameListsFollowTheTables) {
  EXPECT_EQ(EnumNameList<ImagingMode>(), "paper, coherent");
  EXPECT_STREQ(EnumName(RobustLoss::kHuber), "huber");
  RobustLoss loss = RobustLoss::kCauchy;
  EXPECT_FALSE(EnumFromName("HUBER", &loss));
  EXPECT_EQ(loss, RobustLoss::kCauchy);  // unchanged on an unknown name
}

}  // namespace
}  // namespace uwbsar
