// The mav_msgs C++ API against hand-computed values: frames, yaw, gravity, conversions.
#include <cmath>
#include <functional>

#include <gtest/gtest.h>
#include <mav_msgs/conversions.h>
#include <mav_msgs/default_topics.h>
#include <mav_msgs/default_values.h>
#include <mav_msgs/eigen_mav_msgs.h>

namespace {

Eigen::Quaterniond FromEuler(double roll, double pitch, double yaw) {
  return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
}

TEST(MavMsgsCommon, GravityInZurichIsNormalGravityByTheFormula) {
  // 9.780327 ((1 + 0.0053024 sin^2(0.8267) - 0.0000058 sin^2(1.6534)) - 3.155e-7 * 405.94), by hand
  const double s = std::sin(0.8267), s2 = std::sin(1.6534);
  EXPECT_NEAR(mav_msgs::kGravity, 9.780327 * (1 + 0.0053024 * s * s - 0.0000058 * s2 * s2 - 3.155e-7 * 405.94), 1e-12);
  EXPECT_NEAR(mav_msgs::kGravity, 9.8066, 5e-4);
  EXPECT_NEAR(mav_msgs::MagnitudeOfGravity(0.0, 0.0), 9.780327, 1e-12);
}

TEST(MavMsgsCommon, YawAndEulerAnglesOfTheZYXConvention) {
  const Eigen::Quaterniond q = FromEuler(0.1, -0.2, 2.5);
  EXPECT_NEAR(mav_msgs::yawFromQuaternion(q), 2.5, 1e-12);
  Eigen::Vector3d rpy;
  mav_msgs::getEulerAnglesFromQuaternion(q, &rpy);
  EXPECT_TRUE(rpy.isApprox(Eigen::Vector3d(0.1, -0.2, 2.5), 1e-12)) << rpy.transpose();
  Eigen::Quaterniond r = q;
  mav_msgs::setQuaternionYaw(-1.0, &r);
  mav_msgs::getEulerAnglesFromQuaternion(r, &rpy);
  EXPECT_TRUE(rpy.isApprox(Eigen::Vector3d(0.1, -0.2, -1.0), 1e-12)) << rpy.transpose();
}

TEST(MavMsgsCommon, SkewVeeAndRotationVectors) {
  const Eigen::Vector3d v(0.3, -0.4, 1.2), u(-2.0, 0.5, 0.7);
  EXPECT_TRUE((mav_msgs::skewMatrixFromVector(v) * u).isApprox(v.cross(u)));
  EXPECT_TRUE(mav_msgs::vectorFromSkewMatrix(mav_msgs::skewMatrixFromVector(v)).isApprox(v));
  Eigen::Matrix3d R;
  mav_msgs::matrixFromRotationVector(Eigen::Vector3d(0.0, 0.0, M_PI / 2), &R);
  EXPECT_TRUE((R * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_TRUE(mav_msgs::isRotationMatrix(R));
  EXPECT_FALSE(mav_msgs::isRotationMatrix(2.0 * R));
  Eigen::Vector3d back;
  mav_msgs::vectorFromRotationMatrix(R, &back);
  EXPECT_TRUE(back.isApprox(Eigen::Vector3d(0.0, 0.0, M_PI / 2)));
}

TEST(MavMsgsCommon, ZeroQuaternionReadsAsIdentity) {
  geometry_msgs::Quaternion zero;
  zero.w = 0.0;
  EXPECT_TRUE(mav_msgs::quaternionFromMsg(zero).isApprox(Eigen::Quaterniond::Identity()));
  geometry_msgs::Quaternion twice;
  twice.w = 2.0;
  EXPECT_NEAR(mav_msgs::quaternionFromMsg(twice).norm(), 1.0, 1e-15);
}

TEST(MavMsgsConversions, OdometryTwistIsBodyFrame) {
  nav_msgs::Odometry msg;
  msg.header.stamp.fromNSec(1234567890ull);
  msg.pose.pose.position.x = 1.0;
  mav_msgs::quaternionEigenToMsg(FromEuler(0, 0, M_PI / 2), &msg.pose.pose.orientation);
  msg.twist.twist.linear.x = 2.0;  // forward in the body, which points along world +y
  msg.pose.covariance[7] = 0.5;    // row 1, column 1
  mav_msgs::EigenOdometry odometry;
  mav_msgs::eigenOdometryFromMsg(msg, &odometry);
  EXPECT_EQ(odometry.timestamp_ns, 1234567890);
  EXPECT_TRUE(odometry.velocity_B.isApprox(Eigen::Vector3d(2, 0, 0)));
  EXPECT_TRUE(odometry.getVelocityWorld().isApprox(Eigen::Vector3d(0, 2, 0), 1e-12));
  EXPECT_EQ(odometry.pose_covariance_(1, 1), 0.5);
  odometry.setVelocityWorld(Eigen::Vector3d(-3, 0, 0));
  EXPECT_TRUE(odometry.velocity_B.isApprox(Eigen::Vector3d(0, 3, 0), 1e-12));
  nav_msgs::Odometry back;
  mav_msgs::msgOdometryFromEigen(odometry, &back);
  EXPECT_EQ(back.header.stamp, msg.header.stamp);
  EXPECT_EQ(back.pose.covariance[7], 0.5);
  EXPECT_NEAR(back.twist.twist.linear.y, 3.0, 1e-12);
}

TEST(MavMsgsConversions, TrajectoryPointRoundTripAndPositionYaw) {
  mav_msgs::EigenTrajectoryPoint p;
  p.time_from_start_ns = 2500000000;
  p.position_W = {1, 2, 3};
  p.velocity_W = {0.1, 0.2, 0.3};
  p.acceleration_W = {-1, 0, 0.5};
  p.setFromYaw(0.7);
  p.setFromYawRate(0.2);
  p.setFromYawAcc(-0.1);
  trajectory_msgs::MultiDOFJointTrajectoryPoint msg;
  mav_msgs::msgMultiDofJointTrajectoryPointFromEigen(p, &msg);
  mav_msgs::EigenTrajectoryPoint q;
  mav_msgs::eigenTrajectoryPointFromMsg(msg, &q);
  EXPECT_TRUE(q.isApprox(p, 1e-12)) << q.toString();
  EXPECT_NEAR(q.getYaw(), 0.7, 1e-12);
  EXPECT_EQ(q.getYawRate(), 0.2);
  EXPECT_EQ(q.getYawAcc(), -0.1);
  EXPECT_TRUE(q.jerk_W.isZero() && q.snap_W.isZero());

  trajectory_msgs::MultiDOFJointTrajectory hover;
  mav_msgs::msgMultiDofJointTrajectoryFromPositionYaw(Eigen::Vector3d(0, 0, 1), M_PI, &hover);
  ASSERT_EQ(hover.points.size(), 1u);
  EXPECT_EQ(hover.joint_names, std::vector<std::string>{"base_link"});
  EXPECT_EQ(hover.points[0].velocities.size(), 1u);
  EXPECT_EQ(hover.points[0].accelerations.size(), 1u);
  EXPECT_EQ(hover.points[0].transforms[0].translation.z, 1.0);
  EXPECT_NEAR(
      std::abs(mav_msgs::yawFromQuaternion(mav_msgs::quaternionFromMsg(hover.points[0].transforms[0].rotation))), M_PI,
      1e-12);

  hover.header.stamp.fromSec(10.0);
  hover.points.push_back(hover.points[0]);
  hover.points[1].time_from_start = ros::Duration(1.5);
  mav_msgs::EigenTrajectoryPointVector points;
  mav_msgs::eigenTrajectoryPointVectorFromMsg(hover, &points);
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[1].timestamp_ns, 11500000000);
}

TEST(MavMsgsConversions, ActuatorsAndCommands) {
  mav_msgs::EigenActuators a(Eigen::Vector3d(1, 2, 3));
  mav_msgs::Actuators msg;
  mav_msgs::msgActuatorsFromEigen(a, &msg);
  EXPECT_EQ(msg.angular_velocities, (std::vector<double>{1, 2, 3}));
  EXPECT_TRUE(msg.angles.empty() && msg.normalized.empty());
  mav_msgs::EigenActuators back;
  mav_msgs::eigenActuatorsFromMsg(msg, &back);
  EXPECT_EQ(back.angular_velocities, a.angular_velocities);

  mav_msgs::RollPitchYawrateThrust rpyt;
  mav_msgs::msgRollPitchYawrateThrustFromEigen(mav_msgs::EigenRollPitchYawrateThrust(0.1, 0.2, 0.3, {0, 0, 15}), &rpyt);
  mav_msgs::EigenRollPitchYawrateThrust e;
  mav_msgs::eigenRollPitchYawrateThrustFromMsg(rpyt, &e);
  EXPECT_EQ(e.pitch, 0.2);
  EXPECT_EQ(e.thrust.z(), 15.0);
  EXPECT_STREQ(mav_msgs::default_topics::COMMAND_ACTUATORS, "command/motor_speed");
  EXPECT_STREQ(mav_msgs::default_topics::GROUND_TRUTH_TWIST, "ground_truth/twist");
}

TEST(MavMsgsCommon, SquaredRotorSpeedsGiveTheRequestedWrench) {
  // a quadrotor in "+" form: arm 0.2 m, k_f 1e-5, k_m 0.02
  const double l = 0.2, k = 1e-5, c = 0.02;
  Eigen::MatrixXd A(4, 4);
  A << 0, l * k, 0, -l * k,  //
      -l * k, 0, l * k, 0,   //
      -k * c, k * c, -k * c, k * c, k, k, k, k;
  const Eigen::MatrixXd A_inv = A.transpose() * (A * A.transpose()).inverse();
  const Eigen::Vector3d J(0.01, 0.02, 0.03), w(0.5, -0.2, 0.1), dw(1.0, 2.0, -1.0);
  Eigen::VectorXd omega2;
  mav_msgs::getSquaredRotorSpeedsFromAllocationAndState(A_inv, J, 1.5, w, dw, Eigen::Vector3d(0, 0, 9.81), &omega2);
  Eigen::Vector4d expected;
  expected << J.asDiagonal() * dw + w.cross(J.asDiagonal() * w), 1.5 * 9.81;  // tau = J dw + w x J w, T = m |a|
  EXPECT_TRUE((A * omega2).isApprox(expected, 1e-9)) << (A * omega2).transpose();
}

}  // namespace

// ---- the helpers of mav_comm's common.h and the flat-state conversion, against finite differences

TEST(MavMsgsCommon, YawMessagesAndNanoseconds) {
  geometry_msgs::Quaternion q;
  mav_msgs::setQuaternionMsgFromYaw(0.7, &q);
  EXPECT_NEAR(q.w, std::cos(0.35), 1e-12);
  EXPECT_NEAR(q.z, std::sin(0.35), 1e-12);
  EXPECT_EQ(q.x, 0.0);
  geometry_msgs::Vector3 w;
  mav_msgs::setAngularVelocityMsgFromYawRate(-0.4, &w);
  EXPECT_EQ(w.x, 0.0);
  EXPECT_EQ(w.y, 0.0);
  EXPECT_EQ(w.z, -0.4);
  EXPECT_DOUBLE_EQ(mav_msgs::nanosecondsToSeconds(1500000000), 1.5);
  EXPECT_EQ(mav_msgs::secondsToNanoseconds(2.25), 2250000000);
  EXPECT_EQ(mav_msgs::secondsToNanoseconds(mav_msgs::nanosecondsToSeconds(123456789)), 123456789);
}

Eigen::Matrix3d Exp(const Eigen::Vector3d& phi) {
  Eigen::Matrix3d R;
  mav_msgs::matrixFromRotationVector(phi, &R);
  return R;
}

/// omega_W = vee(dR/dt R^T) by central differences.
Eigen::Vector3d OmegaWorldNumeric(const std::function<Eigen::Matrix3d(double)>& R, double t, double h = 1e-5) {
  const Eigen::Matrix3d R_dot = (R(t + h) - R(t - h)) / (2.0 * h);
  return mav_msgs::vectorFromSkewMatrix(R_dot * R(t).transpose());
}

TEST(MavMsgsCommon, AngularVelocityAndAccelerationFromARotationVector) {
  const Eigen::Vector3d phi0(0.4, -0.9, 1.3), phi_dot(0.5, 0.2, -0.7), phi_ddot(-0.3, 0.8, 0.1);
  auto phi = [&](double t) -> Eigen::Vector3d { return phi0 + phi_dot * t + 0.5 * phi_ddot * t * t; };
  auto R = [&](double t) { return Exp(phi(t)); };
  for (double t : {0.0, 0.3, 1.0}) {
    const Eigen::Vector3d rate = phi_dot + phi_ddot * t;
    const Eigen::Vector3d omega = mav_msgs::omegaFromRotationVector(phi(t), rate);
    EXPECT_TRUE(omega.isApprox(OmegaWorldNumeric(R, t), 1e-7)) << omega.transpose();
    const double h = 1e-5;
    const Eigen::Vector3d omega_dot_numeric = (mav_msgs::omegaFromRotationVector(phi(t + h), rate + phi_ddot * h) -
                                               mav_msgs::omegaFromRotationVector(phi(t - h), rate - phi_ddot * h)) /
                                              (2.0 * h);
    EXPECT_TRUE(mav_msgs::omegaDotFromRotationVector(phi(t), rate, phi_ddot).isApprox(omega_dot_numeric, 1e-6));
  }
  // no rotation: omega = dphi/dt
  EXPECT_TRUE(mav_msgs::omegaFromRotationVector(Eigen::Vector3d::Zero(), phi_dot).isApprox(phi_dot));
}

TEST(MavMsgsConversions, FlatOutputsGiveTheStateThatFliesThem) {
  // a(t) = a0 + j0 t + s0 t^2 / 2 and psi(t) = psi0 + r t + r' t^2 / 2 (a flat output's derivatives)
  const Eigen::Vector3d a0(1.2, -0.8, 0.9), j0(0.7, 1.1, -0.5), s0(-0.6, 0.4, 0.8);
  const double psi0 = 0.6, r = 0.9, r_dot = -0.5, g = 9.81;
  struct State {
    Eigen::Quaterniond q;
    Eigen::Vector3d f_B, w_B, dw_B;
  };
  auto state = [&](double t) {
    State x;
    mav_msgs::EigenMavStateFromEigenTrajectoryPoint(a0 + j0 * t + 0.5 * s0 * t * t, j0 + s0 * t, s0,
                                                    psi0 + r * t + 0.5 * r_dot * t * t, r + r_dot * t, r_dot, g, &x.q,
                                                    &x.f_B, &x.w_B, &x.dw_B);
    return x;
  };
  for (double t : {0.0, 0.5}) {
    const State x = state(t);
    const Eigen::Matrix3d R = x.q.toRotationMatrix();
    const Eigen::Vector3d a = a0 + j0 * t + 0.5 * s0 * t * t;
    // the thrust is along body z and gives the acceleration; the heading is psi
    EXPECT_TRUE((R * x.f_B).isApprox(a + Eigen::Vector3d(0, 0, g), 1e-12));
    EXPECT_NEAR(x.f_B.x(), 0.0, 1e-12);
    EXPECT_NEAR(x.f_B.y(), 0.0, 1e-12);
    const double psi = psi0 + r * t + 0.5 * r_dot * t * t;
    EXPECT_NEAR(R.col(1).dot(Eigen::Vector3d(std::cos(psi), std::sin(psi), 0.0)), 0.0, 1e-12);
    // body rates against the orientation's derivative, and their derivative
    auto R_of = [&](double tau) { return state(tau).q.toRotationMatrix(); };
    const Eigen::Vector3d w_B_numeric = R.transpose() * OmegaWorldNumeric(R_of, t);
    EXPECT_TRUE(x.w_B.isApprox(w_B_numeric, 1e-6)) << x.w_B.transpose() << " vs " << w_B_numeric.transpose();
    const double h = 1e-5;
    const Eigen::Vector3d dw_numeric = (state(t + h).w_B - state(t - h).w_B) / (2.0 * h);
    EXPECT_TRUE(x.dw_B.isApprox(dw_numeric, 1e-5)) << x.dw_B.transpose() << " vs " << dw_numeric.transpose();
  }
  // the trajectory-point form: a hover point gives level attitude, g along body z, no rates
  mav_msgs::EigenTrajectoryPoint hover;
  hover.position_W = {1, 2, 3};
  hover.setFromYaw(0.3);
  mav_msgs::EigenMavState s;
  mav_msgs::EigenMavStateFromEigenTrajectoryPoint(hover, &s);
  EXPECT_TRUE(s.position_W.isApprox(hover.position_W));
  EXPECT_TRUE(s.orientation_W_B.isApprox(mav_msgs::quaternionFromYaw(0.3), 1e-12));
  EXPECT_NEAR(s.acceleration_B.z(), mav_msgs::kGravity, 1e-12);
  EXPECT_NEAR(s.angular_velocity_B.norm() + s.angular_acceleration_B.norm(), 0.0, 1e-12);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
