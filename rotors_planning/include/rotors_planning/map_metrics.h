// How well a map built in flight matches the world's ground truth (both OcTrees at the same
// resolution, in the same frame), counted over leaves at the finest depth:
//   precision = |built occupied ∩ truth| / |built occupied|
//   seen truth = truth leaves occupied in the built map or with a face neighbour the built map
//                knows free (the sensor saw the space in front of the surface)
//   recall    = |built occupied ∩ seen truth| / |seen truth|
// and the same with one cell of tolerance (a match within the 26 neighbours), as range noise and
// rounding put a surface hit in the cell next to it.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace octomap {
class OcTree;
}

namespace rotors_planning {

struct MapMetrics {
  size_t built_occupied = 0, built_free = 0, truth_occupied = 0, seen_truth = 0;
  size_t true_positives = 0, true_positives_within_one = 0;  ///< built occupied leaves on (near) the truth
  size_t seen_found = 0, seen_found_within_one = 0;          ///< seen truth leaves found (near) in the built map
  double known_volume_m3 = 0.0;                              ///< [m^3] free and occupied leaves of the built map
  double Precision() const { return built_occupied ? double(true_positives) / built_occupied : 0.0; }
  double PrecisionWithinOne() const {
    return built_occupied ? double(true_positives_within_one) / built_occupied : 0.0;
  }
  double Recall() const { return seen_truth ? double(seen_found) / seen_truth : 0.0; }
  double RecallWithinOne() const { return seen_truth ? double(seen_found_within_one) / seen_truth : 0.0; }
};

/// One labelled cell for plots: centre [m] and class (0 true positive, 1 false positive, 2 seen truth
/// missed, 3 truth not seen, 4 built occupied next to a truth leaf).
struct LabelledCell {
  std::array<double, 3> p_W;
  int label;
};

/// Throws std::invalid_argument when the resolutions differ.
MapMetrics CompareMaps(const octomap::OcTree& built, const octomap::OcTree& truth,
                       std::vector<LabelledCell>* cells = nullptr);

}  // namespace rotors_planning
