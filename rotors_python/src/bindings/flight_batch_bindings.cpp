// rotors_sim._engine.FlightBatch: the batched flight engine (flight_batch/), its arrays shared
// with numpy (views on the engine's memory: no copy per step), its controllers' parameters read
// by the same loaders as the ROS nodes from the numbers Python flattened out of the yaml files.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <octomap/OcTree.h>
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "rotors_flight_batch/flight_batch.h"
#include "rotors_control/parameter_loading.h"
#include "rotors_core/error.h"
#include "rotors_core/geometry/occupancy_mapper.h"
#include "rotors_core/raycast/ray_scene.h"
#include "rotors_params/map_param_reader.h"

namespace py = pybind11;

namespace rotors_python {
namespace {

using rotors_flight_batch::Airframe;
using rotors_flight_batch::CommandMode;
using rotors_flight_batch::DepthCameraParams;
using rotors_flight_batch::FlightBatch;
using rotors_flight_batch::FlightBatchOptions;
using rotors_flight_batch::Obstacle;
using rotors_flight_batch::ObstacleField;
using rotors_flight_batch::VehicleDescription;
using rotors_sim::SimError;

/// A (rows x cols) view of engine memory, kept alive by `owner`.
template <class T>
py::array_t<T> View(T* data, py::ssize_t rows, py::ssize_t cols, py::handle owner, bool writeable) {
  py::array_t<T> a({rows, cols}, {static_cast<py::ssize_t>(cols * sizeof(T)), static_cast<py::ssize_t>(sizeof(T))},
                   data, owner);
  if (!writeable) a.attr("flags").attr("writeable") = false;
  return a;
}

std::unique_ptr<FlightBatch> MakeBatch(const VehicleDescription& d, int count, const std::string& mode,
                                       const std::map<std::string, double>& numbers,
                                       const std::vector<std::string>& others, const std::string& source, int threads,
                                       bool imu, bool noise, const std::vector<uint64_t>& seeds,
                                       uint64_t description_seed, double contact_stiffness_scale,
                                       const std::vector<std::map<std::string, double>>& numbers_each,
                                       const std::string& kernel) {
  FlightBatchOptions o;
  o.count = count;
  o.threads = threads;
  o.mode = rotors_flight_batch::ParseCommandMode(mode);
  o.imu = imu;
  o.noise = noise;
  o.seeds = seeds;
  o.description_seed = description_seed;
  o.contact_stiffness_scale = contact_stiffness_scale;
  o.kernel = kernel;
  if (!(contact_stiffness_scale > 0.0)) throw SimError("contact_stiffness_scale must be > 0");
  if (o.mode != CommandMode::kRotorSpeeds && o.mode != CommandMode::kNormalizedThrust) {
    rotors_params::MapParamReader reader(numbers, std::set<std::string>(others.begin(), others.end()), source);
    std::string why;
    if (o.mode == CommandMode::kLeePosition) {
      why = rotors_control::LoadLeeParameters(reader, &o.lee);
      for (size_t i = 0; why.empty() && i < numbers_each.size(); ++i) {
        rotors_params::MapParamReader each(numbers_each[i], std::set<std::string>(others.begin(), others.end()),
                                           source + " (vehicle " + std::to_string(i) + ")");
        o.lee_each.emplace_back();
        why = rotors_control::LoadLeeParameters(each, &o.lee_each.back());
      }
    } else {
      why = rotors_control::LoadAttitudeGains(reader, &o.attitude.attitude);
      if (why.empty()) why = rotors_control::LoadVehicleParameters(reader, &o.attitude.vehicle);
    }
    if (!why.empty()) throw SimError(why);
  }
  if (d.rotors.size() > 16) throw SimError("FlightBatch: more than 16 rotors");
  return std::make_unique<FlightBatch>(d, o);
}

/// The motor plugin's per-rotor SDF parameters an airframe may set, and where RotorParams keeps them.
const std::vector<std::pair<const char*, double rotors_gazebo_plugins::RotorParams::*>> kRotorFields = {
    {"motorConstant", &rotors_gazebo_plugins::RotorParams::motor_constant},
    {"momentConstant", &rotors_gazebo_plugins::RotorParams::moment_constant},
    {"rotorDragCoefficient", &rotors_gazebo_plugins::RotorParams::rotor_drag_coefficient},
    {"rollingMomentCoefficient", &rotors_gazebo_plugins::RotorParams::rolling_moment_coefficient},
    {"timeConstantUp", &rotors_gazebo_plugins::RotorParams::time_constant_up_s},
    {"timeConstantDown", &rotors_gazebo_plugins::RotorParams::time_constant_down_s},
    {"maxRotVelocity", &rotors_gazebo_plugins::RotorParams::max_rot_velocity},
};

/// The wind plugin's scalar SDF parameters an airframe may set, and where WindParams keeps them.
const std::vector<std::pair<const char*, double rotors_gazebo_plugins::WindParams::*>> kWindFields = {
    {"windSpeedMean", &rotors_gazebo_plugins::WindParams::wind_speed_mean_m_s},
    {"windSpeedVariance", &rotors_gazebo_plugins::WindParams::wind_speed_variance},
    {"windForceMean", &rotors_gazebo_plugins::WindParams::wind_force_mean_n},
    {"windForceVariance", &rotors_gazebo_plugins::WindParams::wind_force_variance},
    {"windGustStart", &rotors_gazebo_plugins::WindParams::wind_gust_start_s},
    {"windGustDuration", &rotors_gazebo_plugins::WindParams::wind_gust_duration_s},
    {"windGustForceMean", &rotors_gazebo_plugins::WindParams::wind_gust_force_mean_n},
    {"windGustForceVariance", &rotors_gazebo_plugins::WindParams::wind_gust_force_variance},
};

/// The odometry plugin's noise parameters (3 values each), and where OdometryNoiseParams keeps them.
const std::vector<std::pair<const char*, Eigen::Vector3d rotors_gazebo_plugins::OdometryNoiseParams::*>>
    kOdometryNoiseFields = {
        {"noiseNormalPosition", &rotors_gazebo_plugins::OdometryNoiseParams::normal_position_m},
        {"noiseNormalQuaternion", &rotors_gazebo_plugins::OdometryNoiseParams::normal_quaternion_rad},
        {"noiseNormalLinearVelocity", &rotors_gazebo_plugins::OdometryNoiseParams::normal_linear_velocity_m_s},
        {"noiseNormalAngularVelocity", &rotors_gazebo_plugins::OdometryNoiseParams::normal_angular_velocity_rad_s},
        {"noiseUniformPosition", &rotors_gazebo_plugins::OdometryNoiseParams::uniform_position_m},
        {"noiseUniformQuaternion", &rotors_gazebo_plugins::OdometryNoiseParams::uniform_quaternion_rad},
        {"noiseUniformLinearVelocity", &rotors_gazebo_plugins::OdometryNoiseParams::uniform_linear_velocity_m_s},
        {"noiseUniformAngularVelocity", &rotors_gazebo_plugins::OdometryNoiseParams::uniform_angular_velocity_rad_s},
};

/// The IMU plugin's noise parameters, and where ImuNoiseParams keeps them.
const std::vector<std::pair<const char*, double rotors_gazebo_plugins::ImuNoiseParams::*>> kImuNoiseFields = {
    {"gyroscopeNoiseDensity", &rotors_gazebo_plugins::ImuNoiseParams::gyroscope_noise_density},
    {"gyroscopeRandomWalk", &rotors_gazebo_plugins::ImuNoiseParams::gyroscope_random_walk},
    {"gyroscopeBiasCorrelationTime", &rotors_gazebo_plugins::ImuNoiseParams::gyroscope_bias_correlation_time_s},
    {"gyroscopeTurnOnBiasSigma", &rotors_gazebo_plugins::ImuNoiseParams::gyroscope_turn_on_bias_sigma},
    {"accelerometerNoiseDensity", &rotors_gazebo_plugins::ImuNoiseParams::accelerometer_noise_density},
    {"accelerometerRandomWalk", &rotors_gazebo_plugins::ImuNoiseParams::accelerometer_random_walk},
    {"accelerometerBiasCorrelationTime", &rotors_gazebo_plugins::ImuNoiseParams::accelerometer_bias_correlation_time_s},
    {"accelerometerTurnOnBiasSigma", &rotors_gazebo_plugins::ImuNoiseParams::accelerometer_turn_on_bias_sigma},
};

/// {"mass": kg, "inertia": 3 x 3 kg m^2, "cog": the CoG in the model frame [m], "actuatorDelay":
/// physics steps, "<SDF name>": one value per rotor, ...; the odometry plugin's noise
/// ("noiseNormalPosition", ...: 3 values each); with an IMU its noise ("gyroscopeNoiseDensity", ...);
/// with a wind plugin its SDF parameters ("windForceMean", ..., "windDirection", "windGustDirection")}
py::dict AirframeDict(const Airframe& a, const VehicleDescription& d) {
  py::dict out;
  for (const auto& [name, field] : kOdometryNoiseFields) out[name] = a.odometry_noise.*field;
  if (d.imu)
    for (const auto& [name, field] : kImuNoiseFields) out[name] = a.imu_noise.*field;
  if (d.wind) {
    for (const auto& [name, field] : kWindFields) out[name] = a.wind.*field;
    out["windDirection"] = a.wind.wind_direction;
    out["windGustDirection"] = a.wind.wind_gust_direction;
  }
  out["mass"] = a.mass_kg;
  out["inertia"] = a.inertia_B_kg_m2;
  out["cog"] = a.p_M_cog;
  out["actuatorDelay"] = a.actuator_delay_steps;
  for (const auto& [name, field] : kRotorFields) {
    std::vector<double> v;
    for (const auto& r : a.rotors) v.push_back(r.*field);
    out[name] = py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
  }
  return out;
}

using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// Sets the airframe parameter `name` (AirframeDict's keys) of `a` from the values at `v`, shaped
/// `shape` (a scalar: no dimension); SimError naming an unknown key or a value of the wrong shape.
void ApplyAirframeValue(Airframe& a, const std::string& name, const double* v, const std::vector<py::ssize_t>& shape,
                        const std::string& who, const VehicleDescription& d) {
  const bool scalar = shape.empty();
  const bool three = shape.size() == 1 && shape[0] == 3;
  auto odometry = std::find_if(kOdometryNoiseFields.begin(), kOdometryNoiseFields.end(),
                               [&](const auto& f) { return name == f.first; });
  if (odometry != kOdometryNoiseFields.end()) {
    if (!three) throw SimError(who + ": " + name + " must be 3 values (x, y, z)");
    a.odometry_noise.*(odometry->second) = {v[0], v[1], v[2]};
    return;
  }
  auto imu =
      std::find_if(kImuNoiseFields.begin(), kImuNoiseFields.end(), [&](const auto& f) { return name == f.first; });
  if (imu != kImuNoiseFields.end()) {
    if (!d.imu) throw SimError(who + ": '" + name + "' given, but the vehicle has no IMU");
    if (!scalar) throw SimError(who + ": " + name + " must be one number");
    a.imu_noise.*(imu->second) = v[0];
    return;
  }
  if (name == "mass") {
    if (!scalar) throw SimError(who + ": mass must be one number [kg]");
    a.mass_kg = v[0];
    return;
  }
  if (name == "inertia") {
    if (shape.size() != 2 || shape[0] != 3 || shape[1] != 3)
      throw SimError(who + ": inertia must be a 3 x 3 array [kg m^2]");
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) a.inertia_B_kg_m2(r, c) = v[3 * r + c];
    return;
  }
  auto wind = std::find_if(kWindFields.begin(), kWindFields.end(), [&](const auto& f) { return name == f.first; });
  const bool direction = name == "windDirection" || name == "windGustDirection";
  if ((wind != kWindFields.end() || direction) && !d.wind.has_value())
    throw SimError(who + ": '" + name + "' given, but the vehicle has no wind plugin (spawn it with one)");
  if (wind != kWindFields.end()) {
    if (!scalar) throw SimError(who + ": " + name + " must be one number");
    a.wind.*(wind->second) = v[0];
    return;
  }
  if (direction) {
    if (!three) throw SimError(who + ": " + name + " must be 3 values");
    (name == "windDirection" ? a.wind.wind_direction : a.wind.wind_gust_direction) = {v[0], v[1], v[2]};
    return;
  }
  if (name == "actuatorDelay") {
    if (!scalar || v[0] != std::floor(v[0]))
      throw SimError(who + ": actuatorDelay must be a whole number of physics steps");
    a.actuator_delay_steps = static_cast<int>(v[0]);
    return;
  }
  if (name == "cog") {
    if (!three) throw SimError(who + ": cog must be 3 values [m] (model frame)");
    a.p_M_cog = {v[0], v[1], v[2]};
    return;
  }
  auto it = std::find_if(kRotorFields.begin(), kRotorFields.end(), [&](const auto& f) { return name == f.first; });
  if (it == kRotorFields.end()) {
    std::string known = "mass, inertia, cog, actuatorDelay";
    for (const auto& f : kRotorFields) known += std::string(", ") + f.first;
    for (const auto& f : kOdometryNoiseFields) known += std::string(", ") + f.first;
    if (d.imu)
      for (const auto& f : kImuNoiseFields) known += std::string(", ") + f.first;
    if (d.wind) {
      for (const auto& f : kWindFields) known += std::string(", ") + f.first;
      known += ", windDirection, windGustDirection";
    }
    throw SimError(who + ": '" + name + "' is not an airframe parameter; use " + known);
  }
  if (shape.size() != 1 || shape[0] != static_cast<py::ssize_t>(a.rotors.size()))
    throw SimError(who + ": " + name + " must have one value per rotor (" + std::to_string(a.rotors.size()) + ")");
  for (size_t r = 0; r < a.rotors.size(); ++r) a.rotors[r].*(it->second) = v[r];
}

/// A value of an airframe dict as doubles; SimError naming it when it is not numbers.
Doubles AirframeValues(const py::handle& value, const std::string& name, const std::string& who) {
  try {
    return Doubles(py::reinterpret_borrow<py::object>(value));
  } catch (const py::error_already_set&) {
    throw SimError(who + ": " + name + " must be numbers");
  }
}

/// `base` with the entries of `values` (AirframeDict's keys; any subset); SimError naming an unknown
/// key or an array of the wrong length.
Airframe AirframeFrom(const Airframe& base, const py::dict& values, int vehicle, const VehicleDescription& d) {
  Airframe a = base;
  const std::string who = "FlightBatch.set_airframe: vehicle " + std::to_string(vehicle);
  for (const auto& [key, value] : values) {
    const std::string name = py::str(key);
    const Doubles v = AirframeValues(value, name, who);
    ApplyAirframeValue(a, name, v.data(), std::vector<py::ssize_t>(v.shape(), v.shape() + v.ndim()), who, d);
  }
  return a;
}

/// One airframe per vehicle of `indices`: the nominal with row j of each array of `values` (the
/// dict's keys as set_airframe's, each array with one row per vehicle).
std::vector<Airframe> AirframesFrom(const Airframe& base, const std::vector<int>& indices, const py::dict& values,
                                    const VehicleDescription& d) {
  const py::ssize_t k = static_cast<py::ssize_t>(indices.size());
  struct Column {
    std::string name;
    Doubles values;
    std::vector<py::ssize_t> row_shape;  ///< one vehicle's value's shape
    py::ssize_t row_size;
  };
  std::vector<Column> columns;
  for (const auto& [key, value] : values) {
    const std::string name = py::str(key);
    Doubles v = AirframeValues(value, name, "FlightBatch.set_airframes");
    if (v.ndim() < 1 || v.shape(0) != k)
      throw SimError("FlightBatch.set_airframes: " + name + " must have one row per vehicle (" + std::to_string(k) +
                     ")");
    std::vector<py::ssize_t> row_shape(v.shape() + 1, v.shape() + v.ndim());
    const py::ssize_t row_size = v.ndim() == 1 ? 1 : v.size() / k;
    columns.push_back({name, std::move(v), std::move(row_shape), row_size});
  }
  std::vector<Airframe> out(indices.size(), base);
  for (py::ssize_t j = 0; j < k; ++j) {
    const std::string who = "FlightBatch.set_airframes: vehicle " + std::to_string(indices[j]);
    for (const Column& c : columns)
      ApplyAirframeValue(out[j], c.name, c.values.data() + j * c.row_size, c.row_shape, who, d);
  }
  return out;
}

}  // namespace

/// Obstacles from rows (shape, x, y, z, half extents x, y, z, yaw): shape 0 a box, 1 a cylinder.
std::vector<Obstacle> ObstacleRows(const py::array_t<double, py::array::c_style | py::array::forcecast>& rows) {
  if (rows.ndim() != 2 || rows.shape(1) != 8)
    throw SimError(
        "ObstacleField.set: obstacles must have shape (K, 8): shape (0 box, 1 cylinder), x, y, z, "
        "half extents x, y, z, yaw");
  std::vector<Obstacle> out(rows.shape(0));
  auto r = rows.unchecked<2>();
  for (py::ssize_t k = 0; k < rows.shape(0); ++k) {
    if (r(k, 0) != 0.0 && r(k, 0) != 1.0)
      throw SimError("ObstacleField.set: obstacle " + std::to_string(k) + ": shape " + std::to_string(r(k, 0)) +
                     " is not 0 (box) or 1 (cylinder)");
    Obstacle& o = out[k];
    o.shape = r(k, 0) == 0.0 ? Obstacle::Shape::kBox : Obstacle::Shape::kCylinder;
    o.center_W = {r(k, 1), r(k, 2), r(k, 3)};
    o.half_extents_m = {r(k, 4), r(k, 5), r(k, 6)};
    o.yaw_rad = r(k, 7);
  }
  return out;
}

DepthCameraParams DepthCameraFrom(const py::dict& values) {
  DepthCameraParams c;
  for (const auto& item : values) {
    const std::string key = py::str(item.first);
    const py::handle v = item.second;
    if (key == "width") c.width_px = v.cast<int>();
    else if (key == "height") c.height_px = v.cast<int>();
    else if (key == "horizontal_fov") c.horizontal_fov_rad = v.cast<double>();
    else if (key == "vertical_fov") c.vertical_fov_rad = v.cast<double>();
    else if (key == "min_range") c.min_range_m = v.cast<double>();
    else if (key == "max_range") c.max_range_m = v.cast<double>();
    else if (key == "xyz") c.p_M_m = v.cast<Eigen::Vector3d>();
    else if (key == "noise") c.noise = v.cast<bool>();
    else
      throw SimError(
          "FlightBatch.set_depth_camera: '" + key +
          "' is not a parameter (width, height, horizontal_fov, vertical_fov, min_range, max_range, xyz, noise)");
  }
  return c;
}

py::dict DepthCameraDict(const DepthCameraParams& c) {
  py::dict d;
  d["width"] = c.width_px, d["height"] = c.height_px;
  d["horizontal_fov"] = c.horizontal_fov_rad, d["vertical_fov"] = c.vertical_fov_rad;
  d["min_range"] = c.min_range_m, d["max_range"] = c.max_range_m;
  d["xyz"] = c.p_M_m;
  d["noise"] = c.noise;
  return d;
}

void BindFlightBatch(py::module_& m) {
  py::class_<ObstacleField, std::shared_ptr<ObstacleField>>(
      m, "ObstacleField", "Static obstacles, one set per environment (see rotors_sim.clutter).")
      .def(py::init<int, double>(), py::arg("environments"), py::arg("max_sphere_radius"))
      .def_property_readonly("environments", &ObstacleField::Environments)
      .def(
          "set",
          [](ObstacleField& f, int env, const py::array_t<double, py::array::c_style | py::array::forcecast>& rows) {
            f.Set(env, ObstacleRows(rows));
          },
          py::arg("env"), py::arg("obstacles"), "Environment env's obstacles: rows (shape, x, y, z, hx, hy, hz, yaw).")
      .def(
          "set_world",
          [](ObstacleField& f, const py::object& world, const Eigen::Vector3d& center, const Eigen::Vector3d& lengths,
             double leaf_m) {
            if (world.is_none()) {
              f.SetWorld(nullptr, nullptr, nullptr);
              return;
            }
            rotors_sim::physics::World& w = PhysicsWorldOf(world);
            auto scene = std::make_shared<rotors_sim::raycast::RayScene>(w);
            rotors_sim::geometry::OccupancyRequest request;
            request.center_W = {center.x(), center.y(), center.z()};
            request.lengths_m = {lengths.x(), lengths.y(), lengths.z()};
            request.leaf_size_m = leaf_m;
            py::gil_scoped_release release;
            scene->Sync();
            const auto tree = rotors_sim::geometry::BuildOccupancy(w, request);
            f.SetWorld(scene, tree.get(), nullptr);
          },
          py::arg("world"), py::arg("center"), py::arg("lengths"), py::arg("leaf"), py::keep_alive<1, 2>(),
          "Every environment also holds `world` (a rotors_sim._engine.World; None: none): its visuals for the rays, "
          "its static collisions' occupancy in the box (center, lengths) at `leaf` m for the spheres.")
      .def_property_readonly("world_occupied_cells", &ObstacleField::WorldOccupiedCells)
      .def(
          "sphere_touches",
          [](const ObstacleField& f, int env, const Eigen::Vector3d& c_W, double r_m) {
            if (env < 0 || env >= f.Environments())
              throw SimError("ObstacleField.sphere_touches: environment " + std::to_string(env) + " is not in 0.." +
                             std::to_string(f.Environments() - 1));
            if (!(r_m >= 0.0 && r_m <= f.MaxSphereRadius()))
              throw SimError("ObstacleField.sphere_touches: radius " + std::to_string(r_m) + " m is not in 0.." +
                             std::to_string(f.MaxSphereRadius()));
            return f.SphereTouches(env, c_W, r_m);
          },
          py::arg("env"), py::arg("center"), py::arg("radius"))
      .def(
          "get",
          [](const ObstacleField& f, int env) {
            if (env < 0 || env >= f.Environments())
              throw SimError("ObstacleField.get: environment " + std::to_string(env) + " is not in 0.." +
                             std::to_string(f.Environments() - 1));
            const auto& obstacles = f.Get(env);
            py::array_t<double> a({static_cast<py::ssize_t>(obstacles.size()), static_cast<py::ssize_t>(8)});
            auto r = a.mutable_unchecked<2>();
            for (size_t k = 0; k < obstacles.size(); ++k) {
              const Obstacle& o = obstacles[k];
              r(k, 0) = o.shape == Obstacle::Shape::kBox ? 0.0 : 1.0;
              for (int c = 0; c < 3; ++c) r(k, 1 + c) = o.center_W[c], r(k, 4 + c) = o.half_extents_m[c];
              r(k, 7) = o.yaw_rad;
            }
            return a;
          },
          py::arg("env"))
      .def(
          "distance",
          [](const ObstacleField& f, int env, const Eigen::Vector3d& p_W) {
            double d = std::numeric_limits<double>::infinity();
            for (const Obstacle& o : f.Get(env)) d = std::min(d, o.Distance(p_W));
            return d;
          },
          py::arg("env"), py::arg("point"), "The distance [m] from point to the nearest obstacle of env (inf: none).")
      .def(
          "cast",
          [](const ObstacleField& f, int env, const Eigen::Vector3d& origin,
             const py::array_t<double, py::array::c_style | py::array::forcecast>& dirs, double near, double far) {
            if (env < 0 || env >= f.Environments())
              throw SimError("ObstacleField.cast: environment " + std::to_string(env) + " is not in 0.." +
                             std::to_string(f.Environments() - 1));
            if (dirs.ndim() != 2 || dirs.shape(1) != 3)
              throw SimError("ObstacleField.cast: dirs must have shape (n, 3)");
            std::vector<Eigen::Vector3d> d(dirs.shape(0));
            auto r = dirs.unchecked<2>();
            for (size_t k = 0; k < d.size(); ++k) d[k] = Eigen::Vector3d(r(k, 0), r(k, 1), r(k, 2)).normalized();
            py::array_t<double> t(static_cast<py::ssize_t>(d.size()));
            {
              py::gil_scoped_release release;
              f.Cast(env, origin, d.data(), d.size(), near, far, t.mutable_data());
            }
            return t;
          },
          py::arg("env"), py::arg("origin"), py::arg("dirs"), py::arg("near") = 0.0, py::arg("far") = 100.0,
          "Distances along rays to the first obstacle (inf: none).");

  py::class_<VehicleDescription>(m, "VehicleDescription",
                                 "What the batched flight engine read from a spawned multirotor.")
      .def_readonly("model_name", &VehicleDescription::model_name)
      .def_readonly("robot_namespace", &VehicleDescription::robot_namespace)
      .def_readonly("mass_kg", &VehicleDescription::mass_kg)
      .def_readonly("inertia_B_kg_m2", &VehicleDescription::inertia_B_kg_m2)
      .def_readonly("p_M_cog", &VehicleDescription::p_M_cog)
      .def_readonly("gravity_W", &VehicleDescription::gravity_W)
      .def_readonly("step_size", &VehicleDescription::step_s)
      .def_readonly("left_out", &VehicleDescription::left_out)
      .def_readonly("contact_points_B", &VehicleDescription::contact_points_B)
      .def_property_readonly(
          "airframe", [](const VehicleDescription& d) { return AirframeDict(rotors_flight_batch::AirframeOf(d), d); },
          "The airframe as FlightBatch.set_airframe takes it: {'mass', 'inertia', 'cog', 'motorConstant', ...}.")
      .def_property_readonly("has_imu", [](const VehicleDescription& d) { return d.imu.has_value(); })
      .def_property_readonly("has_wind", [](const VehicleDescription& d) { return d.wind.has_value(); })
      .def_property_readonly("odometry_divisor", [](const VehicleDescription& d) { return d.odometry->divisor; })
      .def_property_readonly("rotors", [](const VehicleDescription& d) {
        py::list rotors;
        for (const auto& r : d.rotors) {
          py::dict x;
          x["motor_number"] = r.motor_number;
          x["p_B"] = r.p_B_origin;
          x["axis_B"] = r.axis_B;
          x["motor_constant"] = r.params.motor_constant;
          x["moment_constant"] = r.params.moment_constant;
          x["max_rot_velocity"] = r.params.max_rot_velocity;
          x["turning_direction"] = r.params.turning_direction;
          x["spin_inertia_kg_m2"] = r.spin_inertia_kg_m2;
          rotors.append(x);
        }
        return rotors;
      });

  py::class_<FlightBatch>(m, "FlightBatch", "N copies of one multirotor stepped together (see rotors_sim.FlightBatch).")
      .def(py::init(&MakeBatch), py::arg("description"), py::arg("count"), py::arg("mode"), py::arg("numbers"),
           py::arg("others"), py::arg("source"), py::arg("threads") = 0, py::arg("imu") = true, py::arg("noise") = true,
           py::arg("seeds") = std::vector<uint64_t>(), py::arg("description_seed") = 0,
           py::arg("contact_stiffness_scale") = 1.0,
           py::arg("numbers_each") = std::vector<std::map<std::string, double>>(), py::arg("kernel") = "")
      .def(
          "step",
          [](FlightBatch& b, long n) {
            py::gil_scoped_release release;
            b.Step(n);
          },
          py::arg("n") = 1)
      .def(
          "reset",
          [](FlightBatch& b, const std::vector<int>& indices,
             const py::array_t<double, py::array::c_style | py::array::forcecast>& positions,
             const py::array_t<double, py::array::c_style | py::array::forcecast>& yaws) {
            const auto k = static_cast<py::ssize_t>(indices.size());
            if (positions.ndim() != 2 || positions.shape(0) != k || positions.shape(1) != 3)
              throw SimError("FlightBatch.reset: positions must have shape (" + std::to_string(k) + ", 3)");
            if (yaws.ndim() != 1 || yaws.shape(0) != k)
              throw SimError("FlightBatch.reset: yaws must have shape (" + std::to_string(k) + ",)");
            b.Reset(indices, positions.data(), yaws.data());
          },
          py::arg("indices"), py::arg("positions"), py::arg("yaws"))
      .def(
          "airframe", [](const FlightBatch& b, int i) { return AirframeDict(b.GetAirframe(i), b.Description()); },
          py::arg("i"), "Vehicle i's airframe: {'mass': kg, 'inertia': 3 x 3 kg m^2, 'motorConstant': per rotor, ...}.")
      .def_property_readonly(
          "nominal_airframe", [](const FlightBatch& b) { return AirframeDict(b.NominalAirframe(), b.Description()); },
          "The description's airframe (the xacro's).")
      .def(
          "set_airframe",
          [](FlightBatch& b, int i, const py::dict& values) {
            b.SetAirframe(i, AirframeFrom(b.NominalAirframe(), values, i, b.Description()));
          },
          py::arg("i"), py::arg("values"),
          "Vehicle i flies the nominal airframe with `values` (airframe()'s keys, any subset) in place.")
      .def(
          "set_airframes",
          [](FlightBatch& b, const std::vector<int>& indices, const py::dict& values) {
            b.SetAirframes(indices, AirframesFrom(b.NominalAirframe(), indices, values, b.Description()));
          },
          py::arg("indices"), py::arg("values"),
          "Vehicle indices[j] flies the nominal airframe with row j of each array of `values` in place; "
          "on a bad value no vehicle changes.")
      .def("set_seed", &FlightBatch::SetSeed, py::arg("i"), py::arg("seed"),
           "Vehicle i's random_seed (sensor and wind noise) from its next reset on.")
      .def(
          "set_seeds",
          [](FlightBatch& b, const std::vector<int>& indices, const std::vector<int64_t>& seeds) {
            if (indices.size() != seeds.size())
              throw rotors_sim::SimError("set_seeds: " + std::to_string(seeds.size()) + " seeds for " +
                                         std::to_string(indices.size()) + " vehicles");
            for (size_t k = 0; k < indices.size(); ++k) {
              if (indices[k] < 0 || indices[k] >= b.Count())
                throw rotors_sim::SimError("set_seeds: vehicle " + std::to_string(indices[k]) + " is not in 0.." +
                                           std::to_string(b.Count() - 1));
              if (seeds[k] < 0) throw rotors_sim::SimError("seed = " + std::to_string(seeds[k]) + " must be >= 0");
            }
            for (size_t k = 0; k < indices.size(); ++k) b.SetSeed(indices[k], static_cast<uint64_t>(seeds[k]));
          },
          py::arg("indices"), py::arg("seeds"),
          "set_seed for each of `indices` in one call; on a bad one none changes.")
      .def_property_readonly("count", &FlightBatch::Count)
      .def_property_readonly("rotor_count", &FlightBatch::Rotors)
      .def_property_readonly("threads", &FlightBatch::Threads)
      .def_property_readonly("kernel", &FlightBatch::Kernel)
      .def_property_readonly("step_size", &FlightBatch::StepSize)
      .def_property_readonly("command_columns", [](const FlightBatch& b) { return b.CommandColumns(); })
      .def_property_readonly("state_bytes_per_vehicle", &FlightBatch::StateBytesPerVehicle)
      .def_property_readonly("controller_bytes_per_vehicle", &FlightBatch::ControllerBytesPerVehicle)
      .def_property_readonly("noise_bytes_per_vehicle", &FlightBatch::NoiseBytesPerVehicle)
      .def_property_readonly("commands",
                             [](py::object self) {
                               FlightBatch& b = self.cast<FlightBatch&>();
                               return View(b.Commands(), b.Count(), b.CommandColumns(), self, true);
                             })
      .def_property_readonly("odometry",
                             [](py::object self) {
                               FlightBatch& b = self.cast<FlightBatch&>();
                               return View(b.Odometry(), b.Count(), 14, self, false);
                             })
      .def_property_readonly("odometry_count",
                             [](py::object self) {
                               FlightBatch& b = self.cast<FlightBatch&>();
                               return View(b.OdometryCount(), b.Count(), 1, self, false);
                             })
      .def_property_readonly("imu",
                             [](py::object self) {
                               FlightBatch& b = self.cast<FlightBatch&>();
                               return View(b.Imu(), b.Count(), 6, self, false);
                             })
      .def_property_readonly("rotor_speeds",
                             [](py::object self) {
                               FlightBatch& b = self.cast<FlightBatch&>();
                               return View(b.RotorSpeeds(), b.Count(), b.Rotors(), self, false);
                             })
      .def_property_readonly("in_contact",
                             [](py::object self) {
                               FlightBatch& b = self.cast<FlightBatch&>();
                               return View(b.InContact(), b.Count(), 1, self, false);
                             })
      .def_property_readonly("steps",
                             [](py::object self) {
                               FlightBatch& b = self.cast<FlightBatch&>();
                               return View(const_cast<uint64_t*>(b.Steps()), b.Count(), 1, self, false);
                             })
      .def_property_readonly("collided",
                             [](py::object self) {
                               FlightBatch& b = self.cast<FlightBatch&>();
                               return View(b.Collided(), b.Count(), 1, self, false);
                             })
      .def_property_readonly("collision_radius", &FlightBatch::CollisionRadius)
      .def("set_obstacles", &FlightBatch::SetObstacles, py::arg("field"),
           "Vehicle i flies among environment i's obstacles of field (None: none).")
      .def_property_readonly("obstacles", [](const FlightBatch& b) { return b.Obstacles(); })
      .def(
          "set_depth_camera",
          [](FlightBatch& b, const py::object& values) {
            b.SetDepthCamera(values.is_none()
                                 ? std::nullopt
                                 : std::optional<DepthCameraParams>(DepthCameraFrom(values.cast<py::dict>())));
          },
          py::arg("camera"), "A depth camera on every vehicle: a dict of its parameters ({} the defaults), or None.")
      .def_property_readonly("depth_camera",
                             [](const FlightBatch& b) -> py::object {
                               if (!b.DepthCamera()) return py::none();
                               return DepthCameraDict(*b.DepthCamera());
                             })
      .def(
          "render_depth",
          [](FlightBatch& b, const py::object& indices) {
            if (!b.DepthCamera())
              throw SimError("FlightBatch.render_depth: no depth camera; set one with set_depth_camera");
            std::vector<int> vehicles;
            if (indices.is_none()) {
              for (int i = 0; i < b.Count(); ++i) vehicles.push_back(i);
            } else {
              vehicles = indices.cast<std::vector<int>>();
            }
            const auto& c = *b.DepthCamera();
            py::array_t<float> a({static_cast<py::ssize_t>(vehicles.size()), static_cast<py::ssize_t>(c.height_px),
                                  static_cast<py::ssize_t>(c.width_px)});
            float* out = a.mutable_data();
            {
              py::gil_scoped_release release;
              b.RenderDepth(vehicles, out);
            }
            return a;
          },
          py::arg("indices") = py::none(),
          "The depth images now of `indices` (default every vehicle), k x H x W float32 [m] (NaN: out of range).")
      .def(
          "set_range_rays",
          [](FlightBatch& b, const py::object& dirs, const Eigen::Vector3d& xyz, double min_range, double max_range) {
            if (dirs.is_none()) {
              b.SetRangeRays(std::nullopt);
              return;
            }
            const auto a = dirs.cast<py::array_t<double, py::array::c_style | py::array::forcecast>>();
            if (a.ndim() != 2 || a.shape(1) != 3)
              throw SimError("FlightBatch.set_range_rays: dirs must have shape (k, 3)");
            rotors_flight_batch::RangeRays rays;
            auto r = a.unchecked<2>();
            for (py::ssize_t k = 0; k < a.shape(0); ++k) rays.dirs_M.emplace_back(r(k, 0), r(k, 1), r(k, 2));
            rays.p_M_m = xyz;
            rays.min_range_m = min_range, rays.max_range_m = max_range;
            b.SetRangeRays(rays);
          },
          py::arg("dirs"), py::arg("xyz") = Eigen::Vector3d::Zero(), py::arg("min_range") = 0.0,
          py::arg("max_range") = 10.0,
          "Range rays on every vehicle: directions (k x 3, model frame) from xyz, or None.")
      .def(
          "cast_ranges",
          [](FlightBatch& b) {
            if (!b.GetRangeRays())
              throw SimError("FlightBatch.cast_ranges: no range rays; set them with set_range_rays");
            py::array_t<double> a(
                {static_cast<py::ssize_t>(b.Count()), static_cast<py::ssize_t>(b.GetRangeRays()->dirs_M.size())});
            double* out = a.mutable_data();
            {
              py::gil_scoped_release release;
              b.CastRanges(out);
            }
            return a;
          },
          "Every vehicle's range per ray now, N x k [m] (inf: no return).")
      .def(
          "truth",
          [](py::object self) {
            FlightBatch& b = self.cast<FlightBatch&>();
            return View(b.Truth(), b.Count(), 13, self, false);
          },
          "Ground truth of the model frame, N x 13: position_W, orientation (x, y, z, w), velocity_W, "
          "angular_velocity_B (computed at this call).");
}

}  // namespace rotors_python
