// The declared size of an image file, read from its header without decoding it, so
// that a small file declaring a huge image (a "decompression bomb": a 439 KB PNG of
// 20000 x 20000 pixels) is refused before OpenCV allocates it.
// OpenCV 4.6 has no header-only API, so the few formats uwbsar reads maps in are
// parsed here: PNG (IHDR), PNM (P1-P6), BMP, JPEG (SOF) and TIFF (every page's IFD).
#pragma once

#include <string>

namespace uwbsar {

struct ImageHeader {
  std::string format;    ///< "PNG", "PNM", "BMP", "JPEG" or "TIFF"
  double pixels = 0.0;   ///< width x height, summed over the pages of a TIFF
  long long width = 0;   ///< of the first page
  long long height = 0;  ///< of the first page
  long long maxval = 0;  ///< PGM/PPM: the declared largest sample value; 0 for other formats
};

/// Throws InputError naming the file when it cannot be opened, is none of the formats
/// above, or its header is cut short or malformed.
ImageHeader ReadImageHeader(const std::string& path);

/// Throws InputError (one line naming the file, its declared size and the limit) when the
/// header of `path` declares more than `max_pixels` pixels; `what` names the file's role.
void CheckImageSize(const std::string& path, double max_pixels, const std::string& what);

}  // namespace uwbsar
