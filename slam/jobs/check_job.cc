#include "slam/jobs/check_job.h"

#include <algorithm>
#include <cstdio>

#include "core/closest_name.h"
#include "drivers/rosbag/bag_reader.h"
#include "drivers/rosbag/robot_bag.h"
#include "drivers/rosbag/ros_messages.h"
#include "slam/jobs/bag_tally.h"

namespace uwbsar::slam {
namespace {

template <class... Args>
std::string Text(const char* format, Args... args) {
  const int size = std::snprintf(nullptr, 0, format, args...);
  std::string out(static_cast<std::size_t>(size) + 1, '\0');
  std::snprintf(out.data(), out.size(), format, args...);
  out.resize(static_cast<std::size_t>(size));
  return out;
}

/// "once", "2 times".
std::string Times(std::uint64_t n) { return n == 1 ? "once" : std::to_string(n) + " times"; }

/// A configured topic as the bag declares it.
struct TopicFound {
  const rosbag::TopicInfo* topic = nullptr;  ///< null when the bag has no topic of that name
  bool right_type = false;
};

TopicFound Find(const rosbag::BagReader& reader, const std::string& name, const std::string& type) {
  TopicFound found;
  const int i = name.empty() ? -1 : reader.FindTopic(name);
  if (i < 0) return found;
  found.topic = &reader.Info().topics[static_cast<std::size_t>(i)];
  found.right_type = found.topic->type == type;
  return found;
}

/// The error line of a configured topic the bag lacks or holds with another type, naming the
/// key and, for a missing one, the bag's topics of the expected type ("" when it is usable).
std::string TopicProblem(const rosbag::BagInfo& info, const Config& config, const TopicFound& found,
                         const std::string& name, const std::string& type, const std::string& key) {
  if (found.topic != nullptr && found.right_type) return "";
  if (found.topic != nullptr) {
    return name + " has type " + found.topic->type + ", " + key + " expects " + type;
  }
  // Candidates: the bag's topics of that type that no other key names.
  std::vector<std::string> taken = {config.slam.odometry_topic, config.slam.ground_truth_topic};
  for (const RadarConfig& r : config.radars) taken.push_back(r.topic);
  std::vector<std::string> candidates;
  for (const rosbag::TopicInfo& t : info.topics) {
    if (t.type == type && std::find(taken.begin(), taken.end(), t.name) == taken.end()) {
      candidates.push_back(t.name);
    }
  }
  std::string text = "no topic " + name + " (" + key + ") in the bag";
  const std::string closest = DidYouMean(name, candidates);
  if (!closest.empty()) return text + closest;
  if (candidates.empty()) return text + "; it holds no " + type + " topic";
  text += "; its " + type + " topics:";
  for (const std::string& c : candidates) text += " " + c;
  return text;
}

/// Seconds from the start of the bag, to find a message in a player.
double Into(const rosbag::BagInfo& info, TimestampNs t) { return NsToSeconds(t - info.start_ns); }

void AddRadarLines(const rosbag::BagInfo& info, const Config& config, std::size_t i,
                   const TopicFound& found, const RadarTally& r, std::vector<CheckLine>* lines) {
  const RadarConfig& radar = config.radars[i];
  // Named as the configuration's messages name a radar: by name, as entries merge by name.
  const std::string key = "radars[" + radar.name + "]";
  const std::string who = "radar " + radar.name + ": ";
  const std::string problem = TopicProblem(info, config, found, radar.topic,
                                           rosbag::kFloat32MultiArrayType, key + ".topic");
  if (!problem.empty()) {
    lines->push_back({CheckLevel::kError, who + problem});
    return;
  }
  if (r.scans == 0) {
    lines->push_back({CheckLevel::kError, who + radar.topic + " holds no messages: map images " +
                                              "nothing from this radar"});
    return;
  }
  lines->push_back(
      {CheckLevel::kOk, who + Text("%s, %llu scans at %.1f Hz", radar.topic.c_str(),
                                   static_cast<unsigned long long>(r.scans), r.rate_hz())});
  if (r.wrong_length > 0) {
    const double share = static_cast<double>(r.wrong_length) / static_cast<double>(r.scans);
    lines->push_back(
        {share > kMaxLostScanShare ? CheckLevel::kError : CheckLevel::kWarning,
         who + Text("%llu of %llu scans do not have %d samples (%s.num_samples); the first has "
                    "%zu, %.2f s into the bag: map drops them",
                    static_cast<unsigned long long>(r.wrong_length),
                    static_cast<unsigned long long>(r.scans), radar.num_samples, key.c_str(),
                    r.first_wrong_length, Into(info, r.first_wrong_ns))});
  } else if (r.zero == r.scans) {
    lines->push_back({CheckLevel::kError,
                      who + "every scan is zero (radar powered but silent?): map images nothing"});
  } else {
    lines->push_back({CheckLevel::kOk, who + Text("every scan has %d samples (%s.num_samples)",
                                                  radar.num_samples, key.c_str())});
  }
}

/// The odometry's rate against the fastest radar's.
CheckLine OdometryRateLine(const OdometryTally& o, const std::vector<RadarTally>& radars) {
  double scan_hz = 0.0;
  for (const RadarTally& r : radars) scan_hz = std::max(scan_hz, r.rate_hz());
  const double per_interval = o.rate_hz() > 0 ? scan_hz / o.rate_hz() : 0.0;
  if (per_interval > kMaxScansPerOdometry) {
    return {CheckLevel::kWarning,
            Text("odometry at %.1f Hz is %.1f times slower than the scans (%.1f Hz): each scan's "
                 "pose is interpolated over %.0f scans of motion (more than %.0f); record the "
                 "odometry at %.0f Hz or more",
                 o.rate_hz(), per_interval, scan_hz, per_interval, kMaxScansPerOdometry,
                 scan_hz / kMaxScansPerOdometry)};
  }
  return {CheckLevel::kOk, Text("odometry rate: %.1f scans of a radar per odometry interval "
                                "(at most %.0f)",
                                per_interval, kMaxScansPerOdometry)};
}

/// The scans map can place: between two odometry messages at most gating.max_odom_gap_s apart.
CheckLine CoverageLine(const rosbag::BagInfo& info, const Config& config, const OdometryTally& o,
                       const std::vector<RadarTally>& radars) {
  std::uint64_t scans = 0;
  for (const RadarTally& r : radars) scans += r.scans;
  const std::uint64_t after = o.scans_since_last;
  const std::uint64_t lost = o.scans_before + after + o.scans_in_gaps;
  const std::string gap = Text(
      "largest odometry gap %.3f s, %.2f s into the bag; gating.max_odom_gap_s %.3g s",
      NsToSeconds(o.largest_gap_ns), Into(info, o.largest_gap_at_ns), config.gating.max_odom_gap_s);
  if (lost == 0) {
    return {CheckLevel::kOk, Text("odometry covers all %llu scans (", scans) + gap + ")"};
  }
  const bool many = static_cast<double>(lost) > kMaxLostScanShare * static_cast<double>(scans);
  return {
      many ? CheckLevel::kError : CheckLevel::kOk,
      Text("%llu of %llu scans lie outside the odometry: %llu before its first message, %llu "
           "after its last, %llu in %llu gaps (",
           static_cast<unsigned long long>(lost), static_cast<unsigned long long>(scans),
           static_cast<unsigned long long>(o.scans_before), static_cast<unsigned long long>(after),
           static_cast<unsigned long long>(o.scans_in_gaps),
           static_cast<unsigned long long>(o.gaps)) +
          gap + "): map drops them"};
}

void AddOdometryLines(const rosbag::BagInfo& info, const Config& config, const TopicFound& found,
                      const BagTally& tally, std::vector<CheckLine>* lines) {
  const std::string& topic = config.slam.odometry_topic;
  const OdometryTally& o = tally.odometry();
  const std::string problem =
      TopicProblem(info, config, found, topic, rosbag::kOdometryType, "slam.odometry_topic");
  if (!problem.empty() || o.count == 0) {
    lines->push_back({CheckLevel::kError,
                      "odometry: " + (problem.empty() ? topic + " holds no messages" : problem) +
                          ": map cannot place any scan"});
    return;
  }
  lines->push_back({CheckLevel::kOk, Text("odometry: %s, %llu messages at %.1f Hz", topic.c_str(),
                                          static_cast<unsigned long long>(o.count), o.rate_hz())});
  lines->push_back(OdometryRateLine(o, tally.radars()));
  lines->push_back(CoverageLine(info, config, o, tally.radars()));
  if (o.back > 0) {
    lines->push_back(
        {CheckLevel::kError,
         Text("odometry header stamps go back %s, by up to %.3f s; the first at message "
              "%llu, %.2f s into the bag: the order received (which map follows) is not the "
              "order stamped (two publishers on %s, or a clock stepped back?)",
              Times(o.back).c_str(), NsToSeconds(o.largest_back_ns),
              static_cast<unsigned long long>(o.first_back_message), Into(info, o.first_back_ns),
              topic.c_str())});
  } else if (o.header_stamped == 0) {
    lines->push_back({CheckLevel::kInfo,
                      "odometry header stamps: none set (map uses the receive times, in order)"});
  } else {
    lines->push_back({CheckLevel::kOk, "odometry header stamps never go back"});
  }
  const std::string largest =
      Text("%.3f m, message %llu, %.2f s into the bag; gating.max_odom_jump_m %.3g m",
           o.largest_step_m, static_cast<unsigned long long>(o.largest_step_message),
           Into(info, o.largest_step_ns), config.gating.max_odom_jump_m);
  if (o.jumps > 0) {
    lines->push_back({CheckLevel::kWarning, "odometry jumps " + Times(o.jumps) + " (largest " +
                                                largest + "): map takes each jump as no motion"});
  } else {
    lines->push_back({CheckLevel::kOk, "odometry never jumps (largest step " + largest + ")"});
  }
}

CheckLine GroundTruthLine(const rosbag::BagInfo& info, const Config& config,
                          const TopicFound& found, std::uint64_t poses) {
  const std::string& topic = config.slam.ground_truth_topic;
  if (found.topic == nullptr) {
    return {CheckLevel::kInfo, "ground truth: no " +
                                   (topic.empty() ? "slam.ground_truth_topic" : "topic " + topic) +
                                   ": map reports no ATE unless given --ground-truth"};
  }
  const std::string problem =
      TopicProblem(info, config, found, topic, rosbag::kOdometryType, "slam.ground_truth_topic");
  if (!problem.empty())
    return {CheckLevel::kError, "ground truth: " + problem + ": map refuses it"};
  return {CheckLevel::kInfo, Text("ground truth: %s, %llu poses: map reports the ATE",
                                  topic.c_str(), static_cast<unsigned long long>(poses))};
}

}  // namespace

int BagCheck::Count(CheckLevel level) const {
  return static_cast<int>(std::count_if(lines.begin(), lines.end(),
                                        [&](const CheckLine& l) { return l.level == level; }));
}

BagCheck CheckBag(const Config& config, const std::string& bag) {
  rosbag::BagReader reader(bag);
  const rosbag::BagInfo& info = reader.Info();
  // Only the topics the bag holds with the right type are read; the others are reported.
  std::vector<TopicFound> radars;
  std::vector<int> radar_of_sensor;
  rosbag::RobotBagOptions options;
  options.radar_topics.clear();
  for (std::size_t i = 0; i < config.radars.size(); ++i) {
    radars.push_back(Find(reader, config.radars[i].topic, rosbag::kFloat32MultiArrayType));
    if (!radars.back().right_type) continue;
    options.radar_topics.push_back(config.radars[i].topic);
    radar_of_sensor.push_back(static_cast<int>(i));
  }
  const TopicFound odometry = Find(reader, config.slam.odometry_topic, rosbag::kOdometryType);
  const TopicFound truth = Find(reader, config.slam.ground_truth_topic, rosbag::kOdometryType);
  options.odometry_topic = odometry.right_type ? config.slam.odometry_topic : "";
  options.ground_truth_topic = truth.right_type ? config.slam.ground_truth_topic : "";
  BagTally tally(config, std::move(radar_of_sensor));
  const rosbag::RobotBagStats stats = rosbag::ReadRobotBag(reader, options, tally);

  BagCheck check;
  check.lines.push_back(
      {CheckLevel::kInfo,
       Text("bag %s: %s, %llu messages over %.1f s", bag.c_str(), info.storage_identifier.c_str(),
            static_cast<unsigned long long>(stats.messages), NsToSeconds(info.duration_ns()))});
  for (std::size_t i = 0; i < config.radars.size(); ++i) {
    AddRadarLines(info, config, i, radars[i], tally.radars()[i], &check.lines);
  }
  AddOdometryLines(info, config, odometry, tally, &check.lines);
  check.lines.push_back(GroundTruthLine(info, config, truth, tally.ground_truth()));
  return check;
}

std::string FormatCheckLine(const CheckLine& line) {
  static const char* const kNames[] = {"ok      ", "info    ", "warning ", "error   "};
  return kNames[static_cast<int>(line.level)] + line.text;
}

}  // namespace uwbsar::slam
