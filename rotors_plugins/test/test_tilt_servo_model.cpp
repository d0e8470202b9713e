// The position-controlled motor (omav tilt units) against Gazebo's PID on RotorS' wrapped error.
#include <gtest/gtest.h>

#include <cmath>

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
