#include "imaging/zeroed_mat.h"

#include <sys/mman.h>

#include <new>

namespace uwbsar {
namespace {

constexpr size_t kHugePageBytes = size_t{2} << 20;

/// cv::MatAllocator that maps each new matrix's memory (continuous matrices only).
class MappedAllocator : public cv::MatAllocator {
 public:
  cv::UMatData* allocate(int dims, const int* sizes, int type, void* data, size_t* step,
                         cv::AccessFlag /*flags*/, cv::UMatUsageFlags /*usage*/) const override {
    CV_Assert(data == nullptr);  // only ZeroedMat allocates with it
    size_t total = CV_ELEM_SIZE(type);
    for (int i = dims - 1; i >= 0; --i) {
      if (step != nullptr) step[i] = total;
      total *= static_cast<size_t>(sizes[i]);
    }
    const size_t mapped = (total + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
    void* block = mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (block == MAP_FAILED) throw std::bad_alloc();
    madvise(block, mapped, MADV_HUGEPAGE);  // advice only: without it, 4 KiB pages
    auto* u = new cv::UMatData(this);
    u->data = u->origdata = static_cast<uchar*>(block);
    u->size = mapped;
    return u;
  }
  bool allocate(cv::UMatData* u, cv::AccessFlag /*flags*/,
                cv::UMatUsageFlags /*usage*/) const override {
    return u != nullptr;
  }
  void deallocate(cv::UMatData* u) const override {
    if (u == nullptr) return;
    munmap(u->origdata, u->size);
    delete u;
  }
};

}  // namespace

cv::Mat ZeroedMat(int rows, int cols, int type) {
  const size_t bytes = static_cast<size_t>(rows) * static_cast<size_t>(cols) * CV_ELEM_SIZE(type);
  if (bytes < 2 * kHugePageBytes) return cv::Mat::zeros(rows, cols, type);
  // Never destroyed: matrices of static storage may outlive any static allocator.
  static MappedAllocator* const allocator = new MappedAllocator;
  cv::Mat m;
  m.allocator = allocator;
  m.create(rows, cols, type);
  return m;
}

}  // namespace uwbsar
