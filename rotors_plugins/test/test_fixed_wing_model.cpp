// RotorS' fixed-wing model with the techpod's coefficients, against hand computations
// (rotors_fixed_wing_and_more.md section 1.3).
#include <cmath>
#include <fstream>
#include <stdexcept>

#include <gtest/gtest.h>

#include "rotors_gazebo_plugins/models/fixed_wing_model.h"

using rotors_gazebo_plugins::FixedWingAeroParams;
using rotors_gazebo_plugins::FixedWingInputs;
using rotors_gazebo_plugins::FixedWingModel;
using rotors_gazebo_plugins::FixedWingVehicleParams;

namespace {
const std::string kDir = std::string(RESOURCE_DIR) + "/fixed_wing/";

FixedWingModel Techpod() {
  return FixedWingModel(FixedWingAeroParams::FromYaml(kDir + "aero_params_techpod.yaml"),
                        FixedWingVehicleParams::FromYaml(kDir + "techpod.yaml"));
}

/// Airspeed V at angle of attack alpha, no sideslip, in FLU (FRD w = V sin(alpha) is -z in FLU).
Eigen::Vector3d Air(double V, double alpha) { return {V * std::cos(alpha), 0.0, -V * std::sin(alpha)}; }

/// RotorS' plugin's constant density, with which its reference trims the techpod (the standard
/// atmosphere's at 380 m); the model takes the density as an input
constexpr double kRho = 1.18;
double QS(double V) { return 0.5 * kRho * V * V * 0.47; }
}  // namespace

TEST(FixedWingModel, LiftEqualsTheTechpodsWeightAtItsTrimAngleOfAttack) {
  const FixedWingModel m = Techpod();
  const double V = 15.0, alpha = 0.0235, weight_N = 2.81 * 9.81;  // the reference's level flight at 15 m/s
  const auto w = m.Compute(Air(V, alpha), Eigen::Vector3d::Zero(), FixedWingInputs{}, kRho);
  // C_L = 0.2127 + 10.806 a - 46.8324 a^2 + 60.6017 a^3
  const double C_L = 0.2127 + 10.806 * alpha - 46.8324 * alpha * alpha + 60.6017 * alpha * alpha * alpha;
  EXPECT_NEAR(w.lift_coefficient, C_L, 1e-12);
  // lift: the force normal to the airspeed in the x-z plane, upward in FLU
  const Eigen::Vector3d lift_dir(std::sin(alpha), 0.0, std::cos(alpha));
  const double lift_N = w.force_B.dot(lift_dir);
  EXPECT_NEAR(lift_N, QS(V) * C_L, 1e-9);
  EXPECT_NEAR(lift_N / weight_N, 1.0, 0.02);
  // drag along -airspeed: C_D = 0.136 - 0.6737 a + 5.4546 a^2
  const double C_D = 0.136 - 0.6737 * alpha + 5.4546 * alpha * alpha;
  EXPECT_NEAR(-w.force_B.dot(Air(1.0, alpha)), QS(V) * C_D, 1e-9);
}

TEST(FixedWingModel, AnAileronStepRollsRightWingDownAtTheRatePredicted) {
  const FixedWingModel m = Techpod();
  const double V = 15.0, b = 2.59;
  FixedWingInputs u;
  u.aileron_left_rad = 0.1;  // left trailing edge down, right up: Delta a = 0.2
  u.aileron_right_rad = -0.1;
  const auto w = m.Compute(Air(V, 0.0), Eigen::Vector3d::Zero(), u, kRho);
  // C_l = 0.0117 Delta a; M_x = qS b C_l, positive in FRD and FLU alike: right wing down
  EXPECT_NEAR(w.moment_B.x(), QS(V) * b * 0.0117 * 0.2, 1e-9);
  EXPECT_GT(w.moment_B.x(), 0.0);
  // the steady roll rate where roll damping cancels it: p = -C_l,da Da 2V / (b C_l,p)
  const double p_ss = -0.0117 * 0.2 * 2.0 * V / (b * -0.1647);
  EXPECT_NEAR(p_ss, 0.16456, 1e-4);
  const auto at_p = m.Compute(Air(V, 0.0), Eigen::Vector3d(p_ss, 0.0, 0.0), u, kRho);
  EXPECT_NEAR(at_p.moment_B.x(), 0.0, 1e-9);
}

TEST(FixedWingModel, ThrottleElevatorRudderAndLowSpeed) {
  const FixedWingModel m = Techpod();
  FixedWingInputs u;
  u.throttle = 1.0;
  const auto thrust = m.Compute(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), u, kRho);
  EXPECT_NEAR(thrust.force_B.x(), 14.7217, 1e-9);  // c_thrust [0, 14.7217, 0], along x
  EXPECT_EQ(thrust.alpha_rad, 0.0);
  EXPECT_TRUE(thrust.moment_B.allFinite());
  // elevator trailing edge down (+): C_m = 0.0435 - 6.1308 de at alpha 0: nose down, i.e. +y in FLU
  FixedWingInputs elevator;
  elevator.elevator_rad = 0.1;
  const auto e = m.Compute(Air(15.0, 0.0), Eigen::Vector3d::Zero(), elevator, kRho);
  EXPECT_NEAR(e.moment_B.y(), -QS(15.0) * 0.18 * (0.0435 - 6.1308 * 0.1), 1e-9);
  // alpha clamped at 0.27
  const auto stall = m.Compute(Air(15.0, 0.6), Eigen::Vector3d::Zero(), FixedWingInputs{}, kRho);
  EXPECT_DOUBLE_EQ(stall.alpha_rad, 0.27);
}

TEST(FixedWingModel, NormalizedCommandsMapByChannelAndBadOnesAreNamed) {
  const FixedWingVehicleParams v = FixedWingVehicleParams::FromYaml(kDir + "techpod.yaml");
  FixedWingInputs u;
  // channels: aileron_right 0, elevator 1, flap 2, rudder 3, aileron_left 4, throttle 5
  EXPECT_EQ(FixedWingInputs::FromNormalized({1.0, -0.5, 0.0, 0.25, -1.0, 0.7}, v, &u), "");
  EXPECT_NEAR(u.aileron_right_rad, 0.349066, 1e-12);
  EXPECT_NEAR(u.elevator_rad, -0.5 * 0.349066, 1e-12);
  EXPECT_NEAR(u.rudder_rad, 0.25 * 0.349066, 1e-12);
  EXPECT_NEAR(u.aileron_left_rad, -0.349066, 1e-12);
  EXPECT_DOUBLE_EQ(u.throttle, 0.7);
  EXPECT_EQ(FixedWingInputs::FromNormalized({0.0, 0.0}, v, &u), "normalized has 2 values, channel 4 is needed");
  EXPECT_EQ(FixedWingInputs::FromNormalized({0, 0, 0, 0, 0, NAN}, v, &u), "normalized has NaN or inf");
}

TEST(FixedWingModel, ParameterFilesWithAMissingKeyOrAShortListAreNamed) {
  const std::string path = ::testing::TempDir() + "/aero_short.yaml";
  std::ofstream(path) << "alpha_max: 0.27\nalpha_min: -0.27\n";
  try {
    FixedWingAeroParams::FromYaml(path);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("missing key 'c_drag_alpha'"), std::string::npos) << e.what();
  }
  FixedWingAeroParams p = FixedWingAeroParams::FromYaml(kDir + "aero_params_techpod.yaml");
  p.c_lift_alpha.resize(2);
  EXPECT_EQ(p.Validate(), "c_lift_alpha needs 4 coefficients, has 2");
  EXPECT_THROW(FixedWingModel(p, FixedWingVehicleParams{}), std::invalid_argument);
}

// Stall as RotorS' model has it: the lift polynomial C_L(alpha) peaks where dC_L/dalpha = 10.806 -
// 93.6648 a + 181.8051 a^2 = 0 (a = 0.1740 rad) and falls beyond it; alpha is clamped at alpha_max
// (0.27 rad), so from there on the lift stays at C_L(alpha_max).
TEST(FixedWingModel, LiftPeaksAtTheStallAngleFallsBeyondItAndIsHeldPastAlphaMax) {
  const FixedWingModel m = Techpod();
  auto C_L = [&](double alpha) {
    return m.Compute(Air(15.0, alpha), Eigen::Vector3d::Zero(), FixedWingInputs{}, kRho).lift_coefficient;
  };
  const double a_stall = (93.6648 - std::sqrt(93.6648 * 93.6648 - 4 * 181.8051 * 10.806)) / (2 * 181.8051);
  EXPECT_NEAR(a_stall, 0.1740, 1e-3);
  EXPECT_GT(C_L(a_stall), C_L(a_stall - 0.02));
  EXPECT_GT(C_L(a_stall), C_L(a_stall + 0.02));
  EXPECT_LT(C_L(0.25), C_L(a_stall) - 0.05);  // past the stall angle the lift falls
  EXPECT_DOUBLE_EQ(C_L(0.40), C_L(0.27));     // clamped at alpha_max
  const auto w = m.Compute(Air(15.0, 0.40), Eigen::Vector3d::Zero(), FixedWingInputs{}, kRho);
  EXPECT_DOUBLE_EQ(w.alpha_rad, 0.27);
}

// A deflection beyond a surface's range and a throttle outside [0, 1] are one line each (RotorS
// flies them unclamped).
TEST(FixedWingModel, DeflectionsOutOfRangeAndThrottleOutsideZeroOneAreNamed) {
  const FixedWingVehicleParams v = FixedWingVehicleParams::FromYaml(kDir + "techpod.yaml");
  FixedWingInputs u;
  EXPECT_EQ(FixedWingInputs::FromNormalized({0.0, 1.5, 0.0, 0.0, 0.0, 0.5}, v, &u),
            "normalized[1] = 1.5 puts the elevator at 0.523599 rad, outside its deflection range [-0.349066, "
            "0.349066] rad (normalized values are -1 .. 1)");
  EXPECT_EQ(FixedWingInputs::FromNormalized({0.0, 0.0, 0.0, 0.0, 0.0, 1.2}, v, &u),
            "normalized[5] = 1.2: the throttle must be in [0, 1]");
  EXPECT_DOUBLE_EQ(u.elevator_rad, 0.0);  // a refused command changes nothing
}
