// One step of a free rigid body (no joints, no contacts), exactly as the world's solver takes it:
// ODE 0.16's dWorldStep / dWorldQuickStep for a body alone in its island (ode/src/quickstep.cpp,
// step.cpp and util.cpp's dxStepBody, tag 0.16.2): semi-implicit Euler with the implicit
// gyroscopic term of Lacoursiere (2006), ODE's default for every body, and ODE's first-order
// quaternion update. The same operations in the same order, so that a body stepped here and one
// stepped by the world agree to rounding (test_physics.cpp checks it against ODE itself).
// Plain arrays of T: double, or a GCC vector of doubles that steps that many bodies at once, lane
// by lane with the same operations (so a lane equals the scalar step bit for bit); callers keep their
// state in whatever layout suits them (the batched flight engine keeps it as structure of arrays).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstring>
#include <type_traits>

namespace rotors_sim {
namespace physics {

/// A free body's state: position of its CoG and linear velocity [m, m/s], orientation q_WB
/// (w, x, y, z) with its rotation matrix R_WB (row-major, kept in step with q as ODE does) and the
/// angular velocity in the world frame [rad/s] (ODE's avel).
template <class T>
struct FreeBodyStateT {
  T p_W[3], v_W[3], q_WB[4], R_WB[9], omega_W[3];
};
using FreeBodyState = FreeBodyStateT<double>;

/// The body's constants: 1 / mass [1/kg], the inertia about the CoG and its inverse in the body
/// frame (row-major) [kg m^2, 1/(kg m^2)]. S: double (one body, or every lane the same body) or a
/// GCC vector of doubles (a body of its own per lane).
template <class S>
struct FreeBodyInertiaT {
  S inv_mass_kg, I_B[9], inv_I_B[9];
};
using FreeBodyInertia = FreeBodyInertiaT<double>;

/// R_WB from q_WB (w, x, y, z), ODE's dRfromQ.
template <class T>
inline void RotationFromQuaternion(const T q[4], T R[9]) {
  const T qq1 = 2.0 * q[1] * q[1], qq2 = 2.0 * q[2] * q[2], qq3 = 2.0 * q[3] * q[3];
  R[0] = 1.0 - qq2 - qq3;
  R[1] = 2.0 * (q[1] * q[2] - q[0] * q[3]);
  R[2] = 2.0 * (q[1] * q[3] + q[0] * q[2]);
  R[3] = 2.0 * (q[1] * q[2] + q[0] * q[3]);
  R[4] = 1.0 - qq1 - qq3;
  R[5] = 2.0 * (q[2] * q[3] - q[0] * q[1]);
  R[6] = 2.0 * (q[1] * q[3] - q[0] * q[2]);
  R[7] = 2.0 * (q[2] * q[3] + q[0] * q[1]);
  R[8] = 1.0 - qq1 - qq2;
}

/// A_W = R A_B R^T for a body-frame tensor A_B, in ODE's order (dMultiply2_333, then dMultiply0_333).
template <class T, class S>
inline void TensorToWorld(const T R[9], const S A_B[9], T A_W[9]) {
  T tmp[9];  // tmp = A_B R^T
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      tmp[i * 3 + j] = R[j * 3 + 0] * A_B[i * 3 + 0] + R[j * 3 + 1] * A_B[i * 3 + 1] + R[j * 3 + 2] * A_B[i * 3 + 2];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      A_W[i * 3 + j] = tmp[0 * 3 + j] * R[i * 3 + 0] + tmp[1 * 3 + j] * R[i * 3 + 1] + tmp[2 * 3 + j] * R[i * 3 + 2];
}

inline bool AnyNonZero(double x) { return x != 0; }
template <class T>
inline bool AnyNonZero(const T&) {
  return true;
}

/// What one step needs of the body's state alone, before any force is known: the inverse inertia in
/// the world frame and ODE's implicit gyroscopic moment. A caller may compute it first and step the
/// forces in meanwhile: the two halves are StepFreeBody's operations, in its order.
template <class T>
struct FreeBodyStateTerms {
  T inv_I_W[9];
  T tau_gyro_W[3];  ///< added to the external torque (an IEEE sum is the same either way round)
};

/// The first half of a step: FreeBodyStateTerms of `s` for the step h.
template <class T, class S>
inline FreeBodyStateTerms<T> FreeBodyTermsOf(double h, const FreeBodyInertiaT<S>& body, const FreeBodyStateT<T>& s) {
  constexpr bool kScalar = std::is_same_v<T, double>;
  FreeBodyStateTerms<T> out;
  T I_W[9];
  TensorToWorld(s.R_WB, body.inv_I_B, out.inv_I_W);
  TensorToWorld(s.R_WB, body.I_B, I_W);
  const T* w = s.omega_W;

  // Implicit gyroscopic moment: with L = I_W w and I~ = I_W - h [L]x,
  //   tau_gyro = (I_W I~^-1 - 1) L / h,  so that  w_next = I~^-1 I_W w + h I_W^-1 T_ext.
  T L[3];
  for (int i = 0; i < 3; ++i) L[i] = I_W[i * 3 + 0] * w[0] + I_W[i * 3 + 1] * w[1] + I_W[i * 3 + 2] * w[2];
  const T m0 = I_W[0], m1 = I_W[1] + h * L[2], m2 = I_W[2] - h * L[1];
  const T m4 = I_W[3] - h * L[2], m5 = I_W[4], m6 = I_W[5] + h * L[0];
  const T m8 = I_W[6] + h * L[1], m9 = I_W[7] - h * L[0], m10 = I_W[8];
  // (ODE builds I~ as (-[L]x) h + I_W entry by entry; the diagonal's 0 h + I_W is I_W.)
  const double inv_h = 1.0 / h;
  for (T& l : L) l *= inv_h;
  const T det = m0 * (m5 * m10 - m9 * m6) - m1 * (m4 * m10 - m8 * m6) + m2 * (m4 * m9 - m8 * m5);
  // det(I_W - h [L]x) >= det(I_W) > 0 for an inertia (positive definite) and any L: ODE's test for
  // 0 never fails for a body with mass, so the lanes skip it (and a scalar 0 leaves no moment)
  for (T& tau : out.tau_gyro_W) tau = T{};
  if (!kScalar || AnyNonZero(det)) {
    const T d = 1.0 / det;
    const T inv[9] = {(m5 * m10 - m6 * m9) * d, (m9 * m2 - m1 * m10) * d, (m1 * m6 - m5 * m2) * d,
                      (m6 * m8 - m4 * m10) * d, (m0 * m10 - m8 * m2) * d, (m4 * m2 - m0 * m6) * d,
                      (m4 * m9 - m8 * m5) * d,  (m8 * m1 - m0 * m9) * d,  (m0 * m5 - m1 * m4) * d};
    for (int i = 0; i < 3; ++i) {  // row i of M = I_W I~^-1 - 1, then tau_i = M_i . L
      T M_i[3];
      for (int j = 0; j < 3; ++j)
        M_i[j] = I_W[i * 3 + 0] * inv[0 * 3 + j] + I_W[i * 3 + 1] * inv[1 * 3 + j] + I_W[i * 3 + 2] * inv[2 * 3 + j];
      M_i[i] -= 1.0;
      out.tau_gyro_W[i] = M_i[0] * L[0] + M_i[1] * L[1] + M_i[2] * L[2];
    }
  }
  return out;
}

/// The second half: advances `s` by h under the force F_W (gravity included) and torque T_W about
/// the CoG, with the terms FreeBodyTermsOf computed from `s` as it is.
template <class T, class S>
inline void StepFreeBody(double h, const FreeBodyInertiaT<S>& body, const T F_W[3], const T T_W_in[3],
                         const FreeBodyStateTerms<T>& terms, FreeBodyStateT<T>& s) {
  constexpr bool kScalar = std::is_same_v<T, double>;
  const T* w = s.omega_W;
  const T* inv_I_W = terms.inv_I_W;
  // (with det 0 ODE adds no gyroscopic moment; a + 0 is a, so adding the zero is the same)
  const T T_W[3] = {T_W_in[0] + terms.tau_gyro_W[0], T_W_in[1] + terms.tau_gyro_W[1], T_W_in[2] + terms.tau_gyro_W[2]};

  // v += h/m F;  w += I_W^-1 (h T)
  const S s_lin = h * body.inv_mass_kg;
  for (int i = 0; i < 3; ++i) s.v_W[i] = s.v_W[i] + s_lin * F_W[i];
  const T a[3] = {T_W[0] * h, T_W[1] * h, T_W[2] * h};
  T dw[3];
  for (int i = 0; i < 3; ++i) dw[i] = inv_I_W[i * 3 + 0] * a[0] + inv_I_W[i * 3 + 1] * a[1] + inv_I_W[i * 3 + 2] * a[2];
  for (int i = 0; i < 3; ++i) s.omega_W[i] = s.omega_W[i] + dw[i];

  // p += h v (the new v);  q += h/2 (0, w) q (the new w, world frame), normalised;  R from q
  for (int i = 0; i < 3; ++i) s.p_W[i] += h * s.v_W[i];
  T* q = s.q_WB;
  const T dq[4] = {0.5 * (-w[0] * q[1] - w[1] * q[2] - w[2] * q[3]), 0.5 * (w[0] * q[0] + w[1] * q[3] - w[2] * q[2]),
                   0.5 * (-w[0] * q[3] + w[1] * q[0] + w[2] * q[1]), 0.5 * (w[0] * q[2] - w[1] * q[1] + w[2] * q[0])};
  for (int j = 0; j < 4; ++j) q[j] += h * dq[j];
  T l = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
  if constexpr (kScalar) {
    if (l > 0) {
      l = 1.0 / std::sqrt(l);
      for (int j = 0; j < 4; ++j) q[j] *= l;
    } else {
      q[0] = 1;
      q[1] = q[2] = q[3] = 0;
    }
  } else {  // a unit quaternion advanced by a step: never 0
    // lane by lane through an array, which the compiler turns into one vector square root where the
    // lanes' instruction set has one (and math errno is off, as in the batch's kernels)
    double lanes[sizeof(T) / sizeof(double)];
    std::memcpy(lanes, &l, sizeof(T));
    for (double& x : lanes) x = 1.0 / std::sqrt(x);
    std::memcpy(&l, lanes, sizeof(T));
    for (int j = 0; j < 4; ++j) q[j] *= l;
  }
  RotationFromQuaternion(q, s.R_WB);
}

/// Advances `s` by h under the force F_W (gravity included) and torque T_W about the CoG.
template <class T, class S>
inline void StepFreeBody(double h, const FreeBodyInertiaT<S>& body, const T F_W[3], const T T_W_in[3],
                         FreeBodyStateT<T>& s) {
  StepFreeBody(h, body, F_W, T_W_in, FreeBodyTermsOf(h, body, s), s);
}

}  // namespace physics
}  // namespace rotors_sim
