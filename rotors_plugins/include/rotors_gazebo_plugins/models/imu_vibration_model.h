// An IMU that feels the rotors (docs/sensor_realism.md, "IMU vibration"), free of any engine.
//
// Excitation. Rotor i (hub p_i from the body's centre of mass, spin axis z_i with x_i, y_i completing a
// right-handed frame, signed speed w_i, phase phi_i = integral of w_i dt) carries a residual unbalance
// U_i [kg m] and a thrust ripple at the blade-pass frequency n_b w_i:
//   F_i(t) = U_i w_i^2 (x_i cos phi_i + y_i sin phi_i) + r_bp C_T w_i^2 cos(n_b phi_i) z_i
// U_i is measured (residualUnbalance) or follows from a balance grade G (ISO 21940-11): the permissible
// eccentricity e_per = G / Omega_max at the rotor's maximum service speed, U_i = m_rotor e_per.
//
// Response. The airframe answers as the rigid body the engine flies (mass m, inertia J about the CoG);
// the vibration is small, so it adds to the flight's own motion:
//   a_vib = sum_i F_i / m + alpha x p_imu,        alpha = J^-1 sum_i p_i x F_i
//   omega_vib = J^-1 sum_i p_i x integral(F_i dt)
//   integral(F_i dt) = U_i w_i (x_i sin phi_i - y_i cos phi_i) + r_bp C_T w_i sin(n_b phi_i) / n_b z_i
// (the centripetal term omega x (omega x p_imu) of the vibration is second order and left out).
//
// The frame between the rotors and the IMU (FrameMode, optional): one structural mode of natural frequency
// f_n and damping ratio zeta, excited through its base (the rigid body's motion). It passes a sinusoid of
// angular frequency w with the transmissibility
//   T(jw) = (w_n^2 + j 2 zeta w_n w) / (w_n^2 - w^2 + j 2 zeta w_n w),   w_n = 2 pi f_n
// (gain |T| and phase arg T, on all six axes), and the rotors' broadband thrust fluctuation, white with
// density s_T relative to each rotor's thrust, along its spin axis:
//   a_bb = sum_i s_T C_T w_i^2 n_i(t) z_i / m,   n_i unit white noise,  seen by the IMU as T * a_bb
//   (density s_T C_T w_i^2 |T(f)| / m per rotor), stepped exactly at the internal rate.
//
// Sampling, as the ADIS16448 does it: the signal (flight + vibration) is sampled at the internal rate
// f_s (819.2 SPS), filtered by the Bartlett-window FIR of SENS_AVG (two cascaded N_B-tap moving averages,
//   H(f) = [sin(pi N_B f / f_s) / (N_B sin(pi f / f_s))]^2 ),
// and the output register holds the newest filtered sample until the next one: a reader at another rate
// (one read per physics step) decimates, and a rotor above its Nyquist frequency aliases, as on the sensor.
// The white noise and biases of ImuNoiseModel are added to what is read, as before.
#pragma once

#include <complex>
#include <cstdint>
#include <deque>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rotors_gazebo_plugins/models/imu_noise_model.h"

namespace rotors_gazebo_plugins {

struct ImuVibrationParams {
  bool enabled = false;                   ///< (rotorVibration) false: RotorS' IMU, bit for bit
  double balance_grade_mm_s = 6.3;        ///< G [mm/s] (balanceGrade); ISO 21940-11 G 6.3: fans
  double residual_unbalance_kg_m = -1.0;  ///< U [kg m] per rotor (residualUnbalance); < 0: from the grade
  int blade_count = 2;                    ///< n_b (bladeCount)
  double blade_pass_thrust_ripple =
      0.0;                          ///< r_bp: amplitude of the n_b/rev thrust over the mean (bladePassThrustRipple)
  double internal_rate_hz = 819.2;  ///< f_s [Hz] (internalSampleRate); the ADIS16448's
  int bartlett_taps = 16;           ///< N_B = 2^B, B = SENS_AVG[2:0] (bartlettTaps); 16 as PX4's driver sets
  double frame_mode_frequency_hz = 0.0;  ///< f_n [Hz] (frameModeFrequency); 0: the IMU rigid on the body
  double frame_mode_damping = -1.0;      ///< zeta (frameModeDamping); required with a frame mode
  double thrust_noise_density = 0.0;     ///< s_T [1/sqrt(Hz)] (thrustNoiseDensity); 0: no broadband
  /// Empty when valid, else one line naming the bad value and the fix.
  std::string Validate() const;
};

/// One rotor as the vibration sees it, in the body frame B (origin at the CoG, the rigid body's axes).
struct VibratingRotor {
  Eigen::Vector3d p_B = Eigen::Vector3d::Zero();      ///< [m] hub
  Eigen::Vector3d axis_B = Eigen::Vector3d::UnitZ();  ///< unit spin axis; a positive speed turns about it
  double rotor_mass_kg = 0.0;
  double max_rot_velocity_rad_s = 0.0;  ///< Omega_max, where the balance grade holds
  double motor_constant = 0.0;          ///< C_T [N/(rad/s)^2]
  double speed_rad_s = 0.0;             ///< signed speed over the step
};

/// The rigid body that carries the IMU.
struct VibratingBody {
  double mass_kg = 1.0;
  Eigen::Matrix3d inertia_B_kg_m2 = Eigen::Matrix3d::Identity();  ///< about the CoG
  Eigen::Vector3d p_B_imu = Eigen::Vector3d::Zero();              ///< [m] IMU from the CoG
  Eigen::Matrix3d R_BI = Eigen::Matrix3d::Identity();             ///< IMU axes in the body frame
  /// Empty when valid, else one line naming the bad value.
  std::string Validate() const;
};

/// The ADIS16448's Bartlett-window FIR (SENS_AVG): two cascaded N-tap moving averages on 6 channels.
class BartlettFilter {
 public:
  using Vector6d = Eigen::Matrix<double, 6, 1>;
  explicit BartlettFilter(int taps);
  /// Filters one sample; the first sample fills both stages (no start-up transient).
  Vector6d Push(const Vector6d& x);
  /// |H(f)| = [sin(pi N f / f_s) / (N sin(pi f / f_s))]^2
  static double Gain(int taps, double f_hz, double sample_rate_hz);

 private:
  struct MovingAverage {
    std::deque<Vector6d> window;
    Vector6d sum = Vector6d::Zero();
  };
  Vector6d Average(MovingAverage* stage, const Vector6d& x) const;
  int taps_;
  MovingAverage first_, second_;
};

/// One structural mode of the frame between the rotors and the IMU, excited through its base. The
/// broadband state is one mode per rotor (relative displacement and velocity), driven by that rotor's
/// unit white noise and stepped exactly (Van Loan's integral of the noise over a sample period).
class FrameMode {
 public:
  /// natural_frequency_hz 0: a rigid frame (T = 1; the broadband passes as white noise).
  FrameMode(double natural_frequency_hz, double damping_ratio, double sample_rate_hz, uint64_t seed);
  /// T(j 2 pi f) of the equation above; 1 for a rigid frame.
  static std::complex<double> Transmissibility(double natural_frequency_hz, double damping_ratio, double f_hz);
  std::complex<double> Transmissibility(double f_hz) const;
  /// The IMU's acceleration [per unit density of the input] from `sources` unit white inputs, one sample
  /// period on: y_k of each source (density |T(f)| at f, as a density 1 input).
  const std::vector<double>& Next(size_t sources);

 private:
  double natural_frequency_hz_, damping_ratio_, sample_rate_hz_;
  Eigen::Matrix2d phi_ = Eigen::Matrix2d::Identity();          ///< e^{A h}
  Eigen::Matrix2d noise_chol_ = Eigen::Matrix2d::Zero();       ///< chol(Q_d), Q_d = int_0^h e^{At} B B^T e^{A^T t} dt
  Eigen::Matrix2d stationary_chol_ = Eigen::Matrix2d::Zero();  ///< chol(P), P = Phi P Phi^T + Q_d
  Eigen::RowVector2d output_ = Eigen::RowVector2d::Zero();     ///< y = -w_n^2 z - 2 zeta w_n z'
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_;
  std::vector<Eigen::Vector2d> states_;
  std::vector<double> outputs_;
};

class ImuVibrationModel {
 public:
  /// `seed` draws each rotor's initial unbalance angle (uniform), as a real rotor's.
  ImuVibrationModel(const ImuVibrationParams& params, const VibratingBody& body, uint64_t seed);

  /// U [kg m]: residualUnbalance, or m_rotor G / Omega_max (ISO 21940-11).
  double Unbalance(const VibratingRotor& rotor) const;
  /// The vibration's specific force [m/s^2] and angular velocity [rad/s], IMU frame, at the rotor
  /// phases `phases_rad` (the equations above).
  /// (The rotors' lines pass the frame's mode with its transmissibility T.)
  ImuSample Vibration(const std::vector<VibratingRotor>& rotors, const std::vector<double>& phases_rad) const;
  /// The rotors' broadband thrust fluctuation through the frame's mode, IMU frame [m/s^2], one internal
  /// sample on (zero, and no draw, when thrustNoiseDensity is 0).
  Eigen::Vector3d Broadband(const std::vector<VibratingRotor>& rotors);
  /// One reader's period dt: samples flight (interpolated from truth_begin to truth_end) plus vibration
  /// at the internal rate, filters them and returns what the output register holds at the end.
  ImuSample Step(const ImuSample& truth_begin, const ImuSample& truth_end, const std::vector<VibratingRotor>& rotors,
                 double dt_s);
  const std::vector<double>& Phases() const { return phases_rad_; }

 private:
  ImuVibrationParams params_;
  VibratingBody body_;
  Eigen::Matrix3d inverse_inertia_B_;
  std::mt19937_64 rng_;
  std::vector<double> phases_rad_;         ///< at the start of the next period
  std::vector<double> sample_phases_rad_;  ///< at an internal sample (Step's scratch)
  BartlettFilter filter_;
  FrameMode frame_;
  double time_to_next_sample_s_ = 0.0;
  bool have_output_ = false;
  BartlettFilter::Vector6d output_ = BartlettFilter::Vector6d::Zero();
};

}  // namespace rotors_gazebo_plugins
