// The occupied volume of an OcTree as cells of its resolution: pruned leaves (larger cubes of
// equal children) are split back into their cells. Header-only; depends on OctoMap alone.
#pragma once

#include <cmath>

#include <octomap/OcTree.h>

namespace rotors_sim {
namespace geometry {

/// Calls visit(centre) for the centre of every occupied cell of `tree` (tree frame).
template <typename Visit>
void ForEachOccupiedCell(const octomap::OcTree& tree, Visit visit) {
  const double res = tree.getResolution();
  for (auto it = tree.begin_leafs(); it != tree.end_leafs(); ++it) {
    if (!tree.isNodeOccupied(*it)) continue;
    const double size = it.getSize();
    const int n = static_cast<int>(std::lround(size / res));
    const octomap::point3d corner = it.getCoordinate() - octomap::point3d(1, 1, 1) * static_cast<float>(size / 2);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        for (int k = 0; k < n; ++k) visit(corner + octomap::point3d((i + 0.5) * res, (j + 0.5) * res, (k + 0.5) * res));
  }
}

}  // namespace geometry
}  // namespace rotors_sim
