// A saved map read by a command that joins, localises in or merges it (docs/refusals.md, the
// session rule): read under a shared lock on its folder, held for the whole
// run, so that no other process can replace it meanwhile; the checks that keep a saved map
// from being replaced, mixed or joined twice; and the identity of a recording.
#pragma once

#include <string>
#include <vector>

#include "core/folder_lock.h"
#include "slam/app_config.h"
#include "slam/session/session_data.h"

namespace uwbsar::slam {

struct SavedSession {
  std::string path;  ///< the session file
  std::string dir;   ///< its folder
  FolderLock lock;   ///< shared, on `dir`, while the command runs
  SessionData data;
  /// The ground truth of each of data.trajectories (slam/outputs/session_files.h SavedGroundTruth),
  /// read by the commands that join the map, before their work; empty otherwise.
  std::vector<std::vector<OdometrySample>> ground_truth;
};

/// Locks the folder of the session `dir_or_file` (a folder or its session.uwbsar) shared,
/// completing a commit a dead process left in it first, then reads and checks the session
/// against `config` (ReadSession). Throws InputError as ReadSession does, or naming the
/// process that is writing the folder.
SavedSession OpenSavedSession(const std::string& dir_or_file, const Config& config);

/// Whether two paths name the same existing folder (or file).
bool SamePlace(const std::string& a, const std::string& b);

/// Refuses (InputError, one line) to write a command's outputs into `out_dir` when it holds
/// a saved map (session.uwbsar) that the command would replace, unless the command joins that
/// very session (`joined_dirs`: the folders of the sessions it extends) or the user asked to
/// replace it (`overwrite`). `how` names the way out in the message (e.g. "--resume DIR to
/// extend it, or --overwrite to replace it").
void RefuseToReplaceSavedMap(const std::string& out_dir,
                             const std::vector<std::string>& joined_dirs, bool overwrite,
                             const std::string& how);

/// Refuses (InputError) to write localisation outputs into a folder that holds a saved map:
/// localising never changes a map or mixes its folder with another run's files.
void RefuseMapFolderForLocalize(const std::string& out_dir);

/// Refuses (InputError, naming both) to join `runs` (of `what`, e.g. a bag path) into `saved`
/// (read from `saved_path`) when one of them is already a run of it: the same recording
/// (SessionTrajectory::fingerprint) joined twice would count its data twice.
void RefuseRunsAlreadyJoined(const SessionData& saved, const std::string& saved_path,
                             const std::vector<SessionTrajectory>& runs, const std::string& what);

/// The identity of a recording: "bag <storage id> <first_ns> <last_ns> <message count>
/// <hash>", the hash (FNV-1a, 64 bits) over the topic, stamp and bytes of its first 256
/// messages: two simulations of the same route share stamps and counts, never their data.
/// Opens the bag (InputError naming it when it cannot be read) and reads only those messages.
std::string BagFingerprint(const std::string& bag_path);

}  // namespace uwbsar::slam
