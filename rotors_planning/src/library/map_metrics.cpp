#include "rotors_planning/map_metrics.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_set>

#include <octomap/OcTree.h>

namespace rotors_planning {
namespace {

using KeySet = std::unordered_set<octomap::OcTreeKey, octomap::OcTreeKey::KeyHash>;

/// Every finest-depth key of the tree's leaves, split by occupancy (a pruned leaf covers many).
void FinestKeys(const octomap::OcTree& tree, KeySet* occupied, KeySet* free) {
  const unsigned depth = tree.getTreeDepth();
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    KeySet* set = tree.isNodeOccupied(*it) ? occupied : free;
    if (!set) continue;
    const unsigned cells = 1u << (depth - it.getDepth());
    const octomap::OcTreeKey base = it.getIndexKey();  // the leaf's lowest finest key
    for (unsigned i = 0; i < cells; ++i)
      for (unsigned j = 0; j < cells; ++j)
        for (unsigned k = 0; k < cells; ++k) set->insert(octomap::OcTreeKey(base[0] + i, base[1] + j, base[2] + k));
  }
}

bool AnyNear(const KeySet& set, const octomap::OcTreeKey& key, bool faces_only) {
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz) {
        if (faces_only && std::abs(dx) + std::abs(dy) + std::abs(dz) != 1) continue;
        if (set.count(octomap::OcTreeKey(key[0] + dx, key[1] + dy, key[2] + dz))) return true;
      }
  return false;
}

}  // namespace

MapMetrics CompareMaps(const octomap::OcTree& built, const octomap::OcTree& truth, std::vector<LabelledCell>* cells) {
  if (std::abs(built.getResolution() - truth.getResolution()) > 1e-9) {
    throw std::invalid_argument("the maps' resolutions differ: built " + std::to_string(built.getResolution()) +
                                " m, truth " + std::to_string(truth.getResolution()) +
                                " m; build the map at the truth's");
  }
  KeySet built_occupied, built_free, truth_occupied;
  FinestKeys(built, &built_occupied, &built_free);
  FinestKeys(truth, &truth_occupied, nullptr);
  MapMetrics m;
  m.built_occupied = built_occupied.size();
  m.built_free = built_free.size();
  m.truth_occupied = truth_occupied.size();
  m.known_volume_m3 = (m.built_occupied + m.built_free) * std::pow(built.getResolution(), 3);
  auto centre = [&](const octomap::OcTreeKey& key) {
    const octomap::point3d p = built.keyToCoord(key);
    return std::array<double, 3>{p.x(), p.y(), p.z()};
  };
  for (const auto& key : built_occupied) {
    const bool hit = truth_occupied.count(key) > 0;
    const bool near = hit || AnyNear(truth_occupied, key, false);
    m.true_positives += hit;
    m.true_positives_within_one += near;
    if (cells) cells->push_back({centre(key), hit ? 0 : (near ? 4 : 1)});
  }
  for (const auto& key : truth_occupied) {
    const bool found = built_occupied.count(key) > 0;
    const bool seen = found || AnyNear(built_free, key, true);
    if (seen) {
      ++m.seen_truth;
      m.seen_found += found;
      m.seen_found_within_one += found || AnyNear(built_occupied, key, false);
    }
    if (cells && !found) cells->push_back({centre(key), seen ? 2 : 3});
  }
  return m;
}

}  // namespace rotors_planning
