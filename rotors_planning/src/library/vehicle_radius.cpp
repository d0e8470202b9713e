#include "rotors_planning/vehicle_radius.h"

#include <algorithm>
#include <initializer_list>
#include <cmath>
#include <stdexcept>

#include <Eigen/Geometry>
#include <urdf_model/model.h>
#include <urdf_parser/urdf_parser.h>

namespace rotors_planning {
namespace {

double BoundingRadius_m(const urdf::Geometry& geometry, const MeshRadiusFn& mesh_radius) {
  switch (geometry.type) {
    case urdf::Geometry::BOX: {
      const urdf::Vector3& d = static_cast<const urdf::Box&>(geometry).dim;
      return 0.5 * std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    }
    case urdf::Geometry::CYLINDER: {
      const auto& c = static_cast<const urdf::Cylinder&>(geometry);
      return std::hypot(c.radius, 0.5 * c.length);
    }
    case urdf::Geometry::SPHERE: return static_cast<const urdf::Sphere&>(geometry).radius;
    case urdf::Geometry::MESH: {
      const auto& mesh = static_cast<const urdf::Mesh&>(geometry);
      return mesh_radius(mesh.filename) * std::max({mesh.scale.x, mesh.scale.y, mesh.scale.z});
    }
  }
  return 0.0;
}

Eigen::Isometry3d ToEigen(const urdf::Pose& pose) {
  double x, y, z, w;
  pose.rotation.getQuaternion(x, y, z, w);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
  X.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return X;
}

/// X_RL: the pose of `link` in the root link's frame, through the joints' origins (joints at zero).
Eigen::Isometry3d PoseInRoot(const urdf::Link& link) {
  Eigen::Isometry3d X_RL = Eigen::Isometry3d::Identity();
  for (const urdf::Link* l = &link; l->parent_joint; l = l->getParent().get()) {
    X_RL = ToEigen(l->parent_joint->parent_to_joint_origin_transform) * X_RL;
  }
  return X_RL;
}

}  // namespace

double VehicleRadius_m(const std::string& urdf_xml, const MeshRadiusFn& mesh_radius) {
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(urdf_xml);
  if (!model) throw std::invalid_argument("robot_description is no URDF that urdfdom can parse");
  double radius_m = 0.0;
  for (const auto& [name, link] : model->links_) {
    const Eigen::Isometry3d X_RL = PoseInRoot(*link);
    auto include = [&](const urdf::Pose& X_LS, const urdf::GeometrySharedPtr& geometry) {
      if (!geometry) return;
      const Eigen::Vector3d p_RS = X_RL * ToEigen(X_LS).translation();
      radius_m = std::max(radius_m, p_RS.norm() + BoundingRadius_m(*geometry, mesh_radius));
    };
    for (const urdf::CollisionSharedPtr& collision : link->collision_array) {
      if (collision) include(collision->origin, collision->geometry);
    }
    for (const urdf::VisualSharedPtr& visual : link->visual_array) {
      if (visual) include(visual->origin, visual->geometry);
    }
  }
  if (radius_m <= 0.0)
    throw std::invalid_argument("robot_description has no <collision> or <visual> shape to take a radius from");
  return radius_m;
}

}  // namespace rotors_planning
