// RotorS' rotors_control library API (its include/rotors_control/*.h) as a user's code meets it: the
// Firefly defaults, the allocation matrix, the call contract, and rotor speeds that hold a hover.
#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "rotors_control/common.h"
#include "rotors_control/lee_position_controller.h"
#include "rotors_control/roll_pitch_yawrate_thrust_controller.h"

namespace {

using rotors_control::EigenOdometry;

/// Sum of rotor thrusts k_F w^2 [N] and the body torques of the allocation matrix.
Eigen::Vector4d Wrench(const rotors_control::RotorConfiguration& config, const Eigen::VectorXd& w) {
  Eigen::Matrix4Xd A;
  rotors_control::calculateAllocationMatrix(config, &A);
  return A * w.cwiseAbs2();
}

TEST(RotorsControlApi, DefaultsAreTheFirefly) {
  rotors_control::VehicleParameters v;
  EXPECT_DOUBLE_EQ(v.mass_, 1.56779);
  EXPECT_DOUBLE_EQ(v.gravity_, 9.81);
  EXPECT_DOUBLE_EQ(v.inertia_(2, 2), 0.0977);
  ASSERT_EQ(v.rotor_configuration_.rotors.size(), 6u);
  EXPECT_NEAR(v.rotor_configuration_.rotors[0].angle, M_PI / 6.0, 1e-9);
  EXPECT_EQ(v.rotor_configuration_.rotors[0].direction, 1);
  EXPECT_EQ(v.rotor_configuration_.rotors[1].direction, -1);
  rotors_control::LeePositionControllerParameters p;
  EXPECT_TRUE(p.position_gain_.isApprox(Eigen::Vector3d(6, 6, 6)));
  EXPECT_TRUE(p.velocity_gain_.isApprox(Eigen::Vector3d(4.7, 4.7, 4.7)));
  EXPECT_TRUE(p.attitude_gain_.isApprox(Eigen::Vector3d(3, 3, 0.035)));
  EXPECT_TRUE(p.angular_rate_gain_.isApprox(Eigen::Vector3d(0.52, 0.52, 0.025)));
  EXPECT_EQ(p.allocation_matrix_.cols(), 6);
}

TEST(RotorsControlApi, AllocationMatrixColumns) {
  rotors_control::RotorConfiguration config;
  Eigen::Matrix4Xd A;
  rotors_control::calculateAllocationMatrix(config, &A);
  const rotors_control::Rotor& r = config.rotors[1];  // at +y (90 degrees), clockwise
  // a rotor on +y makes a positive roll torque; it makes no pitch torque
  EXPECT_NEAR(A(0, 1), r.arm_length * r.rotor_force_constant, 1e-15);
  EXPECT_NEAR(A(1, 1), 0.0, 1e-15);
  EXPECT_NEAR(A(2, 1), r.rotor_force_constant * r.rotor_moment_constant, 1e-15);  // -d k_F k_M, d = -1
  EXPECT_DOUBLE_EQ(A(3, 1), r.rotor_force_constant);
}

TEST(RotorsControlApi, LeeControllerContractAndHover) {
  rotors_control::LeePositionController lee;
  Eigen::VectorXd w;
  EXPECT_THROW(lee.CalculateRotorVelocities(&w), std::logic_error);
  lee.InitializeParameters();
  EigenOdometry at_set_point(Eigen::Vector3d(0, 0, 1), Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero(),
                             Eigen::Vector3d::Zero());
  lee.SetOdometry(at_set_point);
  lee.CalculateRotorVelocities(&w);
  ASSERT_EQ(w.size(), 6);
  EXPECT_EQ(w.norm(), 0.0);  // no reference yet: the rotors stay stopped
  mav_msgs::EigenTrajectoryPoint hover;
  hover.position_W = {0, 0, 1};
  lee.SetTrajectoryPoint(hover);
  lee.CalculateRotorVelocities(&w);
  // at the set point, level and at rest: thrust m g and no torque
  const Eigen::Vector4d wrench = Wrench(lee.vehicle_parameters_.rotor_configuration_, w);
  EXPECT_NEAR(wrench(3), 1.56779 * 9.81, 1e-9);
  EXPECT_NEAR(wrench.head<3>().norm(), 0.0, 1e-9);
  // 10 cm below the set point it pushes up harder: the position gain
  lee.SetOdometry(EigenOdometry(Eigen::Vector3d(0, 0, 0.9), Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero(),
                                Eigen::Vector3d::Zero()));
  lee.CalculateRotorVelocities(&w);
  EXPECT_NEAR(Wrench(lee.vehicle_parameters_.rotor_configuration_, w)(3), 1.56779 * (9.81 + 6.0 * 0.1 / 1.56779), 1e-9);
}

TEST(RotorsControlApi, ParametersSetBeforeInitializeAreUsed) {
  rotors_control::LeePositionController lee;
  lee.vehicle_parameters_.mass_ = 2.0;
  lee.InitializeParameters();
  mav_msgs::EigenTrajectoryPoint hover;
  lee.SetTrajectoryPoint(hover);
  Eigen::VectorXd w;
  lee.CalculateRotorVelocities(&w);
  EXPECT_NEAR(Wrench(lee.vehicle_parameters_.rotor_configuration_, w)(3), 2.0 * 9.81, 1e-9);
  rotors_control::LeePositionController bad;
  bad.vehicle_parameters_.mass_ = -1.0;
  EXPECT_THROW(bad.InitializeParameters(), std::invalid_argument);
}

TEST(RotorsControlApi, RollPitchYawrateThrustLevelCommandGivesTheThrust) {
  rotors_control::RollPitchYawrateThrustController rpyt;
  rpyt.InitializeParameters();
  rpyt.SetOdometry(EigenOdometry());
  Eigen::VectorXd w;
  rpyt.CalculateRotorVelocities(&w);
  EXPECT_EQ(w.norm(), 0.0);
  rpyt.SetRollPitchYawrateThrust(mav_msgs::EigenRollPitchYawrateThrust(0.0, 0.0, 0.0, Eigen::Vector3d(0, 0, 15.0)));
  rpyt.CalculateRotorVelocities(&w);
  const Eigen::Vector4d wrench = Wrench(rpyt.vehicle_parameters_.rotor_configuration_, w);
  EXPECT_NEAR(wrench(3), 15.0, 1e-9);
  EXPECT_NEAR(wrench.head<3>().norm(), 0.0, 1e-9);
  // a roll command tilts it: a positive roll torque while level
  rpyt.SetRollPitchYawrateThrust(mav_msgs::EigenRollPitchYawrateThrust(0.2, 0.0, 0.0, Eigen::Vector3d(0, 0, 15.0)));
  rpyt.CalculateRotorVelocities(&w);
  EXPECT_GT(Wrench(rpyt.vehicle_parameters_.rotor_configuration_, w)(0), 0.0);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
