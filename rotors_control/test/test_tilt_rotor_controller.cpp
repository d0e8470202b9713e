// The omav's allocation and pose controller against hand computations (tilt_rotor_controller.h).
#include <gtest/gtest.h>

#include <cmath>

#include "rotors_control/tilt_rotor_controller.h"

using namespace rotors_control;

namespace {
// omav.yaml (omav.xacro's six tilt units)
TiltRotorControllerParameters Omav() {
  TiltRotorControllerParameters p;
  p.mass_kg = 4.05503;
  p.gravity_m_s2 = 9.8;
  p.inertia_kg_m2 = Eigen::Vector3d(0.0915482, 0.0949826, 0.177223).asDiagonal();
  const double xy_yaw[6][3] = {{0.0, -0.3, 4.71239},     {0.0, 0.3, 1.5708},      {0.2598, 0.15, 0.5236},
                               {-0.2598, -0.15, 3.6652}, {0.2598, -0.15, 5.7596}, {-0.2598, 0.15, 2.6180}};
  const int upper[6] = {1, -1, 1, -1, -1, 1};
  for (int i = 0; i < 6; ++i) {
    TiltRotorArm a;
    a.position_B = {xy_yaw[i][0], xy_yaw[i][1], 0.0};
    a.yaw_rad = xy_yaw[i][2];
    a.rotor_force_constant = 7.2e-6;
    a.upper_moment_constant = 0.015;
    a.lower_moment_constant = 0.005;
    a.upper_direction = upper[i];
    a.max_rot_velocity_rad_s = 1700.0;
    p.arms.push_back(a);
  }
  return p;
}
}  // namespace

// Level hover: every arm level, every rotor at sqrt(m g / (12 k_F)) = 676.2 rad/s.
TEST(TiltRotorAllocation, HoverIsTwelveEqualRotorsWithLevelArms) {
  const TiltRotorControllerParameters p = Omav();
  TiltRotorAllocation allocation(p.arms);
  Eigen::Matrix<double, 6, 1> w;
  w << 0, 0, p.mass_kg * p.gravity_m_s2, 0, 0, 0;
  const Eigen::VectorXd cmd = allocation.Command(w);
  ASSERT_EQ(cmd.size(), 18);
  const double omega = std::sqrt(p.mass_kg * p.gravity_m_s2 / (12 * 7.2e-6));
  for (int i = 0; i < 12; ++i) EXPECT_NEAR(cmd(i), omega, 1e-6) << i;
  for (int i = 12; i < 18; ++i) EXPECT_NEAR(cmd(i), 0.0, 1e-9) << i;
}

// Full rank: any wrench within the limits is made exactly (forward model of the command = wrench),
// a pure side force included (the body stays level and pushes sideways with tilted arms).
TEST(TiltRotorAllocation, EveryWrenchIsMadeExactly) {
  TiltRotorAllocation allocation(Omav().arms);
  Eigen::FullPivLU<Eigen::MatrixXd> lu(allocation.Matrix());
  EXPECT_EQ(lu.rank(), 6);
  Eigen::Matrix<double, 6, 1> side;
  side << 0, 10.0, 39.7, 0, 0, 0;
  EXPECT_LT((allocation.Wrench(allocation.Command(side)) - side).norm(), 1e-9);
  std::srand(7);
  for (int k = 0; k < 20; ++k) {
    Eigen::Matrix<double, 6, 1> w = Eigen::Matrix<double, 6, 1>::Random();
    w.head<3>() *= 10.0;
    w(2) += 40.0;
    EXPECT_LT((allocation.Wrench(allocation.Command(w)) - w).norm(), 1e-9) << w.transpose();
  }
}

// Rolled 20 degrees and holding position: the body wrench is the weight seen from the body,
// F_B = R^T m g e_z = m g (0, sin 20, cos 20) and no moment; the arms tilt to make it.
TEST(TiltRotorController, RolledTwentyDegreesAtTheSetPointAsksForTheWeightInBodyAxes) {
  const TiltRotorControllerParameters p = Omav();
  TiltRotorController controller(p);
  const double roll = 20.0 * M_PI / 180.0;
  PoseReference reference;
  reference.position_W = {0, 0, 1};
  reference.orientation_W_D = Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
  controller.SetReference(reference);
  VehicleState state;
  state.position_W = reference.position_W;
  state.orientation_W_B = reference.orientation_W_D;
  const Eigen::Matrix<double, 6, 1> w = controller.Wrench(state);
  const double mg = p.mass_kg * p.gravity_m_s2;
  EXPECT_NEAR(w(0), 0.0, 1e-9);
  EXPECT_NEAR(w(1), mg * std::sin(roll), 1e-9);
  EXPECT_NEAR(w(2), mg * std::cos(roll), 1e-9);
  EXPECT_LT(w.tail<3>().norm(), 1e-9);
  const Eigen::VectorXd cmd = controller.Command(state);
  EXPECT_GT(cmd.tail<6>().cwiseAbs().maxCoeff(), 0.1);  // some arms tilted by more than 6 degrees
}

TEST(TiltRotorController, ZerosUntilTheFirstReferenceAndBadParametersNamed) {
  TiltRotorController controller(Omav());
  EXPECT_EQ(controller.Command(VehicleState()), Eigen::VectorXd::Zero(18));
  TiltRotorControllerParameters p = Omav();
  p.arms.resize(2);
  EXPECT_THROW(
      {
        try {
          TiltRotorController bad(p);
        } catch (const std::invalid_argument& e) {
          EXPECT_STREQ(e.what(), "tilt_rotor_configuration has 2 arms; a 6-DoF allocation needs at least 3");
          throw;
        }
      },
      std::invalid_argument);
}
