// Controller laws: attitude error on SO(3), the gyroscopic term, hover thrust and the Lee
// controller's response to position errors.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "rotors_control/attitude_control_law.h"
#include "rotors_control/attitude_controllers.h"
#include "rotors_control/lee_controller.h"
#include "rotors_control/motor_mixer.h"
#include "test_fixtures.h"

using namespace rotors_control;

namespace {
Eigen::Matrix3d Rot(double angle, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}
LeeControllerParameters FireflyLee() {
  LeeControllerParameters p;
  p.position_gain = {6, 6, 6};
  p.velocity_gain = {4.7, 4.7, 4.7};
  p.attitude.attitude_gain = {3, 3, 0.15};
  p.attitude.angular_rate_gain = {0.52, 0.52, 0.18};
  p.vehicle = FireflyYaml();
  return p;
}
}  // namespace

// e_R = 1/2 vee(R_d^T R - R^T R_d) is sin(theta) * axis for a rotation by theta about an axis, so with
// no rate error and J = 0.1 I the law commands alpha = -(K_R / J) sin(theta) axis.
TEST(AttitudeControlLaw, AttitudeErrorOnSO3) {
  const Eigen::Vector3d axis = Eigen::Vector3d(1, -2, 0.5).normalized();
  AttitudeGains gains;
  gains.attitude_gain = {2, 2, 2};
  gains.angular_rate_gain = {0, 0, 0};
  const Eigen::Matrix3d J = Eigen::Matrix3d::Identity() * 0.1;
  for (double theta : {0.0, 0.1, 1.0, 2.5}) {
    const Eigen::Matrix3d R_d = Rot(0.7, {0, 0, 1});
    const Eigen::Matrix3d R = R_d * Rot(theta, axis);
    const Eigen::Vector3d alpha =
        AttitudeControlLaw(gains, J).AngularAcceleration(R, Eigen::Vector3d::Zero(), R_d, Eigen::Vector3d::Zero());
    EXPECT_LT((alpha - (-20.0 * std::sin(theta) * axis)).norm(), 1e-9) << "theta " << theta;
  }
  // pinned by hand: 0.1 rad about x gives alpha_x = -20 sin(0.1) = -1.99667
  const Eigen::Vector3d alpha_x = AttitudeControlLaw(gains, J).AngularAcceleration(
      Rot(0.1, {1, 0, 0}), Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
  EXPECT_NEAR(alpha_x.x(), -1.996668, 1e-6);
  EXPECT_TRUE(Vee(Hat(Eigen::Vector3d(1, 2, 3))).isApprox(Eigen::Vector3d(1, 2, 3)));
}

// With no attitude or rate error the law returns exactly J^-1 (w x J w): it cancels the
// gyroscopic torque (RotorS wrote w x w, which is zero).
TEST(AttitudeControlLaw, CompensatesGyroscopicTorque) {
  AttitudeGains gains;
  const Eigen::Matrix3d J = Eigen::Vector3d(0.0347563, 0.0458929, 0.0977).asDiagonal();
  const AttitudeControlLaw law(gains, J);
  const Eigen::Vector3d w(1.0, 2.0, 0.0);
  const Eigen::Matrix3d R = Rot(0.3, {1, 1, 0});
  // track the current rotation and rate exactly: R_d = R, w_d = R_d^T R w = w
  const Eigen::Vector3d alpha = law.AngularAcceleration(R, w, R, w);
  // by hand, J = diag(Jx, Jy, Jz), w = (1, 2, 0): w x J w = (0, 0, 2 (Jy - Jx)), so alpha = (0, 0, 0.227976)
  EXPECT_NEAR(alpha.x(), 0.0, 1e-12);
  EXPECT_NEAR(alpha.y(), 0.0, 1e-12);
  EXPECT_NEAR(alpha.z(), 2.0 * (0.0458929 - 0.0347563) / 0.0977, 1e-12);
  EXPECT_NEAR(alpha.z(), 0.227976, 1e-6);
}

TEST(LeeController, HoverThrustEqualsWeightAndRotorsStopWithoutReference) {
  LeeController lee(FireflyLee());
  VehicleState s;
  s.position_W = {0, 0, 1};
  EXPECT_TRUE(lee.RotorSpeeds(s).isZero());  // no reference yet
  TrajectoryPoint ref;
  ref.position_W = {0, 0, 1};
  lee.SetTrajectoryPoint(ref);
  double thrust = 0;
  Eigen::Matrix3d R_d;
  lee.ComputeThrustAndAttitude(s, &thrust, &R_d);
  EXPECT_NEAR(thrust, 1.56779 * 9.81, 1e-9);
  EXPECT_TRUE(R_d.isApprox(Eigen::Matrix3d::Identity(), 1e-12));
  const Eigen::VectorXd omega = lee.RotorSpeeds(s);
  EXPECT_NEAR(omega.mean(), 547.6, 0.1);
}

TEST(LeeController, FailedRotorIsLeftOutAndTheOthersCarryTheHover) {
  LeeController lee(FireflyLee());
  VehicleState s;
  s.position_W = {0, 0, 1};
  TrajectoryPoint ref;
  ref.position_W = {0, 0, 1};
  lee.SetTrajectoryPoint(ref);
  ASSERT_EQ(lee.SetRotorSpeedFactor(1, 0.0), "");
  const Eigen::VectorXd omega = lee.RotorSpeeds(s);
  // By hand: with rotor 1 (90 deg, cw) out, zero roll, pitch and yaw torque force rotor 4 (the
  // opposite one) to zero and leave rotors 0, 2, 3, 5 with a quarter of the weight each.
  const double k_F = 8.54858e-6, quarter_weight = 1.56779 * 9.81 / 4.0;
  EXPECT_NEAR(omega[1], 0.0, 1e-9);
  EXPECT_TRUE(lee.YawReleased());
  // the yaw reference is given up: a yawed MAV is not turned back (only the rate is damped)
  VehicleState yawed = s;
  yawed.orientation_W_B = Eigen::AngleAxisd(2.0, Eigen::Vector3d::UnitZ());
  double thrust_yawed = 0.0;
  Eigen::Matrix3d R_d;
  lee.ComputeThrustAndAttitude(yawed, &thrust_yawed, &R_d);
  EXPECT_TRUE(R_d.isApprox(yawed.orientation_W_B.toRotationMatrix(), 1e-12));
  // (within what the yaml's 4-digit angles, 0.5236 for pi/6, leave)
  EXPECT_NEAR(omega[4], 0.0, 0.01);
  for (int i : {0, 2, 3, 5}) EXPECT_NEAR(k_F * omega[i] * omega[i], quarter_weight, 1e-4) << "rotor " << i;
  // derated to half speed: rotor 1 is commanded so that it gives its share at half the speed
  LeeController derated(FireflyLee());
  derated.SetTrajectoryPoint(ref);
  ASSERT_EQ(derated.SetRotorSpeedFactor(1, 0.5), "");
  EXPECT_FALSE(derated.YawReleased());
  const Eigen::VectorXd w = derated.RotorSpeeds(s);
  Eigen::VectorXd real = w;
  real[1] *= 0.5;  // what the derated motor makes of its command
  const Eigen::Matrix4Xd A = AllocationMatrix(FireflyYaml());
  const Eigen::Vector4d wrench = A * real.cwiseAbs2();
  EXPECT_NEAR(wrench[3], 1.56779 * 9.81, 1e-6);
  EXPECT_LT(wrench.head<3>().norm(), 1e-9);
  // torques the five rotors cannot make (rotor 4 would have to push down): the yaw gives way to the
  // nearest feasible value, roll, pitch and thrust stay exact
  const MotorMixer five_rotors([] {
    MultirotorParameters v = FireflyYaml();
    v.rotors[1].rotor_force_constant = 0.0;
    return v;
  }());
  int infeasible = 0;
  for (double alpha_z : {-2.0, 2.0}) {
    const Eigen::VectorXd w2 = five_rotors.RotorSpeeds({0.5, -0.3, alpha_z}, 15.0).cwiseAbs2();
    const Eigen::Vector4d made = five_rotors.Allocation() * w2;
    const Eigen::Vector3d J = FireflyYaml().inertia_kg_m2.diagonal();
    EXPECT_NEAR(made[0], J[0] * 0.5, 1e-6);
    EXPECT_NEAR(made[1], J[1] * -0.3, 1e-6);
    EXPECT_NEAR(made[3], 15.0, 1e-6);
    // the plain pseudo-inverse: feasible (no negative omega^2) -> yaw as asked, else yaw moved
    const Eigen::Matrix4Xd& A5 = five_rotors.Allocation();
    Eigen::Vector4d wrench_asked;
    wrench_asked << J[0] * 0.5, J[1] * -0.3, J[2] * alpha_z, 15.0;
    const Eigen::VectorXd plain = A5.transpose() * (A5 * A5.transpose()).inverse() * wrench_asked;
    if (plain.minCoeff() >= 0.0) {
      EXPECT_NEAR(made[2], wrench_asked[2], 1e-9);
    } else {
      EXPECT_GT(std::abs(made[2] - wrench_asked[2]), 1e-3);
      ++infeasible;
    }
  }
  EXPECT_EQ(infeasible, 1);  // one sign of yaw torque is out of reach here
  // refused: a rotor that does not exist, a factor outside [0, 1], a quadrotor losing a rotor
  EXPECT_NE(lee.SetRotorSpeedFactor(6, 0.0).find("does not exist"), std::string::npos);
  EXPECT_NE(lee.SetRotorSpeedFactor(0, 1.5).find("must be in [0, 1]"), std::string::npos);
  LeeControllerParameters quad = FireflyLee();
  quad.vehicle = PelicanYaml();
  LeeController pelican(quad);
  EXPECT_NE(pelican.SetRotorSpeedFactor(0, 0.0).find("rank 3"), std::string::npos);
}

TEST(LeeController, PositionErrorTiltsTowardsTheReferenceAndYawFollows) {
  LeeController lee(FireflyLee());
  TrajectoryPoint ref;
  ref.position_W = {1, 0, 1};
  ref.yaw_rad = 0.5;
  lee.SetTrajectoryPoint(ref);
  VehicleState s;
  s.position_W = {0, 0, 1};
  double thrust = 0;
  Eigen::Matrix3d R_d;
  lee.ComputeThrustAndAttitude(s, &thrust, &R_d);
  // b3_d = -a/|a| with a = (K_p e_p)/m - g e3: tilted towards +x by atan(6 / (m g))
  EXPECT_NEAR(std::atan2(R_d(0, 2), R_d(2, 2)), std::atan(6.0 / (1.56779 * 9.81)), 1e-9);
  EXPECT_NEAR(R_d(1, 2), 0.0, 1e-12);
  // b2_d = b3_d x b1_d / |.| is orthogonal to the yaw direction b1_d = (cos psi, sin psi, 0)
  EXPECT_NEAR(R_d.col(1).dot(Eigen::Vector3d(std::cos(0.5), std::sin(0.5), 0.0)), 0.0, 1e-12);
  EXPECT_NEAR((R_d.transpose() * R_d - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-12);
}

TEST(AccelerationSaturation, VerticalPriorityThenTiltAndThrust) {
  AccelerationLimits limits;
  limits.max_tilt_rad = M_PI / 4;
  limits.max_m_s2 = 23.0;
  limits.min_up_m_s2 = 2.0;
  // RotorS issue #456: 27 m away and 15 m below the set point (firefly gains): (0, 104, 67) m/s^2
  // asked; the upward part is capped at a_max and nothing is left for the horizontal part
  const Eigen::Vector3d climb = SaturatedAcceleration({0.0, 104.0, 67.0}, limits);
  EXPECT_TRUE(climb.isApprox(Eigen::Vector3d(0.0, 0.0, 23.0), 1e-12)) << climb.transpose();
  // level flight: up = g; the tilt cone allows |a_h| = g tan 45 deg = g, the thrust sqrt(23^2 - g^2) > g
  const Eigen::Vector3d level = SaturatedAcceleration({30.0, -40.0, 9.81}, limits);
  EXPECT_NEAR(level.head<2>().norm(), 9.81, 1e-12);
  EXPECT_NEAR(std::atan2(level.y(), level.x()), std::atan2(-40.0, 30.0), 1e-12);  // direction kept
  EXPECT_NEAR(level.z(), 9.81, 1e-12);
  // steep tilt allowed but little thrust left: |a_h| = sqrt(a_max^2 - a_up^2)
  AccelerationLimits steep = limits;
  steep.max_tilt_rad = 1.5;
  const Eigen::Vector3d up = SaturatedAcceleration({50.0, 0.0, 20.0}, steep);
  EXPECT_NEAR(up.x(), std::sqrt(23.0 * 23.0 - 20.0 * 20.0), 1e-12);
  // a set point far below: the upward part keeps its floor, no flip
  EXPECT_NEAR(SaturatedAcceleration({0.0, 0.0, -30.0}, limits).z(), 2.0, 1e-12);
  // inside all limits: unchanged
  EXPECT_TRUE(SaturatedAcceleration({1.0, 2.0, 10.0}, limits).isApprox(Eigen::Vector3d(1.0, 2.0, 10.0)));
}

TEST(LeeController, FarSetPointClimbsFirstWhenTheThrustSaturates) {
  LeeControllerParameters p = FireflyLee();
  for (auto& r : p.vehicle.rotors) r.max_rot_velocity_rad_s = 838.0;
  p.max_tilt_angle_rad = M_PI / 4;
  LeeController lee(p);
  TrajectoryPoint ref;
  ref.position_W = {2.0, -27.0, 15.0};  // the powerplant's first waypoint, from the ground
  lee.SetTrajectoryPoint(ref);
  double thrust = 0;
  Eigen::Matrix3d R_d;
  lee.ComputeThrustAndAttitude(VehicleState(), &thrust, &R_d);
  EXPECT_NEAR(R_d(2, 2), 1.0, 1e-12);  // b3_d = e3: all thrust goes into the climb
  EXPECT_NEAR(thrust, 6 * 8.54858e-6 * 838.0 * 838.0, 1e-9);
  // without the limits (RotorS): tilted 57 deg, and m a . e3 = 6 * 15 + m g = 105 N asked of rotors
  // that give 36 N
  LeeController rotors(FireflyLee());
  rotors.SetTrajectoryPoint(ref);
  rotors.ComputeThrustAndAttitude(VehicleState(), &thrust, &R_d);
  EXPECT_NEAR(thrust, 6.0 * 15.0 + 1.56779 * 9.81, 1e-9);
  EXPECT_LT(R_d(2, 2), std::cos(0.9));
}

TEST(LeeController, InvalidParametersAreRejected) {
  LeeControllerParameters p = FireflyLee();
  p.vehicle.mass_kg = -1.0;
  try {
    LeeController lee(p);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("mass = -1"), std::string::npos);
  }
}

TEST(AttitudeLevelController, RollPitchYawrateUsesZYXConvention) {
  AttitudeControllerParameters p;
  p.vehicle = FireflyYaml();
  AttitudeLevelController c(p);
  VehicleState s;
  EXPECT_TRUE(c.RotorSpeeds(s).isZero());
  c.SetRollPitchYawrateThrust(0.0, 0.0, 0.0, 1.56779 * 9.81);
  EXPECT_NEAR(c.RotorSpeeds(s).mean(), 547.6, 0.1);  // level: all rotors equal
  // commanding a pitch forward on a level vehicle produces a positive pitch acceleration
  c.SetRollPitchYawrateThrust(0.0, 0.2, 0.0, 1.56779 * 9.81);
  const Eigen::VectorXd omega = c.RotorSpeeds(s);
  const Eigen::Vector4d wrench = MotorMixer(p.vehicle).Allocation() * omega.cwiseAbs2();
  EXPECT_GT(wrench[1], 0.0);
  EXPECT_NEAR(wrench[0], 0.0, 1e-9);
}
