// An IMU that feels the rotors (imu_vibration_model.h): each line of the model against its equation.
// Spectra are single DFT bins (a Goertzel sum) of whole records, amplitudes in the signal's units.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "rotors_gazebo_plugins/models/imu_vibration_model.h"

using namespace rotors_gazebo_plugins;

namespace {

/// Amplitude of the sinusoid at f in samples y taken every dt: 2 |sum y_k e^{-i 2 pi f k dt}| / N.
double Amplitude(const std::vector<double>& y, double dt, double f_hz) {
  double re = 0.0, im = 0.0;
  for (size_t k = 0; k < y.size(); ++k) {
    re += y[k] * std::cos(2.0 * M_PI * f_hz * k * dt);
    im -= y[k] * std::sin(2.0 * M_PI * f_hz * k * dt);
  }
  return 2.0 * std::hypot(re, im) / static_cast<double>(y.size());
}

/// The frequency of the largest bin in [lo, hi] at resolution step.
double PeakFrequency(const std::vector<double>& y, double dt, double lo, double hi, double step) {
  double best_f = lo, best_a = -1.0;
  for (double f = lo; f <= hi; f += step) {
    const double a = Amplitude(y, dt, f);
    if (a > best_a) best_a = a, best_f = f;
  }
  return best_f;
}

VibratingBody FireflyBody() {
  VibratingBody b;
  b.mass_kg = 1.56779;  // RotorS' firefly: body 1.5 + six rotors 0.005 + the IMU and odometry links
  b.inertia_B_kg_m2 = Eigen::Vector3d(0.0347563, 0.0458929, 0.0977).asDiagonal();
  return b;
}

VibratingRotor Rotor(double speed, const Eigen::Vector3d& p_B = Eigen::Vector3d::Zero()) {
  VibratingRotor r;
  r.p_B = p_B;
  r.rotor_mass_kg = 0.005;
  r.max_rot_velocity_rad_s = 838.0;
  r.motor_constant = 8.54858e-06;
  r.speed_rad_s = speed;
  return r;
}

ImuSample Rest() { return {Eigen::Vector3d::Zero(), Eigen::Vector3d(0.0, 0.0, 9.81)}; }

struct Record {
  std::vector<double> ax, ay, az, gx, gy, gz;
};

/// Reads the model every dt for `seconds` with the vehicle at rest.
Record Read(ImuVibrationModel* model, const std::vector<VibratingRotor>& rotors, double dt, double seconds) {
  Record r;
  for (int k = 0; k < static_cast<int>(std::lround(seconds / dt)); ++k) {
    const ImuSample s = model->Step(Rest(), Rest(), rotors, dt);
    r.ax.push_back(s.linear_acceleration_I.x());
    r.ay.push_back(s.linear_acceleration_I.y());
    r.az.push_back(s.linear_acceleration_I.z() - 9.81);
    r.gx.push_back(s.angular_velocity_I.x());
    r.gy.push_back(s.angular_velocity_I.y());
    r.gz.push_back(s.angular_velocity_I.z());
  }
  return r;
}

ImuVibrationParams Params(int taps = 1, double ripple = 0.0) {
  ImuVibrationParams p;
  p.enabled = true;
  p.bartlett_taps = taps;
  p.blade_pass_thrust_ripple = ripple;
  return p;
}

}  // namespace

TEST(ImuVibration, UnbalanceFollowsTheBalanceGrade) {
  // ISO 21940-11: e_per = G / Omega_max; U = m e_per. G 6.3 mm/s at 838 rad/s on a 5 g rotor: 37.6 mg mm.
  ImuVibrationModel model(Params(), FireflyBody(), 1);
  const double u = model.Unbalance(Rotor(500.0));
  EXPECT_NEAR(u, 0.005 * 6.3e-3 / 838.0, 1e-15);
  std::printf("G 6.3 on a 5 g rotor at 838 rad/s: U = %.2f g mm, e_per = %.2f um\n", u * 1e6, 6.3e-3 / 838.0 * 1e6);
  ImuVibrationParams measured = Params();
  measured.residual_unbalance_kg_m = 2.0e-7;  // a measured 0.2 g mm overrides the grade
  EXPECT_EQ(ImuVibrationModel(measured, FireflyBody(), 1).Unbalance(Rotor(500.0)), 2.0e-7);
}

TEST(ImuVibration, PeaksAtTheRotorFrequencyAndTheBladePass) {
  // One rotor at the CoG, the IMU there too, read at the internal rate with no filter: the
  // accelerometer sees U w^2 / m in the rotor plane at f = w / 2 pi and r_bp C_T w^2 / m along the
  // axis at n_b f; the gyroscope nothing (no moment arm).
  const double w = 545.0, fs = 819.2, f = w / (2.0 * M_PI);
  const VibratingBody body = FireflyBody();
  ImuVibrationModel model(Params(1, 0.01), body, 7);
  const Record r = Read(&model, {Rotor(w)}, 1.0 / fs, 20.0);
  const double u = model.Unbalance(Rotor(w));
  const double a_unbalance = u * w * w / body.mass_kg, a_blade = 0.01 * 8.54858e-06 * w * w / body.mass_kg;
  EXPECT_NEAR(Amplitude(r.ax, 1.0 / fs, f), a_unbalance, 0.01 * a_unbalance);
  EXPECT_NEAR(Amplitude(r.ay, 1.0 / fs, f), a_unbalance, 0.01 * a_unbalance);
  EXPECT_NEAR(Amplitude(r.az, 1.0 / fs, 2.0 * f), a_blade, 0.01 * a_blade);
  EXPECT_NEAR(PeakFrequency(r.ax, 1.0 / fs, f - 5.0, f + 5.0, 0.05), f, 0.1);
  EXPECT_NEAR(PeakFrequency(r.az, 1.0 / fs, 2.0 * f - 5.0, 2.0 * f + 5.0, 0.05), 2.0 * f, 0.1);
  for (double g : r.gx) EXPECT_EQ(g, 0.0);
  std::printf("rotor %.2f Hz: unbalance %.5f m/s^2 (model %.5f), blade pass %.2f Hz %.5f m/s^2 (model %.5f)\n", f,
              Amplitude(r.ax, 1.0 / fs, f), a_unbalance, 2.0 * f, Amplitude(r.az, 1.0 / fs, 2.0 * f), a_blade);
}

TEST(ImuVibration, EachRotorItsOwnPeakAndTheGyroscopeFeelsTheMoment) {
  // Six rotors at six speeds on the firefly's arms (0.215 m): six accelerometer peaks, and the
  // gyroscope answers each rotor's moment p x F through J^-1, integrated: |omega| = |J^-1 (p x U w e)|.
  const double arm = 0.215, fs = 819.2;
  std::vector<VibratingRotor> rotors;
  for (int i = 0; i < 6; ++i) {
    const double angle = i * M_PI / 3.0;
    rotors.push_back(Rotor(500.0 + 20.0 * i, arm * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0.0)));
  }
  ImuVibrationModel model(Params(), FireflyBody(), 3);
  const Record r = Read(&model, rotors, 1.0 / fs, 20.0);
  for (const VibratingRotor& rotor : rotors) {
    const double w = rotor.speed_rad_s, f = w / (2.0 * M_PI);
    EXPECT_NEAR(PeakFrequency(r.ax, 1.0 / fs, f - 1.5, f + 1.5, 0.05), f, 0.1);
    // the unbalance turns in the rotor plane: its moment about the arm's normal is along z
    const double u = model.Unbalance(rotor);
    const double gz = u * w * arm / 0.0977;  // |J^-1 (p x U w e)|_z for e perpendicular to p
    EXPECT_NEAR(Amplitude(r.gz, 1.0 / fs, f), gz, 0.02 * gz);
  }
}

TEST(ImuVibration, GyroscopeIsTheIntegralOfTheAngularAcceleration) {
  // d(omega_vib)/dt = J^-1 sum p x F: the finite difference of the gyroscope's vibration against the
  // accelerometer's alpha seen at an IMU one metre away (alpha x p_imu).
  VibratingBody body = FireflyBody();
  body.p_B_imu = Eigen::Vector3d(0.0, 0.0, 1.0);
  ImuVibrationModel model(Params(1, 0.02), body, 5);
  std::vector<VibratingRotor> rotors = {Rotor(600.0, {0.2, 0.05, 0.01}), Rotor(-450.0, {-0.1, 0.2, 0.0})};
  rotors[1].axis_B = Eigen::Vector3d(0.1, 0.0, 1.0).normalized();
  const std::vector<double> phases = {0.3, 1.9};
  const double h = 1e-6;  // a central difference: error of order (w h)^2
  std::vector<double> earlier = phases, later = phases;
  for (size_t i = 0; i < rotors.size(); ++i) {
    earlier[i] -= rotors[i].speed_rad_s * h;
    later[i] += rotors[i].speed_rad_s * h;
  }
  const ImuSample now = model.Vibration(rotors, phases);
  const Eigen::Vector3d alpha =
      (model.Vibration(rotors, later).angular_velocity_I - model.Vibration(rotors, earlier).angular_velocity_I) /
      (2 * h);
  // a_vib = sum F / m + alpha x p_imu: take sum F / m from the same rotors with the IMU at the CoG
  VibratingBody at_cog = body;
  at_cog.p_B_imu.setZero();
  const Eigen::Vector3d a_cog =
      ImuVibrationModel(Params(1, 0.02), at_cog, 5).Vibration(rotors, phases).linear_acceleration_I;
  const Eigen::Vector3d alpha_cross_p = now.linear_acceleration_I - a_cog;
  EXPECT_NEAR((alpha.cross(body.p_B_imu) - alpha_cross_p).norm(), 0.0, 1e-6 * alpha_cross_p.norm());
}

TEST(ImuVibration, BartlettFilterResponseMatchesItsDefinition) {
  // H(f) = [sin(pi N f / f_s) / (N sin(pi f / f_s))]^2, N = 16 at 819.2 SPS: first null at 51.2 Hz
  const double fs = 819.2;
  for (double f : {5.0, 20.0, 40.0, 51.2, 86.7, 120.0, 300.0}) {
    BartlettFilter filter(16);
    std::vector<double> out;
    for (int k = 0; k < 16384; ++k) {
      BartlettFilter::Vector6d x = BartlettFilter::Vector6d::Zero();
      x(0) = std::sin(2.0 * M_PI * f * k / fs);
      out.push_back(filter.Push(x)(0));
    }
    out.erase(out.begin(), out.begin() + 64);  // past the filter's start
    const double expected = BartlettFilter::Gain(16, f, fs);
    EXPECT_NEAR(Amplitude(out, 1.0 / fs, f), expected, 2e-3) << f << " Hz";
    std::printf("Bartlett N=16 at %6.1f Hz: gain %.5f (definition %.5f)\n", f, Amplitude(out, 1.0 / fs, f), expected);
  }
  EXPECT_DOUBLE_EQ(BartlettFilter::Gain(16, 0.0, fs), 1.0);
  EXPECT_NEAR(BartlettFilter::Gain(16, fs / 16.0, fs), 0.0, 1e-20);
}

TEST(ImuVibration, ReadAtAnotherRateTheRotorAliases) {
  // Read every 10 ms (a 100 Hz world), a rotor at 86.7 Hz shows at |86.7 - 100| = 13.3 Hz, with the
  // Bartlett filter's gain at 86.7 Hz: what a 100 Hz reader of a real ADIS16448 sees.
  const double w = 545.0, f = w / (2.0 * M_PI), dt = 0.01, fs = 819.2;
  ImuVibrationModel model(Params(16), FireflyBody(), 11);
  const Record r = Read(&model, {Rotor(w)}, dt, 60.0);
  const double alias = std::abs(f - 1.0 / dt);
  EXPECT_NEAR(PeakFrequency(r.ax, dt, 1.0, 49.0, 0.02), alias, 0.05);
  const double expected = model.Unbalance(Rotor(w)) * w * w / FireflyBody().mass_kg * BartlettFilter::Gain(16, f, fs);
  EXPECT_NEAR(Amplitude(r.ax, dt, alias), expected, 0.05 * expected);
}

TEST(ImuVibration, MotorsOffLeaveTheFlightAsItIs) {
  // No rotor turning: the filtered output is the flight itself (a constant stays that constant), so
  // the IMU shows only ImuNoiseModel's datasheet noise.
  ImuVibrationModel model(Params(16), FireflyBody(), 2);
  for (int k = 0; k < 500; ++k) {
    const ImuSample s = model.Step(Rest(), Rest(), {Rotor(0.0, {0.2, 0.0, 0.0})}, 0.001);
    EXPECT_NEAR((s.linear_acceleration_I - Rest().linear_acceleration_I).norm(), 0.0, 1e-12);
    EXPECT_NEAR(s.angular_velocity_I.norm(), 0.0, 1e-15);
  }
}

TEST(ImuVibration, SameSeedSamePhasesAndErrorsNameTheValue) {
  ImuVibrationModel a(Params(), FireflyBody(), 42), b(Params(), FireflyBody(), 42), c(Params(), FireflyBody(), 43);
  const std::vector<VibratingRotor> rotors = {Rotor(500.0), Rotor(510.0)};
  a.Step(Rest(), Rest(), rotors, 0.01);
  b.Step(Rest(), Rest(), rotors, 0.01);
  c.Step(Rest(), Rest(), rotors, 0.01);
  EXPECT_EQ(a.Phases(), b.Phases());
  EXPECT_NE(a.Phases(), c.Phases());
  ImuVibrationParams p = Params();
  p.bartlett_taps = 12;
  EXPECT_NE(p.Validate().find("bartlettTaps = 12"), std::string::npos) << p.Validate();
  p = Params();
  p.balance_grade_mm_s = std::nan("");
  EXPECT_NE(p.Validate().find("balanceGrade"), std::string::npos);
  p = Params();
  p.enabled = false;
  p.bartlett_taps = 12;
  EXPECT_EQ(p.Validate(), "");  // off: nothing of it is used
}

// ------------------------------- the frame's mode -------------------------------

namespace {
ImuVibrationParams FrameParams(double f_n, double zeta, double thrust_noise_density = 0.0) {
  ImuVibrationParams p = Params(1);
  p.frame_mode_frequency_hz = f_n;
  p.frame_mode_damping = zeta;
  p.thrust_noise_density = thrust_noise_density;
  return p;
}

/// Two-sided spectral density [units^2/Hz] of y sampled at fs at frequency f: Hann-windowed periodograms
/// of `segment` samples, half overlapping, averaged (white noise of variance s^2 gives s^2 / fs).
double Density(const std::vector<double>& y, double fs, double f_hz, size_t segment) {
  std::vector<double> window(segment);
  double w2 = 0.0;
  for (size_t k = 0; k < segment; ++k) {
    window[k] = 0.5 - 0.5 * std::cos(2.0 * M_PI * k / segment);
    w2 += window[k] * window[k];
  }
  double sum = 0.0;
  int count = 0;
  for (size_t start = 0; start + segment <= y.size(); start += segment / 2, ++count) {
    double re = 0.0, im = 0.0;
    for (size_t k = 0; k < segment; ++k) {
      const double v = window[k] * y[start + k], angle = 2.0 * M_PI * f_hz * k / fs;
      re += v * std::cos(angle);
      im -= v * std::sin(angle);
    }
    sum += (re * re + im * im) / (fs * w2);
  }
  return sum / count;
}
}  // namespace

TEST(FrameMode, TransmissibilityIsTheBaseExcitedModes) {
  // |T| = sqrt(1 + (2 zeta r)^2) / sqrt((1 - r^2)^2 + (2 zeta r)^2), r = f / f_n
  const double f_n = 120.0, zeta = 0.05;
  for (double r : {0.0, 0.5, 1.0, std::sqrt(2.0), 3.0}) {
    const double expected =
        std::sqrt(1.0 + std::pow(2 * zeta * r, 2)) / std::sqrt(std::pow(1 - r * r, 2) + std::pow(2 * zeta * r, 2));
    EXPECT_NEAR(std::abs(FrameMode::Transmissibility(f_n, zeta, r * f_n)), expected, 1e-12 * expected) << r;
  }
  EXPECT_NEAR(std::abs(FrameMode::Transmissibility(f_n, zeta, std::sqrt(2.0) * f_n)), 1.0, 1e-12);  // crossover
  EXPECT_EQ(FrameMode::Transmissibility(0.0, zeta, 86.0), std::complex<double>(1.0));               // rigid
}

TEST(FrameMode, EachRotorLinePassesWithTheModesGainAndPhase) {
  // One rotor in the IMU's plane, read at the internal rate without the Bartlett filter: the line at the
  // rotor's frequency is the rigid line times |T|, shifted by arg T. Rotors near, at and past f_n.
  const double fs = 819.2, dt = 1.0 / fs, f_n = 100.0, zeta = 0.08;
  for (double w : {400.0, 2.0 * M_PI * f_n, 900.0, -2.0 * M_PI * f_n}) {
    const double f = std::abs(w) / (2.0 * M_PI);
    ImuVibrationModel rigid(Params(1), FireflyBody(), 21), framed(FrameParams(f_n, zeta), FireflyBody(), 21);
    const VibratingRotor rotor = Rotor(w, {0.2, 0.1, 0.0});  // off the CoG: the gyroscope feels it too
    const Record a = Read(&rigid, {rotor}, dt, 20.0), b = Read(&framed, {rotor}, dt, 20.0);
    const std::complex<double> t = FrameMode::Transmissibility(f_n, zeta, f);
    EXPECT_NEAR(Amplitude(b.ax, dt, f) / Amplitude(a.ax, dt, f), std::abs(t), 0.01 * std::abs(t)) << w;
    EXPECT_NEAR(Amplitude(b.gz, dt, f) / Amplitude(a.gz, dt, f), std::abs(t), 0.01 * std::abs(t)) << w;
    // phase: the framed line's phase minus the rigid one's, at the rotor's frequency
    auto phase = [&](const std::vector<double>& y) {
      double re = 0.0, im = 0.0;
      for (size_t k = 0; k < y.size(); ++k) {
        re += y[k] * std::cos(2.0 * M_PI * f * k * dt);
        im += y[k] * std::sin(2.0 * M_PI * f * k * dt);
      }
      return std::atan2(-im, re);
    };
    const double shift = std::remainder(phase(b.ax) - phase(a.ax), 2.0 * M_PI);
    EXPECT_NEAR(shift, std::arg(t), 0.02) << w;
    std::printf(
        "rotor at %6.1f Hz through a %.0f Hz mode (zeta %.2f): gain %.3f (|T| %.3f), phase %+.3f rad (arg T %+.3f)\n",
        f, f_n, zeta, Amplitude(b.ax, dt, f) / Amplitude(a.ax, dt, f), std::abs(t), shift, std::arg(t));
  }
}

TEST(FrameMode, BroadbandThrustNoiseHasTheModesSpectrum) {
  // A rotor's thrust fluctuation, white with density s_T relative to C_T w^2 along its axis, seen through
  // the mode: the accelerometer's density along the axis is (s_T C_T w^2 / m)^2 |T(f)|^2, summed over the
  // images of the 819.2 SPS sampling; across the axis nothing. Rigid frame: flat at (s_T C_T w^2 / m)^2.
  const double fs = 819.2, dt = 1.0 / fs, w = 545.0, s_t = 0.01, f_n = 150.0, zeta = 0.05;
  const VibratingRotor rotor = Rotor(w);
  ImuVibrationParams quiet = FrameParams(f_n, zeta, s_t);
  quiet.balance_grade_mm_s = 0.0;  // the broadband alone
  ImuVibrationParams rigid_params = quiet;
  rigid_params.frame_mode_frequency_hz = 0.0;
  ImuVibrationModel framed(quiet, FireflyBody(), 31), rigid(rigid_params, FireflyBody(), 32);
  const Record b = Read(&framed, {rotor}, dt, 300.0), r = Read(&rigid, {rotor}, dt, 300.0);
  const double level = s_t * rotor.motor_constant * w * w / FireflyBody().mass_kg;
  // each estimate is the mean of 11 bins 1.6 Hz apart (2 bins of the 1024-sample periodogram) around f
  for (double f : {30.0, 100.0, 150.0, 200.0, 330.0}) {
    double expected = 0.0, measured = 0.0, rigid_measured = 0.0;
    for (int j = -5; j <= 5; ++j) {
      const double fj = f + 1.6 * j;
      for (int m = -400; m <= 400; ++m) expected += std::norm(FrameMode::Transmissibility(f_n, zeta, fj + m * fs));
      measured += Density(b.az, fs, fj, 1024);
      rigid_measured += Density(r.az, fs, fj, 1024);
    }
    expected *= level * level / 11.0, measured /= 11.0, rigid_measured /= 11.0;
    EXPECT_NEAR(measured, expected, 0.05 * expected) << f << " Hz";
    EXPECT_NEAR(rigid_measured, level * level, 0.05 * level * level) << f << " Hz";
    std::printf(
        "broadband through a %.0f Hz mode at %5.1f Hz: density %.3e (model %.3e), rigid %.3e (model %.3e) "
        "(m/s^2)^2/Hz\n",
        f_n, f, measured, expected, rigid_measured, level * level);
  }
  EXPECT_LT(Density(b.ax, fs, 150.0, 1024), 1e-12 * level * level);  // along the spin axis only
  // motors off: no broadband
  ImuVibrationModel off(quiet, FireflyBody(), 33);
  const Record still = Read(&off, {Rotor(0.0)}, dt, 1.0);
  for (double v : still.az) EXPECT_NEAR(v, 0.0, 1e-12);
}

TEST(FrameMode, ErrorsNameTheValue) {
  ImuVibrationParams p = FrameParams(120.0, -1.0);
  EXPECT_NE(p.Validate().find("frameModeDamping = -1"), std::string::npos) << p.Validate();
  p = FrameParams(-3.0, 0.05);
  EXPECT_NE(p.Validate().find("frameModeFrequency = -3"), std::string::npos) << p.Validate();
  p = FrameParams(0.0, -1.0, std::nan(""));
  EXPECT_NE(p.Validate().find("thrustNoiseDensity"), std::string::npos) << p.Validate();
  EXPECT_EQ(FrameParams(0.0, -1.0).Validate(), "");  // rigid: no damping needed
  p = FrameParams(120.0, 0.05);
  p.enabled = false;  // never silently ignored
  EXPECT_NE(p.Validate().find("rotorVibration is off"), std::string::npos) << p.Validate();
}
