// The serialized bytes of DDS samples, for checking the wire format against the
// project's independent CDR code (drivers/rosbag): a reader whose samples are taken
// as serdata (dds_takecdr) and copied out, and injection of ready-made CDR bytes.
#pragma once

#include <dds/dds.h>
#include <dds/ddsi/ddsi_serdata.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "drivers/dds/dds_check.h"
#include "drivers/dds/participant.h"
#include "drivers/dds/ros2_qos.h"

namespace uwbsar::dds::testing {

inline std::vector<std::uint8_t> SerdataBytes(const ddsi_serdata* d) {
  std::vector<std::uint8_t> bytes(ddsi_serdata_size(d));
  ddsi_serdata_to_ser(d, 0, bytes.size(), bytes.data());
  return bytes;
}

/// A reader (and a writer on the same topic entity) exchanging raw CDR.
class RawCdrEndpoint {
 public:
  RawCdrEndpoint(const Participant& participant, const dds_topic_descriptor_t* desc,
                 const std::string& ros_topic, Durability durability = Durability::kVolatile,
                 int depth = 10) {
    Qos qos;
    SetRos2Qos(qos.get(), "reliable", depth, durability);
    const std::string name = RosTopicToDds(ros_topic);
    topic_ = Check(dds_create_topic(participant.handle(), desc, name.c_str(), nullptr, nullptr),
                   "dds_create_topic");
    reader_ = Check(dds_create_reader(participant.handle(), topic_, qos.get(), nullptr),
                    "dds_create_reader");
    writer_ = Check(dds_create_writer(participant.handle(), topic_, qos.get(), nullptr),
                    "dds_create_writer");
  }
  ~RawCdrEndpoint() {
    dds_delete(writer_);
    dds_delete(reader_);
    dds_delete(topic_);
  }
  dds_entity_t reader() const { return reader_; }
  dds_entity_t writer() const { return writer_; }

  /// Every sample waiting in the reader, serialized (encapsulation header first).
  std::vector<std::vector<std::uint8_t>> Take() {
    std::vector<std::vector<std::uint8_t>> out;
    for (;;) {
      ddsi_serdata* d[8] = {};
      dds_sample_info_t info[8];
      const dds_return_t n = dds_takecdr(reader_, d, 8, info, DDS_ANY_STATE);
      if (n <= 0) break;
      for (dds_return_t i = 0; i < n; ++i) {
        if (info[i].valid_data) out.push_back(SerdataBytes(d[i]));
        if (type_ == nullptr) type_ = d[i]->type;
        ddsi_serdata_unref(d[i]);
      }
    }
    return out;
  }

  /// Sends `cdr` (encapsulation header first) as is. Needs the topic's sertype, learnt
  /// from one sample that went through Take() first.
  void WriteCdr(const std::vector<std::uint8_t>& cdr) {
    if (type_ == nullptr) throw std::logic_error("WriteCdr before any Take()");
    ddsrt_iovec_t iov;
    iov.iov_base = const_cast<std::uint8_t*>(cdr.data());
    iov.iov_len = static_cast<ddsrt_iov_len_t>(cdr.size());
    ddsi_serdata* d = ddsi_serdata_from_ser_iov(type_, SDK_DATA, 1, &iov, cdr.size());
    if (d == nullptr) throw std::runtime_error("ddsi_serdata_from_ser_iov rejected the bytes");
    Check(dds_writecdr(writer_, d), "dds_writecdr");
  }

 private:
  dds_entity_t topic_ = 0, reader_ = 0, writer_ = 0;
  const ddsi_sertype* type_ = nullptr;
};

}  // namespace uwbsar::dds::testing
