// Allocation matrix (book eq. 10-11) for a hexacopter and a quadrotor, and its inverse.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "rotors_control/motor_mixer.h"
#include "test_fixtures.h"

using namespace rotors_control;

TEST(MotorMixer, FireflyAllocationMatchesReferenceNumbers) {
  const Eigen::Matrix4Xd A = AllocationMatrix(FireflyYaml());
  ASSERT_EQ(A.cols(), 6);
  // reference section 7.1 [derived]
  EXPECT_NEAR(A(0, 0), 9.1897e-7, 1e-10);
  EXPECT_NEAR(A(0, 1), 1.8379e-6, 1e-10);
  EXPECT_NEAR(A(1, 0), -1.5917e-6, 1e-10);
  EXPECT_NEAR(A(1, 1), 0.0, 1e-10);
  EXPECT_NEAR(A(2, 0), -1.36777e-7, 1e-11);
  EXPECT_NEAR(A(2, 1), 1.36777e-7, 1e-11);
  EXPECT_NEAR(A(3, 4), 8.54858e-6, 1e-15);
}

TEST(MotorMixer, AllocationTimesMixerIsIdentityForHexaAndQuad) {
  for (const MultirotorParameters& v : {FireflyYaml(), PelicanYaml()}) {
    const MotorMixer mixer(v);
    const Eigen::Matrix4Xd& A = mixer.Allocation();
    // a command that keeps all rotors spinning: alpha and thrust come back through A
    const Eigen::Vector3d alpha(0.3, -0.2, 0.1);
    const double thrust = v.mass_kg * 9.81;
    const Eigen::VectorXd omega = mixer.RotorSpeeds(alpha, thrust);
    ASSERT_GT(omega.minCoeff(), 0.0);
    const Eigen::Vector4d wrench = A * omega.cwiseAbs2();
    EXPECT_TRUE(wrench.head<3>().isApprox(v.inertia_kg_m2 * alpha, 1e-9)) << wrench.transpose();
    EXPECT_NEAR(wrench[3], thrust, 1e-9);
  }
}

TEST(MotorMixer, HoverSpeedsMatchTheReference) {
  // reference section 7.2: firefly 547.6, pelican 495.6 rad/s with the yaml mass and g = 9.81
  const Eigen::VectorXd firefly = MotorMixer(FireflyYaml()).RotorSpeeds(Eigen::Vector3d::Zero(), 1.56779 * 9.81);
  EXPECT_NEAR(firefly.minCoeff(), 547.6, 0.1);
  EXPECT_NEAR(firefly.maxCoeff(), 547.6, 0.1);
  const Eigen::VectorXd pelican = MotorMixer(PelicanYaml()).RotorSpeeds(Eigen::Vector3d::Zero(), 1.0 * 9.81);
  EXPECT_NEAR(pelican.mean(), 495.6, 0.1);
}

TEST(MotorMixer, RankDeficientConfigurationIsAClearError) {
  MultirotorParameters v = PelicanYaml();
  for (auto& r : v.rotors) r.angle_rad = 0.0;  // all rotors on one arm: no roll authority
  try {
    MotorMixer mixer(v);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("it needs rank 4"), std::string::npos) << e.what();
  }
}

TEST(MotorMixer, SaturatedThrustKeepsTheTorquesAndTheLimit) {
  MultirotorParameters v = FireflyYaml();
  for (auto& r : v.rotors) r.max_rot_velocity_rad_s = 838.0;
  const MotorMixer mixer(v);
  const Eigen::Vector3d alpha(4.0, -3.0, 0.5);  // [rad/s^2]
  const double demanded_N = 200.0;              // far beyond 6 k_F 838^2 = 36.0 N
  const Eigen::VectorXd omega = mixer.RotorSpeeds(alpha, demanded_N);
  // the fastest rotor sits at the limit, and A omega^2 still gives J alpha
  EXPECT_NEAR(omega.maxCoeff(), 838.0, 1e-6);
  const Eigen::Vector4d wrench = mixer.Allocation() * omega.cwiseAbs2();
  EXPECT_TRUE(wrench.head<3>().isApprox(v.inertia_kg_m2 * alpha, 1e-9)) << wrench.transpose();
  EXPECT_NEAR(wrench[3], mixer.FeasibleThrust(alpha, demanded_N), 1e-9);
  EXPECT_LT(wrench[3], 6 * 8.54858e-6 * 838.0 * 838.0);
  // below the limit nothing changes; without limits (RotorS' yaml) nothing changes either
  EXPECT_DOUBLE_EQ(mixer.FeasibleThrust(alpha, 15.0), 15.0);
  EXPECT_DOUBLE_EQ(MotorMixer(FireflyYaml()).FeasibleThrust(alpha, demanded_N), demanded_N);
}
