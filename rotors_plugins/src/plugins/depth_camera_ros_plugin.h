// The depth-camera plugins' common part: on a <sensor type="depth">, publishes
//   <cameraName>/<imageTopicName> + <cameraInfoTopicName>                the camera's image
//   <cameraName>/<depthImageTopicName> + <depthImageCameraInfoTopicName>  32FC1 depth [m]
//   <cameraName>/<pointCloudTopicName>                                   PointCloud2 (x y z, optical frame)
//   <cameraName>/<disparityTopicName> (ours, when given)                 stereo_msgs/DisparityImage, d = f b / Z
// with depth outside [pointCloudCutoff, pointCloudCutoffMax] as NaN. Subclasses choose the
// parameters' defaults and may add noise to the depth.
#pragma once

#include "rotors_core/error.h"
#include "rotors_core/plugin.h"
#include "rotors_gazebo_plugins/ros/camera_ros.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"

namespace rotors_gazebo_plugins {

class DepthCameraRosPlugin : public rotors_sim::SensorPlugin {
 public:
  void Load(rotors_sim::sensors::SensorPtr sensor, sdf::ElementPtr /*sdf*/) override {
    sensor_ = std::dynamic_pointer_cast<rotors_sim::sensors::CameraSensor>(sensor);
    if (!sensor_ || !sensor_->IsDepth())
      throw rotors_sim::SimError(GetFilename() + " belongs in a <sensor type=\"depth\">, not type '" + sensor->Type() +
                                 "'");
    params_ = ReadParams(Params());
    params_.Apply(*sensor_);
    limiter_ = RateLimiter(params_.update_rate_hz);
    node_ = MakeNode(params_.robot_namespace);
    if (!node_) return;
    const std::string frame =
        !params_.frame_name.empty()
            ? params_.frame_name
            : JoinTopic(JoinTopic(params_.robot_namespace, params_.camera_name), "camera_optical_link");
    const std::string& prefix = params_.camera_name;
    image_ =
        std::make_unique<CameraChannel>(node_, WorldOf(*sensor_), params_, prefix, 0, sensor_->Camera(0), frame, 0.0);
    depth_pub_ = node_->advertise<sensor_msgs::Image>(JoinTopic(prefix, params_.depth_topic), 2);
    depth_info_pub_ = node_->advertise<sensor_msgs::CameraInfo>(JoinTopic(prefix, params_.depth_info_topic), 2);
    points_pub_ = node_->advertise<sensor_msgs::PointCloud2>(JoinTopic(prefix, params_.points_topic), 2);
    if (!params_.disparity_topic.empty())
      disparity_pub_ = node_->advertise<stereo_msgs::DisparityImage>(JoinTopic(prefix, params_.disparity_topic), 2);
    depth_info_ = CameraInfoMsg(sensor_->Camera(0), params_.baseline_m);
    depth_info_.header.frame_id = frame;
    connection_ = sensor_->ConnectUpdated([this] { OnUpdate(); });
  }

 protected:
  /// The plugin's parameters (defaults and extra parameters differ between depth plugins).
  virtual CameraRosParams ReadParams(rotors_sim::SdfParams& params) {
    return CameraRosParams::Read(params, *sensor_, true);
  }
  /// The depth the messages carry: the rendered one, or a noisy copy in `scratch`.
  virtual const rotors_sim::rendering::RenderedFrame& Measured(const rotors_sim::rendering::RenderedFrame& rendered,
                                                               rotors_sim::rendering::RenderedFrame* /*scratch*/) {
    return rendered;
  }

  rotors_sim::sensors::CameraSensorPtr sensor_;

 private:
  void OnUpdate() {
    if (!limiter_.Due(sensor_->LastUpdateTime().Double())) return;
    const ros::Time stamp = ToRos(sensor_->LastUpdateTime());
    image_->Publish(*sensor_, stamp);
    depth_info_.header.stamp = stamp;
    depth_info_pub_.publish(depth_info_);
    const double min_m = params_.cloud_cutoff_min_m, max_m = params_.cloud_cutoff_max_m;
    const bool depth_wanted = depth_pub_.getNumSubscribers() > 0 || points_pub_.getNumSubscribers() > 0 ||
                              (disparity_pub_ && disparity_pub_.getNumSubscribers() > 0);
    if (!depth_wanted) return;
    const rotors_sim::rendering::RenderedFrame& frame = Measured(sensor_->Frame(0), &scratch_);
    if (depth_pub_.getNumSubscribers() > 0) {
      sensor_msgs::ImagePtr depth(new sensor_msgs::Image);
      ToDepthMsg(frame, min_m, max_m, depth.get());
      depth->header = depth_info_.header;
      depth_pub_.publish(depth);
    }
    if (points_pub_.getNumSubscribers() > 0) {
      sensor_msgs::PointCloud2Ptr cloud(new sensor_msgs::PointCloud2);
      ToCloudMsg(frame, sensor_->Camera(0), min_m, max_m, cloud.get());
      cloud->header = depth_info_.header;
      points_pub_.publish(cloud);
    }
    if (disparity_pub_ && disparity_pub_.getNumSubscribers() > 0) {
      stereo_msgs::DisparityImagePtr disparity(new stereo_msgs::DisparityImage);
      ToDisparityMsg(frame, sensor_->Camera(0), params_.baseline_m, min_m, max_m, disparity.get());
      disparity->header = disparity->image.header = depth_info_.header;
      disparity_pub_.publish(disparity);
    }
  }

  CameraRosParams params_;
  rotors_sim::rendering::RenderedFrame scratch_;
  std::shared_ptr<ros::NodeHandle> node_;
  std::unique_ptr<CameraChannel> image_;
  ros::Publisher depth_pub_, depth_info_pub_, points_pub_, disparity_pub_;
  sensor_msgs::CameraInfo depth_info_;
  RateLimiter limiter_{0.0};
  rotors_sim::event::ConnectionPtr connection_;
};

}  // namespace rotors_gazebo_plugins
