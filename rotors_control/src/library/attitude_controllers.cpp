#include "rotors_control/attitude_controllers.h"

#include <cmath>

namespace rotors_control {

AttitudeLevelController::AttitudeLevelController(const AttitudeControllerParameters& params)
    : law_(params.attitude, Validated(params.vehicle).inertia_kg_m2), mixer_(params.vehicle) {}

void AttitudeLevelController::SetRollPitchYawrateThrust(double roll, double pitch, double yaw_rate, double thrust_N) {
  roll_ = roll;
  pitch_ = pitch;
  yaw_rate_ = yaw_rate;
  thrust_N_ = thrust_N;
  mode_ = Mode::kRollPitchYawrate;
}

void AttitudeLevelController::SetAttitudeThrust(const Eigen::Quaterniond& q_WD, double thrust_N) {
  q_WD_ = q_WD.normalized();
  thrust_N_ = thrust_N;
  mode_ = Mode::kAttitude;
}

void AttitudeLevelController::SetRateThrust(const Eigen::Vector3d& omega_des_B, double thrust_N) {
  omega_des_B_ = omega_des_B;
  thrust_N_ = thrust_N;
  mode_ = Mode::kRate;
}

RotorVector AttitudeLevelController::RotorSpeeds(const VehicleState& s) const {
  if (mode_ == Mode::kNone) return RotorVector::Zero(mixer_.Allocation().cols());
  const Eigen::Matrix3d R = s.orientation_W_B.toRotationMatrix();
  Eigen::Vector3d alpha;
  if (mode_ == Mode::kRate) {
    alpha = law_.RateAcceleration(s.angular_velocity_B, omega_des_B_);
  } else if (mode_ == Mode::kAttitude) {
    alpha = law_.AngularAcceleration(R, s.angular_velocity_B, q_WD_.toRotationMatrix(), Eigen::Vector3d::Zero());
  } else {
    const double yaw = std::atan2(R(1, 0), R(0, 0));
    // z-y'-x'': R_d = Rz(yaw) Ry(pitch) Rx(roll)
    const Eigen::Matrix3d R_d =
        (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch_, Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(roll_, Eigen::Vector3d::UnitX()))
            .toRotationMatrix();
    alpha = law_.AngularAcceleration(R, s.angular_velocity_B, R_d, Eigen::Vector3d(0, 0, yaw_rate_));
  }
  return mixer_.RotorSpeeds(alpha, thrust_N_);
}

}  // namespace rotors_control
