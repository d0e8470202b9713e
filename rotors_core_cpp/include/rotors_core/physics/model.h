// A model: links, joints and its plugins (gazebo::physics::Model).
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <sdf/Element.hh>

#include "rotors_core/physics/physics_types.h"
#include "rotors_core/physics/solver_handles.h"
#include "rotors_core/physics/surface.h"
#include "rotors_core/geometry/visual.h"
#include "rotors_core/sensors/sensor.h"

namespace rotors_sim {
class ModelPlugin;
class SensorPlugin;
namespace physics {

class Model {
 public:
  Model(std::string name, World* world, bool is_static);
  ~Model();

  const std::string& GetName() const { return name_; }
  WorldPtr GetWorld() const;
  World* GetWorldRaw() const { return world_; }
  bool IsStatic() const { return static_; }
  sdf::ElementPtr GetSDF() const { return sdf_; }

  LinkPtr GetLink(const std::string& name) const;  ///< nullptr if absent (Gazebo semantics)
  JointPtr GetJoint(const std::string& name) const;
  const Link_V& GetLinks() const { return links_; }
  const Joint_V& GetJoints() const { return joints_; }
  /// The canonical (root) link, whose pose is the model pose.
  LinkPtr GetCanonicalLink() const { return links_.empty() ? nullptr : links_.front(); }

  Pose3d WorldPose() const;
  Vector3d WorldLinearVel() const;
  Vector3d WorldAngularVel() const;
  /// Moves the model rigidly to X_WM and zeroes every velocity (reset and teleport); a static model
  /// moves its links, visuals and collisions (but not a plane's or an octree's).
  void SetWorldPose(const Pose3d& X_WM);
  /// Moves the model as one rigid body: each body's velocity v_W + omega_W x (p_body - p_model).
  void SetWorldTwist(const Vector3d& v_W, const Vector3d& omega_W);
  const Pose3d& InitialPose() const { return X_WM_initial_; }

  // --- Engine side ---
  void SetSDF(sdf::ElementPtr sdf) { sdf_ = std::move(sdf); }
  void AddLink(const LinkPtr& link) { links_.push_back(link); }
  void AddJoint(const JointPtr& joint);
  /// Joints driven kinematically (see Joint); the world advances them every step.
  const Joint_V& KinematicJoints() const { return kinematic_joints_; }
  void AddBody(BodyHandle* body, const Pose3d& X_MB) { bodies_.push_back({body, X_MB, {}}); }
  /// A body's state before the last step (links difference their velocities with it).
  struct BodyStateBefore {
    Vector3d v_W, omega_W;  ///< [m/s] of the body origin (its CoG), [rad/s]
    Quaterniond q_WB;
    double dt_s = 0.0;  ///< the step; 0: no step since spawn or reset
  };
  /// A rigid body's mass properties as the solver has them: the body frame is at its CoG with the
  /// model's axes at spawn (X_MB), the inertia is about the CoG in the body frame.
  struct BodyMassProperties {
    double mass_kg = 0.0;
    Eigen::Matrix3d inertia_B_kg_m2 = Eigen::Matrix3d::Zero();
    Pose3d X_MB;
    const BodyHandle* body = nullptr;  ///< the body (Link::Body() of the links riding on it)
  };
  std::vector<BodyMassProperties> BodyMasses() const;
  /// The axis-aligned box [lo, hi] (world frame) around every collision geom on a body, now; false
  /// when the model has none.
  bool CollisionBoundsW(Vector3d* lo_W, Vector3d* hi_W) const;
  /// Called by the world right before each step.
  void RecordBodiesBeforeStep(double dt_s);
  /// nullptr when the body has not stepped since spawn or the last reset.
  const BodyStateBefore* StateBeforeStep(const BodyHandle* body) const;
  /// Registers a collision geom; the solver keeps the returned GeomInfo as the geom's data.
  struct GeomInfo {
    Link* link;
    std::string scoped_name;  ///< "model::link::collision"
    SurfaceParams surface;
    std::shared_ptr<void> keep_alive;  ///< solver mesh/heightfield data the geom points into
    Pose3d X_LG;                       ///< the geom in its link frame (geoms on a body)
  };
  GeomInfo* AddGeom(GeomHandle* geom, Link* link, const std::string& scoped_name, const SurfaceParams& surface = {});
  /// Collision geoms with their info (for whoever queries the world's geometry).
  const std::vector<std::pair<GeomHandle*, std::unique_ptr<GeomInfo>>>& Geoms() const { return geoms_; }
  void AddVisual(geometry::Visual visual) { visuals_.push_back(std::move(visual)); }
  const std::vector<geometry::Visual>& Visuals() const { return visuals_; }
  void SetInitialPose(const Pose3d& X_WM) { X_WM_initial_ = X_WM; }
  void AddPlugin(std::unique_ptr<ModelPlugin> plugin);
  const std::vector<std::unique_ptr<ModelPlugin>>& Plugins() const { return plugins_; }
  void AddSensor(const sensors::SensorPtr& sensor) { sensors_.push_back(sensor); }
  void AddSensorPlugin(std::unique_ptr<SensorPlugin> plugin);
  const std::vector<sensors::SensorPtr>& Sensors() const { return sensors_; }
  void ResetPlugins();
  /// Unloads plugins (breaking their ModelPtr cycles) and frees the solver's bodies, joints and geoms.
  void Fini();

 private:
  void MoveStatic(const Pose3d& X_WM);
  struct BodyRecord {
    BodyHandle* body;
    Pose3d X_MB;  ///< body frame in the model frame at spawn
    BodyStateBefore before;
  };
  std::string name_;
  World* world_;
  bool static_;
  sdf::ElementPtr sdf_;
  Link_V links_;
  Joint_V joints_;
  Joint_V kinematic_joints_;
  std::vector<BodyRecord> bodies_;
  std::vector<std::pair<GeomHandle*, std::unique_ptr<GeomInfo>>> geoms_;
  std::vector<geometry::Visual> visuals_;
  Pose3d X_WM_initial_;
  bool told_immovable_ = false;  ///< MoveStatic said that a plane or octree collision stays
  std::vector<std::unique_ptr<ModelPlugin>> plugins_;
  std::vector<sensors::SensorPtr> sensors_;
  std::vector<std::unique_ptr<SensorPlugin>> sensor_plugins_;
};

}  // namespace physics
}  // namespace rotors_sim
