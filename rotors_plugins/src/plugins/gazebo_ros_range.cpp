// libgazebo_ros_range.so (gazebo_ros' range plugin): the nearest return of all the beams of a
// <sensor type="ray"> as sensor_msgs/Range, the way an ultrasonic or infrared sensor measures the
// shortest distance in its cone (the seed's Note 9). Parameters: <radiation> ultrasound (default)
// or infrared, <fov> [rad] written to field_of_view (the cone is the sensor's beams),
// <gaussianNoise> [m]; topic <robotNamespace>/<topicName> (default "range").
#include <cmath>

#include "rotors_core/error.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_gazebo_plugins/ros/laser_ros.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"

namespace rotors_gazebo_plugins {

class GazeboRosRange : public RangePlugin {
 protected:
  std::string DefaultTopic() const override { return "range"; }
  void Configure(rotors_sim::SdfParams& params) override {
    std::string radiation = "ultrasound";
    ReadParam(params, "radiation", &radiation);
    if (radiation != "ultrasound" && radiation != "infrared")
      throw rotors_sim::SimError("<radiation> '" + radiation + "' must be ultrasound or infrared");
    prototype_.radiation_type =
        radiation == "ultrasound" ? sensor_msgs::Range::ULTRASOUND : sensor_msgs::Range::INFRARED;
    double fov_rad = 0.05;
    ReadParam(params, "fov", &fov_rad);
    if (!(fov_rad >= 0.0 && fov_rad < M_PI)) throw rotors_sim::SimError("<fov> must be in [0, pi) rad");
    ReadParam(params, "gaussianNoise", &noise_m_);
    if (!(noise_m_ >= 0.0)) throw rotors_sim::SimError("<gaussianNoise> must be >= 0 m");
    prototype_.field_of_view = static_cast<float>(fov_rad);
  }
  void Publish(const RayScan& scan, const ros::Time& stamp) override {
    float range = NearestReturn(scan);
    if (std::isfinite(range) && noise_m_ > 0.0) {
      std::normal_distribution<double> noise(0.0, noise_m_);
      range = std::min(prototype_.max_range, std::max(prototype_.min_range, static_cast<float>(range + noise(rng_))));
    }
    PutRange(range, stamp);
  }

 private:
  double noise_m_ = 0.0;
};

}  // namespace rotors_gazebo_plugins

RSIM_REGISTER_SENSOR_PLUGIN(rotors_gazebo_plugins::GazeboRosRange)
