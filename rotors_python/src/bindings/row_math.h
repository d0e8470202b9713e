// Row-wise math of the Gymnasium environments, in C++ because numpy's per-call cost dominates at
// a few thousand rows: the environments' observations and rewards call it once per step.
#pragma once

#include <cmath>

namespace rotors_python {

/// out = R(q) v for a unit quaternion q = (x, y, z, w):
///   t = u x v + w v,  R(q) v = v + 2 u x t    (u = (x, y, z))
inline void RotateXyzw(const double* q_xyzw, const double* v, double* out) {
  const double x = q_xyzw[0], y = q_xyzw[1], z = q_xyzw[2], w = q_xyzw[3];
  const double a = v[0], b = v[1], c = v[2];
  const double tx = y * c - z * b + w * a;
  const double ty = z * a - x * c + w * b;
  const double tz = x * b - y * a + w * c;
  out[0] = a + 2.0 * (y * tz - z * ty);
  out[1] = b + 2.0 * (z * tx - x * tz);
  out[2] = c + 2.0 * (x * ty - y * tx);
}

/// |(x, y, z)| = sqrt(x^2 + y^2 + z^2), summed left to right
template <typename T>
inline double Norm3(const T* v) {
  const double x = v[0], y = v[1], z = v[2];
  return std::sqrt(x * x + y * y + z * z);
}

/// The hover task's cost of one observation row (rotors_sim/envs/hover.py: position error 0:3,
/// velocity 3:6, body rates 10:13): c = |e_p| + 0.1 |v| + 0.05 |omega|.
template <class T>
inline double HoverCost(const T* obs) {
  return Norm3(obs) + 0.1 * Norm3(obs + 3) + 0.05 * Norm3(obs + 10);
}

}  // namespace rotors_python
