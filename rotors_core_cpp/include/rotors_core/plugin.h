// Plugin base classes and registration, mirroring Gazebo classic's ModelPlugin / WorldPlugin /
// SensorPlugin and GZ_REGISTER_*_PLUGIN, so the physics part of a Gazebo plugin ports with few edits.
#pragma once

#include <string>

#include <sdf/Element.hh>

#include "rotors_core/physics/physics_types.h"
#include "rotors_core/sdf_params.h"
#include "rotors_core/sensors/sensor.h"

namespace rotors_sim {

class PluginBase {
 public:
  virtual ~PluginBase() = default;
  /// Called on reset_world / reset_simulation.
  virtual void Reset() {}
  const std::string& GetHandle() const { return handle_; }
  const std::string& GetFilename() const { return filename_; }
  void SetIdentity(const std::string& handle, const std::string& filename) {
    handle_ = handle;
    filename_ = filename;
  }
  /// The <plugin> element's parameters. Read them through this reader: after Load() the loader
  /// rejects, by name, every child element the plugin did not ask for (AcceptParams()).
  SdfParams& Params() { return params_; }
  void SetParams(sdf::ElementPtr sdf) { params_ = SdfParams(std::move(sdf)); }
  /// Called by the loader after Load(): throws SimError naming an unread parameter.
  void AcceptParams() const {
    if (params_.Used()) params_.RejectUnread();
  }

 private:
  std::string handle_, filename_;
  SdfParams params_;
};

class ModelPlugin : public PluginBase {
 public:
  /// Parses parameters and connects to events; throws SimError (or std::exception) on bad input.
  virtual void Load(physics::ModelPtr model, sdf::ElementPtr sdf) = 0;
};

class WorldPlugin : public PluginBase {
 public:
  virtual void Load(physics::WorldPtr world, sdf::ElementPtr sdf) = 0;
};

class SensorPlugin : public PluginBase {
 public:
  virtual void Load(sensors::SensorPtr sensor, sdf::ElementPtr sdf) = 0;
};

/// Loads `plugin` into `target` (a model, world or sensor) as the loader does: its parameters
/// through Params(), then every parameter it did not read refused (SimError naming it).
template <typename PluginT, typename TargetT>
void LoadPlugin(PluginT& plugin, const TargetT& target, const sdf::ElementPtr& sdf) {
  plugin.SetParams(sdf);
  plugin.Load(target, sdf);
  plugin.AcceptParams();
}

}  // namespace rotors_sim

#define RSIM_REGISTER_SENSOR_PLUGIN(classname)                                                                \
  extern "C" __attribute__((visibility("default"))) rotors_sim::SensorPlugin* RotorsSimCreateSensorPlugin() { \
    return new classname();                                                                                   \
  }
#define GZ_REGISTER_SENSOR_PLUGIN(classname) RSIM_REGISTER_SENSOR_PLUGIN(classname)
#define RSIM_REGISTER_MODEL_PLUGIN(classname)                                                               \
  extern "C" __attribute__((visibility("default"))) rotors_sim::ModelPlugin* RotorsSimCreateModelPlugin() { \
    return new classname();                                                                                 \
  }
#define RSIM_REGISTER_WORLD_PLUGIN(classname)                                                               \
  extern "C" __attribute__((visibility("default"))) rotors_sim::WorldPlugin* RotorsSimCreateWorldPlugin() { \
    return new classname();                                                                                 \
  }
/// Gazebo spellings, for ported plugins.
#define GZ_REGISTER_MODEL_PLUGIN(classname) RSIM_REGISTER_MODEL_PLUGIN(classname)
#define GZ_REGISTER_WORLD_PLUGIN(classname) RSIM_REGISTER_WORLD_PLUGIN(classname)
