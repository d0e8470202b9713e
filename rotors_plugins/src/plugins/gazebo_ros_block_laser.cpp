// libgazebo_ros_block_laser.so (gazebo_ros' block laser): every return of a 2D or 3D scan as
// sensor_msgs/PointCloud (channel "intensity") in the sensor frame, on <robotNamespace>/<topicName>
// (default "points"); <gaussianNoise> [m] adds range noise of its own.
#include "rotors_gazebo_plugins/ros/laser_ros.h"
#include "rotors_gazebo_plugins/plugin_params.h"

namespace rotors_gazebo_plugins {

class GazeboRosBlockLaser : public LaserPlugin {
 protected:
  std::string DefaultTopic() const override { return "points"; }
  void Configure(rotors_sim::SdfParams& params) override {
    ReadParam(params, "gaussianNoise", &noise_m_);
    if (!(noise_m_ >= 0.0)) throw rotors_sim::SimError("<gaussianNoise> must be >= 0 m");
  }
  bool Advertise() override { return AdvertiseListened<sensor_msgs::PointCloud>(&pub_); }
  void Publish(const RayScan& scan, const ros::Time& stamp) override {
    RayScan noisy = scan;
    AddRangeNoise(noise_m_, &rng_, &noisy);     // every scan: the noise sequence whoever listens
    if (pub_.getNumSubscribers() == 0) return;  // nobody on ROS, no in-process reader
    sensor_msgs::PointCloudPtr msg(new sensor_msgs::PointCloud);
    ToBlockCloudMsg(noisy, sensor_->Spec(), sensor_->BeamDirections_S(), msg.get());
    msg->header.stamp = stamp;
    msg->header.frame_id = frame_;
    pub_.publish(msg);
  }

 private:
  double noise_m_ = 0.0;
  rotors_sim::ListenedPublisher pub_;
};

}  // namespace rotors_gazebo_plugins

RSIM_REGISTER_SENSOR_PLUGIN(rotors_gazebo_plugins::GazeboRosBlockLaser)
