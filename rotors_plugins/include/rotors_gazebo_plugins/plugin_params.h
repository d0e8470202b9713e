// Parameter helpers shared by all RotorS plugins: typed reads, Eigen vectors, and a check that
// every <plugin> child element is one the plugin reads (a misspelt name is an error, not a
// silently ignored value as in RotorS issue #336).
#pragma once

#include <initializer_list>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <ignition/math/Vector3.hh>

#include "rotors_core/physics/physics_types.h"
#include "rotors_core/sdf_params.h"

namespace rotors_gazebo_plugins {

using rotors_sim::ReadParam;
using rotors_sim::RequireParam;

/// Reads "x y z" into an Eigen vector.
bool ReadVector(const sdf::ElementPtr& sdf, const std::string& name, Eigen::Vector3d* value);

/// Throws SimError naming the first child element not in `known`.
void CheckKnownParams(const sdf::ElementPtr& sdf, std::initializer_list<const char*> known);
void CheckKnownParams(const sdf::ElementPtr& sdf, const std::vector<std::string>& known);

/// Throws SimError("<what>") if `why` is not empty (for Params::Validate()).
void ThrowIfInvalid(const std::string& why);

/// The <robotNamespace> (required), without leading or trailing '/'.
std::string ReadRobotNamespace(const sdf::ElementPtr& sdf);

/// The link / joint of that name, or SimError("<param> 'name' is not a link of model 'm'").
rotors_sim::physics::LinkPtr RequireLink(const rotors_sim::physics::ModelPtr& model, const std::string& name,
                                         const char* param = "linkName");
rotors_sim::physics::JointPtr RequireJoint(const rotors_sim::physics::ModelPtr& model, const std::string& name,
                                           const char* param = "jointName");

/// Seed from <randomEngineSeed> if given, else from the clock; returns the seed used.
uint64_t ReadSeed(const sdf::ElementPtr& sdf);

}  // namespace rotors_gazebo_plugins
