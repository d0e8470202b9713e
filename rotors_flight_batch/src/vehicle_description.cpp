#include "rotors_flight_batch/vehicle_description.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <variant>

#include "rotors_core/error.h"
#include "rotors_core/physics/joint.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/plugin.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/vehicle_bus.h"

namespace rotors_flight_batch {

using rotors_sim::SimError;
namespace physics = rotors_sim::physics;
namespace rgp = rotors_gazebo_plugins;

namespace {

Eigen::Vector3d ToEigen(const physics::Vector3d& v) { return {v.X(), v.Y(), v.Z()}; }
Eigen::Quaterniond ToEigen(const physics::Quaterniond& q) { return {q.W(), q.X(), q.Y(), q.Z()}; }

/// The largest distance from c_W of a point of `visual` (placed by its link's pose now): a box's
/// corners, a sphere's far side, a cylinder's rims, a mesh's vertices; 0 for the unbounded shapes.
double VisualReach(const rotors_sim::geometry::Visual& visual, const Eigen::Vector3d& c_W) {
  using Type = rotors_sim::geometry::Shape::Type;
  const rotors_sim::geometry::Shape& s = visual.shape;
  const physics::Pose3d X_WV = visual.X_LV + visual.link->WorldPose();
  const Eigen::Vector3d p_WV = ToEigen(X_WV.Pos());
  const Eigen::Matrix3d R_WV = ToEigen(X_WV.Rot()).toRotationMatrix();
  auto reach = [&](const Eigen::Vector3d& p_V) { return (p_WV + R_WV * p_V - c_W).norm(); };
  double r = 0.0;
  switch (s.type) {
    case Type::kBox:
      for (int c = 0; c < 8; ++c)
        r = std::max(r, reach(Eigen::Vector3d((c & 1) ? 0.5 : -0.5, (c & 2) ? 0.5 : -0.5, (c & 4) ? 0.5 : -0.5)
                                  .cwiseProduct(ToEigen(s.box_size_m))));
      break;
    case Type::kSphere: r = (p_WV - c_W).norm() + s.radius_m; break;
    case Type::kCylinder:
      for (int k = 0; k < 360; ++k)
        for (double z : {-s.length_m / 2.0, s.length_m / 2.0})
          r = std::max(r, reach({s.radius_m * std::cos(k * M_PI / 180.0), s.radius_m * std::sin(k * M_PI / 180.0), z}));
      break;
    case Type::kMesh:
      if (s.mesh)
        for (size_t v = 0; v + 2 < s.mesh->vertices_m.size(); v += 3)
          r = std::max(r, reach({s.mesh->vertices_m[v], s.mesh->vertices_m[v + 1], s.mesh->vertices_m[v + 2]}));
      break;
    default: break;
  }
  return r;
}

/// The pose of a link's frame in the body frame B (origin at the body's CoG).
Mount MountOf(const physics::Link& link) {
  const physics::Pose3d& X_BL = link.PoseInBody();
  return {ToEigen(X_BL.Pos()), ToEigen(X_BL.Rot())};
}

RotorMount RotorOf(const physics::Model& model, const rgp::MotorRecord& motor, const std::string& who) {
  if (motor.motor_type != "velocity")
    throw SimError(who + ": motor " + std::to_string(motor.motor_number) + " has motorType '" + motor.motor_type +
                   "' (a servo or a joint effort); the batch flies rotors only (motorType velocity)");
  RotorMount r;
  r.motor_number = motor.motor_number;
  r.params = motor.params;
  r.slowdown = motor.slowdown;
  const physics::JointPtr joint = model.GetJoint(motor.joint_name);
  const physics::LinkPtr link = model.GetLink(motor.link_name);
  if (!joint->IsKinematic())
    throw SimError(who + ": rotor joint '" + motor.joint_name +
                   "' is a solver joint; the batch needs rotors on kinematic joints (<kinematic_joint>)");
  if (joint->GetChild().get() != link.get())
    throw SimError(who + ": rotor link '" + motor.link_name + "' is not the child of its joint '" + motor.joint_name +
                   "'");
  const Mount m = MountOf(*link);
  r.p_B_origin = m.p_B;
  r.p_B_cog = m.p_B + m.q_BS * link->GetInertial().CoG();
  r.axis_B = m.q_BS * Eigen::Vector3d::UnitZ();
  r.spin_inertia_kg_m2 = joint->SpinInertia();
  // the spin moment uses the joint's axis; the rotor's thrust its link's z: RotorS mounts them alike
  const Eigen::Vector3d joint_axis_B = m.q_BS * ToEigen(joint->LocalAxis(0));
  if (r.spin_inertia_kg_m2 > 0.0 && (joint_axis_B - r.axis_B).norm() > 1e-9 && (joint_axis_B + r.axis_B).norm() > 1e-9)
    throw SimError(who + ": rotor joint '" + motor.joint_name + "' turns about another axis than its link's z");
  return r;
}

WindDescription WindOf(const physics::Model& model, const rgp::WindRecord& wind, const std::string& who) {
  if (!wind.speed_topic.empty())
    throw SimError(who + ": the wind plugin takes its speed from the topic '" + wind.speed_topic +
                   "'; the batch has no topics (use a wind profile or field)");
  WindDescription w;
  w.params = wind.params;
  w.seed = wind.seed;
  const Mount m = MountOf(*model.GetLink(wind.link_name));
  w.p_B_link = m.p_B;
  w.p_B_force = m.p_B + m.q_BS * wind.offset_L;
  w.field = wind.field;
  w.profile = wind.profile;
  return w;
}

OdometryDescription OdometryOf(const physics::Model& model, const rgp::OdometryRecord& odometry,
                               const std::string& who) {
  if (odometry.outage_map)
    throw SimError(who + ": odometry '" + odometry.topic + "' has an outage map; the batch has none");
  OdometryDescription o;
  static_cast<rgp::OdometryRecord&>(o) = odometry;
  o.mount = MountOf(*model.GetLink(odometry.link_name));
  return o;
}

ImuDescription ImuOf(const physics::Model& model, const rgp::ImuRecord& imu, const std::string& who) {
  if (imu.rotor_vibration)
    throw SimError(who + ": IMU '" + imu.link_name +
                   "' has rotorVibration on; the batch does not step rotor vibration (fly it in a World, "
                   "or build the vehicle with sensor_realism false)");
  ImuDescription out;
  static_cast<rgp::ImuRecord&>(out) = imu;
  out.mount = MountOf(*model.GetLink(imu.link_name));
  return out;
}

}  // namespace

VehicleDescription DescribeVehicle(const physics::Model& model, const std::string& odometry_topic) {
  const std::string who = "FlightBatch: model '" + model.GetName() + "'";
  VehicleDescription d;
  d.model_name = model.GetName();
  const auto bodies = model.BodyMasses();
  if (bodies.size() != 1)
    throw SimError(who + " has " + std::to_string(bodies.size()) +
                   " rigid bodies; the batch flies one (rotors on kinematic joints, sensors welded)");
  const auto& body = bodies.front();
  d.mass_kg = body.mass_kg;
  d.inertia_B_kg_m2 = body.inertia_B_kg_m2;
  if (body.X_MB.Rot() != physics::Quaterniond::Identity)
    throw SimError(who + ": its body frame is rotated against the model frame; the batch needs them aligned");
  d.p_M_cog = ToEigen(body.X_MB.Pos());
  physics::World* world = model.GetWorldRaw();
  d.gravity_W = ToEigen(world->Gravity());
  d.step_s = world->Physics().max_step_size_s;

  for (const auto& sensor : model.Sensors())
    throw SimError(who + " has the " + sensor->Type() + " sensor '" + sensor->Name() +
                   "'; the batch renders and casts nothing (no cameras, depth cameras or lasers): fly it in a World");

  // what each plugin registered on the vehicle's bus when it loaded (plugin_records.h): its model
  // and the parameters it read and validated; a plugin without a record is one the batch cannot run
  bool motors_seen = false;
  for (const auto& plugin : model.Plugins()) {
    rgp::SdfParams& params = plugin->Params();
    std::shared_ptr<rgp::VehicleBus> bus;  // the plugin's, by its robotNamespace
    if (params.Has("robotNamespace")) {
      const std::string ns = rgp::ReadRobotNamespace(params);
      bus = rgp::VehicleBus::For(*world, ns);
      if (d.robot_namespace.empty()) d.robot_namespace = ns;
    }
    const rgp::PluginRecord* record = bus ? bus->RecordOf(plugin.get()) : nullptr;
    if (!record)
      throw SimError(who + " loads " + plugin->GetFilename() + " ('" + plugin->GetHandle() +
                     "'), which the batch does not simulate; fly it in a World");
    if (const auto* motor = std::get_if<rgp::MotorRecord>(record)) {
      d.rotors.push_back(RotorOf(model, *motor, who));
      motors_seen = true;
    } else if (const auto* wind = std::get_if<rgp::WindRecord>(record)) {
      d.wind = WindOf(model, *wind, who);
      d.wind->before_motors = !motors_seen;
    } else if (const auto* odometry = std::get_if<rgp::OdometryRecord>(record)) {
      if (odometry->topic != odometry_topic) {
        d.left_out.push_back("odometry (" + odometry->topic + ")");
        continue;
      }
      d.odometry = OdometryOf(model, *odometry, who);
    } else if (const auto* imu = std::get_if<rgp::ImuRecord>(record)) {
      if (d.imu) {
        d.left_out.push_back("imu (" + imu->link_name + ")");
        continue;
      }
      d.imu = ImuOf(model, *imu, who);
    } else if (const auto* measuring = std::get_if<rgp::MeasuringRecord>(record)) {
      d.left_out.push_back(measuring->what);
    }  // PlumbingRecord: the batch has its own multirotor base and controller interface
  }
  if (d.rotors.empty()) throw SimError(who + " has no rotors (motor_model plugins); the batch flies multirotors");
  std::sort(d.rotors.begin(), d.rotors.end(),
            [](const RotorMount& a, const RotorMount& b) { return a.motor_number < b.motor_number; });
  for (size_t i = 0; i < d.rotors.size(); ++i)
    if (d.rotors[i].motor_number != static_cast<int>(i))
      throw SimError(who + ": motor numbers must be 0.." + std::to_string(d.rotors.size() - 1));
  if (!d.odometry)
    throw SimError(who + " has no odometry plugin publishing '" + odometry_topic + "' (the controllers' input)");

  // ground contact: the corners of the collision bounding box, in the body frame
  physics::Vector3d lo_W, hi_W;
  if (model.CollisionBoundsW(&lo_W, &hi_W)) {
    const physics::Pose3d X_WM = model.WorldPose();
    const Eigen::Quaterniond q_WM = ToEigen(X_WM.Rot());
    if (q_WM.angularDistance(Eigen::Quaterniond::Identity()) > 1e-9)
      throw SimError(who + " must be described as spawned, upright and unrotated");
    const Eigen::Vector3d p_W_cog = ToEigen(X_WM.Pos()) + d.p_M_cog;
    for (int c = 0; c < 8; ++c)
      d.contact_points_B.push_back(
          Eigen::Vector3d((c & 1) ? hi_W.X() : lo_W.X(), (c & 2) ? hi_W.Y() : lo_W.Y(), (c & 4) ? hi_W.Z() : lo_W.Z()) -
          p_W_cog);
  }
  const Eigen::Vector3d p_W_cog = ToEigen(model.WorldPose().Pos()) + d.p_M_cog;
  for (const Eigen::Vector3d& corner : d.contact_points_B) d.reach_m = std::max(d.reach_m, corner.norm());
  for (const auto& visual : model.Visuals())
    if (visual.link) d.reach_m = std::max(d.reach_m, VisualReach(visual, p_W_cog));
  return d;
}

}  // namespace rotors_flight_batch
