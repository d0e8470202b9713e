#include "rotors_core/ros/state_publisher.h"

#include <gazebo_msgs/LinkStates.h>
#include <gazebo_msgs/ModelStates.h>
#include <geometry_msgs/TransformStamped.h>
#include <sensor_msgs/JointState.h>

#include "rotors_core/physics/joint.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/ros/msg_conversions.h"

namespace rotors_sim {

StatePublisher::StatePublisher(ros::NodeHandle nh, double rate_hz, double max_wall_rate_hz)
    : nh_(nh), period_s_(rate_hz > 0 ? 1.0 / rate_hz : 0.0), wall_limit_(max_wall_rate_hz) {
  model_states_pub_ = nh_.advertise<gazebo_msgs::ModelStates>("/gazebo/model_states", 1);
  link_states_pub_ = nh_.advertise<gazebo_msgs::LinkStates>("/gazebo/link_states", 1);
}

void StatePublisher::Update(const physics::World& world, bool force) {
  const double t = world.SimTime().Double();
  if (!force && (t - last_publish_s_ < period_s_ - 1e-9 || !wall_limit_.Due())) return;
  last_publish_s_ = t;
  ros::Time stamp;
  stamp.fromNSec(world.SimTime().Nanoseconds());

  // model and link states are built only for listeners; TF and joint states always (rviz)
  const bool want_models = model_states_pub_.getNumSubscribers() > 0;
  const bool want_links = link_states_pub_.getNumSubscribers() > 0;
  gazebo_msgs::ModelStates models;
  gazebo_msgs::LinkStates links;
  std::vector<geometry_msgs::TransformStamped> transforms;
  for (const auto& model : world.Models()) {
    if (want_models) {
      models.name.push_back(model->GetName());
      models.pose.push_back(PoseMsg(model->WorldPose()));
      models.twist.push_back(TwistMsg(model->WorldLinearVel(), model->WorldAngularVel()));
    }
    if (want_links) {
      for (const auto& link : model->GetLinks()) {
        links.name.push_back(model->GetName() + "::" + link->GetName());
        links.pose.push_back(PoseMsg(link->WorldPose()));
        links.twist.push_back(TwistMsg(link->WorldLinearVel(), link->WorldAngularVel()));
      }
    }
    if (model->IsStatic()) continue;

    geometry_msgs::TransformStamped tf;
    tf.header.stamp = stamp;
    tf.header.frame_id = "world";
    tf.child_frame_id = model->GetCanonicalLink()->GetName();
    const geometry_msgs::Pose p = PoseMsg(model->WorldPose());
    tf.transform.translation.x = p.position.x;
    tf.transform.translation.y = p.position.y;
    tf.transform.translation.z = p.position.z;
    tf.transform.rotation = p.orientation;
    transforms.push_back(tf);

    sensor_msgs::JointState js;
    js.header.stamp = stamp;
    for (const auto& joint : model->GetJoints()) {
      // welded joints (zero-range revolute in the URDF) report 0, so robot_state_publisher has them
      js.name.push_back(joint->GetName());
      js.position.push_back(joint->Position(0));
      js.velocity.push_back(joint->GetVelocity(0));
    }
    if (js.name.empty()) continue;
    auto it = joint_state_pubs_.find(model->GetName());
    if (it == joint_state_pubs_.end())
      it = joint_state_pubs_
               .emplace(model->GetName(),
                        nh_.advertise<sensor_msgs::JointState>("/" + model->GetName() + "/joint_states", 10))
               .first;
    it->second.publish(js);
  }
  if (!transforms.empty()) tf_broadcaster_.sendTransform(transforms);
  if (want_models) model_states_pub_.publish(models);
  if (want_links) link_states_pub_.publish(links);
}

}  // namespace rotors_sim
