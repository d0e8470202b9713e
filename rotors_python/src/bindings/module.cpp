// rotors_sim._engine: the C++ engine, its plugins and the controller libraries, without ROS.
// The Python package rotors_sim wraps it (xacro, messages, Gymnasium environments).
#include "bindings.h"

PYBIND11_MODULE(_engine, m) {
  m.doc() = "The rotors_simulator engine without ROS (see the rotors_sim package).";
  rotors_python::BindWorld(m);
  rotors_python::BindControllers(m);
  rotors_python::BindFrames(m);
  rotors_python::BindFlightBatch(m);
  rotors_python::BindRowMath(m);
}
