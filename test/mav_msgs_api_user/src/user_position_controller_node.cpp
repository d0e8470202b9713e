// A RotorS user's position controller, as users write them against mav_comm: every message goes
// through the mav_msgs C++ API (EigenOdometry, EigenTrajectoryPoint, EigenActuators, the
// conversions, the default topics, getSquaredRotorSpeedsFromAllocationAndState). The control law
// is Lee's geometric controller on SE(3) with RotorS' gain and vehicle parameters, so its hover
// must match the book's figure. Nothing from this simulator's own libraries is used.
#include <cmath>

#include <Eigen/Dense>
#include <mav_msgs/conversions.h>
#include <mav_msgs/default_topics.h>
#include <mav_msgs/eigen_mav_msgs.h>
#include <ros/ros.h>

namespace user {

Eigen::Vector3d ReadVector(const ros::NodeHandle& nh, const std::string& name) {
  Eigen::Vector3d v;
  if (!nh.getParam(name + "/x", v.x()) || !nh.getParam(name + "/y", v.y()) || !nh.getParam(name + "/z", v.z()))
    throw std::runtime_error("missing parameter " + nh.resolveName(name) + "/{x,y,z}");
  return v;
}

class UserPositionController {
 public:
  explicit UserPositionController(ros::NodeHandle nh, ros::NodeHandle private_nh) {
    position_gain_ = ReadVector(private_nh, "position_gain");
    velocity_gain_ = ReadVector(private_nh, "velocity_gain");
    const Eigen::Vector3d attitude_gain = ReadVector(private_nh, "attitude_gain");
    const Eigen::Vector3d angular_rate_gain = ReadVector(private_nh, "angular_rate_gain");
    if (!private_nh.getParam("mass", mass_)) throw std::runtime_error("missing parameter mass");
    double xx, yy, zz;
    if (!private_nh.getParam("inertia/xx", xx) || !private_nh.getParam("inertia/yy", yy) ||
        !private_nh.getParam("inertia/zz", zz))
      throw std::runtime_error("missing parameter inertia/{xx,yy,zz}");
    inertia_ = {xx, yy, zz};
    // gains normalised by the inertia, so that they act on angular accelerations
    attitude_gain_ = attitude_gain.cwiseQuotient(inertia_);
    angular_rate_gain_ = angular_rate_gain.cwiseQuotient(inertia_);
    ReadAllocation(private_nh);

    motor_pub_ = nh.advertise<mav_msgs::Actuators>(mav_msgs::default_topics::COMMAND_ACTUATORS, 1);
    trajectory_sub_ =
        nh.subscribe(mav_msgs::default_topics::COMMAND_TRAJECTORY, 1, &UserPositionController::OnTrajectory, this);
    odometry_sub_ = nh.subscribe(mav_msgs::default_topics::ODOMETRY, 1, &UserPositionController::OnOdometry, this);
  }

 private:
  /// Rows: roll, pitch, yaw torque and thrust per squared rotor speed; pseudo-inverse kept.
  void ReadAllocation(const ros::NodeHandle& nh) {
    XmlRpc::XmlRpcValue rotors;
    if (!nh.getParam("rotor_configuration", rotors) || rotors.getType() != XmlRpc::XmlRpcValue::TypeStruct)
      throw std::runtime_error("missing parameter rotor_configuration");
    const int n = rotors.size();
    Eigen::MatrixXd A(4, n);
    for (int i = 0; i < n; ++i) {
      const std::string key = "rotor_configuration/" + std::to_string(i) + "/";
      double angle, arm, k_f, k_m, direction;
      if (!nh.getParam(key + "angle", angle) || !nh.getParam(key + "arm_length", arm) ||
          !nh.getParam(key + "rotor_force_constant", k_f) || !nh.getParam(key + "rotor_moment_constant", k_m) ||
          !nh.getParam(key + "direction", direction))
        throw std::runtime_error("incomplete parameter " + key);
      A.col(i) << std::sin(angle) * arm * k_f, -std::cos(angle) * arm * k_f, -direction * k_f * k_m, k_f;
    }
    allocation_inverse_ = A.transpose() * (A * A.transpose()).inverse();
  }

  void OnTrajectory(const trajectory_msgs::MultiDOFJointTrajectoryConstPtr& msg) {
    if (msg->points.empty()) return;
    mav_msgs::eigenTrajectoryPointFromMsg(msg->points.front(), &command_);
    has_command_ = true;
  }

  void OnOdometry(const nav_msgs::OdometryConstPtr& msg) {
    mav_msgs::EigenOdometry odometry;
    mav_msgs::eigenOdometryFromMsg(*msg, &odometry);
    mav_msgs::EigenActuators actuators(Eigen::VectorXd::Zero(allocation_inverse_.rows()));
    if (has_command_) actuators.angular_velocities = RotorVelocities(odometry);
    mav_msgs::Actuators out;
    mav_msgs::msgActuatorsFromEigen(actuators, &out);
    out.header.stamp = msg->header.stamp;
    motor_pub_.publish(out);
  }

  Eigen::VectorXd RotorVelocities(const mav_msgs::EigenOdometry& odometry) const {
    const Eigen::Matrix3d R = odometry.orientation_W_B.toRotationMatrix();
    const Eigen::Vector3d e_p = odometry.position_W - command_.position_W;
    const Eigen::Vector3d e_v = odometry.getVelocityWorld() - command_.velocity_W;
    const double g = 9.81;  // RotorS' controller constant (the simulated world has 9.8: book note 1)
    // a = (K_p e_p + K_v e_v) / m - g e_3 - a_ref
    const Eigen::Vector3d a = (e_p.cwiseProduct(position_gain_) + e_v.cwiseProduct(velocity_gain_)) / mass_ -
                              g * Eigen::Vector3d::UnitZ() - command_.acceleration_W;
    // b_3d = -a / |a|, b_1d from the commanded yaw
    const Eigen::Vector3d b3_d = -a.normalized();
    const double yaw = command_.getYaw();
    const Eigen::Vector3d b1_yaw(std::cos(yaw), std::sin(yaw), 0.0);
    const Eigen::Vector3d b2_d = b3_d.cross(b1_yaw).normalized();
    Eigen::Matrix3d R_d;
    R_d << b2_d.cross(b3_d), b2_d, b3_d;
    // e_R = 1/2 (R_d^T R - R^T R_d)^vee,  e_w = w - R^T R_d w_d
    const Eigen::Vector3d e_R = 0.5 * mav_msgs::vectorFromSkewMatrix(R_d.transpose() * R - R.transpose() * R_d);
    const Eigen::Vector3d w_d(0.0, 0.0, command_.getYawRate());
    const Eigen::Vector3d e_w = odometry.angular_velocity_B - R.transpose() * R_d * w_d;
    const Eigen::Vector3d alpha = -e_R.cwiseProduct(attitude_gain_) - e_w.cwiseProduct(angular_rate_gain_);
    // thrust per unit mass along b_3: -a . R e_3
    const Eigen::Vector3d thrust_acceleration_B(0.0, 0.0, -a.dot(R.col(2)));
    Eigen::VectorXd omega_squared;
    mav_msgs::getSquaredRotorSpeedsFromAllocationAndState(allocation_inverse_, inertia_, mass_,
                                                          odometry.angular_velocity_B, alpha, thrust_acceleration_B,
                                                          &omega_squared);
    return omega_squared.cwiseMax(0.0).cwiseSqrt();
  }

  Eigen::Vector3d position_gain_, velocity_gain_, attitude_gain_, angular_rate_gain_, inertia_;
  double mass_ = 0.0;
  Eigen::MatrixXd allocation_inverse_;
  mav_msgs::EigenTrajectoryPoint command_;
  bool has_command_ = false;
  ros::Publisher motor_pub_;
  ros::Subscriber trajectory_sub_, odometry_sub_;
};

}  // namespace user

int main(int argc, char** argv) {
  ros::init(argc, argv, "user_position_controller_node");
  try {
    user::UserPositionController controller(ros::NodeHandle(), ros::NodeHandle("~"));
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("[user_position_controller] %s", e.what());
    return 1;
  }
  return 0;
}
