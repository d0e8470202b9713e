// rotors_sim._engine.LeePositionController / AttitudeLevelController: the controller libraries of
// rotors_control (no ROS), with their parameters read by the same loaders as the ROS nodes
// (parameter_loading.h) from the same yaml files, flattened by Python into "a/b/c" -> number.
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <utility>
#include <set>
#include <string>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "rotors_control/attitude_controllers.h"
#include "rotors_control/lee_controller.h"
#include "rotors_control/parameter_loading.h"
#include "rotors_gazebo_plugins/models/fixed_wing_model.h"
#include "rotors_gazebo_plugins/models/standard_atmosphere.h"
#include "rotors_core/error.h"
#include "rotors_params/map_param_reader.h"

namespace py = pybind11;

namespace rotors_python {
namespace {

using rotors_control::VehicleState;
using rotors_sim::SimError;

}  // namespace

VehicleState StateFromOdometry(const Eigen::Vector3d& position_W, const Eigen::Vector4d& q_xyzw,
                               const Eigen::Vector3d& velocity_B, const Eigen::Vector3d& angular_velocity_B) {
  if (!position_W.allFinite() || !q_xyzw.allFinite() || !velocity_B.allFinite() || !angular_velocity_B.allFinite())
    throw SimError("controller state must be finite (position, orientation, velocity, angular_velocity)");
  VehicleState s;
  s.position_W = position_W;
  // as mav_msgs::quaternionFromMsg, which the ROS nodes use: normalized, identity when ~0
  const Eigen::Quaterniond q(q_xyzw[3], q_xyzw[0], q_xyzw[1], q_xyzw[2]);
  s.orientation_W_B = q.norm() >= 1.e-6 ? q.normalized() : Eigen::Quaterniond::Identity();
  s.velocity_B = velocity_B;
  s.angular_velocity_B = angular_velocity_B;
  return s;
}

namespace {

/// The reader of the parameter map, with its unknown keys and announcements kept for Python.
struct LoadReport {
  std::vector<std::string> unknown_keys, defaults;
};

template <class Load>
LoadReport LoadWith(const std::map<std::string, double>& numbers, const std::vector<std::string>& others,
                    const std::string& source, Load load) {
  rotors_params::MapParamReader reader(numbers, std::set<std::string>(others.begin(), others.end()), source);
  const std::string why = load(reader);
  if (!why.empty()) throw SimError(why);
  return {reader.UnknownKeys(), reader.Defaults()};
}

/// The Lee controller as lee_position_controller_node runs it: set points due at a sim time are
/// released with the first odometry stamped at or after it.
class PyLee : public OdometryController {
 public:
  PyLee(const std::map<std::string, double>& numbers, const std::vector<std::string>& others, const std::string& source)
      : report_(LoadWith(
            numbers, others, source,
            [this](rotors_params::MapParamReader& r) { return rotors_control::LoadLeeParameters(r, &params_); })),
        controller_(params_) {}

  void SetTrajectoryPoint(const Eigen::Vector3d& p, const Eigen::Vector3d& v, const Eigen::Vector3d& a, double yaw,
                          double yaw_rate, double due_s) {
    rotors_control::TrajectoryPoint point;
    point.position_W = p;
    point.velocity_W = v;
    point.acceleration_W = a;
    point.yaw_rad = yaw;
    point.yaw_rate_rad_s = yaw_rate;
    if (!point.IsFinite()) throw SimError("trajectory point must be finite (position, velocity, acceleration, yaw)");
    if (!std::isfinite(due_s)) throw SimError("due time must be finite");
    if (due_s <= t_odometry_s_) {
      controller_.SetTrajectoryPoint(point);
      pending_.reset();
    } else {
      pending_ = std::make_pair(due_s, point);
    }
  }
  Eigen::VectorXd Answer(const VehicleState& state, double stamp_s) override {
    t_odometry_s_ = stamp_s;
    if (pending_ && pending_->first <= stamp_s) {
      controller_.SetTrajectoryPoint(pending_->second);
      pending_.reset();
    }
    return controller_.RotorSpeeds(state);
  }
  const LoadReport& Report() const { return report_; }
  const rotors_control::LeeControllerParameters& Params() const { return params_; }
  bool HasReference() const { return controller_.HasReference(); }

 private:
  rotors_control::LeeControllerParameters params_;
  LoadReport report_;
  rotors_control::LeeController controller_;
  std::optional<std::pair<double, rotors_control::TrajectoryPoint>> pending_;  ///< (due sim time, point)
  double t_odometry_s_ = -std::numeric_limits<double>::infinity();             ///< stamp of the last odometry
};

class PyAttitude : public OdometryController {
 public:
  PyAttitude(const std::map<std::string, double>& numbers, const std::vector<std::string>& others,
             const std::string& source)
      : report_(LoadWith(numbers, others, source,
                         [this](rotors_params::MapParamReader& r) {
                           std::string why = rotors_control::LoadAttitudeGains(r, &params_.attitude);
                           return why.empty() ? rotors_control::LoadVehicleParameters(r, &params_.vehicle) : why;
                         })),
        controller_(params_) {}

  static void Finite(std::initializer_list<double> values, const char* what) {
    for (double x : values)
      if (!std::isfinite(x)) throw SimError(std::string(what) + " must be finite");
  }
  void RollPitchYawrateThrust(double roll, double pitch, double yaw_rate, double thrust_N) {
    Finite({roll, pitch, yaw_rate, thrust_N}, "roll, pitch, yaw_rate and thrust");
    controller_.SetRollPitchYawrateThrust(roll, pitch, yaw_rate, thrust_N);
  }
  void AttitudeThrust(const Eigen::Vector4d& q_xyzw, double thrust_N) {
    Finite({q_xyzw[0], q_xyzw[1], q_xyzw[2], q_xyzw[3], thrust_N}, "attitude and thrust");
    if (q_xyzw.norm() < 1e-9) throw SimError("attitude must be a non-zero quaternion (x, y, z, w)");
    controller_.SetAttitudeThrust(Eigen::Quaterniond(q_xyzw[3], q_xyzw[0], q_xyzw[1], q_xyzw[2]).normalized(),
                                  thrust_N);
  }
  void RateThrust(const Eigen::Vector3d& omega_B, double thrust_N) {
    Finite({omega_B[0], omega_B[1], omega_B[2], thrust_N}, "rates and thrust");
    controller_.SetRateThrust(omega_B, thrust_N);
  }
  Eigen::VectorXd Answer(const VehicleState& state, double /*stamp_s*/) override {
    return controller_.RotorSpeeds(state);
  }
  const LoadReport& Report() const { return report_; }
  const rotors_control::AttitudeControllerParameters& Params() const { return params_; }

 private:
  rotors_control::AttitudeControllerParameters params_;
  LoadReport report_;
  rotors_control::AttitudeLevelController controller_;
};

py::dict VehicleDict(const rotors_control::MultirotorParameters& v) {
  py::dict d;
  d["mass_kg"] = v.mass_kg;
  d["gravity_m_s2"] = v.gravity_m_s2;
  d["inertia_kg_m2"] = Eigen::Matrix3d(v.inertia_kg_m2);
  py::list rotors;
  for (const auto& r : v.rotors) {
    py::dict rotor;
    rotor["angle_rad"] = r.angle_rad;
    rotor["arm_length_m"] = r.arm_length_m;
    rotor["rotor_force_constant"] = r.rotor_force_constant;
    rotor["rotor_moment_constant"] = r.rotor_moment_constant;
    rotor["direction"] = r.direction;
    rotor["max_rot_velocity_rad_s"] = r.max_rot_velocity_rad_s;
    rotors.append(rotor);
  }
  d["rotors"] = rotors;
  return d;
}

}  // namespace

void BindControllers(py::module_& m) {
  // RotorS' fixed-wing model (engine-free), e.g. for trim computations with the simulator's coefficients
  py::class_<rotors_gazebo_plugins::FixedWingModel>(m, "FixedWingModel")
      .def(py::init([](const std::string& aero_yaml, const std::string& vehicle_yaml) {
             try {
               return rotors_gazebo_plugins::FixedWingModel(
                   rotors_gazebo_plugins::FixedWingAeroParams::FromYaml(aero_yaml),
                   rotors_gazebo_plugins::FixedWingVehicleParams::FromYaml(vehicle_yaml));
             } catch (const std::exception& e) {
               throw SimError(e.what());
             }
           }),
           py::arg("aero_params_yaml"), py::arg("vehicle_params_yaml"))
      .def(
          "compute",
          [](const rotors_gazebo_plugins::FixedWingModel& model, const Eigen::Vector3d& v_air_B,
             const Eigen::Vector3d& omega_B, const std::vector<double>& normalized, double altitude_m) {
            rotors_gazebo_plugins::FixedWingInputs u;
            const std::string why =
                rotors_gazebo_plugins::FixedWingInputs::FromNormalized(normalized, model.Vehicle(), &u);
            if (!why.empty()) throw SimError(why);
            const auto w =
                model.Compute(v_air_B, omega_B, u, rotors_gazebo_plugins::StandardAtmosphereDensity(altitude_m));
            py::dict out;
            out["force_B"] = w.force_B;
            out["moment_B"] = w.moment_B;
            out["alpha"] = w.alpha_rad;
            out["beta"] = w.beta_rad;
            out["airspeed"] = w.airspeed_m_s;
            out["lift_coefficient"] = w.lift_coefficient;
            return out;
          },
          py::arg("v_air_B"), py::arg("omega_B"), py::arg("normalized"), py::arg("altitude_m"),
          "Force and moment (body frame FLU) for the airspeed and rates (FLU) and a normalized command, in "
          "the standard atmosphere at altitude_m [m] (as the plugin: the world's elevation plus the height).");

  const char* state_doc =
      "Rotor speeds [rad/s] for the state as the ROS node takes it from odometry: position_W, "
      "orientation (x, y, z, w), velocity_B and angular_velocity_B in the body frame.";
  auto answer = [](OdometryController& c, const Eigen::Vector3d& p, const Eigen::Vector4d& q,
                   const Eigen::Vector3d& v_B, const Eigen::Vector3d& w_B,
                   double stamp_s) { return c.Answer(StateFromOdometry(p, q, v_B, w_B), stamp_s); };
  py::class_<OdometryController, std::shared_ptr<OdometryController>>(m, "OdometryController")
      .def("answer", answer, py::arg("position"), py::arg("orientation"), py::arg("velocity_B"),
           py::arg("angular_velocity_B"), py::arg("stamp"), state_doc);
  py::class_<PyLee, OdometryController, std::shared_ptr<PyLee>>(m, "LeePositionController")
      .def(py::init<const std::map<std::string, double>&, const std::vector<std::string>&, const std::string&>(),
           py::arg("numbers"), py::arg("others"), py::arg("source"))
      .def("set_trajectory_point", &PyLee::SetTrajectoryPoint, py::arg("position"), py::arg("velocity"),
           py::arg("acceleration"), py::arg("yaw"), py::arg("yaw_rate"), py::arg("due") = -1e300)
      .def_property_readonly("has_reference", &PyLee::HasReference)
      .def_property_readonly("unknown_keys", [](const PyLee& c) { return c.Report().unknown_keys; })
      .def_property_readonly("defaults", [](const PyLee& c) { return c.Report().defaults; })
      .def_property_readonly("vehicle", [](const PyLee& c) { return VehicleDict(c.Params().vehicle); });
  py::class_<PyAttitude, OdometryController, std::shared_ptr<PyAttitude>>(m, "AttitudeLevelController")
      .def(py::init<const std::map<std::string, double>&, const std::vector<std::string>&, const std::string&>(),
           py::arg("numbers"), py::arg("others"), py::arg("source"))
      .def("set_roll_pitch_yawrate_thrust", &PyAttitude::RollPitchYawrateThrust, py::arg("roll"), py::arg("pitch"),
           py::arg("yaw_rate"), py::arg("thrust"))
      .def("set_attitude_thrust", &PyAttitude::AttitudeThrust, py::arg("orientation"), py::arg("thrust"))
      .def("set_rate_thrust", &PyAttitude::RateThrust, py::arg("angular_velocity_B"), py::arg("thrust"))
      .def_property_readonly("unknown_keys", [](const PyAttitude& c) { return c.Report().unknown_keys; })
      .def_property_readonly("defaults", [](const PyAttitude& c) { return c.Report().defaults; })
      .def_property_readonly("vehicle", [](const PyAttitude& c) { return VehicleDict(c.Params().vehicle); });
}

}  // namespace rotors_python
