// libgazebo_ros_velodyne_laser.so and libgazebo_ros_velodyne_gpu_laser.so (velodyne_simulator's
// plugins): a spinning lidar's sweep as sensor_msgs/PointCloud2 with velodyne_pointcloud's fields
// x y z intensity ring time, on <robotNamespace>/<topicName> (default "points"), frame <frameName>.
// Parameters as velodyne_simulator names them: <min_range>, <max_range> [m] (returns outside are
// dropped), <gaussianNoise> [m], <min_intensity>, <organize_cloud> (rings x columns, NaN where no
// return). The sweep is cast over time (each column from the pose at its time, `time` = seconds
// since the header stamp, the sweep's start) unless <instantaneous_scan> is true.
#include "rotors_core/error.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/ros/laser_ros.h"

namespace rotors_gazebo_plugins {

class GazeboRosVelodyneLaser : public LaserPlugin {
 protected:
  std::string DefaultTopic() const override { return "points"; }
  void Configure(rotors_sim::SdfParams& params) override {
    ReadParam(params, "min_range", &options_.min_range_m);
    ReadParam(params, "max_range", &options_.max_range_m);
    ReadParam(params, "min_intensity", &options_.min_intensity);
    ReadParam(params, "organize_cloud", &options_.organize);
    ReadParam(params, "gaussianNoise", &noise_m_);
    if (!(options_.min_range_m >= 0.0) || !(options_.max_range_m > options_.min_range_m))
      throw rotors_sim::SimError("<min_range> " + std::to_string(options_.min_range_m) + " m must be >= 0 and below " +
                                 "<max_range> " + std::to_string(options_.max_range_m) + " m");
    if (!(noise_m_ >= 0.0)) throw rotors_sim::SimError("<gaussianNoise> must be >= 0 m");
    bool instantaneous = false;
    ReadParam(params, "instantaneous_scan", &instantaneous);
    sensor_->SetScanOverTime(!instantaneous);
  }
  bool Advertise() override { return AdvertiseListened<sensor_msgs::PointCloud2>(&pub_); }
  void Publish(const RayScan& scan, const ros::Time& stamp) override {
    if (pub_.getNumSubscribers() == 0) return;
    sensor_msgs::PointCloud2Ptr msg(new sensor_msgs::PointCloud2);
    if (noise_m_ > 0.0) {
      RayScan noisy = scan;
      AddRangeNoise(noise_m_, &rng_, &noisy);
      ToVelodyneCloudMsg(noisy, sensor_->Spec(), sensor_->BeamDirections_S(), options_, msg.get());
    } else {
      ToVelodyneCloudMsg(scan, sensor_->Spec(), sensor_->BeamDirections_S(), options_, msg.get());
    }
    msg->header.stamp = stamp;
    msg->header.frame_id = frame_;
    pub_.publish(msg);
  }

 private:
  VelodyneCloudOptions options_;
  double noise_m_ = 0.0;
  rotors_sim::ListenedPublisher pub_;
};

}  // namespace rotors_gazebo_plugins

RSIM_REGISTER_SENSOR_PLUGIN(rotors_gazebo_plugins::GazeboRosVelodyneLaser)
