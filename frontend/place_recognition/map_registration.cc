#include "frontend/place_recognition/map_registration.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "frontend/place_recognition/loop_validator.h"

namespace uwbsar {
namespace {

/// The correlation settings of the dense refinement, from the registration's.
DenseRefinementConfig CorrelationConfig(const MapRegistrationConfig& c) {
  DenseRefinementConfig d;
  d.enabled = true;
  d.search_m = c.search_m;
  d.search_deg = c.search_deg;
  d.step_deg = c.step_deg;
  d.min_peak_ratio = c.min_peak_ratio;
  d.min_peak_ncc = c.min_peak_ncc;
  d.highpass_sigma_m = c.highpass_sigma_m;
  d.min_overlap_fraction = c.min_overlap_fraction;
  return d;
}

/// The value at `fraction` of the sorted observed values.
float Quantile(std::vector<float> values, double fraction) {
  const double last = static_cast<double>(values.size() - 1);
  const std::size_t k =
      std::min(values.size() - 1, static_cast<std::size_t>(fraction * last + 0.5));
  std::nth_element(values.begin(), values.begin() + static_cast<long>(k), values.end());
  return values[k];
}

}  // namespace

RegistrationImage MakeRegistrationImage(const cv::Mat& detected, const ImageGrid& grid,
                                        const MapRegistrationConfig& config) {
  RegistrationImage out;
  if (detected.empty() || detected.type() != CV_32FC1) return out;
  const double f = config.resolution_m / grid.resolution_m;
  const int cols = static_cast<int>(std::floor(grid.cols / std::max(f, 1e-9)));
  const int rows = static_cast<int>(std::floor(grid.rows / std::max(f, 1e-9)));
  if (cols < 3 || rows < 3) return out;
  // Observed pixels (finite, > 0) and their values, averaged over each output pixel's footprint:
  // a box blur of about the footprint's size, then sampled at the footprint centres with the exact
  // scale (cv::resize would round the size and leave each image its own pixel size).
  cv::Mat weight = (detected > 0) & (detected < 1e30f);
  weight.convertTo(weight, CV_32F, 1.0 / 255.0);
  cv::Mat value = detected.clone();
  value.setTo(0.0f, weight == 0.0f);
  if (f > 1.0) {
    const int k = 2 * static_cast<int>(std::floor(0.5 * f)) + 1;  // odd: centred on the pixel
    cv::blur(value, value, cv::Size(k, k), cv::Point(-1, -1), cv::BORDER_CONSTANT);
    cv::blur(weight, weight, cv::Size(k, k), cv::Point(-1, -1), cv::BORDER_CONSTANT);
  }
  const double c0 = 0.5 * (f - 1.0);
  const cv::Matx23d to_source(f, 0, c0, 0, f, c0);  // output pixel -> source pixel
  cv::Mat v, w;
  cv::warpAffine(value, v, to_source, cv::Size(cols, rows), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                 cv::BORDER_CONSTANT, 0);
  cv::warpAffine(weight, w, to_source, cv::Size(cols, rows),
                 cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_CONSTANT, 0);
  const cv::Mat mask = w >= 0.99f;  // the whole footprint observed
  const cv::Mat normalised = v / cv::max(w, 1e-6f);
  std::vector<float> observed;
  observed.reserve(static_cast<std::size_t>(cols) * rows);
  for (int r = 0; r < rows; ++r) {
    const float* nr = normalised.ptr<float>(r);
    const std::uint8_t* mr = mask.ptr<std::uint8_t>(r);
    for (int c = 0; c < cols; ++c) {
      if (mr[c]) observed.push_back(nr[c]);
    }
  }
  if (observed.size() < 16) return out;
  const float lo = *std::min_element(observed.begin(), observed.end());
  const float hi = Quantile(std::move(observed), config.white_percentile / 100.0);
  const double span = hi > lo ? static_cast<double>(hi - lo) : 1.0;
  // Observed pixels at least 1 (dense_refinement.h reads gray > 0 as observed when no mask).
  normalised.convertTo(out.image.gray, CV_8U, 254.0 / span, 1.0 - 254.0 * lo / span);
  out.image.gray.setTo(0, ~mask);
  out.image.mask = mask;
  out.grid.resolution_m = config.resolution_m;
  out.grid.cols = cols;
  out.grid.rows = rows;
  out.grid.x0_m = grid.ColToX(c0);
  out.grid.y0_m = grid.RowToY(c0);
  return out;
}

PixelRigid MetricToPixelTransform(const ImageGrid& grid_a, const ImageGrid& grid_b,
                                  const Pose2& T_ab) {
  // p_a = R(rot) p_b + t: b's pixel (0, 0) lands on t. Rows grow towards -y, so a metric yaw is a
  // pixel rotation of -yaw.
  const Point2 q_a = T_ab * grid_b.PixelToMetric(0.0, 0.0);
  PixelRigid p;
  p.tx_px = grid_a.XToCol(q_a.x_m);
  p.ty_px = grid_a.YToRow(q_a.y_m);
  p.rotation_deg = -NormalizeAngle(T_ab.yaw_rad) * 180.0 / M_PI;
  return p;
}

MapRegistration RegisterTiles(const RegistrationImage& a, const RegistrationImage& b,
                              const Pose2& T_ab_predicted, const MapRegistrationConfig& config) {
  MapRegistration out;
  if (a.empty() || b.empty()) {
    out.reason = "a tile observes nothing";
    return out;
  }
  const PixelRigid seed = MetricToPixelTransform(a.grid, b.grid, T_ab_predicted);
  out.correlation =
      RefineByCorrelation(a.image, b.image, seed, config.resolution_m, CorrelationConfig(config));
  const DenseRefinement& r = out.correlation;
  if (r.found) {
    out.T_ab = PixelToMetricTransform(a.grid, b.grid, r.transform.tx_px, r.transform.ty_px,
                                      r.transform.rotation_deg);
  }
  out.reason = JudgePeak(r, config.min_peak_ncc, config.min_peak_ratio);
  if (!out.reason.empty()) return out;
  const double sxy = config.sigma_xy_m, syaw = config.sigma_yaw_deg * M_PI / 180.0;
  out.information.diagonal() << 1.0 / (sxy * sxy), 1.0 / (sxy * sxy), 1.0 / (syaw * syaw);
  out.accepted = true;
  return out;
}

}  // namespace uwbsar
