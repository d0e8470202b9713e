// The radius of the sphere around the base link's origin that holds every collision and visual
// shape of a URDF (the planner keeps this much, plus a margin, from every obstacle). Visuals count:
// RotorS' propellers are visuals only, and they sweep the widest disk.
#pragma once

#include <functional>
#include <string>

namespace rotors_planning {

/// [m] the largest distance of a mesh file's vertices from its origin, unscaled; throws
/// std::invalid_argument naming the file when it cannot be read.
using MeshRadiusFn = std::function<double(const std::string& filename)>;

/// Over every link's collisions and visuals: |p_BS| + the shape's bounding radius (box: half
/// diagonal; cylinder: sqrt(r^2 + (l/2)^2); sphere: r; mesh: mesh_radius(file) times the largest
/// scale). Throws std::invalid_argument naming the problem for XML that is no URDF or has no shape.
double VehicleRadius_m(const std::string& urdf_xml, const MeshRadiusFn& mesh_radius);

}  // namespace rotors_planning
