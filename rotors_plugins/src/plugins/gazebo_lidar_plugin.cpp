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
  void Publish(const RayScan& scan, const ros::Time& stamp) override {
    sensor_msgs::RangePtr msg(new sensor_msgs::Range);
    msg->header.stamp = stamp;
    msg->header.frame_id = frame_;
    msg->radiation_type = sensor_msgs::Range::INFRARED;
    msg->field_of_view = 0.0f;
    msg->min_range = static_cast<float>(sensor_->Spec().range_min_m);
    msg->max_range = static_cast<float>(sensor_->Spec().range_max_m);
    msg->range = scan.ranges_m.at(0);
    PublishRange(msg);
  }
};

}  // namespace rotors_gazebo_plugins

RSIM_REGISTER_SENSOR_PLUGIN(rotors_gazebo_plugins::GazeboLidarPlugin)
