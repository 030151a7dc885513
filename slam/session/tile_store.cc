#include "slam/session/tile_store.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <list>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "slam/session/blob_codec.h"

namespace uwbsar {
namespace tile_store_detail {

constexpr int kZstdLevel = 1;  // fast: a tile is written once per keyframe, read a few times
constexpr std::size_t kPage = 4096;

/// The file, its free extents and the cache of decoded tiles.
struct Storage {
  std::mutex mutex;
  std::FILE* file = nullptr;
  std::size_t end = 0;                              // file size
  std::map<std::size_t, std::size_t> free_extents;  // offset -> size, adjacent ones merged
  std::size_t live = 0;
  std::size_t cache_bytes = 0, cached = 0;
  std::uint64_t next_key = 0;
  std::list<std::uint64_t> lru;  // most recent first
  struct Cached {
    cv::Mat tile;
    std::list<std::uint64_t>::iterator at;
  };
  std::unordered_map<std::uint64_t, Cached> cache;

  ~Storage() {
    if (file != nullptr) std::fclose(file);
  }

  /// An extent of at least `size` bytes (rounded up to whole pages, so that extents of
  /// similar tiles fit each other): the smallest free one that fits (its rest stays free), else
  /// the end of the file. Caller holds the mutex.
  std::size_t Allocate(std::size_t* size) {
    *size = (*size + kPage - 1) / kPage * kPage;
    auto best = free_extents.end();
    for (auto it = free_extents.begin(); it != free_extents.end(); ++it) {
      if (it->second >= *size && (best == free_extents.end() || it->second < best->second))
        best = it;
    }
    if (best == free_extents.end()) {
      const std::size_t offset = end;
      end += *size;
      return offset;
    }
    const std::size_t offset = best->first, have = best->second;
    free_extents.erase(best);
    if (have > *size) free_extents.emplace(offset + *size, have - *size);
    return offset;
  }

  /// Returns an extent to the free list, merged with free neighbours. Caller holds the mutex.
  void Free(std::size_t offset, std::size_t size) {
    auto next = free_extents.lower_bound(offset);
    if (next != free_extents.end() && offset + size == next->first) {
      size += next->second;
      next = free_extents.erase(next);
    }
    if (next != free_extents.begin()) {
      auto prev = std::prev(next);
      if (prev->first + prev->second == offset) {
        prev->second += size;
        return;
      }
    }
    free_extents.emplace(offset, size);
  }

  void Evict(std::uint64_t key) {  // caller holds the mutex
    auto it = cache.find(key);
    if (it == cache.end()) return;
    cached -= it->second.tile.total() * it->second.tile.elemSize();
    lru.erase(it->second.at);
    cache.erase(it);
  }

  void Remember(std::uint64_t key, const cv::Mat& tile) {  // caller holds the mutex
    const std::size_t bytes = tile.total() * tile.elemSize();
    if (bytes > cache_bytes || cache.count(key)) return;
    while (cached + bytes > cache_bytes && !lru.empty()) Evict(lru.back());
    lru.push_front(key);
    cache[key] = {tile, lru.begin()};
    cached += bytes;
  }
};

struct Extent {
  std::shared_ptr<Storage> storage;
  std::uint64_t key = 0;
  std::size_t offset = 0, size = 0;  // the tile's bytes
  std::size_t reserved = 0;          // the extent's (whole pages)

  ~Extent() {
    std::lock_guard<std::mutex> lock(storage->mutex);
    storage->Evict(key);
    storage->Free(offset, reserved);
    storage->live -= reserved;
  }
};

}  // namespace tile_store_detail

using tile_store_detail::Extent;
using tile_store_detail::Storage;

TileStore::TileStore(std::size_t cache_bytes) : storage_(std::make_shared<Storage>()) {
  storage_->file = std::tmpfile();  // unlinked already: gone with the process
  if (storage_->file == nullptr) {
    throw std::runtime_error(std::string("tile cache: cannot create a temporary file: ") +
                             std::strerror(errno));
  }
  storage_->cache_bytes = cache_bytes;
}

TileStore::~TileStore() = default;

TileRef TileStore::Put(const cv::Mat& tile) {
  TileRef ref;
  if (tile.empty()) return ref;
  const std::vector<unsigned char> blob =
      session::EncodeTile(tile, /*lossless=*/true, tile_store_detail::kZstdLevel);
  auto extent = std::make_shared<Extent>();
  extent->storage = storage_;
  extent->size = blob.size();
  {
    std::lock_guard<std::mutex> lock(storage_->mutex);
    extent->reserved = blob.size();
    extent->offset = storage_->Allocate(&extent->reserved);
    extent->key = storage_->next_key++;
    storage_->live += extent->reserved;
  }
  const int fd = fileno(storage_->file);
  std::size_t written = 0;
  while (written < blob.size()) {
    const ssize_t n = ::pwrite(fd, blob.data() + written, blob.size() - written,
                               static_cast<off_t>(extent->offset + written));
    if (n <= 0) {
      throw std::runtime_error(std::string("tile cache: cannot write a tile: ") +
                               std::strerror(errno));
    }
    written += static_cast<std::size_t>(n);
  }
  // Not cached: mapping never reads a tile back (its wall profile and features are made
  // before it is stored); the map's outputs and snapshots fill the cache as they read.
  ref.extent_ = std::move(extent);
  return ref;
}

cv::Mat TileRef::Load() const {
  if (!extent_) return memory_;
  Storage& s = *extent_->storage;
  {
    std::lock_guard<std::mutex> lock(s.mutex);
    auto it = s.cache.find(extent_->key);
    if (it != s.cache.end()) {
      s.lru.splice(s.lru.begin(), s.lru, it->second.at);
      return it->second.tile;
    }
  }
  std::vector<unsigned char> blob(extent_->size);
  std::size_t read = 0;
  while (read < blob.size()) {
    const ssize_t n = ::pread(fileno(s.file), blob.data() + read, blob.size() - read,
                              static_cast<off_t>(extent_->offset + read));
    if (n <= 0) {
      throw std::runtime_error(std::string("tile cache: cannot read a tile back: ") +
                               (n == 0 ? "end of file" : std::strerror(errno)));
    }
    read += static_cast<std::size_t>(n);
  }
  const cv::Mat tile = session::DecodeTile(blob, "tile cache");
  std::lock_guard<std::mutex> lock(s.mutex);
  s.Remember(extent_->key, tile);
  return tile;
}

std::size_t TileStore::file_bytes() const {
  std::lock_guard<std::mutex> lock(storage_->mutex);
  return storage_->end;
}

std::size_t TileStore::live_bytes() const {
  std::lock_guard<std::mutex> lock(storage_->mutex);
  return storage_->live;
}

}  // namespace uwbsar
