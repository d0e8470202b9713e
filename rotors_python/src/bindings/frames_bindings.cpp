// rotors_sim._engine.frames and .atmosphere: the one frames module (rotors_plugins'
// autopilot/frames.h) and the one standard atmosphere (models/standard_atmosphere.h) of the
// autopilot codecs, for Python code that meets an autopilot (rotors_hil_interface, tests).
#include <pybind11/eigen.h>

#include "bindings.h"
#include "rotors_gazebo_plugins/autopilot/frames.h"
#include "rotors_gazebo_plugins/models/standard_atmosphere.h"

namespace rotors_python {

void BindFrames(pybind11::module_& m) {
  namespace frames = rotors_gazebo_plugins::frames;
  auto f = m.def_submodule("frames", "ENU/FLU (ours, REP-103) to NED/FRD (the autopilots'), as the codecs convert");
  f.def("ned_from_enu", &frames::NedFromEnu, pybind11::arg("v_ENU"), "(north, east, down) of (east, north, up)");
  f.def("frd_from_flu", &frames::FrdFromFlu, pybind11::arg("v_FLU"), "(forward, right, down) of (forward, left, up)");
  f.def(
      "ned_frd_from_enu_flu",
      [](const Eigen::Vector4d& q_wxyz) {
        const Eigen::Quaterniond q =
            frames::NedFrdFromEnuFlu(Eigen::Quaterniond(q_wxyz[0], q_wxyz[1], q_wxyz[2], q_wxyz[3]));
        return Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
      },
      pybind11::arg("q_ENU_FLU_wxyz"), "q NED <- FRD (w, x, y, z, w >= 0) of q ENU <- FLU (w, x, y, z)");
  auto a = m.def_submodule("atmosphere", "the 1976 standard atmosphere below 11 km");
  a.def("pressure_Pa", &rotors_gazebo_plugins::StandardAtmospherePressure, pybind11::arg("altitude_m"));
  a.def("pressure_altitude_m", &rotors_gazebo_plugins::PressureAltitude, pybind11::arg("pressure_Pa"));
  a.def("temperature_C", &rotors_gazebo_plugins::StandardAtmosphereTemperature_C, pybind11::arg("altitude_m"));
  a.def("density_kg_m3", &rotors_gazebo_plugins::StandardAtmosphereDensity, pybind11::arg("altitude_m"));
}

}  // namespace rotors_python
