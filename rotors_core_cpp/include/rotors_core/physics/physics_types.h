// Shared pointers of the physics layer, named as in gazebo::physics.
#pragma once

#include <memory>
#include <vector>

#include <ignition/math/Pose3.hh>
#include <ignition/math/Vector3.hh>

namespace rotors_sim {
namespace physics {

class World;
class Model;
class Link;
class Joint;
using WorldPtr = std::shared_ptr<World>;
using ModelPtr = std::shared_ptr<Model>;
using LinkPtr = std::shared_ptr<Link>;
using JointPtr = std::shared_ptr<Joint>;
using Link_V = std::vector<LinkPtr>;
using Joint_V = std::vector<JointPtr>;

using Pose3d = ignition::math::Pose3d;
using Vector3d = ignition::math::Vector3d;
using Quaterniond = ignition::math::Quaterniond;

}  // namespace physics
}  // namespace rotors_sim
