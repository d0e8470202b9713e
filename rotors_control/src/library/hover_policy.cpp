#include "rotors_control/hover_policy.h"

#include <sstream>
#include <stdexcept>

namespace rotors_control {

std::string HoverPolicyParameters::Validate() const {
  std::ostringstream why;
  if (layers.empty()) return "the policy has no layers";
  long inputs = HoverPolicy::kFeatureSize;
  for (size_t k = 0; k < layers.size(); ++k) {
    const DenseLayer& l = layers[k];
    if (l.weight.cols() != inputs || l.bias.size() != l.weight.rows()) {
      why << "layer " << k << " has a " << l.weight.rows() << " x " << l.weight.cols() << " weight and "
          << l.bias.size() << " biases; it must take " << inputs << " inputs and have one bias per output";
      return why.str();
    }
    if (!l.weight.allFinite() || !l.bias.allFinite()) {
      why << "layer " << k << " has a NaN or inf weight or bias";
      return why.str();
    }
    inputs = l.weight.rows();
  }
  if (inputs != HoverPolicy::kActionSize) {
    why << "the last layer gives " << inputs << " outputs; the policy must give " << HoverPolicy::kActionSize
        << " (roll, pitch, yaw rate, thrust)";
    return why.str();
  }
  if (observation_high.size() != HoverPolicy::kObservationSize || !(observation_high.array() > 0.0).all())
    return "observation_high must hold 13 values > 0";
  if (!(max_tilt_rad > 0.0 && max_tilt_rad < 1.6)) {
    why << "max_tilt_rad = " << max_tilt_rad << " must be in (0, 1.6)";
    return why.str();
  }
  if (!(max_yaw_rate_rad_s > 0.0) || !std::isfinite(max_yaw_rate_rad_s)) {
    why << "max_yaw_rate_rad_s = " << max_yaw_rate_rad_s << " must be > 0";
    return why.str();
  }
  if (!(max_offset_m > 0.0) || !std::isfinite(max_offset_m)) {
    why << "max_offset_m = " << max_offset_m << " must be > 0";
    return why.str();
  }
  if (!(hover_thrust_n > 0.0) || !std::isfinite(hover_thrust_n)) {
    why << "hover_thrust_n = " << hover_thrust_n << " must be > 0";
    return why.str();
  }
  return "";
}

HoverPolicy::HoverPolicy(HoverPolicyParameters params) : params_(std::move(params)) {
  const std::string why = params_.Validate();
  if (!why.empty()) throw std::invalid_argument(why);
}

Eigen::VectorXd HoverPolicy::Observation(const Eigen::Vector3d& position_W, const Eigen::Quaterniond& orientation_W_B,
                                         const Eigen::Vector3d& velocity_B, const Eigen::Vector3d& angular_velocity_B,
                                         const Eigen::Vector3d& target_W) const {
  Eigen::VectorXd o(kObservationSize);
  // o = [e, R(q_W_B) v_B, q_W_B (x, y, z, w), omega_B],  e = (p - p_target) min(1, d_max / max_i |p - p_target|_i)
  const Eigen::Vector3d e = position_W - target_W;
  const double largest = e.cwiseAbs().maxCoeff();
  o.segment<3>(0) = largest > params_.max_offset_m ? Eigen::Vector3d(e * (params_.max_offset_m / largest)) : e;
  o.segment<3>(3) = orientation_W_B * velocity_B;
  o.segment<4>(6) = orientation_W_B.coeffs();  // Eigen stores (x, y, z, w)
  o.segment<3>(10) = angular_velocity_B;
  const Eigen::ArrayXd& high = params_.observation_high.array();
  return o.array().min(high).max(-high).matrix();
}

Eigen::VectorXd HoverPolicy::Features(const Eigen::VectorXd& o) {
  // f = [o_0..5, R(q) row by row, o_10..12], q = (x, y, z, w) = o_6..9
  Eigen::VectorXd f(kFeatureSize);
  f.head<6>() = o.head<6>();
  const Eigen::Matrix3d R = Eigen::Quaterniond(o[9], o[6], o[7], o[8]).toRotationMatrix();
  for (int r = 0; r < 3; ++r) f.segment<3>(6 + 3 * r) = R.row(r).transpose();
  f.tail<3>() = o.tail<3>();
  return f;
}

Eigen::Vector4d HoverPolicy::Action(const Eigen::VectorXd& observation) const {
  // h_0 = f;  h_{k+1} = tanh(W_k h_k + b_k);  a = clip(W_L h_L + b_L, -1, 1)
  Eigen::VectorXd h = Features(observation);
  for (size_t k = 0; k < params_.layers.size(); ++k) {
    h = params_.layers[k].weight * h + params_.layers[k].bias;
    if (k + 1 < params_.layers.size()) h = h.array().tanh().matrix();
  }
  return h.array().min(1.0).max(-1.0).matrix();
}

RollPitchYawrateThrust HoverPolicy::Command(const Eigen::Vector4d& a) const {
  RollPitchYawrateThrust c;
  c.roll_rad = a[0] * params_.max_tilt_rad;
  c.pitch_rad = a[1] * params_.max_tilt_rad;
  c.yaw_rate_rad_s = a[2] * params_.max_yaw_rate_rad_s;
  c.thrust_n = (a[3] + 1.0) * params_.hover_thrust_n;
  return c;
}

}  // namespace rotors_control
