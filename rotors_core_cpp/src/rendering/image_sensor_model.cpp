#include "rotors_core/rendering/image_sensor_model.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace rotors_sim {
namespace rendering {

bool ImageSensorParams::AnyEffect() const { return TimeWindow() || noise || vignetting != Vignetting::kNone; }

std::string ImageSensorParams::Validate() const {
  std::ostringstream why;
  auto check = [&why](bool ok, const char* name, double value, const char* range) {
    if (!ok && why.str().empty()) why << "<" << name << "> " << value << " must be " << range;
  };
  check(std::isfinite(exposure_s) && exposure_s >= 0.0, "exposureTime", exposure_s, ">= 0 s");
  check(max_subframes >= 1 && max_subframes <= 1024, "maxSubframes", max_subframes, "in 1 .. 1024");
  check(std::isfinite(subframes_per_pixel) && subframes_per_pixel > 0.0, "subframesPerPixel", subframes_per_pixel,
        "> 0");
  check(std::isfinite(line_delay_s) && line_delay_s >= 0.0, "lineDelay", line_delay_s, ">= 0 s (0: global shutter)");
  check(desired_bin >= 1 && desired_bin <= 64, "autoExposureDesiredBin", desired_bin, "in 1 .. 64");
  check(aec_low_pass >= 0 && aec_low_pass <= 2, "autoExposureLowPass", aec_low_pass, "0, 1 or 2");
  check(agc_low_pass >= 0 && agc_low_pass <= 2, "autoGainLowPass", agc_low_pass, "0, 1 or 2");
  check(update_interval_frames >= 0 && update_interval_frames <= 16, "autoExposureUpdateInterval",
        update_interval_frames, "in 0 .. 16 frames");
  check(std::isfinite(row_time_s) && row_time_s > 0.0, "rowTime", row_time_s, "> 0 s");
  check(max_shutter_rows >= 1, "maxShutterWidth", max_shutter_rows, ">= 1 row");
  check(std::isfinite(max_analog_gain) && max_analog_gain >= 1.0, "maxAnalogGain", max_analog_gain, ">= 1");
  check(std::isfinite(reference_exposure_s) && reference_exposure_s > 0.0, "referenceExposure", reference_exposure_s,
        "> 0 s");
  if (noise) {
    check(std::isfinite(full_well_e) && full_well_e >= 1.0, "fullWellCapacity", full_well_e,
          ">= 1 e- (photonNoise is on)");
    check(std::isfinite(read_noise_e) && read_noise_e >= 0.0, "readNoise", read_noise_e, ">= 0 e-");
    check(std::isfinite(prnu) && prnu >= 0.0 && prnu < 1.0, "photoResponseNonUniformity", prnu, "in [0, 1)");
    check(std::isfinite(dsnu_e) && dsnu_e >= 0.0, "darkSignalNonUniformity", dsnu_e, ">= 0 e-");
  }
  check(adc_bits >= 8 && adc_bits <= 16, "adcBits", adc_bits, "in 8 .. 16");
  for (double a : vignetting_coefficients) check(std::isfinite(a), "vignettingCoefficients", a, "finite");
  check(std::isfinite(time_offset_s), "timeOffset", time_offset_s, "finite");
  check(std::isfinite(stamp_jitter_s) && stamp_jitter_s >= 0.0, "stampJitter", stamp_jitter_s, ">= 0 s");
  return why.str();
}

ExposurePlan ExposurePlan::Make(double exposure_s, double line_delay_s, int rows, double image_speed_px_s,
                                double subframes_per_pixel, int max_subframes) {
  ExposurePlan plan;
  // the frame's window: from the first row's exposure start to the last row's end
  const double window_s = exposure_s + (rows - 1) * line_delay_s;
  const double motion_px = std::abs(image_speed_px_s) * window_s;
  const int n =
      window_s > 0.0 ? std::clamp(static_cast<int>(std::ceil(motion_px * subframes_per_pixel)), 1, max_subframes) : 1;
  // midpoints of n equal parts of the window: the midpoint rule for eq. S1's integral
  for (int k = 0; k < n; ++k) plan.times_s.push_back(-window_s / 2.0 + (k + 0.5) * window_s / n);
  plan.row_first.resize(rows);
  plan.row_count.resize(rows);
  for (int r = 0; r < rows; ++r) {
    const double centre_s = (r - (rows - 1) / 2.0) * line_delay_s;  // eq. S2
    const double lo = centre_s - exposure_s / 2.0, hi = centre_s + exposure_s / 2.0;
    const auto first = std::lower_bound(plan.times_s.begin(), plan.times_s.end(), lo - 1e-15);
    const auto end = std::upper_bound(plan.times_s.begin(), plan.times_s.end(), hi + 1e-15);
    if (first < end) {
      plan.row_first[r] = static_cast<int>(first - plan.times_s.begin());
      plan.row_count[r] = static_cast<int>(end - first);
    } else {  // an exposure shorter than the renders' spacing: the render nearest its middle
      int nearest = 0;
      for (int k = 1; k < n; ++k)
        if (std::abs(plan.times_s[k] - centre_s) < std::abs(plan.times_s[nearest] - centre_s)) nearest = k;
      plan.row_first[r] = nearest;
      plan.row_count[r] = 1;
    }
  }
  return plan;
}

AutoExposure::AutoExposure(const ImageSensorParams& p) : p_(p), row_time_s_(p.row_time_s) { Reset(); }

void AutoExposure::Reset() {
  // the power-on exposure: the fixed one when given, else the longest (the register's reset value)
  const double rows = p_.exposure_s > 0.0 ? p_.exposure_s / row_time_s_ : p_.max_shutter_rows;
  rows_ = std::clamp(std::round(rows), 1.0, static_cast<double>(p_.max_shutter_rows));
  gain_ = 1.0;
  frames_since_update_ = 0;
}

void AutoExposure::Update(double mean_full_scale) {
  if (++frames_since_update_ <= p_.update_interval_frames) return;
  frames_since_update_ = 0;
  // eq. S3: the total exposure E = rows gain that brings the mean to the desired bin (a linear
  // sensor), exposure first and then gain; each moves 1 / 2^lpf of the way, in whole rows and in
  // the gain register's steps of 1/16
  const double target = p_.desired_bin / 64.0;
  const double ratio = std::min(target / std::max(mean_full_scale, 1.0 / 1024.0), 64.0);
  const double total = rows_ * gain_ * ratio;
  const double rows_wanted = std::clamp(total, 1.0, static_cast<double>(p_.max_shutter_rows));
  const double gain_wanted = std::clamp(total / rows_wanted, 1.0, p_.max_analog_gain);
  rows_ = std::clamp(std::round(rows_ + (rows_wanted - rows_) / (1 << p_.aec_low_pass)), 1.0,
                     static_cast<double>(p_.max_shutter_rows));
  gain_ = std::clamp(std::round((gain_ + (gain_wanted - gain_) / (1 << p_.agc_low_pass)) * 16.0) / 16.0, 1.0,
                     p_.max_analog_gain);
}

namespace {
/// splitmix64: a counter-based generator (deterministic per pixel and frame, in any order)
inline uint64_t Mix(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// The standard normal's quantiles at the midpoints of 65,536 equal-probability bins: a normal draw
/// from 16 random bits (variance 1 - 2e-4: the tails beyond 4.3 sigma are cut).
const std::array<float, 65536>& NormalQuantiles() {
  static const std::array<float, 65536> table = [] {
    std::array<float, 65536> q{};
    for (size_t i = 0; i < q.size(); ++i) {
      const double p = (i + 0.5) / q.size();
      // Phi^-1(p) by bisection on Phi(x) = erfc(-x / sqrt 2) / 2
      double lo = -12.0, hi = 12.0;
      for (int k = 0; k < 80; ++k) {
        const double mid = 0.5 * (lo + hi);
        (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
      }
      const double x = 0.5 * (lo + hi);
      q[i] = static_cast<float>(x);
    }
    return q;
  }();
  return table;
}
}  // namespace

double StampOffsetS(const ImageSensorParams& p, uint64_t seed) {
  if (p.stamp_jitter_s == 0.0) return p.time_offset_s;
  return p.time_offset_s + p.stamp_jitter_s * NormalQuantiles()[Mix(seed) & 0xffff];
}

void AddGazeboNoise(double mean, double stddev, uint64_t seed, std::vector<uint8_t>* image) {
  if (stddev <= 0.0 && mean == 0.0) return;
  const float* normal = NormalQuantiles().data();
  const uint64_t key = Mix(seed);
  const float m = static_cast<float>(255.0 * mean), sigma = static_cast<float>(255.0 * stddev);
  for (size_t i = 0; i < image->size(); ++i) {
    const float value = (*image)[i] + m + sigma * normal[Mix(key + i) & 0xffff] + 0.5f;
    (*image)[i] = static_cast<uint8_t>(std::min(std::max(value, 0.0f), 255.0f));
  }
}

ImageSensor::ImageSensor(const ImageSensorParams& p, int width_px, int height_px, int channels, double focal_length_px,
                         double cx_px, double cy_px, uint64_t pattern_seed)
    : p_(p), width_(width_px), height_(height_px), channels_(channels) {
  vignetting_.resize(static_cast<size_t>(width_px) * height_px);
  for (int v = 0; v < height_px; ++v)
    for (int u = 0; u < width_px; ++u) {
      // eq. S5, r the distance from the principal point in units of the focal length (tan theta)
      const double r2 = ((u - cx_px) * (u - cx_px) + (v - cy_px) * (v - cy_px)) / (focal_length_px * focal_length_px);
      double factor = 1.0;
      if (p.vignetting == ImageSensorParams::Vignetting::kCos4) {
        factor = 1.0 / ((1.0 + r2) * (1.0 + r2));  // cos^4 theta = 1 / (1 + tan^2 theta)^2
      } else if (p.vignetting == ImageSensorParams::Vignetting::kPolynomial) {
        const double* a = p.vignetting_coefficients;
        factor = std::max(0.0, 1.0 + r2 * (a[0] + r2 * (a[1] + r2 * a[2])));
      }
      vignetting_[static_cast<size_t>(v) * width_px + u] = static_cast<float>(factor);
    }
  if (p.noise && (p.prnu > 0.0 || p.dsnu_e > 0.0)) {
    const auto& normal = NormalQuantiles();
    const size_t n = static_cast<size_t>(width_px) * height_px * channels;
    prnu_gain_.resize(n);
    dsnu_e_.resize(n);
    for (size_t i = 0; i < n; ++i) {
      const uint64_t bits = Mix(pattern_seed ^ Mix(i));
      prnu_gain_[i] = static_cast<float>(1.0 + p.prnu * normal[bits & 0xffff]);
      dsnu_e_[i] = static_cast<float>(p.dsnu_e * normal[(bits >> 16) & 0xffff]);
    }
  }
}

double ImageSensor::ConversionGainDnPerE(double gain) const { return gain * ((1 << p_.adc_bits) - 1) / p_.full_well_e; }

namespace {
/// eq. S4 for one pixel: electrons, the well's limit, read noise, the ADC, the 8-bit output
inline uint8_t ToOutput(double dn_full_scale, double dn, int adc_bits) {
  const double code = std::clamp(std::round(dn), 0.0, dn_full_scale);
  return static_cast<uint8_t>(static_cast<uint32_t>(code) >> (adc_bits - 8));
}
}  // namespace

void ImageSensor::Expose(const std::vector<const std::vector<uint8_t>*>& renders, const ExposurePlan& plan,
                         double exposure_s, double gain, uint64_t noise_seed, std::vector<uint8_t>* out) const {
  // eq. S1: each row the mean of its renders (the midpoint rule)
  const size_t row_values = static_cast<size_t>(width_) * channels_;
  std::vector<float> light(row_values * height_, 0.0f);
  for (int r = 0; r < height_; ++r) {
    const int first = plan.row_first[r], count = plan.row_count[r];
    float* row_light = light.data() + r * row_values;
    for (int k = first; k < first + count; ++k) {
      const uint8_t* row = renders[k]->data() + r * row_values;
      for (size_t i = 0; i < row_values; ++i) row_light[i] += row[i];
    }
    const float inv_count = 1.0f / static_cast<float>(count);
    for (size_t i = 0; i < row_values; ++i) row_light[i] *= inv_count;
  }
  Digitise(light, exposure_s, gain, noise_seed, out);
}

void ImageSensor::Digitise(const std::vector<float>& light, double exposure_s, double gain, uint64_t noise_seed,
                           std::vector<uint8_t>* out) const {
  const size_t row_values = static_cast<size_t>(width_) * channels_;
  out->assign(row_values * height_, 0);
  // eq. S1 and S4: the well fills in proportion to the light and the exposure (an instant counts as
  // the reference exposure); single precision: the output has 8 bits
  const double exposure_scale = (exposure_s > 0.0 ? exposure_s : p_.reference_exposure_s) / p_.reference_exposure_s;
  const int shift = p_.adc_bits - 8;
  const float full_scale = static_cast<float>((1 << p_.adc_bits) - 1);
  const float to_fraction = static_cast<float>(exposure_scale / 255.0);
  const float signal_to_dn = static_cast<float>(gain) * full_scale;  // without noise: DN = well fraction g (2^b - 1)
  const float full_well = static_cast<float>(p_.full_well_e), read_noise = static_cast<float>(p_.read_noise_e);
  const float k_dn_per_e = p_.noise ? static_cast<float>(ConversionGainDnPerE(gain)) : 0.0f;
  const float* normal = NormalQuantiles().data();
  const uint64_t seed = Mix(noise_seed);
  auto to_output = [&](float dn) {
    const float code = std::min(std::max(dn + 0.5f, 0.0f), full_scale);  // round, clamp to the ADC's range
    return static_cast<uint8_t>(static_cast<uint32_t>(code) >> shift);
  };
  auto rows = [&](int row_begin, int row_end) {
    for (int r = row_begin; r < row_end; ++r) {
      const float* row_light = light.data() + r * row_values;
      const float* row_vignetting = vignetting_.data() + static_cast<size_t>(r) * width_;
      uint8_t* out_row = out->data() + r * row_values;
      const size_t row_start = static_cast<size_t>(r) * row_values;
      for (int u = 0; u < width_; ++u) {
        const float vignette = row_vignetting[u] * to_fraction;
        for (int c = 0; c < channels_; ++c) {
          const size_t i = static_cast<size_t>(u) * channels_ + c;
          const float well_fraction = row_light[i] * vignette;
          if (!p_.noise) {
            out_row[i] = to_output(well_fraction * signal_to_dn);
            continue;
          }
          const size_t pixel = row_start + i;
          const uint64_t bits = Mix(seed + pixel);
          const float prnu = prnu_gain_.empty() ? 1.0f : prnu_gain_[pixel];
          const float dsnu = dsnu_e_.empty() ? 0.0f : dsnu_e_[pixel];
          // shot noise: Poisson, as a Gaussian of variance = mean (the mean is many electrons)
          const float mean_e = std::max(0.0f, well_fraction * full_well * prnu);
          const float e = std::min(std::max(0.0f, mean_e + std::sqrt(mean_e) * normal[bits & 0xffff]), full_well);
          const float read_e = e + dsnu + read_noise * normal[(bits >> 16) & 0xffff];
          out_row[i] = to_output(read_e * k_dn_per_e);
        }
      }
    }
  };
  // two halves of the rows at once (a counter-based generator: the same values in any order)
  std::thread top([&] { rows(0, height_ / 2); });
  rows(height_ / 2, height_);
  top.join();
}

namespace {
/// Rows [row_begin, row_end) of VelocityBufferExposure, for C channels. Two passes a row: each
/// pixel's motion and where its samples lie (float arithmetic and selects, no branch), then the
/// samples themselves.
template <int channels>
void VelocityBufferRows(const std::vector<uint8_t>& image, const std::vector<float>& depth_m, int width_px,
                        int height_px, float f, float cx, float cy, const float v[3], const float w[3], float tau,
                        double line_delay_s, float subframes_per_pixel, int max_subframes, int row_begin, int row_end,
                        float* light) {
  const size_t row_values = static_cast<size_t>(width_px) * channels;
  const float x_max = static_cast<float>(width_px - 1), y_max = static_cast<float>(height_px - 1);
  const int x_last = std::max(width_px - 2, 0), y_last = std::max(height_px - 2, 0);
  const size_t dx = width_px > 1 ? channels : 0, dy = height_px > 1 ? row_values : 0;
  const float max_n = static_cast<float>(max_subframes);
  std::vector<float> sx0_row(width_px), sy0_row(width_px), step_x_row(width_px), step_y_row(width_px);
  std::vector<int32_t> n_row(width_px);
  const std::vector<float> no_depth(depth_m.empty() ? width_px : 0, 0.0f);  // no depth: rotation only
  for (int r = row_begin; r < row_end; ++r) {
    const float t_row = static_cast<float>((r - (height_px - 1) / 2.0) * line_delay_s);  // eq. S2
    const float y = r - cy;
    const float* depth_row = depth_m.empty() ? no_depth.data() : depth_m.data() + static_cast<size_t>(r) * width_px;
    // pass 1: the motion of each pixel and where its samples lie
    for (int u = 0; u < width_px; ++u) {
      const float x = u - cx;
      const float z = depth_row[u], one_over_z = 1.0f / z;
      const bool usable = (z > 0.0f) & (z <= std::numeric_limits<float>::max());  // finite, > 0
      const float inv_z = usable ? one_over_z : 0.0f;
      // P / Z = (x / f, y / f, 1);  P' / Z = -v / Z - omega x (P / Z)
      const float q0 = x / f, q1 = y / f;
      const float d0 = -v[0] * inv_z - (w[1] - w[2] * q1), d1 = -v[1] * inv_z - (w[2] * q0 - w[0]),
                  d2 = -v[2] * inv_z - (w[0] * q1 - w[1] * q0);
      const float du = f * d0 - x * d2, dv = f * d1 - y * d2;  // [px/s]
      const float motion_px = std::sqrt(du * du + dv * dv) * tau;
      // n = clamp(ceil(motion spp), 1, max): the ceiling of a value under max_subframes, in integers
      const float m = std::min(motion_px * subframes_per_pixel, max_n);
      int32_t n = static_cast<int32_t>(m);
      n += static_cast<float>(n) < m ? 1 : 0;
      n = std::max(n, 1);  // 1 for a still camera or no exposure (m <= 0)
      // the samples along the motion: p - p' t, t = t_row - tau / 2 + (k + 1/2) tau / n
      const float n_f = static_cast<float>(n);
      const float t0 = t_row - tau / 2.0f + 0.5f * tau / n_f, dt = tau / n_f;
      sx0_row[u] = u - du * t0;
      sy0_row[u] = r - dv * t0;
      step_x_row[u] = -du * dt;
      step_y_row[u] = -dv * dt;
      n_row[u] = n;
    }
    // pass 2: bilinear in fixed point (1/256 pixel), clamped to the image where the segment leaves it
    for (int u = 0; u < width_px; ++u) {
      const size_t px = static_cast<size_t>(r) * width_px + u;
      const int n = n_row[u];
      const float sx0 = sx0_row[u], sy0 = sy0_row[u], step_x = step_x_row[u], step_y = step_y_row[u];
      const float sx1 = sx0 + step_x * (n - 1), sy1 = sy0 + step_y * (n - 1);
      const bool inside = std::min(sx0, sx1) >= 0.0f && std::max(sx0, sx1) < x_last + 1.0f &&
                          std::min(sy0, sy1) >= 0.0f && std::max(sy0, sy1) < y_last + 1.0f;
      int32_t acc[4] = {0, 0, 0, 0};
      int32_t fx = static_cast<int32_t>(std::min(std::max(sx0, 0.0f), x_max) * 256.0f + 0.5f);
      int32_t fy = static_cast<int32_t>(std::min(std::max(sy0, 0.0f), y_max) * 256.0f + 0.5f);
      const int32_t fdx = static_cast<int32_t>(std::lrint(step_x * 256.0f)),
                    fdy = static_cast<int32_t>(std::lrint(step_y * 256.0f));
      const int32_t fx_max = x_last * 256 + 255, fy_max = y_last * 256 + 255;
      for (int k = 0; k < n; ++k, fx += fdx, fy += fdy) {
        const int32_t qx = inside ? fx : std::min(std::max(fx, 0), fx_max);
        const int32_t qy = inside ? fy : std::min(std::max(fy, 0), fy_max);
        const int x0 = qx >> 8, y0 = qy >> 8, ax = qx & 255, ay = qy & 255;
        const uint8_t* p00 = image.data() + (static_cast<size_t>(y0) * width_px + x0) * channels;
        for (int c = 0; c < channels; ++c) {
          const int32_t top = p00[c] * (256 - ax) + p00[c + dx] * ax;
          const int32_t bottom = p00[c + dy] * (256 - ax) + p00[c + dy + dx] * ax;
          acc[c] += top * (256 - ay) + bottom * ay;  // 16 fractional bits
        }
      }
      const float inv_n = 1.0f / static_cast<float>(n);
      for (int c = 0; c < channels; ++c) light[px * channels + c] = acc[c] * (1.0f / 65536.0f) * inv_n;
    }
  }
}
}  // namespace

void VelocityBufferExposure(const std::vector<uint8_t>& image, const std::vector<float>& depth_m, int width_px,
                            int height_px, int channels, double f_px, double cx_px, double cy_px,
                            const CameraTwist& twist, double exposure_s, double line_delay_s,
                            double subframes_per_pixel, int max_subframes, std::vector<float>* light) {
  light->assign(static_cast<size_t>(width_px) * channels * height_px, 0.0f);
  const float v[3] = {static_cast<float>(twist.v_O[0]), static_cast<float>(twist.v_O[1]),
                      static_cast<float>(twist.v_O[2])};
  const float w[3] = {static_cast<float>(twist.omega_O[0]), static_cast<float>(twist.omega_O[1]),
                      static_cast<float>(twist.omega_O[2])};
  if (channels != 1 && channels != 3)
    throw std::invalid_argument("VelocityBufferExposure: " + std::to_string(channels) + " channels; 1 or 3");
  auto rows = [&](int begin, int end) {
    auto run = [&](auto rows_of) {
      rows_of(image, depth_m, width_px, height_px, static_cast<float>(f_px), static_cast<float>(cx_px),
              static_cast<float>(cy_px), v, w, static_cast<float>(exposure_s), line_delay_s,
              static_cast<float>(subframes_per_pixel), max_subframes, begin, end, light->data());
    };
    if (channels == 1) {
      run(VelocityBufferRows<1>);
    } else {
      run(VelocityBufferRows<3>);
    }
  };
  // two halves of the rows at once: the renderer's threads are idle by now
  std::thread top([&] { rows(0, height_px / 2); });
  rows(height_px / 2, height_px);
  top.join();
}

}  // namespace rendering
}  // namespace rotors_sim
