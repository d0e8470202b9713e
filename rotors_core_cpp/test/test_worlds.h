// Worlds and models for the engine tests, as SDF/URDF text.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#include <Eigen/Geometry>
#include <ignition/math/Pose3.hh>

#include "rotors_core/physics/world.h"

/// "x y z roll pitch yaw" of a pose, for SDF text.
inline std::string PoseText(const ignition::math::Pose3d& X) {
  std::ostringstream s;
  s.precision(17);
  s << X.Pos().X() << " " << X.Pos().Y() << " " << X.Pos().Z() << " " << X.Rot().Roll() << " " << X.Rot().Pitch() << " "
    << X.Rot().Yaw();
  return s.str();
}

inline Eigen::Isometry3d ToEigen(const ignition::math::Pose3d& X) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(X.Rot().W(), X.Rot().X(), X.Rot().Y(), X.Rot().Z()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(X.Pos().X(), X.Pos().Y(), X.Pos().Z());
  return T;
}

inline std::string WorldSdf(double step_s, double gravity_z, bool ground, const std::string& solver = "quick",
                            int iters = 1000, const std::string& ground_surface = "") {
  std::ostringstream s;
  s << "<?xml version='1.0'?><sdf version='1.6'><world name='test'>"
    << "<gravity>0 0 " << gravity_z << "</gravity>"
    << "<physics type='ode'><max_step_size>" << step_s << "</max_step_size><real_time_factor>1</real_time_factor>"
    << "<real_time_update_rate>" << 1.0 / step_s << "</real_time_update_rate>"
    << "<ode><solver><type>" << solver << "</type><iters>" << iters << "</iters><sor>1.3</sor></solver>"
    << "<constraints><cfm>0</cfm><erp>0.2</erp><contact_max_correcting_vel>100</contact_max_correcting_vel>"
    << "<contact_surface_layer>0.001</contact_surface_layer></constraints></ode></physics>";
  if (ground) {
    s << "<model name='ground_plane'><static>true</static><link name='link'><collision name='collision'>"
      << "<geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry>" << ground_surface
      << "</collision></link></model>";
  }
  s << "</world></sdf>";
  return s.str();
}

/// A single box link: mass [kg], inertia diag [kg m^2], box size [m].
inline std::string BoxUrdf(const std::string& name, double mass, double ixx, double iyy, double izz, double sx,
                           double sy, double sz, const std::string& extra = "") {
  std::ostringstream s;
  s << "<robot name='" << name << "'><link name='" << name << "/base_link'><inertial><mass value='" << mass
    << "'/><origin xyz='0 0 0'/><inertia ixx='" << ixx << "' ixy='0' ixz='0' iyy='" << iyy << "' iyz='0' izz='" << izz
    << "'/></inertial><collision><geometry><box size='" << sx << " " << sy << " " << sz
    << "'/></geometry></collision></link>" << extra << "</robot>";
  return s.str();
}

/// Unloads the world's plugins and models when a test ends (they hold pointers to the world).
struct WorldGuard {
  rotors_sim::physics::WorldPtr world;
  ~WorldGuard() {
    if (world) world->Fini();
  }
};

// Files the tests write: a temporary folder of this process, a floor mesh and a heightmap ramp.
inline std::filesystem::path TempDir() {
  static std::filesystem::path dir = [] {
    std::filesystem::path d =
        std::filesystem::temp_directory_path() / ("rotors_geometry_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

/// A square floor of two triangles at height z, edge 2 a, as an OBJ file.
inline std::string FloorObj(double a, double z) {
  const std::filesystem::path p = TempDir() / "floor.obj";
  std::ofstream f(p);
  f << "v " << -a << " " << -a << " " << z << "\nv " << a << " " << -a << " " << z << "\nv " << a << " " << a << " "
    << z << "\nv " << -a << " " << a << " " << z << "\nf 1 2 3\nf 1 3 4\n";
  return p.string();
}

/// An n x n 8-bit PGM whose grey value rises linearly with the column: a ramp along +x.
inline std::string RampPgm(int n, const std::string& name = "ramp.pgm", int rows = -1) {
  const std::filesystem::path p = TempDir() / name;
  std::ofstream f(p, std::ios::binary);
  f << "P5\n" << n << " " << (rows < 0 ? n : rows) << "\n255\n";
  for (int r = 0; r < (rows < 0 ? n : rows); ++r)
    for (int c = 0; c < n; ++c) f.put(static_cast<char>(c * 255 / (n - 1)));
  return p.string();
}
