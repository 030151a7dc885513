#include "drivers/dds/ros2_qos.h"

#include <gtest/gtest.h>

#include "core/errors.h"

namespace uwbsar::dds {
namespace {

TEST(RosTopicNameTest, AbsoluteAndRelativeNamesGetTheRtPrefix) {
  EXPECT_EQ(RosTopicToDds("/odom"), "rt/odom");
  EXPECT_EQ(RosTopicToDds("odom"), "rt/odom");
  EXPECT_EQ(RosTopicToDds("/UWBradar0/readings"), "rt/UWBradar0/readings");
}

TEST(RosTopicNameTest, BadNamesAreInputErrors) {
  EXPECT_THROW(RosTopicToDds(""), InputError);
  EXPECT_THROW(RosTopicToDds("/"), InputError);
  EXPECT_THROW(RosTopicToDds("/odom topic"), InputError);
  EXPECT_THROW(RosTopicToDds("/odom-1"), InputError);
}

TEST(RosTopicNameTest, DdsNamesMapBackOnlyForRosTopics) {
  EXPECT_EQ(DdsTopicToRos("rt/odom"), "/odom");
  EXPECT_EQ(DdsTopicToRos("DCPSPublication"), "");
  EXPECT_EQ(DdsTopicToRos("rq/add_two_intsRequest"), "");
}

TEST(Ros2QosTest, ReliableTransientLocalKeepLastWithXcdr1Only) {
  Qos qos;
  SetRos2Qos(qos.get(), "reliable", 5, Durability::kTransientLocal);
  dds_reliability_kind_t reliability;
  dds_duration_t blocking;
  ASSERT_TRUE(dds_qget_reliability(qos.get(), &reliability, &blocking));
  EXPECT_EQ(reliability, DDS_RELIABILITY_RELIABLE);
  dds_history_kind_t history;
  int32_t depth = 0;
  ASSERT_TRUE(dds_qget_history(qos.get(), &history, &depth));
  EXPECT_EQ(history, DDS_HISTORY_KEEP_LAST);
  EXPECT_EQ(depth, 5);
  dds_durability_kind_t durability;
  ASSERT_TRUE(dds_qget_durability(qos.get(), &durability));
  EXPECT_EQ(durability, DDS_DURABILITY_TRANSIENT_LOCAL);
  uint32_t n = 0;
  dds_data_representation_id_t* ids = nullptr;
  ASSERT_TRUE(dds_qget_data_representation(qos.get(), &n, &ids));
  ASSERT_EQ(n, 1u);
  EXPECT_EQ(ids[0], DDS_DATA_REPRESENTATION_XCDR1);
  dds_free(ids);
}

TEST(Ros2QosTest, BestEffortAndBadSettings) {
  Qos qos;
  SetRos2Qos(qos.get(), "best_effort", 1, Durability::kVolatile);
  dds_reliability_kind_t reliability;
  dds_duration_t blocking;
  ASSERT_TRUE(dds_qget_reliability(qos.get(), &reliability, &blocking));
  EXPECT_EQ(reliability, DDS_RELIABILITY_BEST_EFFORT);
  EXPECT_THROW(SetRos2Qos(qos.get(), "Reliable", 1, Durability::kVolatile), InputError);
  EXPECT_THROW(SetRos2Qos(qos.get(), "reliable", 0, Durability::kVolatile), InputError);
}

}  // namespace
}  // namespace uwbsar::dds
