#include "rotors_gazebo_plugins/plugin_params.h"

#include <chrono>

#include "rotors_core/error.h"
#include "rotors_core/physics/model.h"

namespace rotors_gazebo_plugins {

bool ReadVector(SdfParams& params, const std::string& name, Eigen::Vector3d* value) {
  ignition::math::Vector3d v(value->x(), value->y(), value->z());
  if (!ReadParam(params, name, &v)) return false;
  *value = Eigen::Vector3d(v.X(), v.Y(), v.Z());
  return true;
}

void ThrowIfInvalid(const std::string& why) {
  if (!why.empty()) throw rotors_sim::SimError(why);
}

std::string ReadRobotNamespace(SdfParams& params) {
  std::string ns;
  RequireParam(params, "robotNamespace", &ns);
  while (!ns.empty() && ns.front() == '/') ns.erase(ns.begin());
  while (!ns.empty() && ns.back() == '/') ns.pop_back();
  return ns;
}

rotors_sim::physics::LinkPtr RequireLink(const rotors_sim::physics::ModelPtr& model, const std::string& name,
                                         const char* param) {
  auto link = model->GetLink(name);
  if (!link)
    throw rotors_sim::SimError(std::string(param) + " '" + name + "' is not a link of model '" + model->GetName() +
                               "'");
  return link;
}

rotors_sim::physics::JointPtr RequireJoint(const rotors_sim::physics::ModelPtr& model, const std::string& name,
                                           const char* param) {
  auto joint = model->GetJoint(name);
  if (!joint)
    throw rotors_sim::SimError(std::string(param) + " '" + name + "' is not a joint of model '" + model->GetName() +
                               "'");
  return joint;
}

uint64_t ReadSeed(SdfParams& params) {
  int64_t seed = -1;
  if (ReadParam(params, "randomEngineSeed", &seed) && seed >= 0) return static_cast<uint64_t>(seed);
  return static_cast<uint64_t>(std::chrono::high_resolution_clock::now().time_since_epoch().count());
}

bool ReadGazeboPid(SdfParams& params, const std::string& name, bool require_all, TiltServoParams* pid) {
  if (!params.Has(name)) return false;
  SdfParams nested(params.Element()->GetElement(name));
  for (const auto& [key, value] :
       {std::make_pair("p", &pid->p), std::make_pair("i", &pid->i), std::make_pair("d", &pid->d),
        std::make_pair("iMax", &pid->i_max), std::make_pair("iMin", &pid->i_min),
        std::make_pair("cmdMax", &pid->cmd_max), std::make_pair("cmdMin", &pid->cmd_min)}) {
    if (require_all) nested.Require(key, value);
    else nested.Read(key, value);
  }
  nested.RejectUnread();
  return true;
}

RotorParams ReadRotorParams(SdfParams& params) {
  std::string direction;
  RequireParam(params, "turningDirection", &direction);
  RotorParams p;
  RequireParam(params, "rotorDragCoefficient", &p.rotor_drag_coefficient);
  RequireParam(params, "rollingMomentCoefficient", &p.rolling_moment_coefficient);
  RequireParam(params, "maxRotVelocity", &p.max_rot_velocity);
  RequireParam(params, "motorConstant", &p.motor_constant);
  RequireParam(params, "momentConstant", &p.moment_constant);
  RequireParam(params, "timeConstantUp", &p.time_constant_up_s);
  RequireParam(params, "timeConstantDown", &p.time_constant_down_s);
  if (direction == "ccw") {
    p.turning_direction = 1;
  } else if (direction == "cw") {
    p.turning_direction = -1;
  } else {
    throw rotors_sim::SimError("turningDirection = '" + direction + "' must be 'cw' or 'ccw'");
  }
  ThrowIfInvalid(p.Validate());
  return p;
}

double ReadRotorSlowdown(SdfParams& params) {
  double slowdown = 10.0;
  ReadParam(params, "rotorVelocitySlowdownSim", &slowdown);
  if (!(slowdown >= 1.0))
    throw rotors_sim::SimError("rotorVelocitySlowdownSim = " + std::to_string(slowdown) + " must be >= 1");
  return slowdown;
}

WindParams ReadWindParams(SdfParams& params) {
  WindParams p;
  ReadParam(params, "windSpeedMean", &p.wind_speed_mean_m_s);
  ReadParam(params, "windSpeedVariance", &p.wind_speed_variance);
  ReadVector(params, "windDirection", &p.wind_direction);
  ReadParam(params, "windForceMean", &p.wind_force_mean_n);
  ReadParam(params, "windForceVariance", &p.wind_force_variance);
  ReadParam(params, "windGustStart", &p.wind_gust_start_s);
  ReadParam(params, "windGustDuration", &p.wind_gust_duration_s);
  ReadParam(params, "windGustForceMean", &p.wind_gust_force_mean_n);
  ReadParam(params, "windGustForceVariance", &p.wind_gust_force_variance);
  ReadVector(params, "windGustDirection", &p.wind_gust_direction);
  ThrowIfInvalid(p.Validate());
  return p;
}

OdometryNoiseParams ReadOdometryNoise(SdfParams& params) {
  OdometryNoiseParams noise;
  ReadVector(params, "noiseNormalPosition", &noise.normal_position_m);
  ReadVector(params, "noiseNormalQuaternion", &noise.normal_quaternion_rad);
  ReadVector(params, "noiseNormalLinearVelocity", &noise.normal_linear_velocity_m_s);
  ReadVector(params, "noiseNormalAngularVelocity", &noise.normal_angular_velocity_rad_s);
  ReadVector(params, "noiseUniformPosition", &noise.uniform_position_m);
  ReadVector(params, "noiseUniformQuaternion", &noise.uniform_quaternion_rad);
  ReadVector(params, "noiseUniformLinearVelocity", &noise.uniform_linear_velocity_m_s);
  ReadVector(params, "noiseUniformAngularVelocity", &noise.uniform_angular_velocity_rad_s);
  ThrowIfInvalid(noise.Validate());
  return noise;
}

ImuNoiseParams ReadImuNoise(SdfParams& params) {
  ImuNoiseParams p;
  ReadParam(params, "gyroscopeNoiseDensity", &p.gyroscope_noise_density);
  const bool xacro_name = ReadParam(params, "gyroscopeRandomWalk", &p.gyroscope_random_walk);
  double plugin_name_value = p.gyroscope_random_walk;
  if (ReadParam(params, "gyroscopeBiasRandomWalk", &plugin_name_value)) {
    if (xacro_name && plugin_name_value != p.gyroscope_random_walk)
      throw rotors_sim::SimError("<gyroscopeRandomWalk> and <gyroscopeBiasRandomWalk> disagree; give one of them");
    p.gyroscope_random_walk = plugin_name_value;
  }
  ReadParam(params, "gyroscopeBiasCorrelationTime", &p.gyroscope_bias_correlation_time_s);
  ReadParam(params, "gyroscopeTurnOnBiasSigma", &p.gyroscope_turn_on_bias_sigma);
  ReadParam(params, "accelerometerNoiseDensity", &p.accelerometer_noise_density);
  ReadParam(params, "accelerometerRandomWalk", &p.accelerometer_random_walk);
  ReadParam(params, "accelerometerBiasCorrelationTime", &p.accelerometer_bias_correlation_time_s);
  ReadParam(params, "accelerometerTurnOnBiasSigma", &p.accelerometer_turn_on_bias_sigma);
  ThrowIfInvalid(p.Validate());
  return p;
}

ImuVibrationParams ReadImuVibration(SdfParams& params) {
  ImuVibrationParams p;
  ReadParam(params, "rotorVibration", &p.enabled);
  ReadParam(params, "balanceGrade", &p.balance_grade_mm_s);
  ReadParam(params, "residualUnbalance", &p.residual_unbalance_kg_m);
  ReadParam(params, "bladeCount", &p.blade_count);
  ReadParam(params, "bladePassThrustRipple", &p.blade_pass_thrust_ripple);
  ReadParam(params, "internalSampleRate", &p.internal_rate_hz);
  ReadParam(params, "bartlettTaps", &p.bartlett_taps);
  ReadParam(params, "frameModeFrequency", &p.frame_mode_frequency_hz);
  ReadParam(params, "frameModeDamping", &p.frame_mode_damping);
  ReadParam(params, "thrustNoiseDensity", &p.thrust_noise_density);
  ThrowIfInvalid(p.Validate());
  return p;
}

}  // namespace rotors_gazebo_plugins
