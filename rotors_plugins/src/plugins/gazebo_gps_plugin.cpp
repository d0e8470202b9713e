// librotors_gazebo_gps_plugin.so (rotors_reference.md 4.9): a SensorPlugin in a <sensor type="gps">,
// updated at the sensor's <update_rate>. Publishes <ns>/<gpsTopic> (sensor_msgs/NavSatFix: WGS84 at the
// world's <spherical_coordinates>, fix, GPS service, covariance diag(h^2, h^2, v^2)) and
// <ns>/<groundSpeedTopic> (geometry_msgs/TwistStamped, world-frame velocity), both noisy with the
// plugin's standard deviations and stamped with the sensor's update time.
#include <geometry_msgs/TwistStamped.h>
#include <sensor_msgs/NavSatFix.h>

#include "rotors_core/ros/publish_counts.h"
#include "rotors_core/ros/listened_publisher.h"
#include "rotors_core/error.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/plugin.h"
#include "rotors_gazebo_plugins/models/navigation_sensor_models.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/seeded_model.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"

namespace rotors_gazebo_plugins {

class GazeboGpsPlugin : public rotors_sim::SensorPlugin {
 public:
  void Load(rotors_sim::sensors::SensorPtr sensor, sdf::ElementPtr /*sdf*/) override {
    if (sensor->Type() != "gps" && sensor->Type() != "navsat")
      throw rotors_sim::SimError("librotors_gazebo_gps_plugin.so belongs in a <sensor type=\"gps\">, not type '" +
                                 sensor->Type() + "'");
    const std::string ns = ReadRobotNamespace(Params());
    std::string gps_topic = "gps", ground_speed_topic = "ground_speed", link_name;
    ReadParam(Params(), "gpsTopic", &gps_topic);
    ReadParam(Params(), "groundSpeedTopic", &ground_speed_topic);
    if (ReadParam(Params(), "linkName", &link_name) && link_name != sensor->ParentName())
      throw rotors_sim::SimError("<linkName> '" + link_name + "' is not the sensor's link '" + sensor->ParentName() +
                                 "'");
    GpsParams p;
    ReadParam(Params(), "horPosStdDev", &p.hor_pos_std_dev_m);
    ReadParam(Params(), "verPosStdDev", &p.ver_pos_std_dev_m);
    ReadParam(Params(), "horVelStdDev", &p.hor_vel_std_dev_m_s);
    ReadParam(Params(), "verVelStdDev", &p.ver_vel_std_dev_m_s);
    ThrowIfInvalid(p.Validate());
    sensor_ = sensor;
    const auto& o = sensor->ParentLink()->GetModel()->GetWorldRaw()->Origin();
    model_.Emplace(p, GeodeticOrigin{o.latitude_deg, o.longitude_deg, o.elevation_m, o.heading_deg},
                   ReadSeed(Params()));
    fix_.header.frame_id = sensor->ParentName();
    fix_.status.status = sensor_msgs::NavSatStatus::STATUS_FIX;
    fix_.status.service = sensor_msgs::NavSatStatus::SERVICE_GPS;
    fix_.position_covariance_type = sensor_msgs::NavSatFix::COVARIANCE_TYPE_DIAGONAL_KNOWN;
    fix_.position_covariance[0] = fix_.position_covariance[4] = p.hor_pos_std_dev_m * p.hor_pos_std_dev_m;
    fix_.position_covariance[8] = p.ver_pos_std_dev_m * p.ver_pos_std_dev_m;
    node_ = MakeNode(ns);
    gps_pub_ =
        Advertise<sensor_msgs::NavSatFix>(node_, ns, gps_topic, *sensor->ParentLink()->GetModel()->GetWorldRaw(), 10);
    ground_speed_pub_ = Advertise<geometry_msgs::TwistStamped>(node_, ns, ground_speed_topic,
                                                               *sensor->ParentLink()->GetModel()->GetWorldRaw(), 10);
    if (!gps_pub_) return;  // neither ROS nor in-process taps: nobody to publish to
    connection_ = sensor->ConnectUpdated([this] { OnUpdate(); });
  }

  void Reset() override { model_.Reset(); }

 private:
  void OnUpdate() {
    const auto X_WS = sensor_->WorldPose();
    const auto v_W = sensor_->ParentLink()->WorldLinearVel();
    const GpsSample m = model_->Measure({X_WS.Pos().X(), X_WS.Pos().Y(), X_WS.Pos().Z()}, {v_W.X(), v_W.Y(), v_W.Z()});
    fix_.header.stamp = ToRos(sensor_->LastUpdateTime());
    fix_.latitude = m.latitude_longitude_altitude.x();
    fix_.longitude = m.latitude_longitude_altitude.y();
    fix_.altitude = m.latitude_longitude_altitude.z();
    gps_pub_.publish(fix_);
    geometry_msgs::TwistStamped speed;
    speed.header = fix_.header;
    speed.twist.linear = ToVector3Msg(m.ground_speed_W);
    ground_speed_pub_.publish(speed);
  }

  rotors_sim::sensors::SensorPtr sensor_;
  SeededModel<GpsModel> model_;
  sensor_msgs::NavSatFix fix_;
  std::shared_ptr<ros::NodeHandle> node_;
  // ListenedPublisher: no search through every topic per step
  rotors_sim::ListenedPublisher gps_pub_, ground_speed_pub_;
  rotors_sim::event::ConnectionPtr connection_;
};

}  // namespace rotors_gazebo_plugins

RSIM_REGISTER_SENSOR_PLUGIN(rotors_gazebo_plugins::GazeboGpsPlugin)
