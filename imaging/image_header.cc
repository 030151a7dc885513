#include "imaging/image_header.h"

#include <cctype>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <set>
#include <vector>

#include "core/bounded_file.h"
#include "core/errors.h"

namespace uwbsar {
namespace {

/// Random access to the first bytes of a file (headers are near the start; TIFF IFDs
/// may be anywhere, so reads are by offset).
class Bytes {
 public:
  explicit Bytes(const std::string& path) : path_(path), in_(OpenInputFile(path, "image")) {}
  /// Reads n bytes at `offset`; false if the file ends first.
  bool Read(std::uint64_t offset, std::size_t n, std::uint8_t* out) {
    in_.clear();
    in_.seekg(static_cast<std::streamoff>(offset));
    in_.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(n));
    return static_cast<std::size_t>(in_.gcount()) == n;
  }
  [[noreturn]] void Fail(const std::string& format, const std::string& why) const {
    throw InputError(path_ + ": bad " + format + " header: " + why);
  }

 private:
  std::string path_;
  std::ifstream in_;
};

std::uint32_t Be(const std::uint8_t* p, int n) {
  std::uint32_t v = 0;
  for (int i = 0; i < n; ++i) v = (v << 8) | p[i];
  return v;
}
std::uint32_t Le(const std::uint8_t* p, int n) {
  std::uint32_t v = 0;
  for (int i = n - 1; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}

ImageHeader Png(Bytes& b) {
  std::uint8_t h[24];
  if (!b.Read(0, sizeof(h), h)) b.Fail("PNG", "cut short");
  if (h[12] != 'I' || h[13] != 'H' || h[14] != 'D' || h[15] != 'R') b.Fail("PNG", "no IHDR");
  return {"PNG", 0.0, Be(h + 16, 4), Be(h + 20, 4)};
}

ImageHeader Pnm(Bytes& b) {
  // Magic, then width, height and (but for the bitmaps P1, P4) maxval as decimal tokens
  // separated by whitespace and comments.
  std::uint8_t magic = 0;
  b.Read(1, 1, &magic);
  const int tokens = magic == '1' || magic == '4' ? 2 : 3;
  std::uint64_t at = 2;
  long long values[3] = {0, 0, 0};
  for (int i = 0; i < tokens; ++i) {
    long long& v = values[i];
    std::uint8_t c = ' ';
    std::string token;
    while (token.size() <= 12) {
      if (!b.Read(at++, 1, &c)) b.Fail("PNM", "cut short");
      if (c == '#') {
        while (c != '\n' && c != '\r') {
          if (!b.Read(at++, 1, &c)) b.Fail("PNM", "cut short");
        }
      } else if (std::isspace(c)) {
        if (!token.empty()) break;
      } else if (std::isdigit(c)) {
        token.push_back(static_cast<char>(c));
      } else {
        b.Fail("PNM", "width, height or maxval is not a number");
      }
    }
    if (token.empty() || token.size() > 12) {
      b.Fail("PNM", "width, height or maxval is not a number");
    }
    v = std::stoll(token);
  }
  return {"PNM", 0.0, values[0], values[1], values[2]};
}

ImageHeader Bmp(Bytes& b) {
  std::uint8_t h[26];
  if (!b.Read(0, sizeof(h), h)) b.Fail("BMP", "cut short");
  if (Le(h + 14, 4) == 12) return {"BMP", 0.0, Le(h + 18, 2), Le(h + 20, 2)};  // OS/2 core
  const auto height = static_cast<std::int32_t>(Le(h + 22, 4));                // < 0: top-down
  return {"BMP", 0.0, static_cast<std::int32_t>(Le(h + 18, 4)),
          height < 0 ? -static_cast<long long>(height) : height};
}

ImageHeader Jpeg(Bytes& b) {
  std::uint64_t at = 2;
  for (int segment = 0; segment < 10000; ++segment) {
    std::uint8_t m[4];
    if (!b.Read(at, 4, m)) b.Fail("JPEG", "no frame header (SOF)");
    if (m[0] != 0xFF) b.Fail("JPEG", "bad marker");
    if (m[1] == 0xFF) {  // fill byte
      ++at;
      continue;
    }
    const bool standalone = m[1] == 0x01 || (m[1] >= 0xD0 && m[1] <= 0xD8);
    if (standalone) {
      at += 2;
      continue;
    }
    const bool sof = m[1] >= 0xC0 && m[1] <= 0xCF && m[1] != 0xC4 && m[1] != 0xC8 && m[1] != 0xCC;
    if (sof) {
      std::uint8_t f[5];
      if (!b.Read(at + 4, 5, f)) b.Fail("JPEG", "cut short");
      return {"JPEG", 0.0, Be(f + 3, 2), Be(f + 1, 2)};
    }
    at += 2 + Be(m + 2, 2);
  }
  b.Fail("JPEG", "no frame header (SOF)");
}

ImageHeader Tiff(Bytes& b, bool little) {
  auto get = [&](const std::uint8_t* p, int n) { return little ? Le(p, n) : Be(p, n); };
  std::uint8_t h[8];
  if (!b.Read(0, 8, h)) b.Fail("TIFF", "cut short");
  if (get(h + 2, 2) != 42) b.Fail("TIFF", "not a classic TIFF (BigTIFF is not read)");
  ImageHeader out{"TIFF", 0.0, 0, 0};
  std::set<std::uint32_t> seen;
  for (std::uint32_t ifd = get(h + 4, 4); ifd != 0;) {
    if (!seen.insert(ifd).second) b.Fail("TIFF", "the page list loops");
    if (seen.size() > 1000) b.Fail("TIFF", "more than 1000 pages");
    std::uint8_t n[2];
    if (!b.Read(ifd, 2, n)) b.Fail("TIFF", "cut short");
    const std::uint32_t entries = get(n, 2);
    std::vector<std::uint8_t> e(12u * entries + 4u);
    if (!b.Read(ifd + 2u, e.size(), e.data())) b.Fail("TIFF", "cut short");
    long long width = -1, height = -1;
    for (std::uint32_t i = 0; i < entries; ++i) {
      const std::uint8_t* p = e.data() + 12u * i;
      const std::uint32_t tag = get(p, 2), type = get(p + 2, 2);
      if (tag != 256 && tag != 257) continue;
      const long long v = type == 3 ? get(p + 8, 2) : get(p + 8, 4);  // SHORT or LONG
      (tag == 256 ? width : height) = v;
    }
    if (width < 0 || height < 0) b.Fail("TIFF", "a page without width or height");
    if (out.width == 0 && out.height == 0) out.width = width, out.height = height;
    out.pixels += static_cast<double>(width) * static_cast<double>(height);
    ifd = get(e.data() + 12u * entries, 4);
  }
  return out;
}

}  // namespace

ImageHeader ReadImageHeader(const std::string& path) {
  Bytes b(path);
  std::uint8_t m[8] = {};
  if (!b.Read(0, 2, m)) throw InputError(path + ": image file is too short");
  b.Read(0, 8, m);
  ImageHeader h;
  if (m[0] == 0x89 && m[1] == 'P' && m[2] == 'N' && m[3] == 'G') {
    h = Png(b);
  } else if (m[0] == 'P' && m[1] >= '1' && m[1] <= '6') {
    h = Pnm(b);
  } else if (m[0] == 'B' && m[1] == 'M') {
    h = Bmp(b);
  } else if (m[0] == 0xFF && m[1] == 0xD8) {
    h = Jpeg(b);
  } else if ((m[0] == 'I' && m[1] == 'I') || (m[0] == 'M' && m[1] == 'M')) {
    h = Tiff(b, m[0] == 'I');
  } else {
    throw InputError(path +
                     ": image format not supported (its size cannot be checked before "
                     "decoding); use PGM, PNG, BMP, JPEG or TIFF");
  }
  if (h.format != "TIFF") h.pixels = static_cast<double>(h.width) * static_cast<double>(h.height);
  return h;
}

void CheckImageSize(const std::string& path, double max_pixels, const std::string& what) {
  const ImageHeader h = ReadImageHeader(path);
  if (h.pixels <= max_pixels) return;
  char buf[160];
  std::snprintf(buf, sizeof(buf),
                "%s declares %lld x %lld pixels (%.3g%s), more than "
                "limits.max_map_image_pixels (%.3g); refused before decoding",
                h.format.c_str(), h.width, h.height, h.pixels,
                h.format == "TIFF" ? " over all pages" : "", max_pixels);
  throw InputError(path + ": " + what + " " + buf);
}

}  // namespace uwbsar
