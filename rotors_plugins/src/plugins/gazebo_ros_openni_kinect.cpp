// libgazebo_ros_openni_kinect.so (gazebo_ros' Kinect plugin) on a <sensor type="depth">:
//   <cameraName>/<imageTopicName> + <cameraInfoTopicName>            the camera's image
//   <cameraName>/<depthImageTopicName> + <depthImageCameraInfoTopicName>  32FC1 depth [m]
//   <cameraName>/<pointCloudTopicName>                               PointCloud2 (x y z, optical frame)
//   <cameraName>/<disparityTopicName> (ours, when given)             stereo_msgs/DisparityImage, d = f b / Z
// Depth outside [pointCloudCutoff, pointCloudCutoffMax] is NaN. RotorS' VI-sensor names its depth
// image topic "depth/disparity"; it carries depth in metres there too, as in Gazebo.
#include "rotors_core/error.h"
#include "rotors_core/plugin.h"
#include "rotors_gazebo_plugins/ros/camera_ros.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"

namespace rotors_gazebo_plugins {

class GazeboRosOpenniKinect : public rotors_sim::SensorPlugin {
 public:
  void Load(rotors_sim::sensors::SensorPtr sensor, sdf::ElementPtr sdf) override {
    sensor_ = std::dynamic_pointer_cast<rotors_sim::sensors::CameraSensor>(sensor);
    if (!sensor_ || !sensor_->IsDepth())
      throw rotors_sim::SimError("libgazebo_ros_openni_kinect.so belongs in a <sensor type=\"depth\">, not type '" +
                                 sensor->Type() + "'");
    params_ = CameraRosParams::Read(sdf, *sensor_, true);
    limiter_ = RateLimiter(params_.update_rate_hz);
    node_ = MakeNode(params_.robot_namespace);
    if (!node_) return;
    const std::string frame = !params_.frame_name.empty()
                                  ? params_.frame_name
                                  : JoinTopic(JoinTopic(params_.robot_namespace, params_.camera_name), "camera_optical_link");
    const std::string& prefix = params_.camera_name;
    image_ = std::make_unique<CameraChannel>(*node_, params_, prefix, 0, sensor_->Camera(0), frame, 0.0);
    depth_pub_ = node_->advertise<sensor_msgs::Image>(JoinTopic(prefix, params_.depth_topic), 2);
    depth_info_pub_ = node_->advertise<sensor_msgs::CameraInfo>(JoinTopic(prefix, params_.depth_info_topic), 2);
    points_pub_ = node_->advertise<sensor_msgs::PointCloud2>(JoinTopic(prefix, params_.points_topic), 2);
    if (!params_.disparity_topic.empty())
      disparity_pub_ = node_->advertise<stereo_msgs::DisparityImage>(JoinTopic(prefix, params_.disparity_topic), 2);
    depth_info_ = CameraInfoMsg(sensor_->Camera(0), params_.baseline_m);
    depth_info_.header.frame_id = frame;
    connection_ = sensor_->ConnectUpdated([this] { OnUpdate(); });
  }

 private:
  void OnUpdate() {
    if (!limiter_.Due(sensor_->LastUpdateTime().Double())) return;
    const ros::Time stamp = ToRos(sensor_->LastUpdateTime());
    image_->Publish(*sensor_, stamp);
    depth_info_.header.stamp = stamp;
    depth_info_pub_.publish(depth_info_);
    const double min_m = params_.cloud_cutoff_min_m, max_m = params_.cloud_cutoff_max_m;
    if (depth_pub_.getNumSubscribers() > 0) {
      sensor_msgs::ImagePtr depth(new sensor_msgs::Image);
      ToDepthMsg(sensor_->Frame(0), min_m, max_m, depth.get());
      depth->header = depth_info_.header;
      depth_pub_.publish(depth);
    }
    if (points_pub_.getNumSubscribers() > 0) {
      sensor_msgs::PointCloud2Ptr cloud(new sensor_msgs::PointCloud2);
      ToCloudMsg(sensor_->Frame(0), sensor_->Camera(0), min_m, max_m, cloud.get());
      cloud->header = depth_info_.header;
      points_pub_.publish(cloud);
    }
    if (disparity_pub_ && disparity_pub_.getNumSubscribers() > 0) {
      stereo_msgs::DisparityImagePtr disparity(new stereo_msgs::DisparityImage);
      ToDisparityMsg(sensor_->Frame(0), sensor_->Camera(0), params_.baseline_m, min_m, max_m, disparity.get());
      disparity->header = disparity->image.header = depth_info_.header;
      disparity_pub_.publish(disparity);
    }
  }

  rotors_sim::sensors::CameraSensorPtr sensor_;
  CameraRosParams params_;
  std::shared_ptr<ros::NodeHandle> node_;
  std::unique_ptr<CameraChannel> image_;
  ros::Publisher depth_pub_, depth_info_pub_, points_pub_, disparity_pub_;
  sensor_msgs::CameraInfo depth_info_;
  RateLimiter limiter_{0.0};
  rotors_sim::event::ConnectionPtr connection_;
};

}  // namespace rotors_gazebo_plugins

RSIM_REGISTER_SENSOR_PLUGIN(rotors_gazebo_plugins::GazeboRosOpenniKinect)
