// rotors_path_clearance MAP.bt POINTS.txt [dx dy dz]: the smallest distance from a flown or planned
// path (one "x y z" per line, world frame, moved by (dx, dy, dz) [m] into the map's frame) to the
// map's occupied cells, searched within 5 m. Prints "points N, smallest clearance D m at (x, y, z)".
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <vector>

#include <octomap/OcTree.h>

#include "read_octree.h"
#include "rotors_planning/occupancy_grid.h"

int main(int argc, char** argv) {
  if (argc != 3 && argc != 6) {
    std::fprintf(stderr, "usage: rotors_path_clearance MAP.bt POINTS.txt [dx dy dz]\n");
    return 2;
  }
  const auto tree = rotors_planning::ReadOcTree("rotors_path_clearance", argv[1]);
  if (!tree) return 2;
  const Eigen::Vector3d shift =
      argc == 6 ? Eigen::Vector3d(std::atof(argv[3]), std::atof(argv[4]), std::atof(argv[5])) : Eigen::Vector3d::Zero();
  std::ifstream in(argv[2]);
  std::vector<Eigen::Vector3d> points;
  for (Eigen::Vector3d p; in >> p.x() >> p.y() >> p.z();) points.push_back(p + shift);
  if (points.empty()) {
    std::fprintf(stderr, "rotors_path_clearance: no points in '%s'\n", argv[2]);
    return 2;
  }
  const double search_m = 5.0;
  Eigen::Vector3d lo = points.front(), hi = points.front();
  for (const auto& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Eigen::Vector3d pad = Eigen::Vector3d::Constant(search_m + 1.0);
  const rotors_planning::OccupancyGrid grid(*tree, lo - pad, hi + pad);
  double smallest = std::numeric_limits<double>::infinity();
  Eigen::Vector3d where = points.front();
  for (const auto& p : points) {
    const double d = grid.Clearance_m(p, search_m);
    if (d < smallest) {
      smallest = d;
      where = p - shift;
    }
  }
  std::printf("points %zu, smallest clearance %.4f m at (%.2f, %.2f, %.2f)\n", points.size(), smallest, where.x(),
              where.y(), where.z());
  return 0;
}
