// Ros2Subscriber against in-process DDS writers (a second participant on the
// loopback domain): decoded values, events for publishers leaving and returning,
// silent topics, duplicate/out-of-order odometry, unusable samples, wrong types and
// incompatible QoS.
#include "drivers/dds/ros2_subscriber.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/errors.h"
#include "drivers/dds/dds_check.h"
#include "drivers/dds/ros2_convert.h"
#include "drivers/dds/ros2_qos.h"
#include "drivers/dds/ros2_types.h"
#include "test/drivers/dds/dds_test_util.h"

namespace uwbsar::dds {
namespace {

using testing::WaitFor;

// A typed writer on a ROS 2 topic in `participant`.
class Writer {
 public:
  Writer(const Participant& participant, const dds_topic_descriptor_t* desc,
         const std::string& ros_topic, const std::string& reliability = "reliable") {
    Qos qos;
    SetRos2Qos(qos.get(), reliability, 10, Durability::kVolatile);
    topic_ = Check(dds_create_topic(participant.handle(), desc, RosTopicToDds(ros_topic).c_str(),
                                    nullptr, nullptr),
                   "dds_create_topic");
    writer_ = Check(dds_create_writer(participant.handle(), topic_, qos.get(), nullptr),
                    "dds_create_writer");
  }
  ~Writer() {
    dds_delete(writer_);
    dds_delete(topic_);
  }
  void Write(const void* sample, dds_time_t source_time = 0) {
    Check(source_time ? dds_write_ts(writer_, sample, source_time) : dds_write(writer_, sample),
          "dds_write");
  }
  int Matched() const {
    dds_publication_matched_status_t s;
    dds_get_publication_matched_status(writer_, &s);
    return static_cast<int>(s.current_count);
  }

 private:
  dds_entity_t topic_ = 0, writer_ = 0;
};

nav_msgs_msg_dds__Odometry_ Odometry(TimestampNs stamp, double x, double y, double yaw) {
  nav_msgs_msg_dds__Odometry_ msg{};
  msg.header_.stamp_ = NsToStamp(stamp);
  msg.header_.frame_id_ = const_cast<char*>("odom");
  msg.child_frame_id_ = const_cast<char*>("base_footprint");
  msg.pose_.pose_ = PoseToDds({x, y, yaw});
  msg.twist_.twist_.linear_.x_ = 0.4;
  msg.twist_.twist_.angular_.z_ = 0.05;
  return msg;
}

class Ros2SubscriberTest : public testing::CollectingSubscriberTest {
 protected:
  void Subscribe(const std::vector<std::string>& radar, const std::string& odom) {
    SubscribeOn(ours_, config_, radar, odom);
  }

  DdsConfig config_ = testing::LoopbackConfig();
  Participant ours_{config_};
  Participant robot_{config_};
};

TEST_F(Ros2SubscriberTest, RadarScansArriveWithSensorIndexSamplesAndSourceStamp) {
  Subscribe({"/UWBradar0/readings", "/UWBradar1/readings"}, "/odom");
  Writer radar1(robot_, &std_msgs_msg_dds__Float32MultiArray__desc, "/UWBradar1/readings");
  ASSERT_TRUE(WaitFor([&] { return radar1.Matched() > 0; }));
  std::vector<float> data = {0.5f, -1.25f, 3.0f};
  std_msgs_msg_dds__Float32MultiArray_ msg{};
  msg.data_._buffer = data.data();
  msg.data_._length = msg.data_._maximum = 3;
  radar1.Write(&msg, 1700000000000000123LL);
  ASSERT_TRUE(WaitFor([&] { return NumRadar() == 1; }));
  EXPECT_EQ(radar_[0].scan.sensor_id, 1);
  EXPECT_EQ(radar_[0].scan.samples, data);
  EXPECT_EQ(radar_[0].scan.stamp_ns, 1700000000000000123LL);
  EXPECT_TRUE(radar_[0].in_order);
  EXPECT_GT(radar_[0].reception_ns, 0);
  EXPECT_EQ(subscriber_->MatchedPublishers("/UWBradar1/readings"), 1);
  EXPECT_EQ(subscriber_->MatchedPublishers("/UWBradar0/readings"), 0);
  EXPECT_EQ(subscriber_->Stats().radar_samples, 1u);
  EXPECT_EQ(events_.Detail(DdsEventKind::kPublisherMatched),
            "publisher of /UWBradar1/readings found");
}

TEST_F(Ros2SubscriberTest, OdometryDecodesPoseVelocitiesFramesAndStamps) {
  Subscribe({}, "/odom");
  Writer odom(robot_, &nav_msgs_msg_dds__Odometry__desc, "/odom");
  ASSERT_TRUE(WaitFor([&] { return odom.Matched() > 0; }));
  const auto msg = Odometry(1234500000000LL, 1.5, -0.5, 0.75);
  odom.Write(&msg, 99000000000LL);
  ASSERT_TRUE(WaitFor([&] { return NumOdometry() == 1; }));
  const OdometryMessage& m = odometry_[0];
  EXPECT_EQ(m.sample.stamp_ns, 1234500000000LL);
  EXPECT_EQ(m.source_stamp_ns, 99000000000LL);
  EXPECT_DOUBLE_EQ(m.sample.T_world_robot.x_m, 1.5);
  EXPECT_DOUBLE_EQ(m.sample.T_world_robot.y_m, -0.5);
  EXPECT_NEAR(m.sample.T_world_robot.yaw_rad, 0.75, 1e-12);
  EXPECT_DOUBLE_EQ(m.sample.linear_velocity_mps, 0.4);
  EXPECT_DOUBLE_EQ(m.sample.angular_velocity_radps, 0.05);
  EXPECT_EQ(m.frame_id, "odom");
  EXPECT_EQ(m.child_frame_id, "base_footprint");
  EXPECT_TRUE(m.in_order);
}

TEST_F(Ros2SubscriberTest, DuplicateAndOutOfOrderOdometryIsFlaggedCountedAndStillDelivered) {
  Subscribe({}, "/odom");
  Writer odom(robot_, &nav_msgs_msg_dds__Odometry__desc, "/odom");
  ASSERT_TRUE(WaitFor([&] { return odom.Matched() > 0; }));
  for (const TimestampNs t : {100LL, 200LL, 200LL, 150LL, 300LL}) {
    const auto msg = Odometry(t * 1000000, 0, 0, 0);
    odom.Write(&msg);
  }
  ASSERT_TRUE(WaitFor([&] { return NumOdometry() == 5; }));
  std::vector<bool> in_order;
  for (const auto& m : odometry_) in_order.push_back(m.in_order);
  EXPECT_EQ(in_order, (std::vector<bool>{true, true, false, false, true}));
  EXPECT_EQ(events_.Count(DdsEventKind::kDuplicate), 1);
  EXPECT_EQ(events_.Count(DdsEventKind::kOutOfOrder), 1);
  EXPECT_NE(events_.Detail(DdsEventKind::kOutOfOrder).find("on /odom"), std::string::npos);
  const Ros2SubscriberStats stats = subscriber_->Stats();
  EXPECT_EQ(stats.odometry_samples, 5u);
  EXPECT_EQ(stats.events[static_cast<int>(DdsEventKind::kOutOfOrder)], 1u);
}

TEST_F(Ros2SubscriberTest, UnusableOdometryIsReportedNotDelivered) {
  Subscribe({}, "/odom");
  Writer odom(robot_, &nav_msgs_msg_dds__Odometry__desc, "/odom");
  ASSERT_TRUE(WaitFor([&] { return odom.Matched() > 0; }));
  auto nan = Odometry(1000, 0, 0, 0);
  nan.pose_.pose_.position_.x_ = std::numeric_limits<double>::quiet_NaN();
  odom.Write(&nan);
  const auto good = Odometry(2000, 1, 1, 0);
  odom.Write(&good);
  ASSERT_TRUE(WaitFor([&] { return NumOdometry() == 1; }));
  EXPECT_EQ(odometry_[0].sample.stamp_ns, 2000);
  EXPECT_EQ(events_.Count(DdsEventKind::kInvalidSample), 1);
}

TEST_F(Ros2SubscriberTest, PublisherGoneAndBackAreReported) {
  Subscribe({}, "/odom");
  auto odom = std::make_unique<Writer>(robot_, &nav_msgs_msg_dds__Odometry__desc, "/odom");
  ASSERT_TRUE(WaitFor([&] { return events_.Count(DdsEventKind::kPublisherMatched) == 1; }));
  odom.reset();
  ASSERT_TRUE(WaitFor([&] { return events_.Count(DdsEventKind::kPublisherGone) == 1; }));
  EXPECT_EQ(events_.Detail(DdsEventKind::kPublisherGone), "publisher of /odom gone");
  EXPECT_EQ(subscriber_->MatchedPublishers("/odom"), 0);
  odom = std::make_unique<Writer>(robot_, &nav_msgs_msg_dds__Odometry__desc, "/odom");
  ASSERT_TRUE(WaitFor([&] { return events_.Count(DdsEventKind::kPublisherBack) == 1; }));
  EXPECT_EQ(events_.Detail(DdsEventKind::kPublisherBack), "publisher of /odom back");
  EXPECT_EQ(events_.Count(DdsEventKind::kPublisherMatched), 1);
}

TEST_F(Ros2SubscriberTest, MatchedTopicWithoutSamplesIsReportedSilentThenResumed) {
  config_.silence_timeout_s = 0.2;
  Subscribe({"/UWBradar0/readings"}, "");
  Writer radar(robot_, &std_msgs_msg_dds__Float32MultiArray__desc, "/UWBradar0/readings");
  ASSERT_TRUE(WaitFor([&] { return events_.Count(DdsEventKind::kTopicSilent) == 1; }, 5.0));
  EXPECT_EQ(events_.Detail(DdsEventKind::kTopicSilent),
            "no sample on /UWBradar0/readings for 0.2 s");
  float value = 1.0f;
  std_msgs_msg_dds__Float32MultiArray_ msg{};
  msg.data_._buffer = &value;
  msg.data_._length = msg.data_._maximum = 1;
  radar.Write(&msg);
  ASSERT_TRUE(WaitFor([&] { return events_.Count(DdsEventKind::kTopicResumed) == 1; }));
}

TEST_F(Ros2SubscriberTest, WriterWithAnotherTypeOnOurTopicIsReported) {
  Subscribe({}, "/odom");
  Writer wrong(robot_, &geometry_msgs_msg_dds__PoseStamped__desc, "/odom");
  ASSERT_TRUE(WaitFor([&] { return events_.Count(DdsEventKind::kWrongType) == 1; }));
  EXPECT_EQ(events_.Detail(DdsEventKind::kWrongType),
            "topic /odom published with type geometry_msgs::msg::dds_::PoseStamped_, expected "
            "nav_msgs::msg::dds_::Odometry_");
  EXPECT_EQ(subscriber_->MatchedPublishers("/odom"), 0);
}

TEST_F(Ros2SubscriberTest, BestEffortPublisherAgainstReliableSubscriptionIsIncompatibleQos) {
  Subscribe({}, "/odom");
  Writer best_effort(robot_, &nav_msgs_msg_dds__Odometry__desc, "/odom", "best_effort");
  ASSERT_TRUE(WaitFor([&] { return events_.Count(DdsEventKind::kIncompatibleQos) >= 1; }));
  EXPECT_NE(events_.Detail(DdsEventKind::kIncompatibleQos).find("reliability"), std::string::npos)
      << events_.Detail(DdsEventKind::kIncompatibleQos);
}

TEST_F(Ros2SubscriberTest, BestEffortSubscriptionTakesBestEffortPublisher) {
  config_.reliability = "best_effort";
  Subscribe({}, "/odom");
  Writer best_effort(robot_, &nav_msgs_msg_dds__Odometry__desc, "/odom", "best_effort");
  ASSERT_TRUE(WaitFor([&] { return best_effort.Matched() > 0; }));
  const auto msg = Odometry(5, 0, 0, 0);
  best_effort.Write(&msg);
  EXPECT_TRUE(WaitFor([&] { return NumOdometry() == 1; }));
}

TEST_F(Ros2SubscriberTest, StopEndsCallbacksAndIsIdempotent) {
  Subscribe({}, "/odom");
  Writer odom(robot_, &nav_msgs_msg_dds__Odometry__desc, "/odom");
  ASSERT_TRUE(WaitFor([&] { return odom.Matched() > 0; }));
  subscriber_->Stop();
  subscriber_->Stop();
  const auto msg = Odometry(5, 0, 0, 0);
  odom.Write(&msg);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_EQ(NumOdometry(), 0u);
}

TEST_F(Ros2SubscriberTest, ThrowingCallbackIsCountedAndTheThreadGoesOn) {
  Ros2Subscriber::Callbacks callbacks;
  std::atomic<int> calls{0};
  callbacks.on_odometry = [&](OdometryMessage&&) {
    ++calls;
    throw std::runtime_error("caller bug");
  };
  Ros2Subscriber subscriber(ours_, config_, {}, "/odom", callbacks);
  Writer odom(robot_, &nav_msgs_msg_dds__Odometry__desc, "/odom");
  ASSERT_TRUE(WaitFor([&] { return odom.Matched() > 0; }));
  for (const TimestampNs t : {1LL, 2LL}) {
    const auto msg = Odometry(t, 0, 0, 0);
    odom.Write(&msg);
  }
  ASSERT_TRUE(WaitFor([&] { return calls == 2; }));
  EXPECT_EQ(subscriber.Stats().callback_exceptions, 2u);
}

TEST_F(Ros2SubscriberTest, RepeatedOrBadTopicNamesAreInputErrors) {
  EXPECT_THROW(Subscribe({"/radar", "/radar"}, "/odom"), InputError);
  EXPECT_THROW(Subscribe({"/radar"}, "/radar"), InputError);
  EXPECT_THROW(Subscribe({"/radar 0"}, "/odom"), InputError);
  config_.reliability = "sometimes";
  EXPECT_THROW(Subscribe({"/radar"}, "/odom"), InputError);
}

}  // namespace
}  // namespace uwbsar::dds
