#include "rotors_gazebo_plugins/models/imu_vibration_model.h"

#include <cmath>

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

namespace rotors_gazebo_plugins {

namespace {
/// x_i, y_i: a right-handed frame (x_i, y_i, axis) around the spin axis.
void RotorPlane(const Eigen::Vector3d& axis, Eigen::Vector3d* x, Eigen::Vector3d* y) {
  const Eigen::Vector3d helper = std::abs(axis.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  *x = (helper - helper.dot(axis) * axis).normalized();
  *y = axis.cross(*x);
}

/// A sinusoid's phase shift through T for a signed speed: a negative speed runs its phase backwards.
struct Passed {
  double gain = 1.0, shift_rad = 0.0;
};
Passed Pass(const FrameMode& frame, double w_rad_s, double harmonic) {
  const std::complex<double> t = frame.Transmissibility(harmonic * std::abs(w_rad_s) / (2.0 * M_PI));
  return {std::abs(t), w_rad_s < 0.0 ? -std::arg(t) : std::arg(t)};
}
}  // namespace

std::string ImuVibrationParams::Validate() const {
  if (!enabled && (frame_mode_frequency_hz != 0.0 || thrust_noise_density != 0.0))
    return "frameModeFrequency / thrustNoiseDensity are set but rotorVibration is off: the frame's mode and the "
           "thrust's broadband are part of the rotors' vibration; set rotorVibration true (sensor_realism:=true)";
  if (!enabled) return "";
  if (!std::isfinite(balance_grade_mm_s) || balance_grade_mm_s < 0.0)
    return "balanceGrade = " + std::to_string(balance_grade_mm_s) +
           " mm/s must be >= 0 (an ISO 21940-11 grade, e.g. 6.3 for fans)";
  if (!std::isfinite(residual_unbalance_kg_m))
    return "residualUnbalance must be finite (kg m; a negative value takes it from balanceGrade)";
  if (blade_count < 1) return "bladeCount = " + std::to_string(blade_count) + " must be >= 1";
  if (!std::isfinite(blade_pass_thrust_ripple) || blade_pass_thrust_ripple < 0.0 || blade_pass_thrust_ripple > 1.0)
    return "bladePassThrustRipple = " + std::to_string(blade_pass_thrust_ripple) +
           " must be in [0, 1] (a fraction of the mean thrust)";
  if (!std::isfinite(internal_rate_hz) || internal_rate_hz <= 0.0)
    return "internalSampleRate = " + std::to_string(internal_rate_hz) + " Hz must be > 0 (the ADIS16448's is 819.2)";
  if (bartlett_taps < 1 || bartlett_taps > 128 || (bartlett_taps & (bartlett_taps - 1)) != 0)
    return "bartlettTaps = " + std::to_string(bartlett_taps) +
           " must be a power of two from 1 to 128 (2^B, B = SENS_AVG[2:0] of the ADIS16448)";
  if (!std::isfinite(frame_mode_frequency_hz) || frame_mode_frequency_hz < 0.0)
    return "frameModeFrequency = " + std::to_string(frame_mode_frequency_hz) +
           " Hz must be >= 0 (the frame's mode from a tap test; 0 for a rigid frame)";
  if (frame_mode_frequency_hz > 0.0 && !(frame_mode_damping > 0.0 && frame_mode_damping <= 1.0))
    return "frameModeDamping = " + std::to_string(frame_mode_damping) + " must be in (0, 1] with frameModeFrequency " +
           std::to_string(frame_mode_frequency_hz) + " Hz (the mode's damping ratio, from the same measurement)";
  if (!std::isfinite(thrust_noise_density) || thrust_noise_density < 0.0)
    return "thrustNoiseDensity = " + std::to_string(thrust_noise_density) +
           " /sqrt(Hz) must be >= 0 (the thrust's broadband fluctuation over its mean; 0 for none)";
  return "";
}

std::string VibratingBody::Validate() const {
  if (!(mass_kg > 0.0)) return "the IMU's rigid body has mass " + std::to_string(mass_kg) + " kg; it must be > 0";
  if (std::abs(inertia_B_kg_m2.determinant()) < 1e-30) return "the IMU's rigid body has a singular inertia";
  return "";
}

// ------------------------------- BartlettFilter -------------------------------

BartlettFilter::BartlettFilter(int taps) : taps_(taps) {}

BartlettFilter::Vector6d BartlettFilter::Average(MovingAverage* stage, const Vector6d& x) const {
  if (stage->window.empty()) stage->window.assign(taps_, x);
  else {
    stage->window.pop_front();
    stage->window.push_back(x);
  }
  // summed again each time, in one order: no drift of a running sum, the same bits after a reset
  Vector6d sum = Vector6d::Zero();
  for (const Vector6d& v : stage->window) sum += v;
  return sum / static_cast<double>(taps_);
}

BartlettFilter::Vector6d BartlettFilter::Push(const Vector6d& x) { return Average(&second_, Average(&first_, x)); }

double BartlettFilter::Gain(int taps, double f_hz, double sample_rate_hz) {
  const double x = M_PI * f_hz / sample_rate_hz;
  if (std::abs(std::sin(x)) < 1e-15) return 1.0;
  const double h = std::sin(taps * x) / (taps * std::sin(x));
  return h * h;
}

// ------------------------------- FrameMode -------------------------------

FrameMode::FrameMode(double natural_frequency_hz, double damping_ratio, double sample_rate_hz, uint64_t seed)
    : natural_frequency_hz_(natural_frequency_hz),
      damping_ratio_(damping_ratio),
      sample_rate_hz_(sample_rate_hz),
      rng_(seed) {
  if (natural_frequency_hz_ <= 0.0) return;
  const double w_n = 2.0 * M_PI * natural_frequency_hz_, h = 1.0 / sample_rate_hz_;
  // x = (z, z'), z the IMU's displacement from its base:  z'' = -w_n^2 z - 2 zeta w_n z' - a_base
  Eigen::Matrix2d a;
  a << 0.0, 1.0, -w_n * w_n, -2.0 * damping_ratio_ * w_n;
  const Eigen::Vector2d b(0.0, -1.0);
  // Van Loan: exp([[-A, B B^T], [0, A^T]] h) = [[., Phi^-1 Q_d], [0, Phi^T]]
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  m.topLeftCorner<2, 2>() = -a * h;
  m.topRightCorner<2, 2>() = b * b.transpose() * h;
  m.bottomRightCorner<2, 2>() = a.transpose() * h;
  const Eigen::Matrix4d e = m.exp();
  phi_ = e.bottomRightCorner<2, 2>().transpose();
  const Eigen::Matrix2d q_d = phi_ * e.topRightCorner<2, 2>();
  noise_chol_ = Eigen::Matrix2d(q_d.llt().matrixL());
  // P = Phi P Phi^T + Q_d:  (I - Phi (x) Phi) vec(P) = vec(Q_d)
  Eigen::Matrix4d kron;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) kron.block<2, 2>(2 * i, 2 * j) = phi_(i, j) * phi_;
  const Eigen::Vector4d vec_p =
      (Eigen::Matrix4d::Identity() - kron).colPivHouseholderQr().solve(Eigen::Map<const Eigen::Vector4d>(q_d.data()));
  const Eigen::Matrix2d p = Eigen::Map<const Eigen::Matrix2d>(vec_p.data());
  stationary_chol_ = Eigen::Matrix2d(p.llt().matrixL());
  // the IMU's absolute acceleration a_base + z'' = -w_n^2 z - 2 zeta w_n z'
  output_ << -w_n * w_n, -2.0 * damping_ratio_ * w_n;
}

std::complex<double> FrameMode::Transmissibility(double natural_frequency_hz, double damping_ratio, double f_hz) {
  if (natural_frequency_hz <= 0.0) return 1.0;
  const double w_n = 2.0 * M_PI * natural_frequency_hz, w = 2.0 * M_PI * f_hz;
  // T(jw) = (w_n^2 + j 2 zeta w_n w) / (w_n^2 - w^2 + j 2 zeta w_n w)
  const std::complex<double> damping(0.0, 2.0 * damping_ratio * w_n * w);
  return (w_n * w_n + damping) / (w_n * w_n - w * w + damping);
}

std::complex<double> FrameMode::Transmissibility(double f_hz) const {
  return Transmissibility(natural_frequency_hz_, damping_ratio_, f_hz);
}

const std::vector<double>& FrameMode::Next(size_t sources) {
  outputs_.resize(sources);
  if (natural_frequency_hz_ <= 0.0) {
    // a rigid frame: unit-density white noise, variance f_s per sample
    for (double& y : outputs_) y = normal_(rng_) * std::sqrt(sample_rate_hz_);
    return outputs_;
  }
  while (states_.size() < sources)  // a new source starts in the mode's stationary state
    states_.push_back(stationary_chol_ * Eigen::Vector2d(normal_(rng_), normal_(rng_)));
  for (size_t i = 0; i < sources; ++i) {
    states_[i] = phi_ * states_[i] + noise_chol_ * Eigen::Vector2d(normal_(rng_), normal_(rng_));
    outputs_[i] = output_ * states_[i];
  }
  return outputs_;
}

// ------------------------------- ImuVibrationModel -------------------------------

ImuVibrationModel::ImuVibrationModel(const ImuVibrationParams& params, const VibratingBody& body, uint64_t seed)
    : params_(params),
      body_(body),
      inverse_inertia_B_(body.inertia_B_kg_m2.inverse()),
      rng_(seed),
      filter_(params.bartlett_taps),
      frame_(params.frame_mode_frequency_hz, params.frame_mode_damping, params.internal_rate_hz,
             seed ^ 0x9e3779b97f4a7c15ULL) {}

double ImuVibrationModel::Unbalance(const VibratingRotor& rotor) const {
  if (params_.residual_unbalance_kg_m >= 0.0) return params_.residual_unbalance_kg_m;
  if (rotor.max_rot_velocity_rad_s <= 0.0) return 0.0;
  // ISO 21940-11: e_per Omega_max = G
  const double e_per_m = params_.balance_grade_mm_s * 1e-3 / rotor.max_rot_velocity_rad_s;
  return rotor.rotor_mass_kg * e_per_m;
}

ImuSample ImuVibrationModel::Vibration(const std::vector<VibratingRotor>& rotors,
                                       const std::vector<double>& phases_rad) const {
  Eigen::Vector3d force_B = Eigen::Vector3d::Zero(), moment_B = Eigen::Vector3d::Zero();
  Eigen::Vector3d impulse_moment_B = Eigen::Vector3d::Zero();  // sum p_i x integral(F_i dt)
  const double n_b = params_.blade_count;
  for (size_t i = 0; i < rotors.size(); ++i) {
    const VibratingRotor& r = rotors[i];
    const double w = r.speed_rad_s, phi = phases_rad[i];
    Eigen::Vector3d x, y;
    RotorPlane(r.axis_B, &x, &y);
    const double u = Unbalance(r), ripple = params_.blade_pass_thrust_ripple * r.motor_constant;
    // each line as the IMU sees it through the frame: gain |T|, phase arg T at its frequency
    const Passed once = Pass(frame_, w, 1.0), blade_pass = Pass(frame_, w, n_b);
    const double phi_1 = phi + once.shift_rad, phi_b = n_b * phi + blade_pass.shift_rad;
    const double u_t = u * once.gain, ripple_t = ripple * blade_pass.gain;
    // F_i = U w^2 (x cos phi + y sin phi) + r_bp C_T w^2 cos(n_b phi) z
    const Eigen::Vector3d f =
        u_t * w * w * (x * std::cos(phi_1) + y * std::sin(phi_1)) + ripple_t * w * w * std::cos(phi_b) * r.axis_B;
    // integral(F_i dt) = U w (x sin phi - y cos phi) + r_bp C_T w sin(n_b phi) / n_b z
    const Eigen::Vector3d impulse =
        u_t * w * (x * std::sin(phi_1) - y * std::cos(phi_1)) + ripple_t * w * std::sin(phi_b) / n_b * r.axis_B;
    force_B += f;
    moment_B += r.p_B.cross(f);
    impulse_moment_B += r.p_B.cross(impulse);
  }
  // a_vib = sum F / m + alpha x p_imu, alpha = J^-1 sum p x F; omega_vib = J^-1 sum p x integral(F dt)
  const Eigen::Vector3d alpha_B = inverse_inertia_B_ * moment_B;
  const Eigen::Vector3d a_B = force_B / body_.mass_kg + alpha_B.cross(body_.p_B_imu);
  const Eigen::Vector3d omega_B = inverse_inertia_B_ * impulse_moment_B;
  const Eigen::Matrix3d R_IB = body_.R_BI.transpose();
  return {R_IB * omega_B, R_IB * a_B};
}

Eigen::Vector3d ImuVibrationModel::Broadband(const std::vector<VibratingRotor>& rotors) {
  if (params_.thrust_noise_density <= 0.0) return Eigen::Vector3d::Zero();
  const std::vector<double>& y = frame_.Next(rotors.size());
  // a_bb = sum_i s_T C_T w_i^2 n_i z_i / m, through the frame's mode
  Eigen::Vector3d a_B = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < rotors.size(); ++i) {
    const double w = rotors[i].speed_rad_s;
    a_B += params_.thrust_noise_density * rotors[i].motor_constant * w * w * y[i] / body_.mass_kg * rotors[i].axis_B;
  }
  return body_.R_BI.transpose() * a_B;
}

ImuSample ImuVibrationModel::Step(const ImuSample& truth_begin, const ImuSample& truth_end,
                                  const std::vector<VibratingRotor>& rotors, double dt_s) {
  while (phases_rad_.size() < rotors.size())
    phases_rad_.push_back(std::uniform_real_distribution<double>(0.0, 2.0 * M_PI)(rng_));
  const double period_s = 1.0 / params_.internal_rate_hz;
  std::vector<double>& phases = sample_phases_rad_;  // reused: no allocation on the physics step
  phases.resize(rotors.size());
  double tau_s = time_to_next_sample_s_;
  for (; tau_s <= dt_s; tau_s += period_s) {
    for (size_t i = 0; i < rotors.size(); ++i) phases[i] = phases_rad_[i] + rotors[i].speed_rad_s * tau_s;
    ImuSample v = Vibration(rotors, phases);
    v.linear_acceleration_I += Broadband(rotors);
    const double s = dt_s > 0.0 ? tau_s / dt_s : 1.0;  // the flight, interpolated over the period
    BartlettFilter::Vector6d x;
    x << (1.0 - s) * truth_begin.angular_velocity_I + s * truth_end.angular_velocity_I + v.angular_velocity_I,
        (1.0 - s) * truth_begin.linear_acceleration_I + s * truth_end.linear_acceleration_I + v.linear_acceleration_I;
    output_ = filter_.Push(x);
    have_output_ = true;
  }
  time_to_next_sample_s_ = tau_s - dt_s;
  for (size_t i = 0; i < rotors.size(); ++i)
    phases_rad_[i] = std::fmod(phases_rad_[i] + rotors[i].speed_rad_s * dt_s, 2.0 * M_PI);
  if (!have_output_) return truth_end;
  return {output_.head<3>(), output_.tail<3>()};
}

}  // namespace rotors_gazebo_plugins
