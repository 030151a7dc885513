#include "drivers/live/lt102_radar.h"

namespace uwbsar::live {

Lt102Radar::Lt102Radar(const RadarDeviceArgs& args)
    : startup_wait_s_(args.settings.live.lt102.startup_wait_s),
      driver_(args.name, args.sensor_id, args.settings, args.faults, args.sink, args.events,
              args.clock, args.clock_scale),
      link_(args.name, args.device, args.link, &driver_, args.faults, args.power_cycle) {
  if (args.acquisition_gate) driver_.set_acquisition_gate(args.acquisition_gate);
}

bool Lt102Radar::WaitConfigured(double timeout_s, RadarSetup* setup, std::string* error) {
  Lt102Setup lt102;
  if (!driver_.WaitConfigured(timeout_s, &lt102, error)) return false;
  *setup = ToRadarSetup(lt102);
  return true;
}

RadarStartupWait Lt102Radar::startup_wait() const {
  return {startup_wait_s_, "live.lt102.startup_wait_s"};
}

RadarSetup Lt102Radar::ToRadarSetup(const Lt102Setup& setup) {
  RadarSetup out;
  out.range_min_m = setup.range_min_m;
  out.range_max_m = setup.range_max_m;
  out.samples_per_scan = setup.samples_per_scan;
  out.frame_rate_fps = setup.frame_rate_fps;
  out.frame_rate_requested_fps = setup.frame_rate_requested_fps;
  out.description = setup.Describe();
  return out;
}

RadarStats Lt102Radar::ToRadarStats(const Lt102Stats& s) {
  RadarStats out;
  out.startups = s.startups;
  out.startup_failures = s.startup_failures;
  out.config_errors = s.config_errors;
  out.configured = s.configured;
  out.setup = ToRadarSetup(s.setup);
  out.frames_delivered = s.frames_delivered;
  out.frames_repeated = s.frames_repeated;
  out.frames_missed = s.frames_missed;
  out.frames_lost = s.lost;
  out.invalid_frames = s.invalid_frames;
  out.stamp_reanchors = s.stamp_reanchors;
  out.stamp_trace = s.stamp_trace;
  const double requests_per_s =
      s.acquiring_s > 0 ? static_cast<double>(s.requests) / s.acquiring_s : 0.0;
  out.extra = {
      {"frame_requests", s.requests},
      {"frame_answers", s.answers},
      {"requests_per_s", requests_per_s},
      {"late_answers", s.late_answers},
      {"unanswered_at_stop", s.unanswered_at_stop},
      {"request_to_answer_ms.p50", s.answer_p50_ms},
      {"request_to_answer_ms.p99", s.answer_p99_ms},
      {"request_to_answer_ms.max", s.answer_max_ms},
      {"command_requests", s.exchange.requests},
      {"wrong_answers", s.exchange.wrong_answers},
      {"missing_answers", s.exchange.missing_answers},
      {"retries", s.exchange.retries},
      {"stops_sent", s.stops},
  };
  return out;
}

std::unique_ptr<RadarDevice> CreateLt102Radar(const RadarDeviceArgs& args) {
  return std::make_unique<Lt102Radar>(args);
}

}  // namespace uwbsar::live
