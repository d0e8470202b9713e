// librotors_gazebo_pressure_plugin.so (RotorS' rotors_gazebo_plugins/src/gazebo_pressure_plugin.cpp):
// sensor_msgs/FluidPressure on <ns>/<pressureTopic> every physics step: the standard atmosphere at referenceAltitude +
// z_W, plus N(0, pressureVariance).
#include <sensor_msgs/FluidPressure.h>

#include "rotors_gazebo_plugins/models/navigation_sensor_models.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/ros/link_sensor_plugin.h"
#include "rotors_gazebo_plugins/seeded_model.h"

namespace rotors_gazebo_plugins {

class GazeboPressurePlugin : public LinkSensorPlugin<BarometerReading, sensor_msgs::FluidPressure> {
 public:
  void Load(rotors_sim::physics::ModelPtr model, sdf::ElementPtr /*sdf*/) override {
    LoadLink(model, "pressureTopic", "air_pressure");
    PressureParams p;
    ReadParam(Params(), "referenceAltitude", &p.reference_altitude_m);
    ReadParam(Params(), "pressureVariance", &p.pressure_variance_pa2);
    ThrowIfInvalid(p.Validate());
    model_.Emplace(p, ReadSeed(Params()));
    prototype_.variance = p.pressure_variance_pa2;
    StartPublishing(Bus().sensors.barometer);
  }

  void Reset() override { model_.Reset(); }

 private:
  void OnUpdate() override { Put(BarometerReading{model_->Measure(link_->WorldPose().Pos().Z())}); }

  SeededModel<PressureModel> model_;
};

}  // namespace rotors_gazebo_plugins

GZ_REGISTER_MODEL_PLUGIN(rotors_gazebo_plugins::GazeboPressurePlugin)
