// rotors_octomap_distance MAP.bt POINTS.txt [dx dy dz]: how far points (one "x y z" per line, world
// frame, moved by (dx, dy, dz) [m] into the map's frame) lie from the map's occupied cells. The
// distance of a point is that to the nearest occupied cell's cube (0 on or inside one), searched
// within 1 m. Prints the count, the median, the 99th percentile and the largest distance [m], and
// how many points have no occupied cell within 1 m.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <vector>

#include <octomap/octomap.h>

namespace {

/// Distance from p to the axis-aligned cube of half size h around c.
double DistanceToCube(const octomap::point3d& p, const octomap::point3d& c, double h) {
  double d2 = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double excess = std::max(0.0, std::abs(p(a) - c(a)) - h);
    d2 += excess * excess;
  }
  return std::sqrt(d2);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3 && argc != 6) {
    std::fprintf(stderr, "usage: rotors_octomap_distance MAP.bt POINTS.txt [dx dy dz]\n");
    return 2;
  }
  octomap::OcTree tree(0.1);
  if (!tree.readBinary(argv[1])) {
    std::fprintf(stderr, "rotors_octomap_distance: cannot read '%s' as a binary OctoMap (.bt)\n", argv[1]);
    return 2;
  }
  std::ifstream in(argv[2]);
  if (!in) {
    std::fprintf(stderr, "rotors_octomap_distance: cannot read points from '%s'\n", argv[2]);
    return 2;
  }
  const octomap::point3d offset = argc == 6
                                      ? octomap::point3d(std::atof(argv[3]), std::atof(argv[4]), std::atof(argv[5]))
                                      : octomap::point3d(0, 0, 0);
  const double search_m = 1.0;
  std::vector<double> distances;
  size_t lonely = 0;
  double x, y, z;
  while (in >> x >> y >> z) {
    const octomap::point3d p = octomap::point3d(x, y, z) + offset;
    double best = INFINITY;
    const octomap::point3d lo = p - octomap::point3d(1, 1, 1) * search_m, hi = p + octomap::point3d(1, 1, 1) * search_m;
    for (auto it = tree.begin_leafs_bbx(lo, hi); it != tree.end_leafs_bbx(); ++it)
      if (tree.isNodeOccupied(*it)) best = std::min(best, DistanceToCube(p, it.getCoordinate(), it.getSize() / 2));
    if (std::isinf(best)) ++lonely;
    else distances.push_back(best);
  }
  if (distances.empty()) {
    std::printf("points 0, without an occupied cell within %.1f m %zu\n", search_m, lonely);
    return 0;
  }
  std::sort(distances.begin(), distances.end());
  auto quantile = [&](double q) { return distances[static_cast<size_t>(q * (distances.size() - 1))]; };
  std::printf("points %zu, median %.4f m, p99 %.4f m, max %.4f m, without an occupied cell within %.1f m %zu\n",
              distances.size() + lonely, quantile(0.5), quantile(0.99), distances.back(), search_m, lonely);
  return 0;
}
