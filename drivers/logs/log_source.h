// A log held in memory (a text log, a bag read whole) as a MessageSource: odometry and
// radar scans merged in stamp order, odometry first on equal stamps (so a scan can use the
// odometry sample of its own time).
#pragma once

#include <vector>

#include "core/message.h"
#include "core/types.h"

namespace uwbsar {

class LogSource : public MessageSource {
 public:
  /// Both vectors, each in stamp order, must outlive Run().
  LogSource(const std::vector<OdometrySample>& odometry, const std::vector<RadarScan>& scans)
      : odometry_(odometry), scans_(scans) {}
  void Run(const MessageSink& sink) override;

 private:
  const std::vector<OdometrySample>& odometry_;
  const std::vector<RadarScan>& scans_;
};

}  // namespace uwbsar
