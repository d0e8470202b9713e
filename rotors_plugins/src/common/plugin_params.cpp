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

}  // namespace rotors_gazebo_plugins
