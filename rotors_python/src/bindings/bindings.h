// The parts of the rotors_sim._engine module (pybind11).
#pragma once

#include <pybind11/pybind11.h>

namespace rotors_python {
void BindWorld(pybind11::module_& m);
void BindControllers(pybind11::module_& m);
}  // namespace rotors_python
