#include "drivers/dds/participant.h"

#include <gtest/gtest.h>

#include "core/errors.h"
#include "drivers/dds/dds_check.h"
#include "test/drivers/dds/dds_test_util.h"

namespace uwbsar::dds {
namespace {

TEST(ResolveDomainIdTest, ConfiguredIdWinsOverEnvironment) {
  EXPECT_EQ(ResolveDomainId(7, "12"), 7);
}

TEST(ResolveDomainIdTest, UnsetOrEmptyEnvironmentMeansDomainZero) {
  EXPECT_EQ(ResolveDomainId(-1, nullptr), 0);
  EXPECT_EQ(ResolveDomainId(-1, ""), 0);
}

TEST(ResolveDomainIdTest, EnvironmentUsedWhenConfigIsMinusOne) {
  EXPECT_EQ(ResolveDomainId(-1, "42"), 42);
}

TEST(ResolveDomainIdTest, NonNumericEnvironmentIsInputErrorNamingTheVariable) {
  try {
    ResolveDomainId(-1, "robot7");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("ROS_DOMAIN_ID: 'robot7'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ResolveDomainId(-1, "3x"), InputError);
  EXPECT_THROW(ResolveDomainId(-1, "-2"), InputError);
}

TEST(ResolveDomainIdTest, IdsBeyondThePortRangeAreRejected) {
  EXPECT_EQ(ResolveDomainId(-1, "232"), 232);
  EXPECT_THROW(ResolveDomainId(-1, "233"), InputError);
  EXPECT_THROW(ResolveDomainId(300, nullptr), InputError);
}

TEST(CycloneXmlConfigTest, LoopbackUsesUnicastDiscoveryWithoutMulticast) {
  const std::string xml = CycloneXmlConfig("lo", 12);
  EXPECT_NE(xml.find("<NetworkInterface name=\"lo\"/>"), std::string::npos);
  EXPECT_NE(xml.find("<AllowMulticast>false</AllowMulticast>"), std::string::npos);
  EXPECT_NE(xml.find("<Peer address=\"127.0.0.1\"/>"), std::string::npos);
  EXPECT_NE(xml.find("<MaxAutoParticipantIndex>12</MaxAutoParticipantIndex>"), std::string::npos);
}

TEST(CycloneXmlConfigTest, OtherInterfacesKeepMulticastDiscovery) {
  const std::string xml = CycloneXmlConfig("eth0");
  EXPECT_NE(xml.find("<NetworkInterface name=\"eth0\"/>"), std::string::npos);
  EXPECT_EQ(xml.find("AllowMulticast"), std::string::npos);
  EXPECT_EQ(xml.find("Peer"), std::string::npos);
}

TEST(ParticipantTest, JoinsTheConfiguredDomainOnLoopback) {
  const DdsConfig config = testing::LoopbackConfig();
  Participant participant(config);
  EXPECT_GT(participant.handle(), 0);
  EXPECT_EQ(participant.domain_id(), config.domain_id);
  dds_domainid_t id = 0;
  ASSERT_EQ(dds_get_domainid(participant.handle(), &id), DDS_RETCODE_OK);
  EXPECT_EQ(static_cast<int>(id), config.domain_id);
}

TEST(ParticipantTest, ParticipantsOfOneProcessShareTheDomainAndOutliveEachOther) {
  const DdsConfig config = testing::LoopbackConfig();
  auto first = std::make_unique<Participant>(config);
  Participant second(config);
  first.reset();  // the domain must stay while `second` uses it
  dds_domainid_t id = 0;
  EXPECT_EQ(dds_get_domainid(second.handle(), &id), DDS_RETCODE_OK);
  Participant third(config);
  EXPECT_GT(third.handle(), 0);
}

TEST(ParticipantTest, UnknownInterfaceIsDdsErrorNamingTheCall) {
  DdsConfig config = testing::LoopbackConfig();
  config.domain_id = (config.domain_id % 230) + 1;  // a domain no other test here creates
  config.network_interface = "nosuchif0";
  try {
    Participant participant(config);
    FAIL() << "no error";
  } catch (const DdsError& e) {
    EXPECT_NE(std::string(e.what()).find("dds_create_domain"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace uwbsar::dds
