// Vehicle parameters of the shipped yamls (RotorS' rotors_gazebo/resource/<mav>.yaml).
#pragma once

#include <cmath>

#include "rotors_control/vehicle_parameters.h"

namespace rotors_control {

inline MultirotorParameters FireflyYaml() {
  MultirotorParameters v;
  v.mass_kg = 1.56779;
  v.inertia_kg_m2 = Eigen::Vector3d(0.0347563, 0.0458929, 0.0977).asDiagonal();
  const double angles[6] = {0.5236, 1.5708, 2.6180, -2.6180, -1.5708, -0.5236};
  for (int i = 0; i < 6; ++i) v.rotors.push_back({angles[i], 0.215, 8.54858e-6, 1.6e-2, i % 2 == 0 ? 1 : -1});
  return v;
}

inline MultirotorParameters PelicanYaml() {
  MultirotorParameters v;
  v.mass_kg = 1.0;
  v.inertia_kg_m2 = Eigen::Vector3d(0.01, 0.01, 0.02).asDiagonal();
  const double angles[4] = {0.0, M_PI / 2, M_PI, -M_PI / 2};
  const int dirs[4] = {-1, 1, -1, 1};
  for (int i = 0; i < 4; ++i) v.rotors.push_back({angles[i], 0.21, 9.9865e-6, 1.6e-2, dirs[i]});
  return v;
}

}  // namespace rotors_control
