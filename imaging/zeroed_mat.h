// Large images of zeros at the cost of the pages written: their memory is mapped fresh from the
// kernel (zero-filled by definition, no memset) and asks for transparent huge pages, so that
// first writes fault once per 2 MiB instead of once per 4 KiB. A keyframe segment's canvas
// (tens of MiB, written in part) then costs a few faults instead of thousands plus a memset:
// measured in BM_ImageTile, where it was a quarter of a short run's imaging.
#pragma once

#include <opencv2/core.hpp>

namespace uwbsar {

/// A rows x cols matrix of `type`, all zeros, owning its memory like any cv::Mat (small ones come
/// from cv::Mat::zeros).
cv::Mat ZeroedMat(int rows, int cols, int type);

}  // namespace uwbsar
