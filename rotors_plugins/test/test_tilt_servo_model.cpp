// The position-controlled motor (omav tilt units) and the camera gimbal, both Gazebo's PID on
// RotorS' wrapped error.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Geometry>

#include "rotors_gazebo_plugins/models/gimbal_controller.h"
#include "rotors_gazebo_plugins/models/tilt_servo_model.h"

using namespace rotors_gazebo_plugins;

namespace {
TiltServoParams Omav() {  // overactuated_base.xacro's joint_control_pid
  TiltServoParams p;
  p.p = 1.0;
  p.d = 0.01;
  p.i_max = 1.0;
  p.i_min = -1.0;
  p.cmd_max = 2.0;
  p.cmd_min = -2.0;
  return p;
}

/// J theta'' = tau(theta) from theta0 at rest for t_s (semi-implicit Euler, dt 1 ms as the engine).
double Settle(TiltServoModel* servo, double theta0, double theta_ref, double J, double t_s) {
  double theta = theta0, theta_dot = 0.0;
  for (int k = 0; k < static_cast<int>(t_s / 1e-3); ++k) {
    theta_dot += servo->Torque(theta, theta_ref, 1e-3) / J * 1e-3;
    theta += theta_dot * 1e-3;
  }
  return theta;
}
}  // namespace

TEST(TiltServoModel, ErrorIsWrappedToMinusPiPi) {
  EXPECT_NEAR(TiltServoModel::AngleError(0.1, 0.0), 0.1, 1e-12);
  EXPECT_NEAR(TiltServoModel::AngleError(0.1, 2.0 * M_PI - 0.1), 0.2, 1e-12);   // across 0 = 2 pi
  EXPECT_NEAR(TiltServoModel::AngleError(-3.0, 3.0), 2.0 * M_PI - 6.0, 1e-12);  // across pi
  EXPECT_NEAR(TiltServoModel::AngleError(7.0, 7.0 - 4.0 * M_PI), 0.0, 1e-12);
}

TEST(TiltServoModel, TorqueIsMinusPTimesErrorClampedToCmdLimits) {
  TiltServoParams p = Omav();
  p.d = 0.0;
  TiltServoModel servo(p);
  EXPECT_NEAR(servo.Torque(0.5, 0.2, 1e-3), -0.3, 1e-12);  // tau = -p e
  EXPECT_NEAR(servo.Torque(-2.5, 0.0, 1e-3), 2.0, 1e-12);  // p e = -2.5: clamped to cmdMax
}

// The tilt unit (J = 5e-4 kg m^2 with its rotors) settles at the commanded angle, and across pi it
// takes the short way round (the wrapped error), not the 2 pi - 0.28 rad long one.
TEST(TiltServoModel, TiltUnitSettlesAtTheCommandTheShortWayRound) {
  TiltServoModel servo(Omav());
  EXPECT_NEAR(Settle(&servo, 0.0, 0.35, 5e-4, 1.0), 0.35, 1e-4);
  servo.Reset();
  EXPECT_NEAR(Settle(&servo, -3.0, 3.0, 5e-4, 1.0), 3.0 - 2.0 * M_PI, 1e-4);
}

TEST(TiltServoModel, ValidateNamesTheBadGain) {
  TiltServoParams p = Omav();
  p.cmd_min = 3.0;
  EXPECT_NE(p.Validate().find("cmdMin = 3"), std::string::npos);
  p = Omav();
  p.d = -1.0;
  EXPECT_NE(p.Validate().find("must be >= 0"), std::string::npos);
  EXPECT_EQ(Omav().Validate(), "");
}

// The gimbal's Z-X-Y Euler angles: R = R_z(yaw) R_x(roll) R_y(pitch) gives back (yaw, roll, pitch);
// an angle above its command turns its joint back (negative torque), one below forward.
TEST(GimbalController, EulerZXYRoundTripAndTorqueSigns) {
  const Eigen::Vector3d ypr(0.7, -0.3, 1.1);
  const Eigen::Matrix3d R =
      (Eigen::AngleAxisd(ypr.x(), Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(ypr.y(), Eigen::Vector3d::UnitX()) *
       Eigen::AngleAxisd(ypr.z(), Eigen::Vector3d::UnitY()))
          .toRotationMatrix();
  EXPECT_LT((GimbalController::EulerZXY(R) - ypr).norm(), 1e-12);
  GimbalParams p;
  p.yaw = p.roll = p.pitch = Omav();
  GimbalController gimbal(p);
  const Eigen::Vector3d tau = gimbal.Torques(R, Eigen::Vector3d(0.8, -0.3, 1.0), 1e-3);
  EXPECT_GT(tau.x(), 0.0);           // yaw 0.7 below 0.8
  EXPECT_NEAR(tau.y(), 0.0, 1e-12);  // roll on its command
  EXPECT_LT(tau.z(), 0.0);           // pitch 1.1 above 1.0
  p.pitch.cmd_max = -5.0;
  EXPECT_NE(p.Validate().find("pitch_pid: joint_control_pid cmdMin"), std::string::npos);
}
