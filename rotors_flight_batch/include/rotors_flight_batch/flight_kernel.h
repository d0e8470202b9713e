// The physics of one step of the batched flight engine for L vehicles at once: V is a GCC vector of
// L doubles (one lane per vehicle, loaded straight from the structure of arrays), or double for one.
// The same operations in the same order as the full world's plugins and solver (flight_batch.h),
// lane by lane, with no fused multiply-add: every lane equals the scalar step bit for bit. What is
// not the same for every vehicle (controllers, wind draws, sensors) runs in scalar code around it.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>

#include "rotors_core/physics/free_body_step.h"
#include "rotors_core/physics/spin_moment.h"
#include "rotors_flight_batch/group.h"
#include "rotors_flight_batch/lee_lanes.h"
#include "rotors_gazebo_plugins/models/rotor_equations.h"

namespace rotors_flight_batch {

constexpr int kMaxRotors = 16;
constexpr int kMaxContacts = 8;

/// What is the same for every vehicle of a batch, flattened for the kernel. What may differ per
/// vehicle (mass, inertia, the CoG and with it every point in the body frame, the rotors'
/// constants: KernelAirframes) is in KernelArrays.
struct KernelModel {
  struct Rotor {
    double axis_B[3];
    bool cog_on_origin;                        ///< the rotor link's CoG is its origin
    double spin_inertia, direction, slowdown;  ///< J_a; epsilon; the joint turns epsilon omega / slowdown
  };
  /// The same constants as one array over the rotors each, for the kernel that steps one vehicle
  /// with a lane per rotor. Rotors past the last add nothing (zero constants, slowdown 1).
  struct RotorColumns {
    bool every_cog_on_origin = true;  ///< R p_cog_B need not be computed apart
    alignas(32) double axis_B[3][kMaxRotors];
    alignas(32) double spin_inertia[kMaxRotors], direction[kMaxRotors], slowdown[kMaxRotors];
  };
  int rotors = 0, contacts = 0;
  Rotor rotor[kMaxRotors];
  RotorColumns columns;
  double dt = 0, inv_dt = 0, gravity_W[3] = {0, 0, 0};
  bool has_wind = false;  ///< a wind plugin: KernelWind holds its draws (else no wind is read)
  bool wind_before_motors = false;
  bool keep_state_before = false;  ///< write KernelBefore (the IMU measures from it)
};

/// m.columns from m.rotor[0 .. m.rotors - 1] (the rotors past the last add nothing).
void FillRotorColumns(KernelModel& m);

/// Each vehicle's airframe, component k of vehicle i at [k * n + i] as the state: the solver
/// body's mass [kg], 1 / mass, inertia about the CoG and its inverse (9 each, row-major, body
/// frame), the ground contact's spring [N/m] and damper [N s/m]; per rotor (R components each) the
/// motor plugin's constants: C_T, C_D, C_R, -epsilon C_M, omega_max and its first-order filter's
/// factors exp(-dt / tau) up and down; where the rotors sit relative to the CoG, component
/// (c R + r) for axis c of rotor r: the rotor link's origin (its airspeed) and its CoG (where its
/// force acts; the origin's value where the two coincide, so that R p_cog_B is bit for bit R
/// p_origin_B); the collision box's corners, component (3 k + c), and the farthest one's distance.
/// One vehicle's rotor constants and places as one array over the rotors each, for the kernel that
/// steps a lone vehicle with a lane per rotor (contiguous loads, not gathers from the structure of
/// arrays); the same values as KernelAirframes', rotors past the last all zero.
struct RotorColumnsOfOne {
  alignas(64) double motor_constant[kMaxRotors], rotor_drag_coefficient[kMaxRotors];
  alignas(64) double rolling_moment_coefficient[kMaxRotors], reaction_factor[kMaxRotors];
  alignas(64) double max_rot_velocity[kMaxRotors], a_up[kMaxRotors], a_down[kMaxRotors];
  alignas(64) double p_origin_B[3][kMaxRotors], p_cog_B[3][kMaxRotors];
};

struct KernelAirframes {
  const double *mass, *inv_mass, *I_B, *inv_I_B, *contact_k, *contact_c;
  const RotorColumnsOfOne* columns;  ///< per vehicle (n of them)
  const double *p_origin_B, *p_cog_B, *corner_B, *contact_reach_m;
  const double *motor_constant, *rotor_drag_coefficient, *rolling_moment_coefficient, *reaction_factor;
  const double *max_rot_velocity, *a_up, *a_down;
};

/// The batch's arrays, component k of vehicle i at [k * n + i] (n a multiple of the lane count).
struct KernelArrays {
  size_t n;
  double *p_W, *v_W, *q_WB, *R_WB, *omega_W;
  double *omega_rotor, *qdot_applied, *motor_command;
  double* wind_velocity_W;  ///< what the motors see (the wind plugin's last sample)
  KernelAirframes airframe;
};

/// This step's wind of each lane (the scalar pass drew it): force and moment about the CoG, and the
/// new wind speed, [3][L] each.
struct KernelWind {
  const double *force_W, *moment_W, *velocity_W;
};

/// The state before the step, [3][L] / [9][L], for the IMU.
struct KernelBefore {
  double *v_W, *omega_W, *R_WB;
};

namespace kernel_detail {
using rotors_gazebo_plugins::RotorLoads;
using rotors_gazebo_plugins::RotorSpeedStep;
using rotors_sim::physics::SpinMoment;
template <class V>
using Loads = rotors_gazebo_plugins::RotorLoadsT<V>;
/// Lanes of V: 1 for double, the vector's width for a GCC vector of doubles.
template <class V>
struct LaneCount {
  static constexpr size_t value = sizeof(V) / sizeof(double);
};
template <>
struct LaneCount<double> {
  static constexpr size_t value = 1;
};
template <class V>
inline V Load(const double* p) {
  V v;
  std::memcpy(&v, p, sizeof(V));
  return v;
}
template <class V>
inline void Store(double* p, const V& v) {
  std::memcpy(p, &v, sizeof(V));
}
template <class V>
inline V Splat(double x) {
  V v = {};
  return v + x;
}
template <class V>
inline void Cross(const V a[3], const V b[3], V out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}
/// out = R v for a body-frame vector (the same in every lane, S = double, or a lane's own)
template <class V, class S>
inline void Rotate(const V R[9], const S v[3], V out[3]) {
  for (int k = 0; k < 3; ++k) out[k] = R[k * 3 + 0] * v[0] + R[k * 3 + 1] * v[1] + R[k * 3 + 2] * v[2];
}
using rotors_control::law::Any;  // whether any lane of a mask is set (a bool: itself)
inline bool Lane(bool m, size_t) { return m; }
inline bool Lane(int m, size_t) { return m != 0; }
template <class M>
inline bool Lane(const M& m, size_t l) {
  return m[l] != 0;
}
inline double Hypot(double x, double y) { return std::hypot(x, y); }
template <class V>
inline V Hypot(const V& x, const V& y) {
  V r;
  for (size_t k = 0; k < sizeof(V) / sizeof(double); ++k) r[k] = std::hypot(x[k], y[k]);
  return r;
}
/// {x[(r0 + l) n + i] for the lanes l < count, 0 for the rest}
template <class V>
inline V Gather(const double* x, int r0, int count, size_t n, size_t i) {
  auto at = [&](int l) { return l < count ? x[(r0 + l) * n + i] : 0.0; };
  if constexpr (LaneCount<V>::value == 8) {
    return V{at(0), at(1), at(2), at(3), at(4), at(5), at(6), at(7)};
  } else if constexpr (LaneCount<V>::value == 4) {
    return V{at(0), at(1), at(2), at(3)};
  } else {
    static_assert(LaneCount<V>::value == 2, "rotor lanes are AVX-512's eight, AVX2's four or SSE2's two");
    return V{at(0), at(1)};
  }
}
}  // namespace kernel_detail

/// Each rotor's share of one vehicle's step, computed with a lane per rotor (RotorLanes): the
/// motor plugin's force and moment (eqs. 1-5) and the joint's spin moment, [3][kMaxRotors] each.
struct RotorTerms {
  alignas(32) double force_W[3][kMaxRotors], moment_W[3][kMaxRotors], spin_moment_W[3][kMaxRotors];
};

/// The body's state before the step, one vehicle (the input of RotorLanes).
struct OneBody {
  const double *R_WB, *v_W, *omega_W, *wind_velocity_W;
};

/// The motor plugins of vehicle i with a lane per rotor (V a GCC vector of doubles): each rotor's
/// terms, its new speed (omega_rotor) and its joint speed (qdot_applied). The same operations per
/// rotor as StepLanesStrided's per vehicle, so the sums of the terms in rotor order are its F and T
/// bit for bit.
template <class V>
__attribute__((always_inline)) inline void RotorLanes(const KernelModel& m, const KernelArrays& a, size_t i,
                                                      const OneBody& b, RotorTerms& out) {
  using namespace kernel_detail;
  constexpr int L = static_cast<int>(LaneCount<V>::value);
  const KernelModel::RotorColumns& k = m.columns;
  const RotorColumnsOfOne& own = a.airframe.columns[i];
  const size_t n = a.n;
  // the body's state and the model's scalars in locals: the stores below may alias them, and every
  // group of rotors would read them again
  double R[9], w[3], v_W[3], wind_W[3];
  std::memcpy(R, b.R_WB, sizeof(R));
  std::memcpy(w, b.omega_W, sizeof(w));
  std::memcpy(v_W, b.v_W, sizeof(v_W));
  std::memcpy(wind_W, b.wind_velocity_W, sizeof(wind_W));
  const int rotors = m.rotors;
  const double inv_dt = m.inv_dt;
  const bool every_cog_on_origin = k.every_cog_on_origin;
  for (int r0 = 0; r0 < rotors; r0 += L) {
    const int count = rotors - r0 < L ? rotors - r0 : L;
    V ax[3], r_o[3], r_c[3];
    {
      V axis_B[3], p_o_B[3], p_c_B[3];
      for (int c = 0; c < 3; ++c) {
        axis_B[c] = Load<V>(&k.axis_B[c][r0]);
        p_o_B[c] = Load<V>(&own.p_origin_B[c][r0]);
        p_c_B[c] = every_cog_on_origin ? p_o_B[c] : Load<V>(&own.p_cog_B[c][r0]);
      }
      for (int c = 0; c < 3; ++c) {  // R v, as Rotate (a product of doubles is commutative)
        ax[c] = R[c * 3 + 0] * axis_B[0] + R[c * 3 + 1] * axis_B[1] + R[c * 3 + 2] * axis_B[2];
        r_o[c] = R[c * 3 + 0] * p_o_B[0] + R[c * 3 + 1] * p_o_B[1] + R[c * 3 + 2] * p_o_B[2];
        r_c[c] =
            every_cog_on_origin ? r_o[c] : R[c * 3 + 0] * p_c_B[0] + R[c * 3 + 1] * p_c_B[1] + R[c * 3 + 2] * p_c_B[2];
      }
    }
    // the rotors' columns of vehicle i, built in registers (lane by lane through memory would stall
    // on store forwarding)
    const V omega = Gather<V>(a.omega_rotor, r0, count, n, i);
    const V cmd = Gather<V>(a.motor_command, r0, count, n, i);
    const V qdot_before = Gather<V>(a.qdot_applied, r0, count, n, i);
    const V w_x_r[3] = {w[1] * r_o[2] - w[2] * r_o[1], w[2] * r_o[0] - w[0] * r_o[2], w[0] * r_o[1] - w[1] * r_o[0]};
    V air[3];
    for (int c = 0; c < 3; ++c) air[c] = v_W[c] + w_x_r[c] - wind_W[c];
    const Loads<V> loads =
        RotorLoads(omega, ax, air, Load<V>(&own.motor_constant[r0]), Load<V>(&own.rotor_drag_coefficient[r0]),
                   Load<V>(&own.rolling_moment_coefficient[r0]), Load<V>(&own.reaction_factor[r0]));
    V f[3];
    for (int c = 0; c < 3; ++c) f[c] = loads.thrust_F[c] + loads.drag_F[c];
    V torque[3];
    Cross(r_c, f, torque);
#pragma GCC unroll 3
    for (int c = 0; c < 3; ++c) {
      Store(&out.force_W[c][r0], f[c]);
      Store(&out.moment_W[c][r0], torque[c] + loads.reaction_moment_F[c] + loads.rolling_moment_F[c]);
    }
    // the speed dynamics, as StepLanesStrided
    const V y = RotorSpeedStep(omega, cmd, Load<V>(&own.max_rot_velocity[r0]), Load<V>(&own.a_up[r0]),
                               Load<V>(&own.a_down[r0]));
    const V qdot = Load<V>(&k.direction[r0]) * y / Load<V>(&k.slowdown[r0]);
    V spin_moment[3];
    SpinMoment(ax, Load<V>(&k.spin_inertia[r0]), qdot, qdot_before, inv_dt, w, spin_moment);
#pragma GCC unroll 3
    for (int c = 0; c < 3; ++c) Store(&out.spin_moment_W[c][r0], spin_moment[c]);
    for (int l = 0; l < count; ++l) {
      a.omega_rotor[(r0 + l) * n + i] = y[l];
      a.qdot_applied[(r0 + l) * n + i] = qdot[l];
    }
  }
}

/// One physics step of lanes i0 .. i0 + L - 1; returns a contact mask bit per lane. The wind and
/// state-before buffers hold rows of Stride lanes (this call's first). With V = double and a lane
/// type RotorV, the vehicle's rotors are stepped by RotorLanes<RotorV>, a lane per rotor, and summed
/// here in rotor order: the same step bit for bit. (RotorV also keeps the instantiations of each
/// instruction set's file apart: none of them stands in for a baseline one.)
template <class V, size_t Stride, class RotorV = void>
inline unsigned StepLanesStrided(const KernelModel& m, const KernelArrays& a, size_t i0, const KernelWind& wind,
                                 const KernelBefore& before) {
  using namespace kernel_detail;
  constexpr size_t L = LaneCount<V>::value;
  static_assert(Stride >= L, "a row holds at least the call's lanes");
  const size_t n = a.n;
  rotors_sim::physics::FreeBodyStateT<V> s;
  for (int c = 0; c < 3; ++c) {
    s.p_W[c] = Load<V>(&a.p_W[c * n + i0]);
    s.v_W[c] = Load<V>(&a.v_W[c * n + i0]);
    s.omega_W[c] = Load<V>(&a.omega_W[c * n + i0]);
  }
  for (int c = 0; c < 4; ++c) s.q_WB[c] = Load<V>(&a.q_WB[c * n + i0]);
  for (int c = 0; c < 9; ++c) s.R_WB[c] = Load<V>(&a.R_WB[c * n + i0]);
  const V* R = s.R_WB;
  const V* w = s.omega_W;
  const KernelAirframes& af = a.airframe;
  rotors_sim::physics::FreeBodyInertiaT<V> body;
  body.inv_mass_kg = Load<V>(&af.inv_mass[i0]);
  for (int c = 0; c < 9; ++c) {
    body.I_B[c] = Load<V>(&af.I_B[c * n + i0]);
    body.inv_I_B[c] = Load<V>(&af.inv_I_B[c * n + i0]);
  }
  // the free-body step's half that needs no force, first: the core runs its chain (a division) while
  // it steps the rotors
  const rotors_sim::physics::FreeBodyStateTerms<V> body_terms = rotors_sim::physics::FreeBodyTermsOf(m.dt, body, s);
  V F[3] = {}, T[3] = {};
  V wind_v[3] = {};
  for (int c = 0; c < 3 && m.has_wind; ++c)
    wind_v[c] = m.wind_before_motors ? Load<V>(&wind.velocity_W[c * Stride]) : Load<V>(&a.wind_velocity_W[c * n + i0]);
  auto add_wind = [&] {
    for (int c = 0; c < 3 && m.has_wind; ++c) {
      F[c] += Load<V>(&wind.force_W[c * Stride]);
      T[c] += Load<V>(&wind.moment_W[c * Stride]);
    }
  };
  if (m.wind_before_motors) add_wind();

  // the motor plugins (RotorLoads from the speed of the last step, then RotorSpeedStep) and the
  // rotors' spin moments (kinematic joints, SpinMoment)
  V axis_W[kMaxRotors][3], qdot[kMaxRotors];
  RotorTerms terms;
  constexpr bool in_lanes = std::is_same_v<V, double> && !std::is_void_v<RotorV>;  // a lone vehicle only
  if constexpr (in_lanes) {
    RotorLanes<RotorV>(m, a, i0, OneBody{s.R_WB, s.v_W, s.omega_W, wind_v}, terms);
    for (int r = 0; r < m.rotors; ++r)
      for (int c = 0; c < 3; ++c) {
        F[c] += terms.force_W[c][r];
        T[c] += terms.moment_W[c][r];
      }
  }
  for (int r = 0; r < m.rotors && !in_lanes; ++r) {
    const KernelModel::Rotor& p = m.rotor[r];
    V* ax = axis_W[r];
    Rotate(R, p.axis_B, ax);
    V p_o_B[3], r_o[3], w_x_r[3];
    for (int c = 0; c < 3; ++c) p_o_B[c] = Load<V>(&af.p_origin_B[(c * m.rotors + r) * n + i0]);
    Rotate(R, p_o_B, r_o);
    Cross(w, r_o, w_x_r);
    V air[3];
    for (int c = 0; c < 3; ++c) air[c] = s.v_W[c] + w_x_r[c] - wind_v[c];
    const V omega = Load<V>(&a.omega_rotor[r * n + i0]);
    auto constant = [&](const double* x) { return Load<V>(&x[r * n + i0]); };
    const Loads<V> loads = RotorLoads(omega, ax, air, constant(af.motor_constant), constant(af.rotor_drag_coefficient),
                                      constant(af.rolling_moment_coefficient), constant(af.reaction_factor));
    V r_c[3], torque[3], f[3];
    for (int c = 0; c < 3; ++c) f[c] = loads.thrust_F[c] + loads.drag_F[c];
    if (p.cog_on_origin) {
      for (int c = 0; c < 3; ++c) r_c[c] = r_o[c];
    } else {
      V p_c_B[3];
      for (int c = 0; c < 3; ++c) p_c_B[c] = Load<V>(&af.p_cog_B[(c * m.rotors + r) * n + i0]);
      Rotate(R, p_c_B, r_c);
    }
    Cross(r_c, f, torque);
    for (int c = 0; c < 3; ++c) {
      F[c] += f[c];
      T[c] += torque[c] + loads.reaction_moment_F[c] + loads.rolling_moment_F[c];
    }
    const V y = RotorSpeedStep(omega, Load<V>(&a.motor_command[r * n + i0]), constant(af.max_rot_velocity),
                               constant(af.a_up), constant(af.a_down));
    Store(&a.omega_rotor[r * n + i0], y);
    qdot[r] = p.direction * y / p.slowdown;
  }
  if (!m.wind_before_motors) add_wind();
  for (int c = 0; c < 3 && m.has_wind; ++c)
    Store(&a.wind_velocity_W[c * n + i0], Load<V>(&wind.velocity_W[c * Stride]));

  for (int r = 0; r < m.rotors; ++r) {
    const double J = m.rotor[r].spin_inertia;
    if (in_lanes) {
      if (J > 0.0)
        for (int c = 0; c < 3; ++c) T[c] += terms.spin_moment_W[c][r];
      continue;
    }
    const V qdot_before = Load<V>(&a.qdot_applied[r * n + i0]);
    if (J > 0.0) {
      V spin_moment[3];
      rotors_sim::physics::SpinMoment(axis_W[r], J, qdot[r], qdot_before, m.inv_dt, w, spin_moment);
      for (int c = 0; c < 3; ++c) T[c] += spin_moment[c];
    }
    Store(&a.qdot_applied[r * n + i0], qdot[r]);
  }

  // ground contact: a spring and damper at each corner below z = 0, friction limited to the normal force
  unsigned touching = 0;
  if (Any(s.p_W[2] <= Load<V>(&af.contact_reach_m[i0]))) {
    const V zero = {};
    const V contact_k = Load<V>(&af.contact_k[i0]), contact_c = Load<V>(&af.contact_c[i0]);
    for (int k = 0; k < m.contacts; ++k) {
      V corner_B[3], r_k[3];
      for (int c = 0; c < 3; ++c) corner_B[c] = Load<V>(&af.corner_B[(3 * k + c) * n + i0]);
      Rotate(R, corner_B, r_k);
      const V depth = -(s.p_W[2] + r_k[2]);
      if (!Any(depth > zero)) continue;
      V w_x_r[3];
      Cross(w, r_k, w_x_r);
      const V v_k[3] = {s.v_W[0] + w_x_r[0], s.v_W[1] + w_x_r[1], s.v_W[2] + w_x_r[2]};
      const V normal = contact_k * depth - contact_c * v_k[2];
      const auto on = (depth > zero) & (normal > zero);
      V f[3] = {-contact_c * v_k[0], -contact_c * v_k[1], normal};
      const V tangential = Hypot(f[0], f[1]);
      const auto slip = tangential > normal;
      for (int c = 0; c < 2; ++c) f[c] = slip ? f[c] * (normal / tangential) : f[c];
      for (int c = 0; c < 3; ++c) f[c] = on ? f[c] : zero;
      V torque[3];
      Cross(r_k, f, torque);
      for (int c = 0; c < 3; ++c) {
        F[c] += f[c];
        T[c] += torque[c];
      }
      for (size_t l = 0; l < L; ++l)
        if (Lane(on, l)) touching |= 1u << l;
    }
  }

  // gravity, added by the solver after the plugins' forces
  const V mass = Load<V>(&af.mass[i0]);
  for (int c = 0; c < 3; ++c)
    if (m.gravity_W[c] != 0.0) F[c] += mass * m.gravity_W[c];

  if (m.keep_state_before) {
    for (int c = 0; c < 3; ++c) {
      Store(&before.v_W[c * Stride], s.v_W[c]);
      Store(&before.omega_W[c * Stride], s.omega_W[c]);
    }
    for (int c = 0; c < 9; ++c) Store(&before.R_WB[c * Stride], s.R_WB[c]);
  }
  rotors_sim::physics::StepFreeBody(m.dt, body, F, T, body_terms, s);
  for (int c = 0; c < 3; ++c) {
    Store(&a.p_W[c * n + i0], s.p_W[c]);
    Store(&a.v_W[c * n + i0], s.v_W[c]);
    Store(&a.omega_W[c * n + i0], s.omega_W[c]);
  }
  for (int c = 0; c < 4; ++c) Store(&a.q_WB[c * n + i0], s.q_WB[c]);
  for (int c = 0; c < 9; ++c) Store(&a.R_WB[c * n + i0], s.R_WB[c]);
  return touching;
}

template <class V>
inline unsigned StepLanes(const KernelModel& m, const KernelArrays& a, size_t i0, const KernelWind& wind,
                          const KernelBefore& before) {
  return StepLanesStrided<V, kernel_detail::LaneCount<V>::value>(m, a, i0, wind, before);
}

/// The group of vehicles i0 .. i0 + kGroupLanes - 1 in lanes of V, one run of lanes after the other
/// (each lane reads its row's column, so every lane's step is the same whatever V is).
template <class V>
inline unsigned StepGroupIn(const KernelModel& m, const KernelArrays& a, size_t i0, const KernelWind& wind,
                            const KernelBefore& before) {
  constexpr size_t L = kernel_detail::LaneCount<V>::value;
  static_assert(kGroupLanes % L == 0, "a group is whole runs of lanes");
  unsigned touching = 0;
  for (size_t h = 0; h < kGroupLanes; h += L) {
    const KernelWind w{wind.force_W + h, wind.moment_W + h, wind.velocity_W + h};
    const KernelBefore b{before.v_W + h, before.omega_W + h, before.R_WB + h};
    touching |= StepLanesStrided<V, kGroupLanes>(m, a, i0 + h, w, b) << h;
  }
  return touching;
}

/// StepGroupIn as compiled for one instruction set (the wind and state-before buffers hold rows of
/// kGroupLanes lanes).
using StepGroupFn = unsigned (*)(const KernelModel&, const KernelArrays&, size_t, const KernelWind&,
                                 const KernelBefore&);

/// One vehicle in column `lane` of rows of kGroupLanes (a batch's last, incomplete group).
using StepOneFn = unsigned (*)(const KernelModel&, const KernelArrays&, size_t, const KernelWind&, const KernelBefore&);

/// A lone vehicle with its rotors in lanes of V (compiled for V's instruction set, RotorLanes inlined).
template <class V>
inline unsigned StepOneWithRotorLanes(const KernelModel& m, const KernelArrays& a, size_t i, const KernelWind& wind,
                                      const KernelBefore& before) {
  return StepLanesStrided<double, kGroupLanes, V>(m, a, i, wind, before);
}

/// The kernels a batch steps with: a group of vehicles at once, a vehicle alone (its rotors in
/// lanes), and a group's Lee controllers in lanes (their constants packed for them first).
struct Kernels {
  const char* instruction_set;  ///< "avx512", "avx2", "sse2" (x86-64), "neon" (arm64) or "scalar"
  StepGroupFn group;
  StepOneFn one_vehicle;
  PackLeeGroupFn pack_lee;
  LeeGroupFn lee_group;
};

/// The kernels with lanes of V (each instruction set's file instantiates them for its own lane type,
/// as a constant: no code compiled for that set runs before ChooseKernels has checked the CPU).
template <class V>
constexpr Kernels KernelsIn(const char* instruction_set) {
  return {instruction_set, &StepGroupIn<V>, &StepOneWithRotorLanes<V>, &PackLeeGroupIn<V>, &LeeGroupIn<V>};
}

/// The kernels for `instruction_set`. On x86-64: "avx512" (eight vehicles, or a lone vehicle's
/// rotors, in eight AVX-512 lanes; the CPU must have AVX-512F), "avx2" (four AVX2 lanes; the CPU must
/// have them), "sse2" (x86-64's baseline: pairs of lanes); on arm64 "neon" (pairs of lanes);
/// everywhere "scalar" (no lanes), or "" for the fastest this CPU runs. All give the same step bit
/// for bit. SimError for another name, or for a set this CPU lacks.
Kernels ChooseKernels(const std::string& instruction_set);

/// One vehicle (a batch's last, incomplete group) in column `lane` of rows of kGroupLanes, by
/// kernels.one_vehicle.
unsigned StepOneOfGroup(const Kernels& kernels, const KernelModel& m, const KernelArrays& a, size_t i, size_t lane,
                        const KernelWind& wind, const KernelBefore& before);

}  // namespace rotors_flight_batch
