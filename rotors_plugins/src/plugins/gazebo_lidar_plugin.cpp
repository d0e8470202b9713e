// librotors_gazebo_lidar_plugin.so (RotorS' single-beam lidar, from PX4): RotorS sends the range of
// the first beam with the sensor's min and max over Gazebo transport to its MAVLink interface; here
// the same reading goes out on ROS as sensor_msgs/Range (radiation INFRARED, field_of_view 0) on
// <robotNamespace>/<topicName> (defaults: the model's name and "lidar"), frame <frameName>
// (default: the sensor's link). Out-of-range readings as REP 117 says.
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_gazebo_plugins/ros/laser_ros.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"

namespace rotors_gazebo_plugins {

class GazeboLidarPlugin : public RangePlugin {
 protected:
  std::string DefaultTopic() const override { return "lidar"; }
  void Configure(rotors_sim::SdfParams& /*params*/) override {
    prototype_.radiation_type = sensor_msgs::Range::INFRARED;
    prototype_.field_of_view = 0.0f;
  }
  void Publish(const RayScan& scan, const ros::Time& stamp) override { PutRange(scan.ranges_m.at(0), stamp); }
};

}  // namespace rotors_gazebo_plugins

RSIM_REGISTER_SENSOR_PLUGIN(rotors_gazebo_plugins::GazeboLidarPlugin)
