// A learnt hover-and-waypoint policy (rotors_python/examples/train_policy.py, trained on the batched
// flight engine) as a controller: odometry and a target in, a roll-pitch-yawrate-thrust command out,
// as RotorS' position controllers hand it to the attitude controller. No ROS and no learning
// framework: the policy is a multilayer perceptron read from plain numpy arrays (policy_file.h).
//
// Observation (the batch's RotorS/Hover-v0, rotors_sim/envs/hover.py), clipped to +-observation_high:
//   o = [e, R(q_W_B) v_B, q_W_B (x, y, z, w), omega_B]
//   e = (p_W - p_target_W) min(1, d_max / max_i |p_W - p_target_W|_i)
// A target farther than the policy learnt (d_max per axis: the training starts' largest offset) is
// approached through the point d_max from the vehicle on the way to it.
// Features (what the network sees; the rotation matrix is continuous in the attitude, where the
// quaternion's components jump with its sign):
//   f = [o_0..5, R(q) row by row (9), o_10..12]
// Network: h_0 = f,  h_{k+1} = tanh(W_k h_k + b_k),  a = clip(W_L h_L + b_L, -1, 1)
// Command (the batch's attitude action, rotors_sim/envs/batched.py):
//   roll = a_0 max_tilt,  pitch = a_1 max_tilt,  yaw rate = a_2 max_yaw_rate,  thrust = (a_3 + 1) T_hover
// with T_hover the training airframe's weight (stored with the policy: the policy learnt that
// scale, whatever the flown vehicle weighs).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace rotors_control {

struct DenseLayer {
  Eigen::MatrixXd weight;  ///< outputs x inputs
  Eigen::VectorXd bias;    ///< outputs
};

/// One parameter struct: everything the policy file holds.
struct HoverPolicyParameters {
  std::vector<DenseLayer> layers;    ///< tanh between them, none after the last
  Eigen::VectorXd observation_high;  ///< 13 clip bounds of the observation
  double max_tilt_rad = 0.6;         ///< roll and pitch at |a| = 1
  double max_yaw_rate_rad_s = 2.0;   ///< yaw rate at |a| = 1
  double hover_thrust_n = 0.0;       ///< T_hover: the thrust at a_3 = 0
  double max_offset_m = 0.5;         ///< d_max: the largest position error per axis the policy sees
  /// Empty when the layers chain from 18 features to 4 actions and every number is finite,
  /// else one line naming the bad part.
  std::string Validate() const;
};

struct RollPitchYawrateThrust {
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
  double yaw_rate_rad_s = 0.0;
  double thrust_n = 0.0;
};

class HoverPolicy {
 public:
  static constexpr int kObservationSize = 13;
  static constexpr int kFeatureSize = 18;
  static constexpr int kActionSize = 4;
  /// Throws std::invalid_argument with Validate()'s line.
  explicit HoverPolicy(HoverPolicyParameters params);

  /// The observation above for the state (velocity and angular velocity in the body frame, as
  /// nav_msgs/Odometry's twist) and the target.
  Eigen::VectorXd Observation(const Eigen::Vector3d& position_W, const Eigen::Quaterniond& orientation_W_B,
                              const Eigen::Vector3d& velocity_B, const Eigen::Vector3d& angular_velocity_B,
                              const Eigen::Vector3d& target_W) const;
  /// The features f of an observation.
  static Eigen::VectorXd Features(const Eigen::VectorXd& observation);
  /// a in [-1, 1]^4 for an observation (through its features).
  Eigen::Vector4d Action(const Eigen::VectorXd& observation) const;
  /// The command for an action.
  RollPitchYawrateThrust Command(const Eigen::Vector4d& action) const;

  const HoverPolicyParameters& Parameters() const { return params_; }

 private:
  HoverPolicyParameters params_;
};

}  // namespace rotors_control
