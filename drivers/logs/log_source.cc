#include "drivers/logs/log_source.h"

namespace uwbsar {

void LogSource::Run(const MessageSink& sink) {
  Message m;
  std::size_t i = 0, j = 0;
  while (i < odometry_.size() || j < scans_.size()) {
    if (j >= scans_.size() ||
        (i < odometry_.size() && odometry_[i].stamp_ns <= scans_[j].stamp_ns)) {
      m.kind = Message::Kind::kOdometry;
      m.odometry = odometry_[i++];
      m.stamp_ns = m.odometry.stamp_ns;
    } else {
      m.kind = Message::Kind::kRadarScan;
      m.scan = scans_[j++];
      m.stamp_ns = m.scan.stamp_ns;
    }
    sink(m);
  }
}

}  // namespace uwbsar
