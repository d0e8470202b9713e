// Rotor model against book eqs. 1-5 and the first-order speed dynamics.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Geometry>

#include "rotors_gazebo_plugins/models/rotor_model.h"

using namespace rotors_gazebo_plugins;

namespace {
RotorParams Firefly(int direction) {
  RotorParams p;
  p.motor_constant = 8.54858e-6;
  p.moment_constant = 0.016;
  p.rotor_drag_coefficient = 8.06428e-5;
  p.rolling_moment_coefficient = 1e-6;
  p.time_constant_up_s = 0.0125;
  p.time_constant_down_s = 0.025;
  p.max_rot_velocity = 838;
  p.turning_direction = direction;
  return p;
}

RotorModel AtSpeed(const RotorParams& p, double omega) {
  RotorModel m(p);
  for (int i = 0; i < 20000; ++i) m.UpdateSpeed(omega, 1e-3);
  return m;
}
}  // namespace

// tau dy/dt = u - y: 1 - exp(-1) = 63.2 % of a step after one time constant, up and down.
TEST(RotorModel, SpeedStepReaches63PercentAfterTimeConstant) {
  const RotorParams p = Firefly(1);
  const double dt = 1e-4;
  RotorModel up(p);
  for (int i = 0; i < static_cast<int>(std::round(p.time_constant_up_s / dt)); ++i) up.UpdateSpeed(500.0, dt);
  EXPECT_NEAR(up.Omega() / 500.0, 1.0 - std::exp(-1.0), 1e-9);

  RotorModel down = AtSpeed(p, 500.0);
  for (int i = 0; i < static_cast<int>(std::round(p.time_constant_down_s / dt)); ++i) down.UpdateSpeed(0.0, dt);
  EXPECT_NEAR((500.0 - down.Omega()) / 500.0, 1.0 - std::exp(-1.0), 1e-9);

  // the same holds at the simulator's 0.01 s step, sampled at multiples of tau (exact discretisation)
  RotorModel coarse(p);
  coarse.UpdateSpeed(500.0, 0.0125);
  EXPECT_NEAR(coarse.Omega() / 500.0, 1.0 - std::exp(-1.0), 1e-12);
}

TEST(RotorModel, CommandIsClampedToZeroAndMaxSpeed) {
  RotorModel m = AtSpeed(Firefly(1), 2000.0);
  EXPECT_NEAR(m.Omega(), 838.0, 1e-6);
  RotorModel n = AtSpeed(Firefly(1), -100.0);
  EXPECT_EQ(n.Omega(), 0.0);
}

TEST(RotorModel, ThrustAndReactionMomentFollowEquations1And4) {
  for (int eps : {1, -1}) {
    const RotorModel m = AtSpeed(Firefly(eps), 543.3);
    const RotorWrench w = m.ComputeWrench(Eigen::Vector3d::Zero());
    const double thrust = 8.54858e-6 * 543.3 * 543.3;  // eq. 1: omega^2 C_T
    EXPECT_NEAR(w.thrust_R.z(), thrust, 1e-9);
    EXPECT_NEAR(w.thrust_R.head<2>().norm(), 0.0, 1e-15);
    // eq. 4: M_D = -eps C_M F_T : a ccw rotor (eps = +1) turns the body clockwise
    EXPECT_NEAR(w.reaction_moment_R.z(), -eps * 0.016 * thrust, 1e-12);
    EXPECT_NEAR(m.SignedOmega(), eps * 543.3, 1e-6);
    EXPECT_TRUE(w.drag_R.isZero());
  }
}

// The book's firefly (1.54503 kg with its rotors, g 9.8) hovers with 6 rotors at 543.3 rad/s: the
// model's steady thrust there carries the weight (to the 4 digits of the book's speed).
TEST(RotorModel, SixRotorsAtTheBooksHoverSpeedCarryTheFirefly) {
  double total_thrust_N = 0.0;
  for (int i = 0; i < 6; ++i)
    total_thrust_N += AtSpeed(Firefly(i % 2 ? 1 : -1), 543.3).ComputeWrench(Eigen::Vector3d::Zero()).thrust_R.z();
  EXPECT_NEAR(total_thrust_N / (1.54503 * 9.8), 1.0, 2e-4);
  // a rotor commanded 1 % faster gives 2 % more thrust (F ~ omega^2)
  const double F0 = AtSpeed(Firefly(1), 543.3).ComputeWrench(Eigen::Vector3d::Zero()).thrust_R.z();
  const double F1 = AtSpeed(Firefly(1), 543.3 * 1.01).ComputeWrench(Eigen::Vector3d::Zero()).thrust_R.z();
  EXPECT_NEAR(F1 / F0, 1.0201, 1e-9);
}

// eq. 2: F_D = -omega C_D v_perp, eq. 3: M_R = omega C_R v_perp, eq. 5: v_perp = v - (v.e_z) e_z.
TEST(RotorModel, AirspeedInRotorPlaneGivesDragAndRollingMoment) {
  const RotorModel m = AtSpeed(Firefly(1), 500.0);
  const Eigen::Vector3d v_A(3.0, -1.0, 2.0);  // the axial part (2.0) causes neither
  const RotorWrench w = m.ComputeWrench(v_A);
  const Eigen::Vector3d v_perp(3.0, -1.0, 0.0);
  EXPECT_TRUE(w.drag_R.isApprox(-500.0 * 8.06428e-5 * v_perp, 1e-9));
  EXPECT_TRUE(w.rolling_moment_R.isApprox(500.0 * 1e-6 * v_perp, 1e-9));
  EXPECT_NEAR(w.thrust_R.z(), 8.54858e-6 * 500.0 * 500.0, 1e-9);
}

// Wind enters through the airspeed v_A = v - v_wind: a hovering rotor in a 5 m/s wind feels the
// same drag as one flying at -5 m/s in still air.
TEST(RotorModel, WindChangesDragAsEquation2Predicts) {
  const RotorModel m = AtSpeed(Firefly(-1), 543.3);
  const Eigen::Vector3d wind_W(5.0, 0.0, 0.0), v_hub_W = Eigen::Vector3d::Zero();
  const RotorWrench w = m.ComputeWrench(v_hub_W - wind_W);
  EXPECT_NEAR(w.drag_R.x(), 543.3 * 8.06428e-5 * 5.0, 1e-9);  // pushed downwind
  const RotorWrench still = m.ComputeWrench(Eigen::Vector3d(-5.0, 0, 0));
  EXPECT_TRUE(w.drag_R.isApprox(still.drag_R));
}

// One model in any frame: RotorLoads with the axis and airspeed in the world (as the batch calls it)
// is the plugin's rotor-frame wrench rotated into the world, to rounding; and lanes of it (a GCC
// vector, as the batch's kernels) equal the scalar bit for bit.
TEST(RotorModel, TheEquationsGiveTheSameLoadsInAnyFrameAndInLanes) {
  const RotorModel m = AtSpeed(Firefly(-1), 612.0);
  const Eigen::Matrix3d R_WR = (Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()) *
                                Eigen::AngleAxisd(-0.7, Eigen::Vector3d(1, 2, 3).normalized()))
                                   .toRotationMatrix();
  const Eigen::Vector3d v_A_W(2.5, -1.5, 0.8);
  const RotorWrench w_R = m.ComputeWrench(R_WR.transpose() * v_A_W);
  const Eigen::Vector3d e_W = R_WR.col(2);
  const double e[3] = {e_W.x(), e_W.y(), e_W.z()}, v[3] = {v_A_W.x(), v_A_W.y(), v_A_W.z()};
  const RotorParams& p = m.Params();
  const RotorLoadsT<double> l = RotorLoads(m.Omega(), e, v, p.motor_constant, p.rotor_drag_coefficient,
                                           p.rolling_moment_coefficient, m.ReactionFactor());
  EXPECT_TRUE(Eigen::Vector3d(l.thrust_F[0], l.thrust_F[1], l.thrust_F[2]).isApprox(R_WR * w_R.thrust_R, 1e-12));
  EXPECT_TRUE(Eigen::Vector3d(l.drag_F[0], l.drag_F[1], l.drag_F[2]).isApprox(R_WR * w_R.drag_R, 1e-12));
  EXPECT_TRUE(Eigen::Vector3d(l.rolling_moment_F[0], l.rolling_moment_F[1], l.rolling_moment_F[2])
                  .isApprox(R_WR * w_R.rolling_moment_R, 1e-12));
  EXPECT_TRUE(Eigen::Vector3d(l.reaction_moment_F[0], l.reaction_moment_F[1], l.reaction_moment_F[2])
                  .isApprox(R_WR * w_R.reaction_moment_R, 1e-12));

  typedef double Pair __attribute__((vector_size(16)));
  const Pair omega = {m.Omega(), 300.0}, e2[3] = {{e[0], e[0]}, {e[1], e[1]}, {e[2], e[2]}},
             v2[3] = {{v[0], -v[0]}, {v[1], -v[1]}, {v[2], -v[2]}};
  const RotorLoadsT<Pair> lanes = RotorLoads(omega, e2, v2, p.motor_constant, p.rotor_drag_coefficient,
                                             p.rolling_moment_coefficient, m.ReactionFactor());
  const double e_again[3] = {e[0], e[1], e[2]}, v_flipped[3] = {-v[0], -v[1], -v[2]};
  const RotorLoadsT<double> second = RotorLoads(300.0, e_again, v_flipped, p.motor_constant, p.rotor_drag_coefficient,
                                                p.rolling_moment_coefficient, m.ReactionFactor());
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(lanes.drag_F[c][0], l.drag_F[c]);
    EXPECT_EQ(lanes.drag_F[c][1], second.drag_F[c]);
    EXPECT_EQ(lanes.rolling_moment_F[c][1], second.rolling_moment_F[c]);
    EXPECT_EQ(lanes.reaction_moment_F[c][0], l.reaction_moment_F[c]);
  }
  // the speed dynamics in lanes: each lane is RotorModel::UpdateSpeed
  RotorModel a = AtSpeed(Firefly(1), 400.0), b = AtSpeed(Firefly(1), 700.0);
  const double dt = 0.002, a_up = std::exp(-dt / p.time_constant_up_s), a_down = std::exp(-dt / p.time_constant_down_s);
  const Pair y = RotorSpeedStep(Pair{a.Omega(), b.Omega()}, Pair{650.0, -5.0}, Pair{838.0, 838.0}, Pair{a_up, a_up},
                                Pair{a_down, a_down});
  EXPECT_EQ(y[0], a.UpdateSpeed(650.0, dt));
  EXPECT_EQ(y[1], b.UpdateSpeed(-5.0, dt));
}

TEST(RotorModel, ValidateNamesTheBadParameter) {
  RotorParams p = Firefly(1);
  p.time_constant_up_s = -0.01;
  EXPECT_NE(p.Validate().find("timeConstantUp = -0.01 must be > 0 s"), std::string::npos) << p.Validate();
  p = Firefly(1);
  p.motor_constant = 0.0;
  EXPECT_NE(p.Validate().find("motorConstant"), std::string::npos);
  EXPECT_TRUE(Firefly(1).Validate().empty());
}
