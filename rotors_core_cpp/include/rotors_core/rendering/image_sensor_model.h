// How an image sensor turns the light of a frame into pixel values, free of GL and ROS: exposure
// over a time window (motion blur), a rolling shutter's row times, auto exposure and gain, a
// photon-transfer noise model (shot noise, read noise, fixed-pattern noise, the ADC, clipping) and
// vignetting. The renderer gives the scene's light as images at instants (RotorS' images: the
// sensor's output at referenceExposure and unit gain, without noise); this model says at which
// instants to render (ExposurePlan) and makes the frame from those renders (ImageSensor).
// docs/sensor_realism.md gives each equation, its parameters and their sources.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rotors_sim {
namespace rendering {

/// Every effect is off by default; ImageSensorParams{} makes RotorS' image (ImageSensor is not used).
struct ImageSensorParams {
  // --- exposure (eq. S1): E(u, v) = 1/tau int_{t_r - tau/2}^{t_r + tau/2} L(u, v, t) dt
  double exposure_s = 0.0;  ///< <exposureTime> [s], fixed exposure (no auto exposure); 0: an instant
  int max_subframes = 32;   ///< <maxSubframes>: renders per frame at most (the blur's cost cap)
  /// <blurMethod>: how the exposure window is rendered. kSubframes: renders at instants across it
  /// (the reference); kVelocityBuffer: one render, each pixel averaged along its image motion
  /// (the motion field of a static scene from the depth and the camera's twist; faster, exact for a
  /// turning camera, approximate at depth edges and for moving objects)
  enum class BlurMethod { kSubframes, kVelocityBuffer };
  BlurMethod blur_method = BlurMethod::kSubframes;
  /// <subframesPerPixel>: renders per pixel of predicted image motion over the frame's window
  double subframes_per_pixel = 1.0;
  // --- rolling shutter (eq. S2): row r is exposed around t_r = t_c + (r - (H - 1) / 2) line_delay
  double line_delay_s = 0.0;  ///< <lineDelay> [s]; 0: a global shutter
  // --- auto exposure and gain (eq. S3), the MT9V034's AEC/AGC
  bool auto_exposure = false;      ///< <autoExposure>
  int desired_bin = 58;            ///< <autoExposureDesiredBin> 1..64: target mean = bin / 64 of full scale
  int aec_low_pass = 0;            ///< <autoExposureLowPass> 0..2: a step moves 1 / 2^n of the way
  int agc_low_pass = 2;            ///< <autoGainLowPass> 0..2
  int update_interval_frames = 2;  ///< <autoExposureUpdateInterval>: frames skipped between updates
  double row_time_s = 31.333e-6;   ///< <rowTime> [s]: the exposure's unit (846 pixel clocks at 27 MHz)
  int max_shutter_rows = 480;      ///< <maxShutterWidth> [rows]: the longest exposure auto exposure sets
  double max_analog_gain = 4.0;    ///< <maxAnalogGain>: 1 .. this
  // --- photon transfer (eq. S4)
  bool noise = false;         ///< <photonNoise>
  double full_well_e = 0.0;   ///< <fullWellCapacity> [e-]
  double read_noise_e = 0.0;  ///< <readNoise> [e-], referred to the pixel (before the gain)
  double prnu = 0.0;          ///< <photoResponseNonUniformity>: sigma of the per-pixel gain, fraction
  double dsnu_e = 0.0;        ///< <darkSignalNonUniformity> [e-]: sigma of the per-pixel offset
  int adc_bits = 10;          ///< <adcBits>; the output keeps the 8 most significant bits
  /// <referenceExposure> [s]: the exposure at which the rendered image is the output at unit gain
  double reference_exposure_s = 480 * 31.333e-6;
  // --- vignetting (eq. S5)
  enum class Vignetting { kNone, kCos4, kPolynomial };
  Vignetting vignetting = Vignetting::kNone;            ///< <vignetting>: none, cos4 or polynomial
  double vignetting_coefficients[3] = {0.0, 0.0, 0.0};  ///< <vignettingCoefficients> a1 a2 a3
  // --- timing (eq. S6): stamp = t_c + offset + jitter
  double time_offset_s = 0.0;   ///< <timeOffset> [s]: stamp minus the middle of the exposure
  double stamp_jitter_s = 0.0;  ///< <stampJitter> [s]: sigma of a Gaussian per-frame stamp error

  /// Any effect on: the frame goes through ImageSensor (all off: the renderer's image as it is).
  bool AnyEffect() const;
  /// The exposure is a window (blur, rolling shutter) rather than an instant.
  bool TimeWindow() const { return exposure_s > 0.0 || line_delay_s > 0.0 || auto_exposure; }
  /// Empty when valid, else one line naming the bad parameter and its range.
  std::string Validate() const;
};

/// The instants of a frame to render, relative to the middle of its exposure t_c [s], and which of
/// them each row averages.
struct ExposurePlan {
  std::vector<double> times_s;            ///< render instants, ascending
  std::vector<int> row_first, row_count;  ///< row r averages renders [first, first + count)

  /// A frame of `rows` rows exposed `exposure_s` each, rows `line_delay_s` apart, whose image moves
  /// `image_speed_px_s` (the fastest point): renders spaced so that the image moves at most
  /// 1 / subframes_per_pixel pixel between them, at most max_subframes, one for a still camera.
  static ExposurePlan Make(double exposure_s, double line_delay_s, int rows, double image_speed_px_s,
                           double subframes_per_pixel, int max_subframes);
};

/// A camera's twist in its optical frame O (x right, y down, z forward): v_O [m/s], omega_O [rad/s].
struct CameraTwist {
  double v_O[3] = {0, 0, 0}, omega_O[3] = {0, 0, 0};
};

/// eq. S1 and S2 by a velocity buffer: one render (image, W x H x C bytes, and its optical-axis
/// depth, NaN for the sky) made at the middle of the exposure; each pixel's image velocity is the
/// motion field of a static scene, u' = (f P'_x - x P'_z) / Z, v' = (f P'_y - y P'_z) / Z,
/// P' = -v_O - omega_O x P (x, y from the principal point, 1/Z = 0 for the sky); pixel p of row r
/// averages the render at p - p' t over its row's window t in [t_r - tau/2, t_r + tau/2] (bilinear,
/// samples spaced by 1 / subframes_per_pixel pixel, at most max_subframes). light: 0..255 per value.
void VelocityBufferExposure(const std::vector<uint8_t>& image, const std::vector<float>& depth_m, int width_px,
                            int height_px, int channels, double f_px, double cx_px, double cy_px,
                            const CameraTwist& twist, double exposure_s, double line_delay_s,
                            double subframes_per_pixel, int max_subframes, std::vector<float>* light);

/// Gazebo's <noise> on a frame the image sensor made without photon noise: value + 255 N(mean,
/// stddev), rounded and clamped, from a counter-based generator (deterministic in the seed). With
/// photon noise on, the photon-transfer model is the sensor's noise and <noise> is not added.
void AddGazeboNoise(double mean, double stddev, uint64_t seed, std::vector<uint8_t>* image);

/// The stamp of a frame minus the middle of its exposure (eq. S6): <timeOffset> plus a Gaussian of
/// sigma <stampJitter> drawn from `seed` (deterministic).
double StampOffsetS(const ImageSensorParams& p, uint64_t seed);

/// The auto exposure and gain of one camera (eq. S3): every update_interval + 1 frames the mean of
/// the last frame is compared with the desired bin; exposure moves first (up to max_shutter_rows),
/// then the analog gain, each through its low-pass filter; the new values apply from the next frame.
class AutoExposure {
 public:
  explicit AutoExposure(const ImageSensorParams& p);
  /// The exposure and gain for the next frame, after a frame of mean `mean_full_scale` in [0, 1].
  void Update(double mean_full_scale);
  double ExposureS() const { return rows_ * row_time_s_; }
  double Gain() const { return gain_; }
  void Reset();

 private:
  ImageSensorParams p_;
  double row_time_s_;
  double rows_, gain_ = 1.0;
  int frames_since_update_ = 0;
};

/// Makes a frame (8 bits per channel) from renders of relative light in [0, 1] (the renderer's
/// image / 255, linear): eqs. S1, S2, S4, S5. One per camera: it keeps the fixed-pattern noise.
class ImageSensor {
 public:
  ImageSensor(const ImageSensorParams& p, int width_px, int height_px, int channels, double focal_length_px,
              double cx_px, double cy_px, uint64_t pattern_seed);

  /// out = the frame: row r averages renders plan.row_first[r] .. + row_count[r] (each W x H x C
  /// bytes), scaled by exposure_s / reference_exposure_s and the gain and the vignetting, then
  /// digitised (with noise when on, drawn from `noise_seed`).
  void Expose(const std::vector<const std::vector<uint8_t>*>& renders, const ExposurePlan& plan, double exposure_s,
              double gain, uint64_t noise_seed, std::vector<uint8_t>* out) const;
  /// The same from the light already averaged over each pixel's exposure (0..255 per value).
  void Digitise(const std::vector<float>& light, double exposure_s, double gain, uint64_t noise_seed,
                std::vector<uint8_t>* out) const;

  /// The vignetting factor V(u, v) (eq. S5).
  double Vignetting(int u, int v) const { return vignetting_[static_cast<size_t>(v) * width_ + u]; }
  /// K = gain (2^bits - 1) / full well [DN per e-, at the ADC]; 8-bit output: K / 2^(bits - 8).
  double ConversionGainDnPerE(double gain) const;

 private:
  ImageSensorParams p_;
  int width_, height_, channels_;
  std::vector<float> vignetting_;          ///< W x H
  std::vector<float> prnu_gain_, dsnu_e_;  ///< per pixel, when on
};

}  // namespace rendering
}  // namespace rotors_sim
