// librotors_gazebo_wind_plugin.so (reference section 4.6): wind speed that acts through the rotor
// model (airspeed, eqs. 2-3) and RotorS' force-on-link mode with a timed gust. The variance
// parameters are used (seeded); RotorS ignored them. Publishes wind_speed and external_force.
// The wind speed, in order of precedence:
//   1. RotorS' custom static wind field (useCustomStaticWindField, customWindFieldPath: hemicyl
//      format, trilinear on its terrain-following grid) where the link is inside the grid;
//   2. ours: the last rotors_comm/WindSpeed received on <windSpeedSubTopic> (an external wind
//      generator drives it);
//   3. ours: <windProfilePath>, a "t vx vy vz" file interpolated in sim time;
//   4. windSpeedMean (+ variance) along windDirection.
#include <geometry_msgs/WrenchStamped.h>
#include <rotors_comm/WindSpeed.h>

#include <optional>

#include "rotors_core/ros/publish_counts.h"
#include "rotors_core/ros/listened_publisher.h"
#include "rotors_core/error.h"
#include "rotors_core/geometry/uri_resolver.h"
#include "rotors_core/event.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/plugin.h"
#include "rotors_gazebo_plugins/models/wind_field.h"
#include "rotors_gazebo_plugins/models/wind_model.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/seeded_model.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"
#include "rotors_gazebo_plugins/vehicle_bus.h"

namespace rotors_gazebo_plugins {

class GazeboWindPlugin : public rotors_sim::ModelPlugin {
 public:
  void Load(rotors_sim::physics::ModelPtr model, sdf::ElementPtr /*sdf*/) override {
    namespace_ = ReadRobotNamespace(Params());
    std::string link_name = "base_link", force_topic = "external_force", speed_topic = "wind_speed";
    Eigen::Vector3d offset = Eigen::Vector3d::Zero();
    bool custom_field = false;
    ReadParam(Params(), "linkName", &link_name);
    ReadParam(Params(), "frameId", &frame_id_);
    ReadParam(Params(), "windForcePubTopic", &force_topic);
    ReadParam(Params(), "windSpeedPubTopic", &speed_topic);
    if (!ReadVector(Params(), "xyzOffset", &offset))
      throw rotors_sim::SimError("missing required parameter <xyzOffset>");
    ReadParam(Params(), "useCustomStaticWindField", &custom_field);
    std::string field_path, profile_path, speed_sub_topic;
    ReadParam(Params(), "customWindFieldPath", &field_path);
    ReadParam(Params(), "windProfilePath", &profile_path);
    ReadParam(Params(), "windSpeedSubTopic", &speed_sub_topic);
    if (custom_field && field_path.empty())
      throw rotors_sim::SimError("useCustomStaticWindField = true needs <customWindFieldPath>");
    if (!custom_field && !field_path.empty())
      ROS_WARN("[wind_plugin] %s: <customWindFieldPath> '%s' is not used: <useCustomStaticWindField> is false",
               namespace_.c_str(), field_path.c_str());
    try {
      if (custom_field) field_ = std::make_shared<const WindField>(WindField::Load(ResolvePath(field_path)));
      if (!profile_path.empty())
        profile_ = std::make_shared<const WindProfile>(WindProfile::Load(ResolvePath(profile_path)));
    } catch (const std::runtime_error& e) {
      throw rotors_sim::SimError(e.what());
    }
    const WindParams p = ReadWindParams(Params());
    const uint64_t seed = ReadSeed(Params());
    wind_.Emplace(p, seed);
    link_ = RequireLink(model, link_name);
    offset_L_ = {offset.x(), offset.y(), offset.z()};
    world_ = model->GetWorldRaw();
    bus_ = VehicleBus::For(*model->GetWorldRaw(), namespace_);
    bus_->Register(this, WindRecord{p, seed, link_name, offset, speed_sub_topic, field_, profile_});
    node_ = MakeNode(namespace_);
    force_pub_ = Advertise<geometry_msgs::WrenchStamped>(node_, namespace_, force_topic, *model->GetWorldRaw(), 10);
    speed_pub_ = Advertise<rotors_comm::WindSpeed>(node_, namespace_, speed_topic, *model->GetWorldRaw(), 10);
    if (node_) {
      if (!speed_sub_topic.empty())
        speed_sub_ = node_->subscribe(speed_sub_topic, 1, &GazeboWindPlugin::OnWindSpeed, this);
    }
    connection_ = rotors_sim::event::Events::ConnectWorldUpdateBegin(
        [this](const rotors_sim::common::UpdateInfo& info) { OnUpdate(info); });
  }

  /// The gusts drawn again from the seed; an external wind received before is forgotten.
  void Reset() override {
    wind_.Reset();
    external_speed_W_.reset();
  }

 private:
  /// "package://", absolute, or (as RotorS) relative to the simulator's working directory.
  static std::string ResolvePath(const std::string& path) {
    return path.rfind("package://", 0) == 0 ? rotors_sim::geometry::UriResolver::Resolve(path) : path;
  }

  void OnWindSpeed(const rotors_comm::WindSpeedConstPtr& msg) {
    const Eigen::Vector3d v(msg->velocity.x, msg->velocity.y, msg->velocity.z);
    if (!v.allFinite()) {
      ROS_ERROR_THROTTLE(1.0, "[wind_plugin] %s: ignoring a wind speed with NaN or inf", namespace_.c_str());
      return;
    }
    external_speed_W_ = v;
  }

  void OnUpdate(const rotors_sim::common::UpdateInfo& info) {
    WindSample s = wind_->Sample(info.simTime.Double());
    if (external_speed_W_) {
      s.velocity_W = *external_speed_W_;
    } else if (profile_) {
      s.velocity_W = profile_->Velocity(info.simTime.Double());
    }
    if (field_) {
      const auto p = link_->WorldPose().Pos();
      Eigen::Vector3d v_field;
      if (field_->Velocity({p.X(), p.Y(), p.Z()}, &v_field)) s.velocity_W = v_field;
    }
    bus_->wind_velocity_W = s.velocity_W;
    const rotors_sim::physics::Vector3d force_W(s.force_W.x(), s.force_W.y(), s.force_W.z());
    if (force_W != rotors_sim::physics::Vector3d::Zero) link_->AddForceAtRelativePosition(force_W, offset_L_);
    if (!force_pub_) return;
    const ros::Time stamp = ToRos(info.simTime);
    geometry_msgs::WrenchStamped wrench;
    wrench.header.stamp = stamp;
    wrench.header.frame_id = frame_id_;
    wrench.wrench.force = ToVector3Msg(s.force_W);
    force_pub_.publish(wrench);
    rotors_comm::WindSpeed speed;
    speed.header = wrench.header;
    speed.velocity = ToVector3Msg(s.velocity_W);
    speed_pub_.publish(speed);
  }

  std::string namespace_, frame_id_ = "world";
  rotors_sim::physics::Vector3d offset_L_;
  SeededModel<WindModel> wind_;
  std::shared_ptr<const WindField> field_;      ///< shared with its record on the bus
  std::shared_ptr<const WindProfile> profile_;  ///< shared with its record on the bus
  std::optional<Eigen::Vector3d> external_speed_W_;
  rotors_sim::physics::LinkPtr link_;
  rotors_sim::physics::World* world_ = nullptr;
  std::shared_ptr<VehicleBus> bus_;  ///< shared by the vehicle's plugins
  std::shared_ptr<ros::NodeHandle> node_;
  // ListenedPublisher: no search through every topic per step
  rotors_sim::ListenedPublisher force_pub_, speed_pub_;
  ros::Subscriber speed_sub_;
  rotors_sim::event::ConnectionPtr connection_;
};

}  // namespace rotors_gazebo_plugins

GZ_REGISTER_MODEL_PLUGIN(rotors_gazebo_plugins::GazeboWindPlugin)
