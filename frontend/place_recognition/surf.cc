#include "frontend/place_recognition/surf.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace uwbsar {
namespace {

constexpr int kHaarSize0 = 9;    // filter side of the first layer (scale 1.2)
constexpr int kHaarSizeInc = 6;  // filter side increment between layers of octave 0
constexpr double kScalePerSide = 1.2 / 9.0;
constexpr double kOrientationRadius = 6.0;  // in units of the keypoint scale
constexpr double kOrientationSigma = 2.5;   // Gaussian weight, units of scale
constexpr double kOrientationWindowRad = M_PI / 3.0;
constexpr double kOrientationStepRad = 5.0 * M_PI / 180.0;
constexpr double kDescriptorSigma = 3.3;  // Gaussian weight, units of scale

/// Box sums over an integral image; boxes are clamped to the image.
class Integral {
 public:
  explicit Integral(const cv::Mat& image8u) : rows_(image8u.rows), cols_(image8u.cols) {
    cv::integral(image8u, sum_, CV_64F);
  }
  /// Sum over rows [r0, r1) and columns [c0, c1).
  double Box(int r0, int c0, int r1, int c1) const {
    r0 = std::clamp(r0, 0, rows_);
    r1 = std::clamp(r1, 0, rows_);
    c0 = std::clamp(c0, 0, cols_);
    c1 = std::clamp(c1, 0, cols_);
    if (r1 <= r0 || c1 <= c0) return 0.0;
    const double* a = sum_.ptr<double>(r0);
    const double* b = sum_.ptr<double>(r1);
    return b[c1] - b[c0] - a[c1] + a[c0];
  }
  /// Haar wavelet responses of side `side` (even) centred at the pixel nearest (x, y).
  void Haar(double x, double y, int side, double* dx, double* dy) const {
    const int h = side / 2;
    const int c = static_cast<int>(std::lround(x));
    const int r = static_cast<int>(std::lround(y));
    *dx = Box(r - h, c, r + h, c + h) - Box(r - h, c - h, r + h, c);
    *dy = Box(r, c - h, r + h, c + h) - Box(r - h, c - h, r, c + h);
  }
  int rows() const { return rows_; }
  int cols() const { return cols_; }

 private:
  cv::Mat sum_;
  int rows_, cols_;
};

/// One lobe of a box filter: offsets from the filter's top-left corner and weight per pixel.
struct Lobe {
  int c0, r0, c1, r1;
  double weight;
};

/// The 9x9 box approximations of Lxx, Lyy, Lxy (SURF paper Fig. 1) as {x0, y0, x1, y1, w},
/// scaled to a filter of side `side`; each lobe's weight is divided by its area so the
/// response is a mean-intensity difference whatever the scale.
std::vector<Lobe> ScaledLobes(const int (*tmpl)[5], int n, int side) {
  const double ratio = side / 9.0;
  std::vector<Lobe> lobes;
  for (int k = 0; k < n; ++k) {
    Lobe l;
    l.c0 = static_cast<int>(std::lround(ratio * tmpl[k][0]));
    l.r0 = static_cast<int>(std::lround(ratio * tmpl[k][1]));
    l.c1 = static_cast<int>(std::lround(ratio * tmpl[k][2]));
    l.r1 = static_cast<int>(std::lround(ratio * tmpl[k][3]));
    l.weight = tmpl[k][4] / static_cast<double>((l.c1 - l.c0) * (l.r1 - l.r0));
    lobes.push_back(l);
  }
  return lobes;
}

struct HessianFilter {
  explicit HessianFilter(int side_px) : side(side_px) {
    static const int kDxx[3][5] = {{0, 2, 3, 7, 1}, {3, 2, 6, 7, -2}, {6, 2, 9, 7, 1}};
    static const int kDyy[3][5] = {{2, 0, 7, 3, 1}, {2, 3, 7, 6, -2}, {2, 6, 7, 9, 1}};
    static const int kDxy[4][5] = {
        {1, 1, 4, 4, 1}, {5, 1, 8, 4, -1}, {1, 5, 4, 8, -1}, {5, 5, 8, 8, 1}};
    dxx = ScaledLobes(kDxx, 3, side);
    dyy = ScaledLobes(kDyy, 3, side);
    dxy = ScaledLobes(kDxy, 4, side);
  }
  static double Apply(const Integral& in, const std::vector<Lobe>& lobes, int top, int left) {
    double v = 0.0;
    for (const Lobe& l : lobes) {
      v += l.weight * in.Box(top + l.r0, left + l.c0, top + l.r1, left + l.c1);
    }
    return v;
  }
  /// Top-left corner of the filter whose centre is nearest pixel `centre`.
  int Corner(int centre) const { return centre - side / 2; }
  /// Exact centre of a filter whose top-left corner is `corner`.
  double Centre(int corner) const { return corner + (side - 1) * 0.5; }

  int side;
  std::vector<Lobe> dxx, dyy, dxy;
};

/// det(H) = Dxx Dyy - (0.9 Dxy)^2 sampled every `step` px; 0 where the filter leaves the image.
cv::Mat LayerDeterminant(const Integral& in, const HessianFilter& f, int step) {
  const int rows = (in.rows() + step - 1) / step;
  const int cols = (in.cols() + step - 1) / step;
  cv::Mat det(rows, cols, CV_32F, cv::Scalar(0));
  cv::parallel_for_(cv::Range(0, rows), [&](const cv::Range& range) {
    for (int i = range.start; i < range.end; ++i) {
      const int top = f.Corner(i * step);
      if (top < 0 || top + f.side > in.rows()) continue;
      float* out = det.ptr<float>(i);
      for (int j = 0; j < cols; ++j) {
        const int left = f.Corner(j * step);
        if (left < 0 || left + f.side > in.cols()) continue;
        const double xx = HessianFilter::Apply(in, f.dxx, top, left);
        const double yy = HessianFilter::Apply(in, f.dyy, top, left);
        const double xy = HessianFilter::Apply(in, f.dxy, top, left);
        out[j] = static_cast<float>(xx * yy - 0.81 * xy * xy);
      }
    }
  });
  return det;
}

/// Newton step of a 3-D quadratic through the 3x3x3 neighbourhood (Brown and Lowe).
/// Returns false when the extremum lies more than one sample away.
bool Interpolate(const cv::Mat& below, const cv::Mat& here, const cv::Mat& above, int i, int j,
                 cv::Vec3d* offset) {
  auto v = [&](const cv::Mat& m, int di, int dj) {
    return static_cast<double>(m.at<float>(i + di, j + dj));
  };
  const cv::Vec3d b(-(v(here, 0, 1) - v(here, 0, -1)) / 2, -(v(here, 1, 0) - v(here, -1, 0)) / 2,
                    -(v(above, 0, 0) - v(below, 0, 0)) / 2);
  const double dxx = v(here, 0, 1) - 2 * v(here, 0, 0) + v(here, 0, -1);
  const double dyy = v(here, 1, 0) - 2 * v(here, 0, 0) + v(here, -1, 0);
  const double dss = v(above, 0, 0) - 2 * v(here, 0, 0) + v(below, 0, 0);
  const double dxy = (v(here, 1, 1) - v(here, 1, -1) - v(here, -1, 1) + v(here, -1, -1)) / 4;
  const double dxs = (v(above, 0, 1) - v(above, 0, -1) - v(below, 0, 1) + v(below, 0, -1)) / 4;
  const double dys = (v(above, 1, 0) - v(above, -1, 0) - v(below, 1, 0) + v(below, -1, 0)) / 4;
  const cv::Matx33d a(dxx, dxy, dxs, dxy, dyy, dys, dxs, dys, dss);
  cv::Vec3d x;
  if (!cv::solve(a, b, x, cv::DECOMP_LU)) return false;
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(x[k]) || std::abs(x[k]) > 1.0) return false;
  }
  *offset = x;
  return true;
}

/// Whether dets[layer](i, j) exceeds its 26 neighbours in the 3x3x3 scale-space block.
bool IsStrictMaximum(const std::vector<cv::Mat>& dets, int layer, int i, int j) {
  const float val = dets[layer].at<float>(i, j);
  for (int dl = -1; dl <= 1; ++dl) {
    const cv::Mat& d = dets[layer + dl];
    for (int di = -1; di <= 1; ++di) {
      const float* nrow = d.ptr<float>(i + di);
      for (int dj = -1; dj <= 1; ++dj) {
        if ((dl || di || dj) && !(val > nrow[j + dj])) return false;
      }
    }
  }
  return true;
}

std::vector<cv::KeyPoint> FastHessian(const Integral& in, const cv::Mat& mask,
                                      const SurfParams& p) {
  std::vector<cv::KeyPoint> keypoints;
  std::mutex lock;
  for (int octave = 0; octave < p.octaves; ++octave) {
    const int step = 1 << octave;
    std::vector<HessianFilter> filters;
    for (int layer = 0; layer < p.octave_layers + 2; ++layer) {
      filters.emplace_back((kHaarSize0 + kHaarSizeInc * layer) << octave);
    }
    if (filters.back().side > std::min(in.rows(), in.cols())) break;
    std::vector<cv::Mat> dets;
    for (const HessianFilter& f : filters) dets.push_back(LayerDeterminant(in, f, step));
    const int rows = dets[0].rows, cols = dets[0].cols;
    for (int layer = 1; layer <= p.octave_layers; ++layer) {
      const HessianFilter& f = filters[layer];
      // The neighbourhood in the layer above must lie inside the image.
      const int margin = (filters[layer + 1].side / 2) / step + 1;
      cv::parallel_for_(
          cv::Range(margin, std::max(margin, rows - margin)), [&](const cv::Range& r) {
            std::vector<cv::KeyPoint> found;
            for (int i = r.start; i < r.end; ++i) {
              const float* row = dets[layer].ptr<float>(i);
              for (int j = margin; j < cols - margin; ++j) {
                const float val = row[j];
                if (!(val > p.hessian_threshold) || val <= 0.0f) continue;
                const int cy = i * step, cx = j * step;
                if (!mask.empty() &&
                    mask.at<uchar>(std::min(cy, mask.rows - 1), std::min(cx, mask.cols - 1)) == 0) {
                  continue;
                }
                if (!IsStrictMaximum(dets, layer, i, j)) continue;
                cv::Vec3d offset;
                if (!Interpolate(dets[layer - 1], dets[layer], dets[layer + 1], i, j, &offset)) {
                  continue;
                }
                const int top = f.Corner(cy), left = f.Corner(cx);
                const double trace = HessianFilter::Apply(in, f.dxx, top, left) +
                                     HessianFilter::Apply(in, f.dyy, top, left);
                const double side = f.side + offset[2] * (f.side - filters[layer - 1].side);
                cv::KeyPoint kp(static_cast<float>(f.Centre(left) + offset[0] * step),
                                static_cast<float>(f.Centre(top) + offset[1] * step),
                                static_cast<float>(side), -1.0f, val, octave,
                                trace > 0 ? 1 : (trace < 0 ? -1 : 0));
                found.push_back(kp);
              }
            }
            std::lock_guard<std::mutex> guard(lock);
            keypoints.insert(keypoints.end(), found.begin(), found.end());
          });
    }
  }
  // parallel_for_ makes the order depend on scheduling: sort for reproducible output.
  std::sort(keypoints.begin(), keypoints.end(), [](const cv::KeyPoint& a, const cv::KeyPoint& b) {
    if (a.response != b.response) return a.response > b.response;
    if (a.pt.y != b.pt.y) return a.pt.y < b.pt.y;
    return a.pt.x < b.pt.x;
  });
  return keypoints;
}

/// Dominant direction of Haar responses within 6 s (degrees in [0, 360), image axes).
float Orientation(const Integral& in, const cv::KeyPoint& kp) {
  const double s = kp.size * kScalePerSide;
  const int side = std::max(2, 2 * static_cast<int>(std::lround(2.0 * s)));  // 4 s, even
  std::vector<double> angle, wx, wy;
  const int radius = static_cast<int>(kOrientationRadius);
  for (int i = -radius; i <= radius; ++i) {
    for (int j = -radius; j <= radius; ++j) {
      if (i * i + j * j >= radius * radius) continue;
      double dx, dy;
      in.Haar(kp.pt.x + i * s, kp.pt.y + j * s, side, &dx, &dy);
      const double w = std::exp(-(i * i + j * j) / (2.0 * kOrientationSigma * kOrientationSigma));
      if (dx == 0.0 && dy == 0.0) continue;
      angle.push_back(std::atan2(dy, dx));
      wx.push_back(w * dx);
      wy.push_back(w * dy);
    }
  }
  double best_norm = -1.0, best_x = 1.0, best_y = 0.0;
  for (double start = -M_PI; start < M_PI; start += kOrientationStepRad) {
    double sx = 0.0, sy = 0.0;
    for (std::size_t k = 0; k < angle.size(); ++k) {
      double d = angle[k] - start;
      if (d < 0) d += 2 * M_PI;
      if (d < kOrientationWindowRad) {
        sx += wx[k];
        sy += wy[k];
      }
    }
    const double norm = sx * sx + sy * sy;
    if (norm > best_norm) {
      best_norm = norm;
      best_x = sx;
      best_y = sy;
    }
  }
  double deg = std::atan2(best_y, best_x) * 180.0 / M_PI;
  if (deg < 0) deg += 360.0;
  if (deg >= 360.0) deg -= 360.0;
  return static_cast<float>(deg);
}

/// The 64-d descriptor: a 20 s window rotated to the keypoint's angle, 4x4 sub-regions
/// of 5x5 samples of Haar responses (side 2 s) expressed in the rotated frame.
void Describe(const Integral& in, const cv::KeyPoint& kp, float* out) {
  const double s = kp.size * kScalePerSide;
  const int side = std::max(2, 2 * static_cast<int>(std::lround(s)));  // 2 s, even
  const double theta = kp.angle < 0 ? 0.0 : kp.angle * M_PI / 180.0;
  const double c = std::cos(theta), sn = std::sin(theta);
  const double inv_two_sigma2 = 1.0 / (2.0 * (kDescriptorSigma * s) * (kDescriptorSigma * s));
  double d[64] = {0.0};
  for (int a = 0; a < 4; ++a) {
    for (int b = 0; b < 4; ++b) {
      double* cell = d + (b * 4 + a) * 4;
      for (int k = 0; k < 5; ++k) {
        for (int l = 0; l < 5; ++l) {
          const double u = (a * 5 + k - 10 + 0.5) * s;
          const double v = (b * 5 + l - 10 + 0.5) * s;
          double dx, dy;
          in.Haar(kp.pt.x + c * u - sn * v, kp.pt.y + sn * u + c * v, side, &dx, &dy);
          const double w = std::exp(-(u * u + v * v) * inv_two_sigma2);
          const double rx = w * (c * dx + sn * dy);
          const double ry = w * (-sn * dx + c * dy);
          cell[0] += rx;
          cell[1] += std::abs(rx);
          cell[2] += ry;
          cell[3] += std::abs(ry);
        }
      }
    }
  }
  double norm = 0.0;
  for (double v : d) norm += v * v;
  norm = std::sqrt(norm);
  for (int k = 0; k < 64; ++k) out[k] = norm > 0 ? static_cast<float>(d[k] / norm) : 0.0f;
}

}  // namespace

void Surf::detectAndCompute(cv::InputArray image, cv::InputArray mask,
                            std::vector<cv::KeyPoint>& keypoints, cv::OutputArray descriptors,
                            bool use_provided_keypoints) {
  const cv::Mat img = image.getMat();
  CV_Assert(img.empty() || img.type() == CV_8UC1);
  const cv::Mat m = mask.getMat();
  CV_Assert(m.empty() || (m.type() == CV_8UC1 && m.size() == img.size()));
  if (img.empty()) {
    keypoints.clear();
    if (descriptors.needed()) descriptors.release();
    return;
  }
  const Integral in(img);
  if (!use_provided_keypoints) {
    keypoints = FastHessian(in, m, params_);  // strongest first
    if (params_.max_keypoints > 0 && static_cast<int>(keypoints.size()) > params_.max_keypoints) {
      keypoints.resize(params_.max_keypoints);
    }
  }
  for (cv::KeyPoint& kp : keypoints) kp.angle = params_.upright ? 0.0f : Orientation(in, kp);
  if (!descriptors.needed()) return;
  descriptors.create(static_cast<int>(keypoints.size()), 64, CV_32F);
  cv::Mat desc = descriptors.getMat();
  cv::parallel_for_(cv::Range(0, static_cast<int>(keypoints.size())), [&](const cv::Range& r) {
    for (int k = r.start; k < r.end; ++k) Describe(in, keypoints[k], desc.ptr<float>(k));
  });
}

}  // namespace uwbsar
