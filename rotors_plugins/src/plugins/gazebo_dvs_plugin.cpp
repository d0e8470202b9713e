// librotors_gazebo_dvs_plugin.so (ours): an event camera on a <sensor type="camera"> with
// <update_rate> 0 (it looks at every physics step). It renders adaptively, as ESIM does: whenever
// the image may have moved <pixelsPerRender> pixels since the last render (the camera's twist, the
// last render's near depth) or <maxRenderInterval> has passed; EventCameraModel turns each render
// into events between it and the one before. Publishes <ns>/<cameraName>/<eventsTopicName>
// (dvs_msgs/EventArray, rpg_dvs_ros' message) at <eventsRate>, and image_raw / camera_info at
// <imageRate> (the frames event pipelines expect beside the events). Renders only while someone
// listens to the events.
#include <dvs_msgs/EventArray.h>

#include <algorithm>
#include <cmath>

#include "rotors_core/error.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/plugin.h"
#include "rotors_gazebo_plugins/models/event_camera_model.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/ros/camera_ros.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"

namespace rotors_gazebo_plugins {

class GazeboDvsPlugin : public rotors_sim::SensorPlugin {
 public:
  void Load(rotors_sim::sensors::SensorPtr sensor, sdf::ElementPtr /*sdf*/) override {
    sensor_ = std::dynamic_pointer_cast<rotors_sim::sensors::CameraSensor>(sensor);
    if (!sensor_ || sensor_->Type() != "camera")
      throw rotors_sim::SimError("librotors_gazebo_dvs_plugin.so belongs in a <sensor type=\"camera\">, not type '" +
                                 sensor->Type() + "'");
    if (sensor_->UpdateRate() != 0.0)
      throw rotors_sim::SimError(
          "an event camera's <sensor> needs <update_rate>0</update_rate> (it looks at every "
          "physics step and renders when the image has moved), not " +
          std::to_string(sensor_->UpdateRate()));
    EventCameraParams p;
    ReadParam(Params(), "contrastThresholdPositive", &p.contrast_threshold_pos);
    ReadParam(Params(), "contrastThresholdNegative", &p.contrast_threshold_neg);
    ReadParam(Params(), "contrastThresholdSigma", &p.contrast_threshold_sigma);
    ReadParam(Params(), "refractoryPeriod", &p.refractory_period_s);
    ReadParam(Params(), "logEpsilon", &p.log_epsilon);
    ThrowIfInvalid(p.Validate());
    std::string events_topic = "events";
    double image_rate_hz = 30.0;
    ReadParam(Params(), "eventsTopicName", &events_topic);
    ReadParam(Params(), "eventsRate", &events_rate_hz_);
    ReadParam(Params(), "imageRate", &image_rate_hz);
    ReadParam(Params(), "pixelsPerRender", &pixels_per_render_);
    ReadParam(Params(), "maxRenderInterval", &max_render_interval_s_);
    if (!(events_rate_hz_ > 0.0) || !(image_rate_hz > 0.0) || !(pixels_per_render_ > 0.0) ||
        !(max_render_interval_s_ > 0.0))
      throw rotors_sim::SimError("eventsRate, imageRate, pixelsPerRender and maxRenderInterval must be > 0");
    const CameraRosParams params = CameraRosParams::Read(Params(), *sensor_, false);
    if (sensor_->Camera(0).format == rotors_sim::rendering::PixelFormat::kB8G8R8 ||
        sensor_->Camera(0).format == rotors_sim::rendering::PixelFormat::kR8G8B8)
      channels_ = 3;
    const auto& in = sensor_->Camera(0).intrinsics;
    model_ = std::make_unique<EventCameraModel>(p, in.width_px, in.height_px, ReadSeed(Params()));
    sensor_->SetGroundTruthDepth(true);  // the near depth for the adaptive sampling
    image_limiter_ = RateLimiter(image_rate_hz);
    node_ = MakeNode(params.robot_namespace);
    if (!node_) return;
    const std::string frame =
        !params.frame_name.empty()
            ? params.frame_name
            : JoinTopic(JoinTopic(params.robot_namespace, params.camera_name), "camera_optical_link");
    msg_.header.frame_id = frame;
    msg_.width = in.width_px;
    msg_.height = in.height_px;
    events_pub_ = node_->advertise<dvs_msgs::EventArray>(JoinTopic(params.camera_name, events_topic), 10);
    channel_ = std::make_unique<CameraChannel>(node_, WorldOf(*sensor_), params, params.camera_name, 0,
                                               sensor_->Camera(0), frame, 0.0);
    connection_ = sensor_->ConnectUpdated([this] { OnStep(); });
  }

  void Reset() override {
    model_->Reset();
    msg_.events.clear();
    next_publish_s_ = 0.0;
  }

 private:
  void OnStep() {
    const double t = sensor_->LastUpdateTime().Double();
    if (image_limiter_.Due(t)) channel_->Publish(*sensor_, ToRos(sensor_->LastUpdateTime()));
    if (events_pub_.getNumSubscribers() == 0) {
      model_->Reset();  // nobody listens: no renders; the next listener starts from a fresh render
      return;
    }
    // adaptive sampling: the image's fastest point's speed bound, as the image sensor's exposure plan
    const auto& in = sensor_->Camera(0).intrinsics;
    const auto link = sensor_->ParentLink();
    const double speed_px_s = in.ImageSpeedBoundPxS(link->WorldAngularVel().Length(), link->WorldLinearVel().Length(),
                                                    std::max(near_depth_m_, in.near_m));
    moved_px_ += speed_px_s * (t - last_step_s_);
    last_step_s_ = t;
    if (!model_->Started() || moved_px_ >= pixels_per_render_ || t - last_render_s_ >= max_render_interval_s_) {
      const rotors_sim::rendering::RenderedFrame& frame = sensor_->Frame(0);
      grey_.resize(static_cast<size_t>(frame.width_px) * frame.height_px);
      for (size_t i = 0; i < grey_.size(); ++i) {  // Rec. 601 luma of a colour camera
        const uint8_t* px = frame.image.data() + i * channels_;
        grey_[i] = channels_ == 1 ? px[0] : static_cast<uint8_t>(0.299 * px[0] + 0.587 * px[1] + 0.114 * px[2] + 0.5);
      }
      events_.clear();
      model_->Process(grey_, t, &events_);
      for (const DvsEvent& e : events_) {
        dvs_msgs::Event event;
        event.x = e.x;
        event.y = e.y;
        event.ts = ros::Time(std::max(e.t_s, 0.0));
        event.polarity = e.polarity;
        msg_.events.push_back(event);
      }
      float nearest = in.far_m;
      for (size_t i = 0; i < frame.depth_m.size(); i += 17)
        if (std::isfinite(frame.depth_m[i])) nearest = std::min(nearest, frame.depth_m[i]);
      near_depth_m_ = nearest;
      moved_px_ = 0.0;
      last_render_s_ = t;
    }
    if (t >= next_publish_s_) {
      msg_.header.stamp = ToRos(sensor_->LastUpdateTime());
      events_pub_.publish(msg_);
      msg_.events.clear();
      next_publish_s_ = t + 1.0 / events_rate_hz_;
    }
  }

  rotors_sim::sensors::CameraSensorPtr sensor_;
  std::unique_ptr<EventCameraModel> model_;
  std::shared_ptr<ros::NodeHandle> node_;
  ros::Publisher events_pub_;
  std::unique_ptr<CameraChannel> channel_;
  RateLimiter image_limiter_{30.0};
  dvs_msgs::EventArray msg_;
  std::vector<uint8_t> grey_;
  std::vector<DvsEvent> events_;
  int channels_ = 1;
  double events_rate_hz_ = 30.0, pixels_per_render_ = 1.0, max_render_interval_s_ = 0.01;
  double moved_px_ = 0.0, last_step_s_ = 0.0, last_render_s_ = 0.0, next_publish_s_ = 0.0, near_depth_m_ = 1.0;
  rotors_sim::event::ConnectionPtr connection_;
};

}  // namespace rotors_gazebo_plugins

RSIM_REGISTER_SENSOR_PLUGIN(rotors_gazebo_plugins::GazeboDvsPlugin)
