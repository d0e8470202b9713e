// The batch's kernels alone (no world, no ROS): every kernel this build's target offers steps the
// same bits as the scalar step, and the step holds a hover and falls as gravity says. Built for the
// host by catkin and for arm64 by make test-arm64 (run under qemu-user there).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "rotors_flight_batch/flight_kernel.h"
#include "rotors_flight_batch/flight_kernel_target.h"
#include "rotors_control/lee_controller.h"
#include "rotors_core/error.h"

namespace rotors_flight_batch {
namespace {

constexpr double kDt = 0.002, kMassKg = 1.56779, kG = 9.81;
constexpr double kMotorConstant = 8.54858e-06;  // the firefly's C_T [N/(rad/s)^2]

/// A hexacopter with the firefly's geometry (arm 0.215 m, rotors 3.7 cm above the CoG, spin
/// inertia on, four ground-contact corners); rotor 2's link has its CoG off its origin unless
/// `rotor2_cog_on_origin`.
KernelModel Hexacopter(bool rotor2_cog_on_origin = false) {
  KernelModel m;
  m.rotors = 6;
  for (int r = 0; r < m.rotors; ++r) {
    KernelModel::Rotor& k = m.rotor[r];
    k.axis_B[0] = k.axis_B[1] = 0.0;
    k.axis_B[2] = 1.0;
    k.direction = r % 2 ? -1.0 : 1.0;
    k.spin_inertia = 1e-5;
    k.slowdown = 10.0;
    k.cog_on_origin = r != 2 || rotor2_cog_on_origin;
  }
  FillRotorColumns(m);
  m.contacts = 4;
  m.dt = kDt;
  m.inv_dt = 1.0 / kDt;
  m.gravity_W[2] = -kG;
  m.keep_state_before = true;
  return m;
}

/// Each vehicle's airframe (structure of arrays, as the batch keeps it): the firefly's numbers (C_T,
/// C_M 0.016, tau 1/80 and 1/40 s, its inertia), vehicle i's mass and motor constants times
/// Scale(i) (1 for all unless `vary`).
struct Airframes {
  size_t n;
  bool vary;
  std::vector<double> mass, inv_mass, I_B, inv_I_B, contact_k, contact_c, p_origin_B, p_cog_B, corner_B, reach;
  std::vector<double> motor_constant, drag, rolling, reaction, max_rot, a_up, a_down;
  std::vector<RotorColumnsOfOne> columns;

  double Scale(size_t i) const { return vary ? 0.85 + 0.3 * static_cast<double>(i % 7) / 6.0 : 1.0; }

  Airframes(const KernelModel& m, size_t count, bool vary_them) : n(count), vary(vary_them) {
    const size_t R = m.rotors;
    for (auto* v : {&mass, &inv_mass, &contact_k, &contact_c, &reach}) v->assign(n, 0.0);
    for (auto* v : {&I_B, &inv_I_B}) v->assign(9 * n, 0.0);
    for (auto* v : {&p_origin_B, &p_cog_B}) v->assign(3 * R * n, 0.0);
    corner_B.assign(3 * kMaxContacts * n, 0.0);
    for (auto* v : {&motor_constant, &drag, &rolling, &reaction, &max_rot, &a_up, &a_down}) v->assign(R * n, 0.0);
    columns.assign(n, RotorColumnsOfOne{});
    const double I[3] = {0.0347563, 0.0458929, 0.0977}, w = 0.3 / kDt;
    for (size_t i = 0; i < n; ++i) {
      const double s = Scale(i), mass_kg = kMassKg * s;
      mass[i] = mass_kg;
      inv_mass[i] = 1.0 / mass_kg;
      contact_k[i] = mass_kg * w * w / 4.0;
      contact_c[i] = mass_kg * w / 2.0;
      for (int k = 0; k < 3; ++k) {
        I_B[k * 4 * n + i] = I[k] * s;
        inv_I_B[k * 4 * n + i] = 1.0 / (I[k] * s);
      }
      for (int c = 0; c < 4; ++c) {
        const double corner[3] = {c % 2 ? 0.2 : -0.2, c / 2 ? 0.2 : -0.2, -0.1};
        for (int k = 0; k < 3; ++k) corner_B[(3 * c + k) * n + i] = corner[k];
      }
      reach[i] = std::sqrt(0.2 * 0.2 * 2 + 0.1 * 0.1);
      RotorColumnsOfOne& own = columns[i];
      for (size_t r = 0; r < R; ++r) {
        const double angle = M_PI / 6.0 + r * M_PI / 3.0;
        const double p[3] = {0.215 * std::cos(angle), 0.215 * std::sin(angle), 0.037};
        for (int c = 0; c < 3; ++c) {
          own.p_origin_B[c][r] = p_origin_B[(c * R + r) * n + i] = p[c];
          own.p_cog_B[c][r] = p_cog_B[(c * R + r) * n + i] = p[c] + (c == 2 && !m.rotor[r].cog_on_origin ? 0.01 : 0.0);
        }
        own.motor_constant[r] = motor_constant[r * n + i] = kMotorConstant * (vary ? 2.0 - s : 1.0);
        own.rotor_drag_coefficient[r] = drag[r * n + i] = 8.06428e-05;
        own.rolling_moment_coefficient[r] = rolling[r * n + i] = 1e-06;
        own.reaction_factor[r] = reaction[r * n + i] = -m.rotor[r].direction * 0.016;
        own.max_rot_velocity[r] = max_rot[r * n + i] = 838.0;
        own.a_up[r] = a_up[r * n + i] = std::exp(-kDt * 80.0);
        own.a_down[r] = a_down[r * n + i] = std::exp(-kDt * 40.0);
      }
    }
  }
  KernelAirframes View() const {
    return {mass.data(),      inv_mass.data(),       I_B.data(),        inv_I_B.data(), contact_k.data(),
            contact_c.data(), columns.data(),        p_origin_B.data(), p_cog_B.data(), corner_B.data(),
            reach.data(),     motor_constant.data(), drag.data(),       rolling.data(), reaction.data(),
            max_rot.data(),   a_up.data(),           a_down.data()};
  }
};

/// The state of n vehicles (structure of arrays, as the batch keeps it), their airframes and buffers.
struct Fleet {
  size_t n;
  Airframes airframes;
  std::vector<double> p, v, q, R, w, omega_rotor, qdot, command, wind_v, before_v, before_w, before_R;
  Fleet(const KernelModel& m, size_t count, unsigned seed, bool vary = true) : n(count), airframes(m, count, vary) {
    p.resize(3 * n), v.resize(3 * n), q.resize(4 * n), R.resize(9 * n), w.resize(3 * n);
    omega_rotor.resize(kMaxRotors * n), qdot.resize(kMaxRotors * n), command.resize(kMaxRotors * n);
    wind_v.assign(3 * n, 0.0), before_v.resize(3 * kGroupLanes), before_w.resize(3 * kGroupLanes),
        before_R.resize(9 * kGroupLanes);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (size_t i = 0; i < n; ++i) {
      double quat[4], norm = 0.0;
      for (double& c : quat) {
        c = u(rng);
        norm += c * c;
      }
      for (int c = 0; c < 4; ++c) q[c * n + i] = quat[c] / std::sqrt(norm);
      double qi[4], Ri[9];
      for (int c = 0; c < 4; ++c) qi[c] = q[c * n + i];
      rotors_sim::physics::RotationFromQuaternion(qi, Ri);
      for (int c = 0; c < 9; ++c) R[c * n + i] = Ri[c];
      for (int c = 0; c < 3; ++c) {
        p[c * n + i] = c == 2 ? 0.05 + 0.3 * (u(rng) + 1.0) : u(rng);  // some start touching the ground
        v[c * n + i] = u(rng);
        w[c * n + i] = 2.0 * u(rng);
      }
      for (int r = 0; r < kMaxRotors; ++r) {
        omega_rotor[r * n + i] = 500.0 + 300.0 * u(rng);
        command[r * n + i] = 500.0 + 400.0 * u(rng);  // some past the maximum, some below 0 after the clamp
      }
    }
  }
  KernelArrays Arrays() {
    return {n,           p.data(),       v.data(),      q.data(),        R.data(), w.data(), omega_rotor.data(),
            qdot.data(), command.data(), wind_v.data(), airframes.View()};
  }
  /// steps every vehicle: groups of kGroupLanes in the kernel's lanes, the rest one by one with the rotors in lanes
  void Step(const Kernels& kernels, const KernelModel& m) {
    const KernelArrays a = Arrays();
    const KernelWind wind{nullptr, nullptr, nullptr};
    const KernelBefore before{before_v.data(), before_w.data(), before_R.data()};
    size_t i = 0;
    for (; i + kGroupLanes <= n; i += kGroupLanes) kernels.group(m, a, i, wind, before);
    for (size_t l = 0; i < n; ++i, ++l) StepOneOfGroup(kernels, m, a, i, l, wind, before);
  }
  bool SameBits(const Fleet& o) const {
    auto same = [](const std::vector<double>& x, const std::vector<double>& y) {
      return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(double)) == 0;
    };
    return same(p, o.p) && same(v, o.v) && same(q, o.q) && same(R, o.R) && same(w, o.w) &&
           same(omega_rotor, o.omega_rotor) && same(qdot, o.qdot);
  }
};

std::vector<std::string> KernelNames() {
  std::vector<std::string> names;
  for (const TargetKernel& k : TargetKernels())
    if (k.cpu_has_it) names.push_back(k.kernels.instruction_set);
  return names;
}

TEST(FlightKernel, EveryKernelOfThisTargetStepsTheScalarBits) {
  const KernelModel m = Hexacopter();
  // 16 vehicles in two groups of eight, 3 alone (a batch's last, incomplete group), each its own airframe
  Fleet scalar(m, 2 * kGroupLanes + 3, 7);
  const Kernels none = ChooseKernels("scalar");
  for (int s = 0; s < 500; ++s) scalar.Step(none, m);
  for (double z : scalar.p) ASSERT_TRUE(std::isfinite(z));
  const std::vector<std::string> names = KernelNames();
  ASSERT_FALSE(names.empty());
  std::string flown;
  for (const std::string& name : names) {
    Fleet lanes(m, 2 * kGroupLanes + 3, 7);
    const Kernels kernels = ChooseKernels(name);
    for (int s = 0; s < 500; ++s) lanes.Step(kernels, m);
    EXPECT_TRUE(lanes.SameBits(scalar)) << "kernel " << name << " differs from the scalar step";
    flown += name + " ";
  }
  std::printf("kernels of %s on this CPU, each equal to the scalar step bit for bit over 500 steps: %s\n", kTargetName,
              flown.c_str());
  EXPECT_EQ(ChooseKernels("").instruction_set, names.front());
}

TEST(FlightKernel, UnknownKernelIsOneLineNamingTheChoices) {
  try {
    ChooseKernels("mmx");
    FAIL() << "no error";
  } catch (const rotors_sim::SimError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("unknown kernel 'mmx'; use "), std::string::npos) << what;
    EXPECT_NE(what.find("scalar"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

/// At omega_h = sqrt(m g / (6 C_T)) on every rotor, level and at rest, the thrust is the weight
/// (eq. 1: F = 6 C_T omega_h^2 = m g) and the reaction moments cancel (eq. 4, three each way); each
/// vehicle with its own mass and C_T at its own omega_h.
TEST(FlightKernel, HoverSpeedHoldsTheBodyStill) {
  const KernelModel m = Hexacopter(true);
  for (const std::string& name : KernelNames()) {
    Fleet f(m, kGroupLanes + 3, 3);  // a group in lanes, three alone
    for (size_t i = 0; i < f.n; ++i) {
      const double omega_h = std::sqrt(f.airframes.mass[i] * kG / (6.0 * f.airframes.motor_constant[i]));
      const double level[4] = {1, 0, 0, 0}, I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
      for (int c = 0; c < 4; ++c) f.q[c * f.n + i] = level[c];
      for (int c = 0; c < 9; ++c) f.R[c * f.n + i] = I3[c];
      for (int c = 0; c < 3; ++c) f.v[c * f.n + i] = f.w[c * f.n + i] = 0.0;
      f.p[0 * f.n + i] = f.p[1 * f.n + i] = 0.0;
      f.p[2 * f.n + i] = 2.0;
      for (int r = 0; r < m.rotors; ++r) {
        f.omega_rotor[r * f.n + i] = f.command[r * f.n + i] = omega_h;
        f.qdot[r * f.n + i] = m.rotor[r].direction * omega_h / m.rotor[r].slowdown;
      }
    }
    const Kernels kernels = ChooseKernels(name);
    for (int s = 0; s < 500; ++s) f.Step(kernels, m);  // 1 s
    for (size_t i = 0; i < f.n; ++i) {
      EXPECT_NEAR(f.p[2 * f.n + i], 2.0, 1e-9) << name;
      EXPECT_NEAR(f.v[2 * f.n + i], 0.0, 1e-9) << name;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(f.w[c * f.n + i], 0.0, 1e-9) << name;
    }
  }
}

/// Rotors stopped, high above the ground: semi-implicit Euler gives v_N = -g N dt and
/// z_N = z_0 - g dt^2 N (N + 1) / 2 exactly (to rounding).
TEST(FlightKernel, StoppedRotorsFallAsGravitySays) {
  const KernelModel m = Hexacopter();
  for (const std::string& name : KernelNames()) {
    Fleet f(m, kGroupLanes + 3, 4);
    for (size_t i = 0; i < f.n; ++i) {
      for (int c = 0; c < 3; ++c) f.v[c * f.n + i] = f.w[c * f.n + i] = 0.0;
      f.p[2 * f.n + i] = 100.0;
      for (int r = 0; r < kMaxRotors; ++r)
        f.omega_rotor[r * f.n + i] = f.command[r * f.n + i] = f.qdot[r * f.n + i] = 0.0;
    }
    const Kernels kernels = ChooseKernels(name);
    const int N = 1000;
    for (int s = 0; s < N; ++s) f.Step(kernels, m);
    for (size_t i = 0; i < f.n; ++i) {
      EXPECT_NEAR(f.v[2 * f.n + i], -kG * N * kDt, 1e-10) << name;
      EXPECT_NEAR(f.p[2 * f.n + i], 100.0 - kG * kDt * kDt * N * (N + 1) / 2.0, 1e-9) << name;
    }
  }
}

/// A hexacopter's Lee controller (the firefly's geometry, rotors limited to 838 rad/s), gains and
/// mass scaled per vehicle; a tilt limit on some.
rotors_control::LeeControllerParameters HexacopterLee(double scale, bool tilt_limit) {
  rotors_control::LeeControllerParameters p;
  p.vehicle.mass_kg = 1.56779 * scale;
  p.vehicle.inertia_kg_m2 = Eigen::Vector3d(0.0347563, 0.0458929, 0.0977).asDiagonal();
  const double angles[6] = {0.52359878, 1.57079633, 2.61799388, -2.61799388, -1.57079633, -0.52359878};
  for (int r = 0; r < 6; ++r) {
    rotors_control::RotorGeometry g;
    g.angle_rad = angles[r];
    g.direction = r % 2 == 0 ? 1 : -1;
    g.max_rot_velocity_rad_s = 838.0;
    p.vehicle.rotors.push_back(g);
  }
  p.position_gain *= scale;
  p.max_tilt_angle_rad = tilt_limit ? 0.6 : 0.0;
  return p;
}

/// Eight vehicles' Lee controllers in each kernel's lanes give each LeeController's rotor speeds bit
/// for bit, over states that reach every branch of the laws: the tilt and thrust limits, a rotor
/// that would need a negative omega^2 (yaw gives way), a failed rotor (yaw released), none.
TEST(FlightKernel, LeeControllersInLanesAreEachVehiclesController) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<rotors_control::LeeController> lee;
  for (size_t l = 0; l < kGroupLanes; ++l) lee.emplace_back(HexacopterLee(1.0 + 0.05 * l, l % 2 == 1));
  ASSERT_TRUE(lee[3].SetRotorSpeedFactor(2, 0.0).empty());  // a failed rotor: yaw released
  ASSERT_TRUE(lee[3].YawReleased());
  LeeConstantsT<double> each[kGroupLanes];
  for (size_t l = 0; l < kGroupLanes; ++l) each[l] = lee[l].Constants();
  int compared = 0, at_zero = 0, at_max = 0;  // the yaw's and the thrust's limits reached
  for (int trial = 0; trial < 200; ++trial) {
    LeeInputsT<double> in[kGroupLanes];
    std::vector<rotors_control::RotorVector> expected;
    for (size_t l = 0; l < kGroupLanes; ++l) {
      rotors_control::TrajectoryPoint point;
      const double far = trial % 3 == 0 ? 20.0 : 1.0;  // far set points saturate tilt and thrust
      point.position_W = {far * u(rng), far * u(rng), far * u(rng)};
      point.yaw_rad = 3.0 * u(rng);
      point.yaw_rate_rad_s = u(rng);
      lee[l].SetTrajectoryPoint(point);
      rotors_control::VehicleState state;
      state.position_W = {u(rng), u(rng), u(rng)};
      state.orientation_W_B = Eigen::Quaterniond(1.0, 0.4 * u(rng), 0.4 * u(rng), u(rng)).normalized();
      state.velocity_B = {2.0 * u(rng), 2.0 * u(rng), u(rng)};
      state.angular_velocity_B = {3.0 * u(rng), 3.0 * u(rng), 5.0 * u(rng)};  // fast yaw: yaw clamps
      in[l] = lee[l].Inputs(state);
      expected.push_back(lee[l].RotorSpeeds(state));
      for (int r = 0; r < 6; ++r) {
        at_zero += expected.back()[r] == 0.0;
        at_max += std::abs(expected.back()[r] - 838.0) < 1e-6;
      }
    }
    for (const std::string& name : KernelNames()) {
      const Kernels kernels = ChooseKernels(name);
      LeeGroupConstants group;
      kernels.pack_lee(each, &group);
      LeeGroupSpeeds omega;
      kernels.lee_group(6, group, in, omega);
      for (size_t l = 0; l < kGroupLanes; ++l)
        for (int r = 0; r < 6; ++r) {
          ASSERT_EQ(std::memcmp(&omega[r][l], &expected[l][r], sizeof(double)), 0)
              << name << ", trial " << trial << ", vehicle " << l << ", rotor " << r << ": " << omega[r][l]
              << " against " << expected[l][r];
          ++compared;
        }
    }
  }
  std::printf(
      "%d rotor speeds of eight Lee controllers in lanes, each equal to its controller's (%d at 0, %d at "
      "omega_max)\n",
      compared, at_zero, at_max);
  EXPECT_GT(at_zero, 0);
  EXPECT_GT(at_max, 0);
}

}  // namespace
}  // namespace rotors_flight_batch
