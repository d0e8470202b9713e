// Wind that varies in space or time, engine-free:
//   WindField:   RotorS' custom static wind field (customWindFieldPath, the hemicyl format): a
//                terrain-following grid of n_x x n_y columns; column (i, j) spans bottom_z to top_z and
//                holds a level at bottom_z + f_k (top_z - bottom_z) for each vertical_spacing_factor
//                f_k. u, v, w are listed x fastest, then y, then level. The velocity at a point is
//                interpolated linearly along each of the four surrounding columns, then bilinearly
//                in x and y (trilinear on the terrain-following grid).
//   WindProfile: a wind velocity over time from a text file ("t vx vy vz" per line, '#' comments),
//                interpolated linearly, held at the first and last values outside.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace rotors_gazebo_plugins {

class WindField {
 public:
  /// Parses the file; throws std::runtime_error("<path>: <what is wrong>").
  static WindField Load(const std::string& path);
  /// The field's velocity at p_W [m/s]; false outside the grid (horizontally or vertically).
  bool Velocity(const Eigen::Vector3d& p_W, Eigen::Vector3d* v_W) const;

  double min_x = 0.0, min_y = 0.0, res_x = 0.0, res_y = 0.0;
  int n_x = 0, n_y = 0;
  std::vector<double> vertical_spacing_factors;  ///< f_k, increasing in [0, 1]
  std::vector<double> bottom_z, top_z;           ///< per column, index i + j n_x
  std::vector<double> u, v, w;                   ///< index i + j n_x + k n_x n_y

 private:
  /// The velocity along column (i, j) at height z, linear between its levels; false outside it.
  bool ColumnVelocity(int i, int j, double z, Eigen::Vector3d* v_W) const;
};

class WindProfile {
 public:
  /// Parses the file; throws std::runtime_error("<path>:<line>: <what is wrong>").
  static WindProfile Load(const std::string& path);
  Eigen::Vector3d Velocity(double t_s) const;

  std::vector<double> t_s;
  std::vector<Eigen::Vector3d> velocity_W;
};

}  // namespace rotors_gazebo_plugins
