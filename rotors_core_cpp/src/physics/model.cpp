#include "rotors_core/physics/model.h"

#include <algorithm>
#include <iostream>

#include "rotors_core/event.h"
#include "rotors_core/physics/joint.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/plugin.h"
#include "physics/ode_convert.h"
#include "physics/ode_handles.h"
#include "physics/pose_math.h"

namespace rotors_sim {
namespace physics {

Model::Model(std::string name, World* world, bool is_static)
    : name_(std::move(name)), world_(world), static_(is_static) {}

Model::~Model() { Fini(); }

void Model::Fini() {
  plugins_.clear();
  sensor_plugins_.clear();
  sensors_.clear();
  for (auto& link : links_) link->ClearJoints();
  kinematic_joints_.clear();
  joints_.clear();
  for (auto& g : geoms_) dGeomDestroy(Ode(g.first));
  geoms_.clear();  // after the geoms: the mesh data they point into
  visuals_.clear();
  for (auto& b : bodies_) dBodyDestroy(Ode(b.body));
  bodies_.clear();
  links_.clear();
}

WorldPtr Model::GetWorld() const { return world_ ? world_->shared_from_this() : nullptr; }

LinkPtr Model::GetLink(const std::string& name) const {
  for (const auto& link : links_)
    if (link->GetName() == name) return link;
  return nullptr;
}

JointPtr Model::GetJoint(const std::string& name) const {
  for (const auto& joint : joints_)
    if (joint->GetName() == name) return joint;
  return nullptr;
}

Pose3d Model::WorldPose() const {
  auto link = GetCanonicalLink();
  return link ? link->WorldPose() : X_WM_initial_;
}

Vector3d Model::WorldLinearVel() const {
  auto link = GetCanonicalLink();
  return link ? link->WorldLinearVel() : Vector3d::Zero;
}

Vector3d Model::WorldAngularVel() const {
  auto link = GetCanonicalLink();
  return link ? link->WorldAngularVel() : Vector3d::Zero;
}

std::vector<Model::BodyMassProperties> Model::BodyMasses() const {
  std::vector<BodyMassProperties> out;
  for (const auto& b : bodies_) {
    dMass m;
    dBodyGetMass(Ode(b.body), &m);
    BodyMassProperties p;
    p.mass_kg = m.mass;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) p.inertia_B_kg_m2(i, j) = m.I[i * 4 + j];
    p.X_MB = b.X_MB;
    p.body = b.body;
    out.push_back(p);
  }
  return out;
}

bool Model::CollisionBoundsW(Vector3d* lo_W, Vector3d* hi_W) const {
  bool any = false;
  for (const auto& g : geoms_) {
    if (!g.second->link || g.second->link->IsStatic()) continue;
    dReal aabb[6];
    dGeomGetAABB(Ode(g.first), aabb);
    const Vector3d lo(aabb[0], aabb[2], aabb[4]), hi(aabb[1], aabb[3], aabb[5]);
    if (!any) {
      *lo_W = lo;
      *hi_W = hi;
      any = true;
    } else {
      *lo_W = Vector3d(std::min(lo_W->X(), lo.X()), std::min(lo_W->Y(), lo.Y()), std::min(lo_W->Z(), lo.Z()));
      *hi_W = Vector3d(std::max(hi_W->X(), hi.X()), std::max(hi_W->Y(), hi.Y()), std::max(hi_W->Z(), hi.Z()));
    }
  }
  return any;
}

void Model::RecordBodiesBeforeStep(double dt_s) {
  for (auto& b : bodies_) {
    dBodyID body = Ode(b.body);
    b.before.v_W = ode_convert::Vec(dBodyGetLinearVel(body));
    b.before.omega_W = ode_convert::Vec(dBodyGetAngularVel(body));
    b.before.q_WB = ode_convert::Quat(dBodyGetQuaternion(body));
    b.before.dt_s = dt_s;
  }
}

const Model::BodyStateBefore* Model::StateBeforeStep(const BodyHandle* body) const {
  for (const auto& b : bodies_)
    if (b.body == body) return b.before.dt_s > 0.0 ? &b.before : nullptr;
  return nullptr;
}

void Model::AddJoint(const JointPtr& joint) {
  joints_.push_back(joint);
  if (joint->IsKinematic()) kinematic_joints_.push_back(joint);
}

void Model::SetWorldPose(const Pose3d& X_WM) {
  if (bodies_.empty()) {  // a static model moves as a whole, as in Gazebo: links, visuals, collisions
    MoveStatic(X_WM);
    return;
  }
  for (const auto& joint : kinematic_joints_) joint->ResetKinematic();
  for (const auto& b : bodies_) {
    ode_convert::SetBodyPose(Ode(b.body), Compose(X_WM, b.X_MB));
    dBodySetLinearVel(Ode(b.body), 0, 0, 0);
    dBodySetAngularVel(Ode(b.body), 0, 0, 0);
    dBodyEnable(Ode(b.body));
  }
  for (auto& b : bodies_) b.before.dt_s = 0.0;  // at rest: no acceleration until the next step
  for (const auto& link : links_) link->InvalidatePose();
}

void Model::MoveStatic(const Pose3d& X_WM) {
  const Pose3d X_MW_old = Inverse(WorldPose());
  for (const auto& link : links_) link->SetStaticPose(Compose(X_WM, Compose(X_MW_old, link->WorldPose())));
  for (const auto& [handle, info] : geoms_) {
    dGeomID geom = Ode(handle);
    const int geom_class = dGeomGetClass(geom);
    if (geom_class == dPlaneClass || !dGeomGetSpace(geom) || geom_class >= dFirstUserClass) {
      // an infinite plane or an octree stays where it was built (said once per model)
      if (!told_immovable_)
        std::cerr << "[rotors_sim] model '" << name_
                  << "': its plane and octree collisions do not move "
                     "with it (only its other collisions, links and visuals do)\n";
      told_immovable_ = true;
      continue;
    }
    ode_convert::SetGeomPose(geom, Compose(info->link->WorldPose(), info->X_LG));
  }
}

void Model::SetWorldTwist(const Vector3d& v_W, const Vector3d& omega_W) {
  const Vector3d p_WM = WorldPose().Pos();
  for (const auto& b : bodies_) {
    const dReal* p = dBodyGetPosition(Ode(b.body));
    // rigid motion: v_body = v + omega x r, r from the model origin to the body
    const Vector3d v_body_W = v_W + omega_W.Cross(Vector3d(p[0], p[1], p[2]) - p_WM);
    dBodySetLinearVel(Ode(b.body), v_body_W.X(), v_body_W.Y(), v_body_W.Z());
    dBodySetAngularVel(Ode(b.body), omega_W.X(), omega_W.Y(), omega_W.Z());
    dBodyEnable(Ode(b.body));
  }
  for (auto& b : bodies_) b.before.dt_s = 0.0;  // no acceleration until the next step
}

Model::GeomInfo* Model::AddGeom(GeomHandle* geom, Link* link, const std::string& scoped_name,
                                const SurfaceParams& surface) {
  auto info = std::make_unique<GeomInfo>(GeomInfo{link, scoped_name, surface, nullptr, Pose3d()});
  dGeomSetData(Ode(geom), info.get());
  geoms_.emplace_back(geom, std::move(info));
  return geoms_.back().second.get();
}

void Model::AddPlugin(std::unique_ptr<ModelPlugin> plugin) { plugins_.push_back(std::move(plugin)); }

void Model::AddSensorPlugin(std::unique_ptr<SensorPlugin> plugin) { sensor_plugins_.push_back(std::move(plugin)); }

void Model::ResetPlugins() {
  for (auto& plugin : plugins_) plugin->Reset();
  for (auto& plugin : sensor_plugins_) plugin->Reset();
  for (auto& sensor : sensors_) sensor->Reset();
}

}  // namespace physics
}  // namespace rotors_sim
