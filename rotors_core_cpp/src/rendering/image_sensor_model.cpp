#include "rotors_core/rendering/image_sensor_model.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

namespace rotors_sim {
namespace rendering {

bool ImageSensorParams::AnyEffect() const {
  return TimeWindow() || noise || vignetting != Vignetting::kNone;
}

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
  for (double a : vignetting_coefficients)
    check(std::isfinite(a), "vignettingCoefficients", a, "finite");
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
  const int n = window_s > 0.0 ? std::clamp(static_cast<int>(std::ceil(motion_px * subframes_per_pixel)), 1,
                                            max_subframes)
                               : 1;
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

ImageSensor::ImageSensor(const ImageSensorParams& p, int width_px, int height_px, int channels,
                         double focal_length_px, double cx_px, double cy_px, uint64_t pattern_seed)
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

double ImageSensor::ConversionGainDnPerE(double gain) const {
  return gain * ((1 << p_.adc_bits) - 1) / p_.full_well_e;
}

namespace {
/// eq. S4 for one pixel: electrons, the well's limit, read noise, the ADC, the 8-bit output
inline uint8_t ToOutput(double dn_full_scale, double dn, int adc_bits) {
  const double code = std::clamp(std::round(dn), 0.0, dn_full_scale);
  return static_cast<uint8_t>(static_cast<uint32_t>(code) >> (adc_bits - 8));
}
}  // namespace

void ImageSensor::Expose(const std::vector<const std::vector<uint8_t>*>& renders, const ExposurePlan& plan,
                         double exposure_s, double gain, uint64_t noise_seed, std::vector<uint8_t>* out) const {
  const size_t row_values = static_cast<size_t>(width_) * channels_;
  out->assign(row_values * height_, 0);
  // eq. S1 and S4: the well fills in proportion to the light and the exposure (an instant counts as
  // the reference exposure)
  const double exposure_scale = (exposure_s > 0.0 ? exposure_s : p_.reference_exposure_s) / p_.reference_exposure_s;
  const double full_scale = (1 << p_.adc_bits) - 1;
  const double k_dn_per_e = p_.noise ? ConversionGainDnPerE(gain) : 0.0;
  const auto& normal = NormalQuantiles();
  std::vector<float> light(row_values);
  for (int r = 0; r < height_; ++r) {
    const int first = plan.row_first[r], count = plan.row_count[r];
    std::fill(light.begin(), light.end(), 0.0f);
    for (int k = first; k < first + count; ++k) {
      const uint8_t* row = renders[k]->data() + r * row_values;
      for (size_t i = 0; i < row_values; ++i) light[i] += row[i];
    }
    const float to_fraction = static_cast<float>(exposure_scale / (255.0 * count));
    uint8_t* out_row = out->data() + r * row_values;
    for (int u = 0; u < width_; ++u) {
      const float vignette = vignetting_[static_cast<size_t>(r) * width_ + u] * to_fraction;
      for (int c = 0; c < channels_; ++c) {
        const size_t i = static_cast<size_t>(u) * channels_ + c;
        const double well_fraction = light[i] * vignette;
        if (!p_.noise) {
          out_row[i] = ToOutput(full_scale, well_fraction * gain * full_scale, p_.adc_bits);
          continue;
        }
        const size_t pixel = static_cast<size_t>(r) * row_values + i;
        const uint64_t bits = Mix(noise_seed ^ Mix(pixel));
        const double prnu = prnu_gain_.empty() ? 1.0 : prnu_gain_[pixel];
        const double dsnu = dsnu_e_.empty() ? 0.0 : dsnu_e_[pixel];
        // shot noise: Poisson, as a Gaussian of variance = mean (the mean is many electrons)
        const double mean_e = well_fraction * p_.full_well_e * prnu;
        const double e = std::min(std::max(0.0, mean_e + std::sqrt(mean_e) * normal[bits & 0xffff]), p_.full_well_e);
        const double read_e = e + dsnu + p_.read_noise_e * normal[(bits >> 16) & 0xffff];
        out_row[i] = ToOutput(full_scale, read_e * k_dn_per_e, p_.adc_bits);
      }
    }
  }
}

}  // namespace rendering
}  // namespace rotors_sim
