// The laws of Lee's position controller as templates over the number type T: double for one
// vehicle (LeeController, AttitudeControlLaw and MotorMixer run them so, for the ROS nodes, the
// world and Python alike), or a GCC vector of doubles, a lane per vehicle (the batched flight
// engine steps groups of vehicles so). Where the one-vehicle law branches, the template selects,
// lane by lane, between values both computed; every lane does the same operations in the same
// order and the project builds without fused multiply-add, so a lane equals the call for one
// vehicle bit for bit. Plain arrays, matrices row-major; no Eigen, no ROS.
//   R(q)                                  Eigen's toRotationMatrix
//   a = (K_p e_p + K_v e_v) / m - g e3 - a_d   (Lee2010 eqs. 6-7, the negative desired acceleration),
//       saturated with vertical priority (SaturatedAcceleration)
//   f = -m a . R e3                       Lee2010 eq. (15)
//   b3_d = -a / |a|, b2_d = (b3_d x b1_d) / |.|, R_d = [b2_d x b3_d, b2_d, b3_d]
//   alpha = -K~_R e_R - K~_w e_w + J^-1 (w x J w) - w x R^T R_d w_d   Lee2010 eqs. (10), (11), (16) / J
//   omega^2 = A^T (A A^T)^-1 blockdiag(J, 1) [alpha; f], yaw and thrust given up first (MotorMixer)
#pragma once

#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <type_traits>

namespace rotors_control {

constexpr int kMaxMixerRotors = 16;

namespace law {

template <class T>
inline T Splat(double x) {
  if constexpr (std::is_same_v<T, double>) {
    return x;
  } else {
    T v = {};
    return v + x;
  }
}
/// std::min's and std::max's results (the first when neither is smaller), lane by lane.
template <class T>
inline T Min(const T& a, const T& b) {
  return b < a ? b : a;
}
template <class T>
inline T Max(const T& a, const T& b) {
  return a < b ? b : a;
}
/// std::clamp(v, lo, hi).
template <class T>
inline T Clamp(const T& v, const T& lo, const T& hi) {
  return v < lo ? lo : (hi < v ? hi : v);
}
template <class T>
inline T Sqrt(const T& x) {
  if constexpr (std::is_same_v<T, double>) {
    return std::sqrt(x);
  } else {
    double lanes[sizeof(T) / sizeof(double)];
    std::memcpy(lanes, &x, sizeof(T));
    for (double& l : lanes) l = std::sqrt(l);
    T r;
    std::memcpy(&r, lanes, sizeof(T));
    return r;
  }
}
inline bool Any(bool m) { return m; }
template <class M>
inline bool Any(const M& m) {
  for (size_t k = 0; k < sizeof(M) / sizeof(m[0]); ++k)
    if (m[k]) return true;
  return false;
}
/// A 0/1 flag of the constants as a lane mask.
template <class T>
inline auto On(const T& flag) {
  return flag != Splat<T>(0.0);
}
template <class T>
inline void Cross(const T a[3], const T b[3], T out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}
template <class T>
inline T Dot(const T a[3], const T b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
/// out = M v (M row-major 3 x 3)
template <class T>
inline void Multiply(const T M[9], const T v[3], T out[3]) {
  for (int i = 0; i < 3; ++i) out[i] = M[i * 3 + 0] * v[0] + M[i * 3 + 1] * v[1] + M[i * 3 + 2] * v[2];
}
/// (A^T B)(i, j) = sum_k A(k, i) B(k, j)
template <class T>
inline T TransposeTimes(const T A[9], const T B[9], int i, int j) {
  return A[0 * 3 + i] * B[0 * 3 + j] + A[1 * 3 + i] * B[1 * 3 + j] + A[2 * 3 + i] * B[2 * 3 + j];
}

}  // namespace law

/// One Lee controller's constants as the laws read them: T = double for one vehicle, or a lane type
/// (each lane one vehicle's). Every member is a T, so that a group's constants are rows of lanes
/// (flags are 1 or 0).
template <class T>
struct LeeConstantsT {
  T mass_kg, gravity_m_s2;
  T position_gain[3], velocity_gain[3];
  // the desired acceleration's limits (SaturatedAcceleration)
  T limits_active, tilt_limited, tan_max_tilt, thrust_limited, max_m_s2, min_up_m_s2;
  // the attitude law: K~_R, K~_w (gains over the inertia), J and J^-1 (row-major)
  T k_R[3], k_omega[3], J[9], J_inv[9];
  // the mixer: A^T (A A^T)^-1 blockdiag(J, 1) by rotor (rows), omega_max^2, every rotor limited
  T mixer[kMaxMixerRotors][4], omega_max_squared[kMaxMixerRotors], rotors_limited;
};

/// What a Lee controller reads at one step: the odometry (q normalised, w x y z) and its reference.
template <class T>
struct LeeInputsT {
  T position_W[3], q_WB[4], velocity_B[3], angular_velocity_B[3];
  T reference_position_W[3], reference_velocity_W[3], reference_acceleration_W[3], reference_yaw_rate_rad_s;
  T b1_reference[3];  ///< (cos, sin, 0) of the reference's yaw
  T yaw_released;     ///< 1: a rotor has failed, hold the current heading
};

namespace law {

/// R_WB from q (w, x, y, z), as Eigen's toRotationMatrix.
template <class T>
inline void RotationOf(const T q[4], T R[9]) {
  const T tx = 2.0 * q[1], ty = 2.0 * q[2], tz = 2.0 * q[3];
  const T twx = tx * q[0], twy = ty * q[0], twz = tz * q[0];
  const T txx = tx * q[1], txy = ty * q[1], txz = tz * q[1];
  const T tyy = ty * q[2], tyz = tz * q[2], tzz = tz * q[3];
  R[0] = 1.0 - (tyy + tzz), R[1] = txy - twz, R[2] = txz + twy;
  R[3] = txy + twz, R[4] = 1.0 - (txx + tzz), R[5] = tyz - twx;
  R[6] = txz - twy, R[7] = tyz + twx, R[8] = 1.0 - (txx + tyy);
}

/// a_des with its upward part clamped to [min_up, max(max, min_up)] first, then its horizontal part
/// shortened (direction kept) to a_up tan(max_tilt) (when tilt_limited) and to sqrt(max^2 - a_up^2)
/// (when thrust_limited).
template <class T>
inline void SaturatedAcceleration(const LeeConstantsT<T>& c, const T a_des[3], T out[3]) {
  const T a_up = Clamp(a_des[2], c.min_up_m_s2, Max(c.max_m_s2, c.min_up_m_s2));
  T a_h_max = Splat<T>(std::numeric_limits<double>::infinity());
  a_h_max = On(c.tilt_limited) ? a_up * c.tan_max_tilt : a_h_max;
  const T thrust_room = Sqrt(Max(c.max_m_s2 * c.max_m_s2 - a_up * a_up, Splat<T>(0.0)));
  a_h_max = On(c.thrust_limited) ? Min(a_h_max, thrust_room) : a_h_max;
  const T a_h_norm = Sqrt(a_des[0] * a_des[0] + a_des[1] * a_des[1]);
  const T scale = a_h_norm > a_h_max ? a_h_max / a_h_norm : Splat<T>(1.0);
  out[0] = scale * a_des[0];
  out[1] = scale * a_des[1];
  out[2] = a_up;
}

/// Lee2010 eq. (15) and the desired attitude: thrust f [N] and R_WD (row-major) for the state with
/// rotation R.
template <class T>
inline void ThrustAndAttitude(const LeeConstantsT<T>& c, const LeeInputsT<T>& in, const T R[9], T* thrust_N,
                              T R_WD[9]) {
  T e_p[3], v_W[3], e_v[3], a[3];
  for (int k = 0; k < 3; ++k) e_p[k] = in.position_W[k] - in.reference_position_W[k];
  Multiply(R, in.velocity_B, v_W);
  for (int k = 0; k < 3; ++k) e_v[k] = v_W[k] - in.reference_velocity_W[k];
  const double e3[3] = {0.0, 0.0, 1.0};
  for (int k = 0; k < 3; ++k)
    a[k] = (c.position_gain[k] * e_p[k] + c.velocity_gain[k] * e_v[k]) / c.mass_kg - c.gravity_m_s2 * e3[k] -
           in.reference_acceleration_W[k];
  {
    const T minus_a[3] = {-a[0], -a[1], -a[2]};
    T saturated[3];
    SaturatedAcceleration(c, minus_a, saturated);
    for (int k = 0; k < 3; ++k) a[k] = On(c.limits_active) ? -saturated[k] : a[k];
  }
  const T R_e3[3] = {R[2], R[5], R[8]};
  *thrust_N = -c.mass_kg * Dot(a, R_e3);
  // b1_d: the reference's heading, or the current one where yaw is given up
  T b1[3] = {in.b1_reference[0], in.b1_reference[1], in.b1_reference[2]};
  const auto released = On(in.yaw_released);
  if (Any(released)) {
    if constexpr (std::is_same_v<T, double>) {
      const double yaw = std::atan2(R[3], R[0]);
      b1[0] = std::cos(yaw), b1[1] = std::sin(yaw), b1[2] = 0.0;
    } else {
      for (size_t l = 0; l < sizeof(T) / sizeof(double); ++l) {
        if (!released[l]) continue;
        const double yaw = std::atan2(R[3][l], R[0][l]);
        b1[0][l] = std::cos(yaw), b1[1][l] = std::sin(yaw), b1[2][l] = 0.0;
      }
    }
  }
  const T a_norm = Sqrt(Dot(a, a));
  T b3[3], b2[3], b1_d[3];
  for (int k = 0; k < 3; ++k) b3[k] = -a[k] / a_norm;
  Cross(b3, b1, b2);
  const T b2_squared = Dot(b2, b2);
  const T b2_norm = Sqrt(b2_squared);
  for (int k = 0; k < 3; ++k) b2[k] = b2_squared > Splat<T>(0.0) ? b2[k] / b2_norm : b2[k];
  Cross(b2, b3, b1_d);
  for (int k = 0; k < 3; ++k) {
    R_WD[k * 3 + 0] = b1_d[k];
    R_WD[k * 3 + 1] = b2[k];
    R_WD[k * 3 + 2] = b3[k];
  }
}

/// Lee2010 eqs. (10), (11) and (16) over J: the desired angular acceleration [rad/s^2, body].
template <class T>
inline void AngularAcceleration(const T k_R[3], const T k_omega[3], const T J[9], const T J_inv[9], const T R[9],
                                const T omega_B[3], const T R_WD[9], const T omega_D[3], T alpha[3]) {
  // e_R = 1/2 vee(R_d^T R - R^T R_d): entries (2, 1), (0, 2), (1, 0)
  const int vee[3][2] = {{2, 1}, {0, 2}, {1, 0}};
  T e_R[3];
  for (int k = 0; k < 3; ++k) {
    const int i = vee[k][0], j = vee[k][1];
    e_R[k] = 0.5 * (TransposeTimes(R_WD, R, i, j) - TransposeTimes(R, R_WD, i, j));
  }
  // e_w = w - R^T R_d w_d
  T R_T_R_d[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R_T_R_d[i * 3 + j] = TransposeTimes(R, R_WD, i, j);
  T omega_d_B[3], J_w[3], w_x_J_w[3], gyro[3], w_x_w_d[3];
  Multiply(R_T_R_d, omega_D, omega_d_B);
  Multiply(J, omega_B, J_w);
  Cross(omega_B, J_w, w_x_J_w);
  Multiply(J_inv, w_x_J_w, gyro);
  Cross(omega_B, omega_d_B, w_x_w_d);
  for (int k = 0; k < 3; ++k) {
    const T e_omega = omega_B[k] - omega_d_B[k];
    alpha[k] = -k_R[k] * e_R[k] - k_omega[k] * e_omega + gyro[k] - w_x_w_d[k];
  }
}

/// The yaw input nearest to `yaw` with without_yaw + per_yaw yaw >= 0 on every rotor (`yaw` itself
/// when no value achieves that).
template <class T>
inline T FeasibleYaw(int rotors, const T without_yaw[], const T per_yaw[], const T& yaw) {
  const T zero = Splat<T>(0.0);
  T lo = Splat<T>(-std::numeric_limits<double>::infinity()), hi = Splat<T>(std::numeric_limits<double>::infinity());
  for (int i = 0; i < rotors; ++i) {
    lo = per_yaw[i] > zero ? Max(lo, -without_yaw[i] / per_yaw[i]) : lo;
    hi = per_yaw[i] < zero ? Min(hi, without_yaw[i] / -per_yaw[i]) : hi;
  }
  return lo <= hi ? Clamp(yaw, lo, hi) : yaw;
}

/// The largest thrust <= thrust_N that keeps every rotor within omega_max while producing alpha
/// (thrust_N where the rotors have no limit).
template <class T>
inline T FeasibleThrust(int rotors, const T mixer[][4], const T omega_max_squared[], const T& rotors_limited,
                        const T alpha[3], const T& thrust_N) {
  const T zero = Splat<T>(0.0);
  T feasible = thrust_N;
  for (int i = 0; i < rotors; ++i) {
    const T torque_part = mixer[i][0] * alpha[0] + mixer[i][1] * alpha[1] + mixer[i][2] * alpha[2];
    const T c = mixer[i][3];
    feasible = c > zero ? Min(feasible, (omega_max_squared[i] - torque_part) / c) : feasible;
  }
  return On(rotors_limited) ? Max(feasible, zero) : thrust_N;
}

/// Rotor speeds [rad/s] for alpha [rad/s^2, body] and thrust [N]: yaw gives way where a rotor would
/// need a negative omega^2, the thrust where one would pass its omega_max.
template <class T>
inline void MixerRotorSpeeds(int rotors, const T mixer[][4], const T omega_max_squared[], const T& rotors_limited,
                             const T alpha[3], const T& thrust_N, T omega[]) {
  T per_yaw[kMaxMixerRotors], first[kMaxMixerRotors], base[kMaxMixerRotors];
  for (int i = 0; i < rotors; ++i) {
    per_yaw[i] = mixer[i][2];
    first[i] = mixer[i][0] * alpha[0] + mixer[i][1] * alpha[1] + mixer[i][3] * thrust_N;
  }
  T alpha_z = FeasibleYaw(rotors, first, per_yaw, alpha[2]);
  const T alpha_feasible[3] = {alpha[0], alpha[1], alpha_z};
  const T thrust = FeasibleThrust(rotors, mixer, omega_max_squared, rotors_limited, alpha_feasible, thrust_N);
  const auto kept = thrust == thrust_N;
  for (int i = 0; i < rotors; ++i)
    base[i] = kept ? first[i] : mixer[i][0] * alpha[0] + mixer[i][1] * alpha[1] + mixer[i][3] * thrust;
  // with the thrust kept, the first pass stands (a second clamp changes nothing)
  if (!(Any(kept) && !Any(!kept))) alpha_z = kept ? alpha_z : FeasibleYaw(rotors, base, per_yaw, alpha_z);
  for (int i = 0; i < rotors; ++i) omega[i] = Sqrt(Max(base[i] + per_yaw[i] * alpha_z, Splat<T>(0.0)));
}

/// Lee's controller at one step: rotor speeds [rad/s] (rotors of them).
template <class T>
inline void LeeRotorSpeeds(int rotors, const LeeConstantsT<T>& c, const LeeInputsT<T>& in, T omega[]) {
  T R[9], R_WD[9], thrust, alpha[3];
  RotationOf(in.q_WB, R);
  ThrustAndAttitude(c, in, R, &thrust, R_WD);
  const T zero = Splat<T>(0.0);
  const T omega_D[3] = {zero, zero, On(in.yaw_released) ? zero : in.reference_yaw_rate_rad_s};
  AngularAcceleration(c.k_R, c.k_omega, c.J, c.J_inv, R, in.angular_velocity_B, R_WD, omega_D, alpha);
  MixerRotorSpeeds(rotors, c.mixer, c.omega_max_squared, c.rotors_limited, alpha, thrust, omega);
}

}  // namespace law
}  // namespace rotors_control
