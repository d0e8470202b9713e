// The moment a spinning rotor puts on the body that carries it (a kinematic joint, Joint), written
// once for the world and the batched flight engine. T is double or a GCC vector of doubles (one lane
// per body or per rotor), every lane computed as the scalar.
#pragma once

namespace rotors_sim {
namespace physics {

/// M_W = -dh/dt = -(omega_W x h_W) - J_a qddot a_W,  h_W = J_a qdot a_W,  qddot = (qdot - qdot_before) / dt:
/// the gyroscopic and spin-up moment of a rotor with spin inertia J_a [kg m^2] turning at qdot [rad/s]
/// about the unit axis a_W, on a body turning at omega_W [rad/s]. inv_dt = 1 / dt [1/s]. J and W are T or
/// double (the same for every lane).
template <class T, class J, class W>
inline void SpinMoment(const T a_W[3], const J& spin_inertia, const T& qdot, const T& qdot_before, double inv_dt,
                       const W omega_W[3], T M_W[3]) {
  const T J_qdot = spin_inertia * qdot;
  const T h_W[3] = {a_W[0] * J_qdot, a_W[1] * J_qdot, a_W[2] * J_qdot};
  const T J_qddot = spin_inertia * ((qdot - qdot_before) * inv_dt);
  const T w_x_h[3] = {omega_W[1] * h_W[2] - omega_W[2] * h_W[1], omega_W[2] * h_W[0] - omega_W[0] * h_W[2],
                      omega_W[0] * h_W[1] - omega_W[1] * h_W[0]};
  for (int c = 0; c < 3; ++c) M_W[c] = -w_x_h[c] - a_W[c] * J_qddot;
}

}  // namespace physics
}  // namespace rotors_sim
