// The image sensor model against its equations (docs/sensor_realism.md): the photon transfer curve
// gives back the model's conversion gain and read noise, quantisation and clipping, vignetting,
// the exposure plan, auto exposure; and rendered: motion blur of a turning camera is omega tau f,
// a rolling shutter skews a vertical edge by line delay x rows x omega x f, a global shutter does
// not, and a frame's stamp is the middle of its exposure plus the offset.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numeric>
#include <sstream>
#include <vector>

#include "rotors_core/error.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/rendering/image_sensor_model.h"
#include "rotors_core/sensors/camera_sensor.h"
#include "rotors_core/world_loader.h"
#include "test_worlds.h"

using namespace rotors_sim;
using rendering::ExposurePlan;
using rendering::ImageSensor;
using rendering::ImageSensorParams;

namespace {

constexpr int kW = 752, kH = 480;

/// A flat render of `value` (0..255), one channel.
std::vector<uint8_t> Flat(uint8_t value, int w = kW, int h = kH) {
  return std::vector<uint8_t>(static_cast<size_t>(w) * h, value);
}

/// One render for every row.
ExposurePlan Still(int rows = kH) { return ExposurePlan::Make(0.0, 0.0, rows, 0.0, 1.0, 1); }

ImageSensorParams NoisyMt9v034() {
  ImageSensorParams p;
  p.noise = true;
  p.full_well_e = 5888.0;  // 37.7 dB SNR max
  p.read_noise_e = 10.47;  // full well / 10^(55 / 20)
  return p;
}

// eq. S4: var = K mu + K^2 sigma_r^2 + 1/12 in the 8-bit output (K its conversion gain, DN/e-):
// EMVA 1288's photon transfer method (two frames per level: their difference removes the fixed
// pattern) gives back K and sigma_r.
TEST(ImageSensor, PhotonTransferCurveGivesBackTheGainAndReadNoise) {
  ImageSensorParams p = NoisyMt9v034();
  p.prnu = 0.01;  // a fixed pattern, which the method must not see
  p.dsnu_e = 5.0;
  const double gain = 4.0;
  const ImageSensor sensor(p, kW, kH, 1, 448.0, 375.5, 239.5, 11);
  std::vector<double> means, variances;
  for (int level = 3; level <= 57; level += 6) {  // up to 0.22 of the well: below clipping at gain 4
    const std::vector<uint8_t> render = Flat(static_cast<uint8_t>(level));
    std::vector<uint8_t> a, b;
    sensor.Expose({&render}, Still(), 0.0, gain, 1000 + level, &a);
    sensor.Expose({&render}, Still(), 0.0, gain, 2000 + level, &b);
    double sum = 0.0, diff2 = 0.0;
    for (size_t i = 0; i < a.size(); ++i) {
      sum += a[i] + b[i];
      diff2 += (double(a[i]) - b[i]) * (double(a[i]) - b[i]);
    }
    const double n = a.size();
    // floor(DN / 4) of the 10-bit code: the 8-bit mean is 3/8 DN below the signal / 4
    means.push_back(sum / (2 * n) + 0.375);
    variances.push_back(diff2 / (2 * n));
  }
  // least squares var = K mu + c
  const double n = means.size();
  const double mx = std::accumulate(means.begin(), means.end(), 0.0) / n;
  const double my = std::accumulate(variances.begin(), variances.end(), 0.0) / n;
  double sxy = 0, sxx = 0;
  for (size_t i = 0; i < means.size(); ++i) {
    sxy += (means[i] - mx) * (variances[i] - my);
    sxx += (means[i] - mx) * (means[i] - mx);
  }
  const double K8 = sxy / sxx, intercept = my - K8 * mx;
  const double K8_model = sensor.ConversionGainDnPerE(gain) / 4.0;
  const double read_noise_e = std::sqrt(intercept - 1.0 / 12.0) / K8;
  std::printf("photon transfer at gain %.0f: K %.5f DN/e- (model %.5f), read noise %.2f e- (model %.2f)\n", gain, K8,
              K8_model, read_noise_e, p.read_noise_e);
  EXPECT_NEAR(K8 / K8_model, 1.0, 0.05);
  EXPECT_NEAR(read_noise_e / p.read_noise_e, 1.0, 0.05);
}

TEST(ImageSensor, QuantisationAndClippingAreTheAdcs) {
  ImageSensorParams p;
  p.vignetting = ImageSensorParams::Vignetting::kCos4;  // an effect on, vignetting off at the centre
  const ImageSensor sensor(p, 1, 1, 1, 1.0, 0.0, 0.0, 1);
  for (int value = 0; value < 256; ++value) {
    const std::vector<uint8_t> render(1, static_cast<uint8_t>(value));
    std::vector<uint8_t> out;
    sensor.Expose({&render}, Still(1), 0.0, 1.0, 0, &out);
    // 10-bit code round(L 1023), its 8 most significant bits
    EXPECT_EQ(out[0], static_cast<int>(std::lround(value / 255.0 * 1023.0)) >> 2) << value;
    sensor.Expose({&render}, Still(1), 0.0, 4.0, 0, &out);
    EXPECT_EQ(out[0], std::min(1023, static_cast<int>(std::lround(4.0 * value / 255.0 * 1023.0))) >> 2) << value;
  }
  // a well filled past its capacity holds the full well: no shot noise is left, only the read
  // noise (sigma 10.5 e- = 1.8 DN10) below the ADC's full scale
  const ImageSensor noisy(NoisyMt9v034(), kW, kH, 1, 448.0, 375.5, 239.5, 1);
  const std::vector<uint8_t> bright = Flat(255);
  std::vector<uint8_t> out;
  noisy.Expose({&bright}, Still(), 2.0 * p.reference_exposure_s, 1.0, 5, &out);
  double sum = 0.0;
  for (uint8_t v : out) {
    ASSERT_GE(v, 252);  // 5.5 sigma of read noise below full scale
    sum += v;
  }
  EXPECT_GT(sum / out.size(), 254.8);
}

// eq. S5: cos^4 theta, tan theta = r / f, and a flat field's corner-to-centre ratio is it
TEST(ImageSensor, AFlatFieldsCornerToCentreRatioIsTheVignettingModels) {
  ImageSensorParams p;
  p.vignetting = ImageSensorParams::Vignetting::kCos4;
  const double f = 448.1, cx = 375.5, cy = 239.5;
  const ImageSensor sensor(p, kW, kH, 1, f, cx, cy, 1);
  const std::vector<uint8_t> flat = Flat(255);
  std::vector<uint8_t> out;
  sensor.Expose({&flat}, Still(), 0.0, 1.0, 0, &out);
  const double tan2 = (cx * cx + cy * cy) / (f * f);
  const double model = 1.0 / ((1.0 + tan2) * (1.0 + tan2));
  const double centre = out[240 * kW + 376], corner = out[0];
  std::printf("cos^4 vignetting: corner / centre %.4f, model %.4f\n", corner / centre, model);
  EXPECT_NEAR(corner / centre, model, 1.5 / centre);
  EXPECT_DOUBLE_EQ(sensor.Vignetting(0, 0), static_cast<float>(model));
  p.vignetting = ImageSensorParams::Vignetting::kPolynomial;
  p.vignetting_coefficients[0] = -0.3;
  const ImageSensor poly(p, kW, kH, 1, f, cx, cy, 1);
  EXPECT_NEAR(poly.Vignetting(0, 0), 1.0 - 0.3 * tan2, 1e-6);
}

TEST(ImageSensor, ExposurePlanCoversTheWindowAndEachRowsExposure) {
  // a still camera: one render at the middle, whatever the exposure
  ExposurePlan still = ExposurePlan::Make(0.02, 0.0, kH, 0.0, 1.0, 32);
  ASSERT_EQ(still.times_s.size(), 1u);
  EXPECT_EQ(still.times_s[0], 0.0);
  // 10 px of motion over a 20 ms global shutter: 10 renders, every row all of them
  ExposurePlan blur = ExposurePlan::Make(0.02, 0.0, kH, 500.0, 1.0, 32);
  ASSERT_EQ(blur.times_s.size(), 10u);
  EXPECT_NEAR(blur.times_s.front(), -0.009, 1e-12);
  EXPECT_NEAR(blur.times_s.back(), 0.009, 1e-12);
  for (int r = 0; r < kH; ++r) ASSERT_TRUE(blur.row_first[r] == 0 && blur.row_count[r] == 10) << r;
  // a rolling shutter without exposure: rows in bands, the first row the first render, the last the last
  ExposurePlan rolling = ExposurePlan::Make(0.0, 30e-6, kH, 1000.0, 1.0, 32);
  ASSERT_EQ(rolling.times_s.size(), 15u);  // 14.37 ms of readout x 1000 px/s
  EXPECT_EQ(rolling.row_first.front(), 0);
  EXPECT_EQ(rolling.row_first.back(), 14);
  for (int r = 0; r < kH; ++r) EXPECT_EQ(rolling.row_count[r], 1);
  // the cap
  EXPECT_EQ(ExposurePlan::Make(0.02, 0.0, kH, 1e6, 1.0, 32).times_s.size(), 32u);
}

// eq. S3: a step in scene brightness within the exposure's range: the mean is back at the desired
// bin within update interval + 2 frames (the update waits for its frame, then the next frame shows it)
TEST(ImageSensor, AutoExposureReturnsToTheDesiredBinAfterABrightnessStep) {
  ImageSensorParams p;
  p.auto_exposure = true;
  p.desired_bin = 32;  // half of full scale
  rendering::AutoExposure ae(p);
  const double target = 32 / 64.0;
  // a linear sensor: mean = light x exposure / reference exposure x gain
  auto mean_of = [&](double light) {
    return std::min(1.0, light * ae.ExposureS() / p.reference_exposure_s * ae.Gain());
  };
  double light = 0.6;  // 400 rows at unit gain
  for (int k = 0; k < 30; ++k) ae.Update(mean_of(light));
  EXPECT_NEAR(mean_of(light), target, 0.01);
  const double settled_exposure = ae.ExposureS();
  light = 0.9;  // 1.5 times brighter (unclipped: 0.75 of full scale before the update)
  int frames = 0;
  while (std::abs(mean_of(light) - target) > 0.01 && frames < 50) {
    ae.Update(mean_of(light));
    ++frames;
  }
  std::printf(
      "auto exposure: a 1.5x brighter scene back at the desired bin after %d frames (exposure %.2f -> %.2f ms)\n",
      frames, settled_exposure * 1e3, ae.ExposureS() * 1e3);
  EXPECT_LE(frames, p.update_interval_frames + 2);
  EXPECT_NEAR(ae.ExposureS(), settled_exposure / 1.5, p.row_time_s);
  EXPECT_EQ(ae.Gain(), 1.0);
}

// each camera its own auto exposure: a stereo pair seeing different brightness settles on
// different exposures, each with its mean at the desired bin
TEST(ImageSensor, TwoCamerasSeeingDifferentBrightnessSettleOnDifferentExposures) {
  ImageSensorParams p;
  p.auto_exposure = true;
  p.desired_bin = 32;
  rendering::AutoExposure left(p), right(p);
  auto mean_of = [&](const rendering::AutoExposure& ae, double light) {
    return std::min(1.0, light * ae.ExposureS() / p.reference_exposure_s * ae.Gain());
  };
  for (int k = 0; k < 30; ++k) {
    left.Update(mean_of(left, 0.6));
    right.Update(mean_of(right, 0.9));
  }
  std::printf("stereo auto exposure: left %.2f ms, right %.2f ms\n", left.ExposureS() * 1e3, right.ExposureS() * 1e3);
  EXPECT_NEAR(mean_of(left, 0.6), 0.5, 0.01);
  EXPECT_NEAR(mean_of(right, 0.9), 0.5, 0.01);
  EXPECT_NEAR(left.ExposureS() / right.ExposureS(), 1.5, 0.01);
}

TEST(ImageSensor, BadParametersAreOneLineErrors) {
  ImageSensorParams p;
  p.exposure_s = -0.01;
  EXPECT_EQ(p.Validate(), "<exposureTime> -0.01 must be >= 0 s");
  p = ImageSensorParams();
  p.noise = true;
  EXPECT_NE(p.Validate().find("<fullWellCapacity> 0 must be >= 1 e- (photonNoise is on)"), std::string::npos);
  p = ImageSensorParams();
  p.desired_bin = 70;
  EXPECT_NE(p.Validate().find("autoExposureDesiredBin"), std::string::npos);
  EXPECT_TRUE(ImageSensorParams().Validate().empty());
}

// --- rendered: a camera on a link turning at omega about its vertical axis, looking at a white
// wall whose left edge is on the optical axis (black sky, unlit: the wall is 255, the sky 0)

constexpr double kOmega = 2.5;  // [rad/s]

std::string TurningCameraWorld() {
  std::ostringstream s;
  std::string w = WorldSdf(0.001, 0.0, false, "world");
  s << w.substr(0, w.find("</world>")) << "<scene><ambient>1 1 1 1</ambient><background>0 0 0 1</background></scene>"
    << "<light name='sun' type='directional'><diffuse>0 0 0 1</diffuse><direction>0 0 -1</direction></light>"
    << "<model name='wall'><static>true</static><pose>5 -2.5 0 0 0 0</pose><link name='link'><visual name='v'>"
    << "<geometry><box><size>0.1 5 20</size></box></geometry><material><diffuse>1 1 1 1</diffuse></material>"
    << "</visual></link></model>"
    << "<model name='rig'><pose>0 0 0 0 0 0</pose><link name='link'><inertial><mass>1</mass><inertia><ixx>0.01</ixx>"
    << "<iyy>0.01</iyy><izz>0.01</izz></inertia></inertial><sensor name='cam' type='camera'>"
    << "<update_rate>20</update_rate><camera><horizontal_fov>1.3962634</horizontal_fov><image><width>752</width>"
    << "<height>480</height><format>L8</format></image><clip><near>0.02</near><far>100</far></clip></camera>"
    << "</sensor></link></model></world></sdf>";
  return s.str();
}

/// The camera turning at kOmega, its frame at the first update after `params` are set.
struct TurningCamera {
  WorldGuard g;
  sensors::CameraSensorPtr cam;
  explicit TurningCamera(const ImageSensorParams& params) : g{WorldLoader::LoadString(TurningCameraWorld(), "turn")} {
    cam = std::dynamic_pointer_cast<sensors::CameraSensor>(g.world->ModelByName("rig")->Sensors().at(0));
    cam->SetImageSensor(params);
    g.world->ModelByName("rig")->GetLink("link")->SetWorldAngularVel({0, 0, kOmega});
    g.world->Step(1);
  }
  double F() const { return cam->Camera(0).intrinsics.FocalLengthPx(); }
};

/// With ROTORS_FIGURE_DIR set, the frame as <dir>/<name>.pgm (docs/sensor_realism.md's figure).
void SaveFigure(const rendering::RenderedFrame& f, const std::string& name) {
  const char* dir = std::getenv("ROTORS_FIGURE_DIR");
  if (!dir) return;
  std::ofstream out(std::string(dir) + "/" + name + ".pgm", std::ios::binary);
  out << "P5\n" << f.width_px << " " << f.height_px << "\n255\n";
  out.write(reinterpret_cast<const char*>(f.image.data()), static_cast<std::streamsize>(f.image.size()));
}

/// Where row v of an L8 frame crosses `level` (0..255) going right, with linear interpolation.
double Crossing(const rendering::RenderedFrame& f, int v, double level) {
  const uint8_t* row = f.image.data() + static_cast<size_t>(v) * f.width_px;
  const bool rising = row[f.width_px - 1] > row[0];
  for (int u = 1; u < f.width_px; ++u) {
    const double a = row[u - 1], b = row[u];
    if ((rising && a < level && b >= level) || (!rising && a > level && b <= level))
      return u - 1 + (level - a) / (b - a);
  }
  return NAN;
}

// eq. S1: a turn at omega during an exposure tau smears an edge over omega tau f pixels; a
// box blur's 10-90 % rise is 0.8 of its width
TEST(ImageSensor, MotionBlurOfATurningCameraIsOmegaTauF) {
  ImageSensorParams p;
  p.exposure_s = 0.02;
  p.reference_exposure_s = 0.02;  // the wall at 255, unclipped
  TurningCamera blurred(p);
  const rendering::RenderedFrame& f = blurred.cam->Frame(0);
  const double width_px = (Crossing(f, 240, 0.9 * 255) - Crossing(f, 240, 0.1 * 255)) / 0.8;
  const double expected_px = kOmega * p.exposure_s * blurred.F();
  std::printf("blur: edge spread %.2f px, omega tau f = %.2f px, %d renders\n", std::abs(width_px), expected_px,
              blurred.cam->SubframesOf(0));
  EXPECT_NEAR(std::abs(width_px), expected_px, 0.1 * expected_px);
  EXPECT_NEAR(blurred.cam->ExposureS(0), 0.02, 1e-12);
  SaveFigure(f, "blur");

  // no exposure: the edge as sharp as RotorS' (the same image, bit for bit)
  TurningCamera sharp(ImageSensorParams{});
  const rendering::RenderedFrame& s = sharp.cam->Frame(0);
  EXPECT_LE(std::abs(Crossing(s, 240, 0.9 * 255) - Crossing(s, 240, 0.1 * 255)), 1.0);
  EXPECT_EQ(sharp.cam->SubframesOf(0), 1);
  SaveFigure(s, "sharp");
}

// eq. S2: row r is read (r - (H - 1) / 2) line_delay after the middle row; a vertical edge moving
// at omega f px/s leans by line_delay (H - 1) omega f pixels from the first row to the last
TEST(ImageSensor, RollingShutterSkewsAVerticalEdgeAndAGlobalShutterDoesNot) {
  ImageSensorParams p;
  p.line_delay_s = 30e-6;
  TurningCamera rolling(p);
  const rendering::RenderedFrame& f = rolling.cam->Frame(0);
  const double skew_px = Crossing(f, kH - 1, 127.5) - Crossing(f, 0, 127.5);
  const double expected_px = p.line_delay_s * (kH - 1) * kOmega * rolling.F();
  std::printf("rolling shutter: skew %.2f px, line delay x rows x omega x f = %.2f px, %d renders\n", std::abs(skew_px),
              expected_px, rolling.cam->SubframesOf(0));
  EXPECT_NEAR(std::abs(skew_px), expected_px, 0.1 * expected_px);
  SaveFigure(f, "rolling");

  ImageSensorParams global;
  global.exposure_s = 0.001;
  global.reference_exposure_s = 0.001;
  TurningCamera still_rows(global);
  const rendering::RenderedFrame& g = still_rows.cam->Frame(0);
  EXPECT_LE(std::abs(Crossing(g, kH - 1, 127.5) - Crossing(g, 0, 127.5)), 0.5);
}

// the velocity buffer (one render, each pixel averaged along its motion field) against the
// sub-frame reference on the same scenes: the blur's spread and the rolling shutter's skew within
// 10 % of their equations, and the frames within 3 levels of the reference on average
TEST(ImageSensor, VelocityBufferIsWithinItsStatedErrorOfTheSubframes) {
  auto mean_abs_difference = [](const rendering::RenderedFrame& a, const rendering::RenderedFrame& b) {
    double sum = 0.0;
    for (size_t i = 0; i < a.image.size(); ++i) sum += std::abs(int(a.image[i]) - int(b.image[i]));
    return sum / a.image.size();
  };
  ImageSensorParams p;
  p.exposure_s = 0.02;
  p.reference_exposure_s = 0.02;
  TurningCamera reference(p);
  p.blur_method = ImageSensorParams::BlurMethod::kVelocityBuffer;
  TurningCamera fast(p);
  const rendering::RenderedFrame& f = fast.cam->Frame(0);
  const double width_px = (Crossing(f, 240, 0.9 * 255) - Crossing(f, 240, 0.1 * 255)) / 0.8;
  const double expected_px = kOmega * p.exposure_s * fast.F();
  const double blur_difference = mean_abs_difference(f, reference.cam->Frame(0));
  std::printf(
      "velocity buffer: edge spread %.2f px (omega tau f %.2f px), %d render, mean |difference| from the "
      "sub-frames %.2f levels\n",
      std::abs(width_px), expected_px, fast.cam->SubframesOf(0), blur_difference);
  EXPECT_NEAR(std::abs(width_px), expected_px, 0.1 * expected_px);
  EXPECT_EQ(fast.cam->SubframesOf(0), 1);
  EXPECT_LT(blur_difference, 3.0);

  ImageSensorParams rs;
  rs.line_delay_s = 30e-6;
  TurningCamera rolling_reference(rs);
  rs.blur_method = ImageSensorParams::BlurMethod::kVelocityBuffer;
  TurningCamera rolling(rs);
  const rendering::RenderedFrame& g = rolling.cam->Frame(0);
  const double skew_px = Crossing(g, kH - 1, 127.5) - Crossing(g, 0, 127.5);
  const double skew_expected_px = rs.line_delay_s * (kH - 1) * kOmega * rolling.F();
  const double rs_difference = mean_abs_difference(g, rolling_reference.cam->Frame(0));
  std::printf("velocity buffer, rolling shutter: skew %.2f px (expected %.2f px), mean |difference| %.2f levels\n",
              std::abs(skew_px), skew_expected_px, rs_difference);
  EXPECT_NEAR(std::abs(skew_px), skew_expected_px, 0.1 * skew_expected_px);
  EXPECT_LT(rs_difference, 3.0);
}

// eq. S6: the stamp is the middle of the exposure (the update's time) plus the offset, and jitter
// is a Gaussian of the stated sigma, the same for the same frame
TEST(ImageSensor, StampIsTheMiddleOfTheExposurePlusTheOffset) {
  ImageSensorParams p;
  p.exposure_s = 0.01;
  p.time_offset_s = 0.0025;
  TurningCamera camera(p);
  EXPECT_DOUBLE_EQ(camera.cam->StampOffsetS(0), 0.0025);
  p.stamp_jitter_s = 0.001;
  double sum = 0, sum2 = 0;
  const int n = 4000;
  for (int k = 0; k < n; ++k) {
    const double e = rendering::StampOffsetS(p, k) - p.time_offset_s;
    sum += e;
    sum2 += e * e;
  }
  EXPECT_NEAR(sum / n, 0.0, 4 * 0.001 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.001, 0.05 * 0.001);
  EXPECT_EQ(rendering::StampOffsetS(p, 7), rendering::StampOffsetS(p, 7));
}

}  // namespace
