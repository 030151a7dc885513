// A finished (or locked) SlamSystem as a session (slam/session/session_data.h): what
// `uwbsar map` saves as session.uwbsar. The run is trajectory 0 of the session.
#pragma once

#include "slam/map_job.h"
#include "slam/outputs/map_outputs.h"
#include "slam/session/session_data.h"

namespace uwbsar::slam {

/// The session of one mapped run. Reads the SLAM state: call after Finish(), or hold
/// run.slam->LockState(). Throws std::logic_error when a keyframe has no features.
SessionData CaptureSession(const MapRun& run);

/// Adds session.uwbsar (CaptureSession(run)) to what `stage` commits next: `uwbsar map` and
/// `demo` save the map they write, so `--resume`, `localize` and `merge` can use it. `run`
/// must outlive the commit.
void SaveSessionWithOutputs(MapOutputStage* stage, const MapRun& run);

}  // namespace uwbsar::slam
