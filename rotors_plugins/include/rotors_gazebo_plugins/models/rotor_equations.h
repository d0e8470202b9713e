// The equations of one rotor (book section 2.1, eqs. 1-5) and its speed dynamics, written once and
// generic over the number type: T is double (RotorModel, the motor plugin) or a GCC vector of doubles
// (the batched flight engine, one lane per vehicle or per rotor), every lane computed with the same
// operations in the same order as the scalar, so a lane equals the scalar bit for bit (no fused
// multiply-add). No Eigen and no engine here: the batch's kernels include it in translation units
// compiled for their own instruction set.
#pragma once

#include "rotors_gazebo_plugins/models/first_order_filter.h"

namespace rotors_gazebo_plugins {

/// One rotor's loads (eqs. 1-5) in a frame F, applied at the rotor hub. T: double or lanes.
template <class T>
struct RotorLoadsT {
  T thrust_F[3];           ///< F_T, eq. 1
  T drag_F[3];             ///< F_D, eq. 2
  T rolling_moment_F[3];   ///< M_R, eq. 3
  T reaction_moment_F[3];  ///< M_D, eq. 4
};

/// Eqs. 1-5 for a rotor turning at omega [rad/s] about the unit axis e_F, with the airspeed
/// v_A_F = v_hub - v_wind, both in one frame F (the rotor frame, where e = e_z, or the world). The
/// coefficients C are double or lanes of them: C_T, C_D, C_R and the reaction factor -epsilon C_M.
template <class T, class C>
inline RotorLoadsT<T> RotorLoads(const T& omega, const T e_F[3], const T v_A_F[3], const C& motor_constant,
                                 const C& rotor_drag_coefficient, const C& rolling_moment_coefficient,
                                 const C& reaction_factor) {
  RotorLoadsT<T> out;
  // eq. 1: F_T = omega^2 C_T e
  const T thrust = omega * omega * motor_constant;
  // eq. 4: M_D = -epsilon C_M F_T
  const T reaction = reaction_factor * thrust;
  // eq. 5: v_perp = v_A - (v_A . e) e, the airspeed in the rotor plane
  const T v_par = v_A_F[0] * e_F[0] + v_A_F[1] * e_F[1] + v_A_F[2] * e_F[2];
  const T drag = omega * rotor_drag_coefficient, rolling = omega * rolling_moment_coefficient;
  for (int c = 0; c < 3; ++c) {
    const T v_perp = v_A_F[c] - v_par * e_F[c];
    out.thrust_F[c] = thrust * e_F[c];
    // eq. 2: F_D = -omega C_D v_perp
    out.drag_F[c] = -(drag * v_perp);
    // eq. 3: M_R = omega C_R v_perp  (the book's sign; RotorS applies the opposite one)
    out.rolling_moment_F[c] = rolling * v_perp;
    out.reaction_moment_F[c] = reaction * e_F[c];
  }
  return out;
}

/// The speed dynamics over one step: the command clamped to [0, max], then the exact
/// discretisation of  tau domega/dt = u - omega  with u held (FirstOrderFilter::Blend):
/// omega_k = a omega_{k-1} + (1 - a) u,  a = exp(-dt / tau_up) while u > omega, else exp(-dt / tau_down).
/// T is double or lanes; max, a_up and a_down of the same type.
template <class T>
inline T RotorSpeedStep(const T& omega, const T& omega_cmd, const T& max_rot_velocity, const T& a_up, const T& a_down) {
  const T zero = {};
  const T u = omega_cmd < zero ? zero : (max_rot_velocity < omega_cmd ? max_rot_velocity : omega_cmd);
  const T a = u > omega ? a_up : a_down;
  return FirstOrderFilter::Blend(omega, u, a);
}

}  // namespace rotors_gazebo_plugins
