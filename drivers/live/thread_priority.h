// Real-time scheduling for the threads that talk to devices.
//
// A polled LT102 hands out only the frame it holds when asked: a link thread that waits
// for the CPU behind other work asks late, and the frames acquired in between are
// overwritten at the radar. Under a busy-thread-per-core load the polling rate fell from
// 100 to about 30 frames/s per radar on the 2-core test machine. Device drivers on robots
// run their I/O threads under SCHED_FIFO for this reason; these threads block on the serial
// port almost all the time, so they take little CPU from mapping.
#pragma once

#include <string>

namespace uwbsar::live {

/// Puts the calling thread under SCHED_FIFO at `priority` (1..99). Returns "" on success,
/// otherwise the reason (typically: not permitted without root, CAP_SYS_NICE or an rtprio
/// limit). `priority` <= 0 leaves the thread as it is and returns "".
std::string SetCurrentThreadRealtime(int priority);

/// SetCurrentThreadRealtime, logging one warning per process when it is refused (the run
/// goes on at normal priority). `who` names the thread in the warning.
void RequestRealtimeOrWarn(int priority, const std::string& who);

}  // namespace uwbsar::live
