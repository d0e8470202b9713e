// rotors_octomap_compare A.bt B.bt [dx dy dz]: how far two OctoMaps of the same resolution agree.
// Every occupied leaf of A, moved by (dx, dy, dz) [m], is looked up in B; prints the occupied
// volumes, the shared volume, intersection over union, and the parts of each that lie within one
// leaf of the other (a one-cell tolerance for surfaces sampled on shifted grids).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include <octomap/octomap.h>

#include "rotors_core/geometry/octree_cells.h"

namespace {

std::unique_ptr<octomap::OcTree> Read(const char* path) {
  std::unique_ptr<octomap::OcTree> tree(new octomap::OcTree(0.1));
  if (!tree->readBinary(path)) {
    std::fprintf(stderr, "rotors_octomap_compare: cannot read '%s' as a binary OctoMap (.bt)\n", path);
    std::exit(2);
  }
  return tree;
}

bool Occupied(const octomap::OcTree& tree, const octomap::point3d& p) {
  const octomap::OcTreeNode* node = tree.search(p);
  return node && tree.isNodeOccupied(node);
}

bool OccupiedNear(const octomap::OcTree& tree, const octomap::point3d& p, double step) {
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      for (int k = -1; k <= 1; ++k)
        if (Occupied(tree, p + octomap::point3d(i * step, j * step, k * step))) return true;
  return false;
}

struct Overlap {
  double volume_m3 = 0.0, shared_m3 = 0.0, near_m3 = 0.0;
};

/// The occupied cells of `a`, moved by `offset`, looked up in `b`.
Overlap Compare(const octomap::OcTree& a, const octomap::OcTree& b, const octomap::point3d& offset) {
  Overlap o;
  const double res = a.getResolution(), cell = res * res * res;
  rotors_sim::geometry::ForEachOccupiedCell(a, [&](const octomap::point3d& centre) {
    const octomap::point3d p = centre + offset;
    o.volume_m3 += cell;
    if (Occupied(b, p)) o.shared_m3 += cell;
    if (OccupiedNear(b, p, res)) o.near_m3 += cell;
  });
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3 && argc != 6) {
    std::fprintf(stderr, "usage: rotors_octomap_compare A.bt B.bt [dx dy dz]  (A's leaves are moved by d [m])\n");
    return 2;
  }
  const auto a = Read(argv[1]);
  const auto b = Read(argv[2]);
  if (std::abs(a->getResolution() - b->getResolution()) > 1e-9) {
    std::fprintf(stderr, "rotors_octomap_compare: resolutions differ (%g m and %g m); compare maps of one leaf size\n",
                 a->getResolution(), b->getResolution());
    return 2;
  }
  const octomap::point3d d = argc == 6 ? octomap::point3d(std::atof(argv[3]), std::atof(argv[4]), std::atof(argv[5]))
                                       : octomap::point3d(0, 0, 0);
  const Overlap ab = Compare(*a, *b, d);
  const Overlap ba = Compare(*b, *a, d * -1.0);
  const double uni = ab.volume_m3 + ba.volume_m3 - ab.shared_m3;
  std::printf("occupied A %.3f m^3, B %.3f m^3, both %.3f m^3\n", ab.volume_m3, ba.volume_m3, ab.shared_m3);
  std::printf("intersection over union %.4f\n", uni > 0 ? ab.shared_m3 / uni : 1.0);
  std::printf("A within one leaf of B %.4f, B within one leaf of A %.4f\n",
              ab.volume_m3 > 0 ? ab.near_m3 / ab.volume_m3 : 1.0, ba.volume_m3 > 0 ? ba.near_m3 / ba.volume_m3 : 1.0);
  return 0;
}
