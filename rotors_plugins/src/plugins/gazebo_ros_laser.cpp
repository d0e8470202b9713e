// libgazebo_ros_laser.so and libgazebo_ros_gpu_laser.so (gazebo_ros' 2D laser plugins): a one-row
// <sensor type="ray|gpu_ray"> as sensor_msgs/LaserScan on <robotNamespace>/<topicName> (default
// "scan"), frame <frameName> (default: the sensor's link). REP 117: +inf where nothing is within
// max range, -inf where a surface is closer than min range.
#include "rotors_core/error.h"
#include "rotors_gazebo_plugins/ros/laser_ros.h"

namespace rotors_gazebo_plugins {

class GazeboRosLaser : public LaserPlugin {
 protected:
  std::string DefaultTopic() const override { return "scan"; }
  void Configure(rotors_sim::SdfParams& /*params*/) override {
    if (sensor_->Spec().vertical_count != 1)
      throw rotors_sim::SimError("a LaserScan has one row, but sensor '" + sensor_->Name() + "' has " +
                                 std::to_string(sensor_->Spec().vertical_count) +
                                 " vertical samples (use libgazebo_ros_block_laser.so or "
                                 "libgazebo_ros_velodyne_laser.so for a 3D scan)");
  }
  bool Advertise() override { return AdvertiseListened<sensor_msgs::LaserScan>(&pub_); }
  void Publish(const RayScan& scan, const ros::Time& stamp) override {
    if (pub_.getNumSubscribers() == 0) return;  // nobody on ROS, no in-process reader
    sensor_msgs::LaserScanPtr msg(new sensor_msgs::LaserScan);
    const double rate = sensor_->UpdateRate();
    ToLaserScanMsg(scan, sensor_->Spec(), rate > 0 ? 1.0 / rate : 0.0, sensor_->ScanOverTime(), msg.get());
    msg->header.stamp = stamp;
    msg->header.frame_id = frame_;
    pub_.publish(msg);
  }

 private:
  rotors_sim::ListenedPublisher pub_;
};

}  // namespace rotors_gazebo_plugins

RSIM_REGISTER_SENSOR_PLUGIN(rotors_gazebo_plugins::GazeboRosLaser)
