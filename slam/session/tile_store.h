// Detected tiles out of core (issue "a working day"): once a keyframe's features and wall
// profile are made, SlamSystem keeps its detected tile in a cache file and a TileRef to it;
// memory holds poses, features and profiles, and the tiles read back on demand (the mosaic,
// the navigation grid, the session) through a cache of decoded tiles under a byte budget
// (limits.tile_cache_mb).
//
// The cache file is anonymous: created with tmpfile() in the system's temporary folder and
// already unlinked, so it never outlives the process (a crash or a kill leaves nothing). A
// tile's extent is reused once the last TileRef to it is gone (a retired keyframe's, once no
// snapshot holds it), so the file follows the keyframes kept, not the hours driven. Tiles are
// stored losslessly (float32 + zstd): what is read back equals what was stored.
//
// Thread safety: TileStore and TileRef may be used from any thread (reads are pread()s and the
// cache has its own mutex).
#pragma once

#include <cstddef>
#include <memory>
#include <opencv2/core.hpp>

namespace uwbsar {

namespace tile_store_detail {
struct Storage;
struct Extent;
}  // namespace tile_store_detail

/// A detected tile (CV_32FC1): in the store's file, or held in memory. Copies share it.
class TileRef {
 public:
  TileRef() = default;
  /// A tile held in memory (a resumed session's, a test's).
  explicit TileRef(cv::Mat in_memory) : memory_(std::move(in_memory)) {}

  bool empty() const { return !extent_ && memory_.empty(); }
  /// The tile (decoded from the file through the store's cache when it is there). Throws
  /// std::runtime_error when the file cannot be read back.
  cv::Mat Load() const;
  /// Whether the tile lives in a store's file (false: in memory, or empty).
  bool stored() const { return extent_ != nullptr; }

 private:
  friend class TileStore;
  std::shared_ptr<const tile_store_detail::Extent> extent_;
  cv::Mat memory_;
};

class TileStore {
 public:
  /// `cache_bytes`: decoded tiles kept in memory at most (least recently used go first).
  /// Throws std::runtime_error when no temporary file can be created.
  explicit TileStore(std::size_t cache_bytes);
  ~TileStore();
  TileStore(const TileStore&) = delete;
  TileStore& operator=(const TileStore&) = delete;

  /// Writes `tile` to the file and returns a reference to it (empty for an empty tile).
  /// Throws std::runtime_error on a write error (a full disk).
  TileRef Put(const cv::Mat& tile);

  /// The file's size and the bytes of live tiles in it.
  std::size_t file_bytes() const;
  std::size_t live_bytes() const;

 private:
  std::shared_ptr<tile_store_detail::Storage> storage_;
};

}  // namespace uwbsar
