// librotors_gazebo_magnetometer_plugin.so (RotorS' rotors_gazebo_plugins/src/gazebo_magnetometer_plugin.cpp):
// sensor_msgs/MagneticField on <ns>/<magnetometerTopic> every physics step, B_B = R_WB^T m_W + b_B + n with covariance
// diag(sigma^2). The reference field is given as north, east, down [T] and placed in the ENU
// world correctly (RotorS used N, E, D as x, y, z); with worldMagneticModel (a WMM .COF file) it is
// the World Magnetic Model's field at the world's <spherical_coordinates> instead, at the date
// worldMagneticModelYear (default: today), as PX4's Gazebo magnetometer takes it.
#include <sensor_msgs/MagneticField.h>

#include <chrono>

#include "rotors_gazebo_plugins/models/navigation_sensor_models.h"
#include "rotors_gazebo_plugins/models/world_magnetic_model.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/ros/link_sensor_plugin.h"
#include "rotors_gazebo_plugins/seeded_model.h"

namespace rotors_gazebo_plugins {

class GazeboMagnetometerPlugin : public LinkSensorPlugin<MagnetometerReading, sensor_msgs::MagneticField> {
 public:
  void Load(rotors_sim::physics::ModelPtr model, sdf::ElementPtr /*sdf*/) override {
    LoadLink(model, "magnetometerTopic", "magnetic_field");
    MagnetometerParams p;
    ReadParam(Params(), "refMagNorth", &p.reference_NED_T.x());
    ReadParam(Params(), "refMagEast", &p.reference_NED_T.y());
    ReadParam(Params(), "refMagDown", &p.reference_NED_T.z());
    std::string wmm_file;
    if (ReadParam(Params(), "worldMagneticModel", &wmm_file) && !wmm_file.empty()) {
      const WorldMagneticModel wmm = WorldMagneticModel::FromFile(wmm_file);
      double year =
          DecimalYear(std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count());
      ReadParam(Params(), "worldMagneticModelYear", &year);
      const auto& o = world_->Origin();
      p.reference_NED_T = wmm.FieldNed_T(o.latitude_deg, o.longitude_deg, o.elevation_m, year);
    }
    ReadVector(Params(), "noiseNormal", &p.noise_normal_T);
    ReadVector(Params(), "noiseUniformInitialBias", &p.noise_uniform_initial_bias_T);
    ThrowIfInvalid(p.Validate());
    model_.Emplace(p, ReadSeed(Params()));
    for (int i = 0; i < 3; ++i) prototype_.magnetic_field_covariance[i * 4] = p.noise_normal_T[i] * p.noise_normal_T[i];
    StartPublishing(Bus().sensors.magnetometer);
  }

  void Reset() override { model_.Reset(); }

 private:
  void OnUpdate() override {
    const auto q = link_->WorldPose().Rot();
    Put(MagnetometerReading{model_->Measure(Eigen::Quaterniond(q.W(), q.X(), q.Y(), q.Z()))});
  }

  SeededModel<MagnetometerModel> model_;
};

}  // namespace rotors_gazebo_plugins

GZ_REGISTER_MODEL_PLUGIN(rotors_gazebo_plugins::GazeboMagnetometerPlugin)
