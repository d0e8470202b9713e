// rotors_sim._engine.World: one world of the engine, with its plugins exactly as under ROS (same
// code; with no ROS master they publish into the world's MessageTaps, which Python reads), and
// step_all: many worlds stepped on threads with the GIL released.
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "rotors_flight_batch/vehicle_description.h"
#include "rotors_core/error.h"
#include "rotors_core/geometry/uri_resolver.h"
#include "rotors_core/model_builder.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/ros/message_taps.h"
#include "rotors_core/sensors/camera_sensor.h"
#include "rotors_core/sensors/ray_sensor.h"
#include "rotors_core/world_loader.h"
#include "rotors_gazebo_plugins/vehicle_bus.h"

namespace py = pybind11;

namespace rotors_python {
namespace {

using rotors_sim::SimError;
using rotors_sim::physics::ModelPtr;
using rotors_sim::physics::Pose3d;
using rotors_sim::physics::Vector3d;
using rotors_sim::physics::WorldPtr;

py::array_t<double> ToArray(const Vector3d& v) {
  return py::array_t<double>(3, std::vector<double>{v.X(), v.Y(), v.Z()}.data());
}

Vector3d ToVector3(const std::vector<double>& v, const std::string& what) {
  if (v.size() != 3) throw SimError(what + " needs 3 numbers, got " + std::to_string(v.size()));
  for (double x : v)
    if (!std::isfinite(x)) throw SimError(what + " must be finite, got " + std::to_string(x));
  return Vector3d(v[0], v[1], v[2]);
}

/// A NumPy view of `data` that keeps `owner` alive (no copy).
template <typename T, typename Owner>
py::array View(const T* data, std::vector<py::ssize_t> shape, const std::shared_ptr<Owner>& owner) {
  auto* keep = new std::shared_ptr<Owner>(owner);
  py::capsule base(keep, [](void* p) { delete static_cast<std::shared_ptr<Owner>*>(p); });
  return py::array(py::dtype::of<T>(), shape, {}, data, base);
}

class PyWorld {
 public:
  explicit PyWorld(WorldPtr world) : world_(std::move(world)) {
    rotors_sim::MessageTaps::Of(*world_).Enable();  // the plugins of every vehicle spawned from now on
  }
  ~PyWorld() {
    if (world_) world_->Fini();
  }
  static rotors_sim::WorldLoadOptions Options(bool shadows) {
    rotors_sim::WorldLoadOptions load;
    load.shadows = shadows;
    load.skipped_plugins["librotors_gazebo_ros_interface_plugin.so"] = "not needed, no ROS";
    return load;
  }

  rotors_sim::physics::World& W() const { return *world_; }

  std::string Spawn(const std::string& xml, const std::string& name, const std::vector<double>& xyz,
                    const std::vector<double>& rpy) {
    const Vector3d p = ToVector3(xyz, "spawn position"), a = ToVector3(rpy, "spawn orientation (roll, pitch, yaw)");
    rotors_sim::SpawnRequest request{xml, name, Pose3d(p.X(), p.Y(), p.Z(), a.X(), a.Y(), a.Z())};
    return rotors_sim::ModelBuilder::Spawn(world_, request)->GetName();
  }

  void Step(long steps) {
    if (steps < 0) throw SimError("step(n): n = " + std::to_string(steps) + " must be >= 0");
    py::gil_scoped_release release;
    Advance(static_cast<unsigned>(steps));
  }

  /// n steps; before each, every attached controller answers a new odometry message with a motor
  /// command (what a controller node does in lockstep). Runs without the GIL.
  void Advance(unsigned steps) {
    if (attached_.empty()) {
      world_->Step(steps);
      return;
    }
    for (unsigned i = 0; i < steps; ++i) {
      for (Attached& a : attached_) a.AnswerNewOdometry();
      world_->Step(1);
    }
  }

  void AttachController(const std::string& ns, const std::string& odometry_topic,
                        std::shared_ptr<OdometryController> controller) {
    auto bus = Bus(ns);
    const OdometryFeed* feed = FeedOfOdometry(*bus, ns, odometry_topic);
    for (Attached& a : attached_)
      if (a.bus == bus) {
        a.controller = std::move(controller);
        a.feed = feed;
        return;
      }
    attached_.push_back(Attached{ns, bus, feed, std::move(controller), feed->count});
  }
  void DetachControllers() { attached_.clear(); }

  void Listen(const std::vector<std::string>& topics) { rotors_sim::MessageTaps::Of(*world_).Restrict(topics); }

  ModelPtr Model(const std::string& name) const {
    ModelPtr model = world_->ModelByName(name);
    if (model) return model;
    std::string names;
    for (const auto& m : world_->Models()) names += (names.empty() ? "" : ", ") + m->GetName();
    throw SimError("no model '" + name + "' in the world (models: " + (names.empty() ? "none" : names) + ")");
  }

  rotors_sim::physics::LinkPtr Link(const std::string& model_name, const std::string& link_name) const {
    ModelPtr model = Model(model_name);
    if (link_name.empty()) return model->GetCanonicalLink();
    auto link = model->GetLink(link_name);
    if (!link) throw SimError("model '" + model_name + "' has no link '" + link_name + "'");
    return link;
  }

  /// (position_W, orientation_W (x, y, z, w), velocity_W, angular_velocity_W) of a link.
  py::tuple LinkState(const std::string& model, const std::string& link_name) const {
    auto link = Link(model, link_name);
    const Pose3d X = link->WorldPose();
    const auto& q = X.Rot();
    return py::make_tuple(ToArray(X.Pos()),
                          py::array_t<double>(4, std::vector<double>{q.X(), q.Y(), q.Z(), q.W()}.data()),
                          ToArray(link->WorldLinearVel()), ToArray(link->WorldAngularVel()));
  }

  void SetModelState(const std::string& name, const std::vector<double>& position, const std::vector<double>& q_xyzw,
                     const std::vector<double>& velocity, const std::vector<double>& angular_velocity) {
    ModelPtr model = Model(name);
    const Vector3d p = ToVector3(position, "position");
    if (q_xyzw.size() != 4)
      throw SimError("orientation needs 4 numbers (x, y, z, w), got " + std::to_string(q_xyzw.size()));
    rotors_sim::physics::Quaterniond q(q_xyzw[3], q_xyzw[0], q_xyzw[1], q_xyzw[2]);
    if (!(q.W() * q.W() + q.X() * q.X() + q.Y() * q.Y() + q.Z() * q.Z() > 1e-12) ||
        !std::isfinite(q.W() + q.X() + q.Y() + q.Z()))
      throw SimError("orientation must be a finite, non-zero quaternion");
    q.Normalize();
    model->SetWorldPose(Pose3d(p, q));
    model->SetWorldTwist(ToVector3(velocity, "velocity"), ToVector3(angular_velocity, "angular_velocity"));
  }

  std::shared_ptr<rotors_gazebo_plugins::VehicleBus> Bus(const std::string& ns) const {
    auto bus = rotors_gazebo_plugins::VehicleBus::For(*world_, ns);
    if (bus->rotor_count == 0) throw SimError("no vehicle with motor models in namespace '" + ns + "'");
    return bus;
  }
  void SetMotorSpeeds(const std::string& ns, const std::vector<double>& speeds) {
    const std::string why = Bus(ns)->SetMotorCommand(speeds);
    if (!why.empty()) throw SimError("motor command for '" + ns + "' " + why);
  }
  std::vector<double> RotorSpeeds(const std::string& ns) const { return Bus(ns)->rotor_speed_rad_s; }
  /// RC channels [us] for the vehicle's autopilot interface (Betaflight's RC packet).
  void SetRc(const std::string& ns, const std::vector<int>& channels_us) {
    const std::string why = Bus(ns)->SetRcChannels(channels_us);
    if (!why.empty()) throw SimError("RC for '" + ns + "' " + why);
  }
  /// How many outputs the vehicle's autopilot has answered with so far.
  uint64_t AutopilotAnswers(const std::string& ns) const { return Bus(ns)->autopilot_answers; }
  /// A fixed wing's normalized command (surfaces and throttle by channel), as Actuators.normalized.
  void SetActuators(const std::string& ns, const std::vector<double>& normalized) {
    auto bus = rotors_gazebo_plugins::VehicleBus::For(*world_, ns);
    const std::string why = bus->SetNormalizedCommand(normalized);
    if (!why.empty()) throw SimError("actuator command for '" + ns + "' " + why);
  }

  py::object Message(const std::string& topic) const {
    const rotors_sim::TappedMessage* slot = rotors_sim::MessageTaps::Of(*world_).Find(topic);
    if (!slot || !slot->message) return py::none();
    const std::string bytes = slot->Serialized();
    return py::make_tuple(slot->datatype, slot->count, py::bytes(bytes));
  }
  /// The last reading of the odometry sensor on `topic` (resolved) as (count, [t, p(3), q xyzw(4),
  /// v_B(3), w_B(3)]), read from the vehicle bus; None before the first one (or since a reset).
  py::object OdometryArray(const std::string& ns, const std::string& topic) const {
    auto bus = rotors_gazebo_plugins::VehicleBus::For(*world_, ns);
    const OdometryFeed* feed = FeedOfOdometry(*bus, ns, topic);
    if (!feed->fresh) return py::none();
    const auto& m = feed->latest;
    const Eigen::Vector4d q = m.q_WS.coeffs();  // x y z w
    std::vector<double> values{feed->time_s, m.p_W.x(),     m.p_W.y(),     m.p_W.z(),    q[0],
                               q[1],         q[2],          q[3],          m.v_S.x(),    m.v_S.y(),
                               m.v_S.z(),    m.omega_S.x(), m.omega_S.y(), m.omega_S.z()};
    return py::make_tuple(feed->count, py::array_t<double>(values.size(), values.data()));
  }

  /// The last reading of the IMU on `topic` (resolved) as (count, [t, gyro_I(3) rad/s, specific
  /// force_I(3) m/s^2]), read from the vehicle bus; None before the first one (or since a reset).
  py::object ImuArray(const std::string& ns, const std::string& topic) const {
    auto bus = rotors_gazebo_plugins::VehicleBus::For(*world_, ns);
    const auto* feed = FeedNamed(bus->sensors.imu, ns, topic, "IMU", "IMUs");
    if (!feed->fresh) return py::none();
    const auto& m = feed->latest.measured;
    std::vector<double> values{feed->time_s,
                               m.angular_velocity_I.x(),
                               m.angular_velocity_I.y(),
                               m.angular_velocity_I.z(),
                               m.linear_acceleration_I.x(),
                               m.linear_acceleration_I.y(),
                               m.linear_acceleration_I.z()};
    return py::make_tuple(feed->count, py::array_t<double>(values.size(), values.data()));
  }

  std::vector<std::tuple<std::string, std::string, uint64_t>> Topics() const {
    std::vector<std::tuple<std::string, std::string, uint64_t>> out;
    auto& taps = rotors_sim::MessageTaps::Of(*world_);
    for (const std::string& topic : taps.Topics()) {
      const auto* slot = taps.Find(topic);
      out.emplace_back(topic, slot->datatype, slot->count);
    }
    return out;
  }

  template <class S>
  std::shared_ptr<S> SensorOf(const std::string& model_name, const std::string& sensor, const char* kind) const {
    ModelPtr model = Model(model_name);
    std::string names;
    for (const auto& s : model->Sensors()) {
      if (s->Name() == sensor) {
        auto typed = std::dynamic_pointer_cast<S>(s);
        if (!typed)
          throw SimError("sensor '" + sensor + "' of model '" + model_name + "' is a " + s->Type() + ", not a " + kind);
        return typed;
      }
      names += (names.empty() ? "" : ", ") + s->Name();
    }
    throw SimError("model '" + model_name + "' has no sensor '" + sensor +
                   "' (sensors: " + (names.empty() ? "none" : names) + ")");
  }

  py::array CameraImage(const std::string& model, const std::string& sensor, size_t index, bool depth) {
    auto camera = SensorOf<rotors_sim::sensors::CameraSensor>(model, sensor, "camera");
    if (index >= camera->CameraCount())
      throw SimError("camera index " + std::to_string(index) + " out of range: sensor '" + sensor + "' has " +
                     std::to_string(camera->CameraCount()) + " camera(s)");
    if (depth) camera->SetGroundTruthDepth(true);  // a plain camera renders its depth from now on
    const auto& frame = camera->Frame(index);
    const py::ssize_t h = frame.height_px, w = frame.width_px;
    if (depth) return View(frame.depth_m.data(), {h, w}, camera);
    const py::ssize_t channels = h * w > 0 ? static_cast<py::ssize_t>(frame.image.size()) / (h * w) : 0;
    return View(frame.image.data(), {h, w, channels}, camera);
  }

  py::dict LaserScan(const std::string& model, const std::string& sensor) const {
    auto laser = SensorOf<rotors_sim::sensors::RaySensor>(model, sensor, "ray sensor");
    const auto& spec = laser->Spec();
    const auto& scan = laser->LastScan();
    py::dict out;
    out["scan_count"] = laser->ScanCount();
    out["start_time_s"] = scan.start.Double();
    const py::ssize_t rows = spec.vertical_count, cols = spec.horizontal_count;
    const bool full = static_cast<py::ssize_t>(scan.ranges_m.size()) == rows * cols;
    out["ranges_m"] = full ? View(scan.ranges_m.data(), {rows, cols}, laser) : py::array_t<float>(0);
    out["intensities"] = full && scan.intensities.size() == scan.ranges_m.size()
                             ? View(scan.intensities.data(), {rows, cols}, laser)
                             : py::array_t<float>(0);
    out["column_time_s"] =
        View(scan.column_time_s.data(), {static_cast<py::ssize_t>(scan.column_time_s.size())}, laser);
    return out;
  }

  py::list Contacts() const {
    py::list out;
    for (const auto& c : world_->Contacts()) {
      py::dict d;
      d["collision1"] = c.collision1;
      d["collision2"] = c.collision2;
      d["position_W"] = ToArray(c.position_W);
      d["normal_W"] = ToArray(c.normal_W);
      d["depth_m"] = c.depth_m;
      d["force1_W"] = ToArray(c.force1_W);
      out.append(d);
    }
    return out;
  }

  /// True when a contact of the last step involves a collision of `model` (names "model::link::collision").
  bool InContact(const std::string& model) const {
    const std::string prefix = model + "::";
    for (const auto& c : world_->Contacts())
      if (c.collision1.compare(0, prefix.size(), prefix) == 0 || c.collision2.compare(0, prefix.size(), prefix) == 0)
        return true;
    return false;
  }

  std::vector<std::string> ModelNames() const {
    std::vector<std::string> names;
    for (const auto& m : world_->Models()) names.push_back(m->GetName());
    return names;
  }
  std::vector<std::tuple<std::string, std::string>> SensorNames(const std::string& model) const {
    std::vector<std::tuple<std::string, std::string>> out;
    for (const auto& s : Model(model)->Sensors()) out.emplace_back(s->Name(), s->Type());
    return out;
  }

 private:
  using OdometryFeed = rotors_gazebo_plugins::SensorFeed<rotors_gazebo_plugins::OdometryMeasurement>;
  /// The feed of the `sensor` on `topic` (resolved) among `feeds` of the vehicle `ns` (SimError
  /// naming the vehicle's `listed` when none publishes there).
  template <class Reading>
  static const rotors_gazebo_plugins::SensorFeed<Reading>* FeedNamed(
      const rotors_gazebo_plugins::SensorFeeds<Reading>& feeds, const std::string& ns, const std::string& topic,
      const char* sensor, const char* listed) {
    if (const auto* feed = feeds.Find(topic)) return feed;
    std::string topics;
    for (const std::string& t : feeds.Topics()) topics += (topics.empty() ? "" : ", ") + t;
    throw SimError(std::string("no ") + sensor + " publishes '" + topic + "' in vehicle '" + ns + "' (its " + listed +
                   ": " + (topics.empty() ? "none" : topics) + ")");
  }
  static const OdometryFeed* FeedOfOdometry(const rotors_gazebo_plugins::VehicleBus& bus, const std::string& ns,
                                            const std::string& topic) {
    return FeedNamed(bus.sensors.odometry, ns, topic, "odometry sensor", "odometry");
  }

  struct Attached {
    std::string ns;
    std::shared_ptr<rotors_gazebo_plugins::VehicleBus> bus;
    const OdometryFeed* feed;  ///< on `bus`
    std::shared_ptr<OdometryController> controller;
    uint64_t seen;
    void AnswerNewOdometry() {
      if (!feed->fresh || feed->count == seen) return;
      seen = feed->count;
      const auto& m = feed->latest;
      const Eigen::VectorXd speeds =
          controller->Answer(StateFromOdometry(m.p_W, m.q_WS.coeffs(), m.v_S, m.omega_S), feed->time_s);
      const std::string why = bus->SetMotorCommand(std::vector<double>(speeds.data(), speeds.data() + speeds.size()));
      if (!why.empty()) throw SimError("attached controller of '" + ns + "': motor command " + why);
    }
  };
  WorldPtr world_;
  std::vector<Attached> attached_;
};

/// Steps every world n times, the worlds shared out over `threads` threads, with the GIL released.
void StepAll(const std::vector<PyWorld*>& worlds, long steps, int threads) {
  if (steps < 0) throw SimError("step_all: n = " + std::to_string(steps) + " must be >= 0");
  // a world given twice would be stepped by two threads at once
  for (size_t i = 0; i < worlds.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (worlds[i] == worlds[j])
        throw SimError("step_all: worlds[" + std::to_string(j) + "] and worlds[" + std::to_string(i) +
                       "] are the same world; give each world once");
  if (threads < 1) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  threads = std::min<int>(threads, static_cast<int>(worlds.size()));
  py::gil_scoped_release release;
  std::exception_ptr first_error;
  std::mutex error_mutex;
  auto run = [&](int t) {
    try {
      for (size_t i = t; i < worlds.size(); i += threads) worlds[i]->Advance(static_cast<unsigned>(steps));
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!first_error) first_error = std::current_exception();
    }
  };
  if (threads <= 1) {
    run(0);
  } else {
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) pool.emplace_back(run, t);
    for (auto& thread : pool) thread.join();
  }
  if (first_error) std::rethrow_exception(first_error);
}

}  // namespace

rotors_sim::physics::World& PhysicsWorldOf(const py::handle& world) {
  if (!py::isinstance<PyWorld>(world)) throw SimError("expected a rotors_sim._engine.World (rotors_sim.World.engine)");
  return world.cast<PyWorld&>().W();
}

void BindWorld(py::module_& m) {
  static py::exception<SimError> sim_error(m, "SimError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const SimError& e) {
      PyErr_SetString(sim_error.ptr(), e.what());
    }
  });

  m.def("add_model_path", &rotors_sim::geometry::UriResolver::AddModelPath, py::arg("folder"),
        "A folder of Gazebo model folders for model:// URIs (after GAZEBO_MODEL_PATH).");

  py::class_<PyWorld>(m, "World", "One world of the engine (see rotors_sim.World).")
      .def_static(
          "load_file",
          [](const std::string& path, bool shadows) {
            return std::make_unique<PyWorld>(rotors_sim::WorldLoader::LoadFile(path, PyWorld::Options(shadows)));
          },
          py::arg("path"), py::arg("shadows") = true)
      .def_static(
          "load_string",
          [](const std::string& sdf, const std::string& name, bool shadows) {
            return std::make_unique<PyWorld>(rotors_sim::WorldLoader::LoadString(sdf, name, PyWorld::Options(shadows)));
          },
          py::arg("sdf"), py::arg("source_name") = "<string>", py::arg("shadows") = true)
      .def("spawn", &PyWorld::Spawn, py::arg("xml"), py::arg("name"), py::arg("xyz"), py::arg("rpy"))
      .def("remove_model", [](PyWorld& w, const std::string& name) { return w.W().RemoveModel(name); })
      .def("step", &PyWorld::Step, py::arg("n") = 1)
      .def("reset", [](PyWorld& w) { w.W().ResetSimulation(); })
      .def("reset_world", [](PyWorld& w) { w.W().ResetWorld(); })
      .def_property_readonly("time", [](const PyWorld& w) { return w.W().SimTime().Double(); })
      .def_property_readonly("iterations", [](const PyWorld& w) { return w.W().Iterations(); })
      .def_property(
          "step_size", [](const PyWorld& w) { return w.W().Physics().max_step_size_s; },
          [](PyWorld& w, double step_s) {
            if (!(step_s > 0.0 && step_s <= 0.1))
              throw SimError("step_size = " + std::to_string(step_s) + " s must be in (0, 0.1]");
            if (w.W().ModelCount() > 0)
              for (const auto& m : w.W().Models())
                if (!m->Plugins().empty())
                  throw SimError("set step_size before spawning vehicles (model '" + m->GetName() +
                                 "' has plugins that read it at load)");
            w.W().SetMaxStepSize(step_s);
          })
      .def_property_readonly("gravity", [](const PyWorld& w) { return ToArray(w.W().Gravity()); })
      .def("model_names", &PyWorld::ModelNames)
      .def("sensor_names", &PyWorld::SensorNames, py::arg("model"))
      .def("link_state", &PyWorld::LinkState, py::arg("model"), py::arg("link") = "")
      .def("set_model_state", &PyWorld::SetModelState, py::arg("model"), py::arg("position"), py::arg("orientation"),
           py::arg("velocity"), py::arg("angular_velocity"))
      .def("set_motor_speeds", &PyWorld::SetMotorSpeeds, py::arg("namespace"), py::arg("speeds"))
      .def("rotor_speeds", &PyWorld::RotorSpeeds, py::arg("namespace"))
      .def("set_rc", &PyWorld::SetRc, py::arg("namespace"), py::arg("channels_us"))
      .def("autopilot_answers", &PyWorld::AutopilotAnswers, py::arg("namespace"))
      .def("set_actuators", &PyWorld::SetActuators, py::arg("namespace"), py::arg("normalized"))
      .def("message", &PyWorld::Message, py::arg("topic"))
      .def("odometry_array", &PyWorld::OdometryArray, py::arg("namespace"), py::arg("topic"))
      .def("imu_array", &PyWorld::ImuArray, py::arg("namespace"), py::arg("topic"))
      .def("topics", &PyWorld::Topics)
      .def("listen", &PyWorld::Listen, py::arg("topics"))
      .def("attach_controller", &PyWorld::AttachController, py::arg("namespace"), py::arg("odometry_topic"),
           py::arg("controller"))
      .def("detach_controllers", &PyWorld::DetachControllers)
      .def(
          "describe_multirotor",
          [](const PyWorld& w, const std::string& model, const std::string& odometry_topic) {
            return rotors_flight_batch::DescribeVehicle(*w.Model(model), odometry_topic);
          },
          py::arg("model"), py::arg("odometry_topic"),
          "What the batched flight engine reads from a spawned multirotor (its VehicleDescription).")
      .def("camera_image", &PyWorld::CameraImage, py::arg("model"), py::arg("sensor"), py::arg("index") = 0,
           py::arg("depth") = false)
      .def("laser_scan", &PyWorld::LaserScan, py::arg("model"), py::arg("sensor"))
      .def("contacts", &PyWorld::Contacts)
      .def("in_contact", &PyWorld::InContact, py::arg("model"));

  m.def("step_all", &StepAll, py::arg("worlds"), py::arg("n"), py::arg("threads") = 0,
        "Steps every world n times on `threads` threads (0: one per core), the GIL released.");
}

}  // namespace rotors_python
