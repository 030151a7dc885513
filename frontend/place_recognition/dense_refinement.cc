#include "frontend/place_recognition/dense_refinement.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace uwbsar {
namespace {

constexpr double kNoCorrelation = -2.0;  // below any NCC: shifts with too little overlap

/// An image as values and 0/1 weights (the mask). The values are high-passed: the local mean
/// over the measured pixels (a Gaussian of `highpass_px`, normalised by the mask's) is taken
/// off, so that broad bands (a wall's echo, the clutter level) do not make every nearby shift
/// correlate nearly as well as the right one; what is left is the scatterers' fine pattern,
/// which correlates at one shift only. In units of the 8-bit range, so the float correlations'
/// sums stay small and lose nothing to cancellation.
struct Weighted {
  cv::Mat value;   ///< CV_32F, 0 where not measured
  cv::Mat weight;  ///< CV_32F, 1 measured, 0 not
};

Weighted ToWeighted(const FeatureImage& image, double highpass_px) {
  Weighted w;
  const cv::Mat mask = image.mask.empty() ? cv::Mat(image.gray > 0) : image.mask;
  mask.convertTo(w.weight, CV_32F, 1.0 / 255.0);
  cv::threshold(w.weight, w.weight, 0.5, 1.0, cv::THRESH_BINARY);
  cv::Mat gray;
  image.gray.convertTo(gray, CV_32F, 1.0 / 255.0);
  gray = gray.mul(w.weight);
  cv::Mat local_sum, local_weight;
  cv::GaussianBlur(gray, local_sum, cv::Size(), highpass_px);
  cv::GaussianBlur(w.weight, local_weight, cv::Size(), highpass_px);
  cv::Mat local_mean = local_sum / cv::max(local_weight, 1e-3f);
  w.value = (gray - local_mean).mul(w.weight);
  return w;
}

cv::Matx23d Rigid(double rotation_deg, double tx, double ty) {
  const double r = rotation_deg * M_PI / 180.0;
  const double c = std::cos(r), s = std::sin(r);
  return {c, -s, tx, s, c, ty};
}

/// The seed followed by a rotation of `rotation_deg` about `c` (pixels of a):
/// p -> R (M_seed p - c) + c.
cv::Matx23d AboutCentre(const PixelRigid& seed, double rotation_deg, const cv::Point2d& c) {
  const double d = rotation_deg * M_PI / 180.0;
  const double x = seed.tx_px - c.x, y = seed.ty_px - c.y;
  const double cd = std::cos(d), sd = std::sin(d);
  return Rigid(seed.rotation_deg + rotation_deg, cd * x - sd * y + c.x, sd * x + cd * y + c.y);
}

/// NCC of `a` against `b` warped by `warp` (b pixels to a pixels) for every shift u in
/// [-S, S]^2 of the warped image (row u_y + S, column u_x + S). The template is the warped b
/// over the seed's overlap box (inside a by S pixels), so every shift compares the same b
/// pixels; shifts overlapping less than half of the seed's count get kNoCorrelation.
cv::Mat Surface(const Weighted& a, const Weighted& b, const cv::Matx23d& warp, int S,
                const cv::Rect& box) {
  Weighted bw;
  cv::warpAffine(b.value, bw.value, warp, a.value.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT, 0);
  cv::warpAffine(b.weight, bw.weight, warp, a.value.size(), cv::INTER_NEAREST, cv::BORDER_CONSTANT,
                 0);
  bw.value = bw.value.mul(bw.weight);  // bilinear taps across the mask edge
  const cv::Rect search(box.x - S, box.y - S, box.width + 2 * S, box.height + 2 * S);
  const cv::Mat ia = a.value(search), wa = a.weight(search);
  const cv::Mat tb = bw.value(box), wb = bw.weight(box);
  const cv::Mat ia2 = ia.mul(ia), tb2 = tb.mul(tb);
  auto corr = [](const cv::Mat& image, const cv::Mat& templ) {
    cv::Mat r;
    cv::matchTemplate(image, templ, r, cv::TM_CCORR);
    return r;
  };
  const cv::Mat n = corr(wa, wb), sa = corr(ia, wb), saa = corr(ia2, wb), sb = corr(wa, tb),
                sbb = corr(wa, tb2), sab = corr(ia, tb);
  const float n_seed = n.at<float>(S, S);
  cv::Mat ncc(n.size(), CV_64F, cv::Scalar(kNoCorrelation));
  for (int y = 0; y < n.rows; ++y) {
    for (int x = 0; x < n.cols; ++x) {
      const double k = n.at<float>(y, x);
      if (!(k >= 0.5 * n_seed) || k < 16) continue;
      const double ma = sa.at<float>(y, x), mb = sb.at<float>(y, x);
      const double va = saa.at<float>(y, x) - ma * ma / k;
      const double vb = sbb.at<float>(y, x) - mb * mb / k;
      if (!(va > 0 && vb > 0)) continue;
      ncc.at<double>(y, x) = (sab.at<float>(y, x) - ma * mb / k) / std::sqrt(va * vb);
    }
  }
  return ncc;
}

/// Offset of a parabola's vertex through (-1, l), (0, c), (1, r), within [-0.5, 0.5].
double Vertex(double l, double c, double r) {
  const double d = l - 2.0 * c + r;
  if (!(d < 0) || l <= kNoCorrelation || r <= kNoCorrelation) return 0.0;
  return std::clamp(0.5 * (l - r) / d, -0.5, 0.5);
}

/// The correlation that competes with the peak at `peak`: the highest one outside the peak's
/// lobe (the connected shifts around it whose correlation is at least half the peak's), or,
/// when the lobe reaches the window's edge (a ridge, e.g. a lone wall that fits anywhere along
/// itself), the lobe's highest value on that edge. 0 when neither is above 0.
double SecondPeak(const cv::Mat& s, const cv::Point& peak) {
  const double half = 0.5 * s.at<double>(peak);
  cv::Mat above;
  cv::compare(s, half, above, cv::CMP_GE);
  cv::Mat labels;
  cv::connectedComponents(above, labels, 8, CV_32S);
  const int lobe = labels.at<int>(peak);
  double second = 0.0;
  for (int y = 0; y < s.rows; ++y) {
    for (int x = 0; x < s.cols; ++x) {
      const bool edge = x == 0 || y == 0 || x == s.cols - 1 || y == s.rows - 1;
      if (labels.at<int>(y, x) != lobe || edge) second = std::max(second, s.at<double>(y, x));
    }
  }
  return second;
}

/// One search around `seed`; `recentre` is set to the integer peak (shift and rotation step)
/// when the peak lies in the outer half of the window, where the surface shows only one side of
/// its lobe.
DenseRefinement Search(const Weighted& wa, const Weighted& wb, const PixelRigid& seed, int S,
                       const DenseRefinementConfig& config, PixelRigid* recentre,
                       bool* off_centre) {
  DenseRefinement out;
  *off_centre = false;
  // The seed's overlap: its fraction of the smaller measured area, and its bounding box (kept
  // S pixels inside a, so that every shift of the template stays inside a).
  const cv::Matx23d seed_warp = Rigid(seed.rotation_deg, seed.tx_px, seed.ty_px);
  cv::Mat warped_weight;
  cv::warpAffine(wb.weight, warped_weight, seed_warp, wa.weight.size(), cv::INTER_NEAREST,
                 cv::BORDER_CONSTANT, 0);
  const cv::Mat both = wa.weight.mul(warped_weight);
  const double measured = std::min(cv::sum(wa.weight)[0], cv::sum(wb.weight)[0]);
  out.overlap_fraction = measured > 0 ? cv::sum(both)[0] / measured : 0.0;
  if (!(out.overlap_fraction >= config.min_overlap_fraction)) {
    out.reason = "too little overlap";
    return out;
  }
  cv::Mat both8;
  both.convertTo(both8, CV_8U);
  const cv::Rect inner(S, S, wa.weight.cols - 2 * S, wa.weight.rows - 2 * S);
  const cv::Rect box = cv::boundingRect(both8) & inner;
  if (box.area() <= 0) {
    out.reason = "too little overlap";
    return out;
  }
  // Rotations about the overlap's centre, so that a rotation step does not also move the
  // overlap by its lever arm from pixel (0, 0).
  const cv::Point2d c(box.x + 0.5 * (box.width - 1), box.y + 0.5 * (box.height - 1));
  const int K = static_cast<int>(std::floor(config.search_deg / config.step_deg + 1e-9));
  std::vector<cv::Mat> surfaces;
  int best_k = 0;
  cv::Point best_u(-1, -1);
  double best = kNoCorrelation;
  for (int k = -K; k <= K; ++k) {
    surfaces.push_back(Surface(wa, wb, AboutCentre(seed, k * config.step_deg, c), S, box));
    double v;
    cv::Point u;
    cv::minMaxLoc(surfaces.back(), nullptr, &v, nullptr, &u);
    if (v > best) {
      best = v;
      best_k = k;
      best_u = u;
    }
  }
  if (!(best > 0)) {
    out.reason = "no positive correlation";
    return out;
  }
  const cv::Mat& s = surfaces[best_k + K];
  out.peak_ncc = best;
  out.second_ncc = SecondPeak(s, best_u);
  out.peak_ratio = out.second_ncc > 0 ? out.peak_ncc / out.second_ncc : 1e9;
  {
    const cv::Matx23d at = AboutCentre(seed, best_k * config.step_deg, c);
    *recentre = {at(0, 2) + best_u.x - S, at(1, 2) + best_u.y - S,
                 seed.rotation_deg + best_k * config.step_deg};
    *off_centre = std::abs(best_u.x - S) * 2 > S || std::abs(best_u.y - S) * 2 > S ||
                  std::abs(best_k) * 2 > K;
  }
  if (best_u.x == 0 || best_u.y == 0 || best_u.x == s.cols - 1 || best_u.y == s.rows - 1 ||
      (K > 0 && std::abs(best_k) == K)) {
    out.reason = "correlation peak at the edge of the search window";
    return out;
  }
  const double ux =
      best_u.x - S +
      Vertex(s.at<double>(best_u.y, best_u.x - 1), best, s.at<double>(best_u.y, best_u.x + 1));
  const double uy =
      best_u.y - S +
      Vertex(s.at<double>(best_u.y - 1, best_u.x), best, s.at<double>(best_u.y + 1, best_u.x));
  double dk = 0.0;
  if (K > 0) {
    dk = Vertex(surfaces[best_k + K - 1].at<double>(best_u), best,
                surfaces[best_k + K + 1].at<double>(best_u));
  }
  // The peak's transform: its rotation step (interpolated) about c, then the shift.
  const cv::Matx23d peak = AboutCentre(seed, (best_k + dk) * config.step_deg, c);
  out.transform.rotation_deg = seed.rotation_deg + (best_k + dk) * config.step_deg;
  out.transform.tx_px = peak(0, 2) + ux;
  out.transform.ty_px = peak(1, 2) + uy;
  out.found = true;
  return out;
}

}  // namespace

std::vector<unsigned char> PackForRefinement(const FeatureImage& image) {
  std::vector<unsigned char> packed;
  if (image.gray.empty() || image.mask.size() != image.gray.size()) return packed;
  cv::Mat plane;
  cv::max(image.gray, 1, plane);
  plane.setTo(0, image.mask == 0);
  cv::imencode(".png", plane, packed, {cv::IMWRITE_PNG_COMPRESSION, 1});
  return packed;
}

FeatureImage UnpackForRefinement(const std::vector<unsigned char>& packed) {
  FeatureImage image;
  if (!packed.empty()) image.gray = cv::imdecode(packed, cv::IMREAD_GRAYSCALE);
  return image;
}

DenseRefinement RefineByCorrelation(const FeatureImage& a, const FeatureImage& b,
                                    const PixelRigid& seed, double resolution_m,
                                    const DenseRefinementConfig& config) {
  const double highpass_px = config.highpass_sigma_m / resolution_m;
  const Weighted wa = ToWeighted(a, highpass_px), wb = ToWeighted(b, highpass_px);
  const int S = std::max(1, static_cast<int>(std::lround(config.search_m / resolution_m)));
  PixelRigid recentre;
  bool off_centre = false;
  DenseRefinement out = Search(wa, wb, seed, S, config, &recentre, &off_centre);
  if (!off_centre) return out;
  // The peak lay in the window's outer half (or on its edge): there the surface shows one
  // flank of the peak's lobe only, and SecondPeak would take that flank, on the window's edge,
  // for a competitor. Search once more, centred on it.
  const double overlap_fraction = out.overlap_fraction;
  out = Search(wa, wb, recentre, S, config, &recentre, &off_centre);
  out.overlap_fraction = overlap_fraction;
  return out;
}

std::string JudgePeak(const DenseRefinement& r, double min_peak_ncc, double min_peak_ratio) {
  char buf[200];
  if (!r.found) return r.reason;
  if (r.peak_ncc < min_peak_ncc) {
    std::snprintf(buf, sizeof(buf), "correlation peak %.3f < %.3f", r.peak_ncc, min_peak_ncc);
    return buf;
  }
  if (r.peak_ratio < min_peak_ratio) {
    std::snprintf(buf, sizeof(buf), "correlation peak not distinct (%.3f / %.3f = %.2f < %.2f)",
                  r.peak_ncc, r.second_ncc, r.peak_ratio, min_peak_ratio);
    return buf;
  }
  return "";
}

}  // namespace uwbsar
