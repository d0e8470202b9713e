// rotors_map_compare BUILT.bt TRUTH.bt [CELLS.csv]: precision and recall of a map built in flight, and its observed
// volume, against the world's ground truth (rotors_planning/map_metrics.h), printed as "name value" lines; CELLS.csv
// gets x,y,z,label of every cell for plots (0 true positive, 1 false positive, 2 seen truth missed, 3 truth not seen, 4
// occupied next to a truth leaf).
#include <algorithm>
#include <cstdio>
#include <exception>
#include <vector>

#include <octomap/OcTree.h>

#include "read_octree.h"
#include "rotors_planning/map_metrics.h"

int main(int argc, char** argv) {
  if (argc != 3 && argc != 4) {
    std::fprintf(stderr, "usage: rotors_map_compare BUILT.bt TRUTH.bt [CELLS.csv]\n");
    return 2;
  }
  const auto built_ptr = rotors_planning::ReadOcTree("rotors_map_compare", argv[1]);
  const auto truth_ptr = built_ptr ? rotors_planning::ReadOcTree("rotors_map_compare", argv[2]) : nullptr;
  if (!truth_ptr) return 2;
  const octomap::OcTree &built = *built_ptr, &truth = *truth_ptr;
  std::vector<rotors_planning::LabelledCell> cells;
  rotors_planning::MapMetrics m;
  try {
    m = rotors_planning::CompareMaps(built, truth, argc == 4 ? &cells : nullptr);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rotors_map_compare: %s\n", e.what());
    return 2;
  }
  // the truth's box: the box world/get_octomap was asked for, as far as its occupied leaves reach
  double x0, y0, z0, x1, y1, z1;
  truth.getMetricMin(x0, y0, z0);
  truth.getMetricMax(x1, y1, z1);
  const double truth_box_m3 = std::max(0.0, (x1 - x0) * (y1 - y0) * (z1 - z0));
  std::printf("truth_box_m3 %.1f\n", truth_box_m3);
  std::printf("resolution %.4f\nbuilt_occupied %zu\nbuilt_free %zu\ntruth_occupied %zu\nseen_truth %zu\n",
              built.getResolution(), m.built_occupied, m.built_free, m.truth_occupied, m.seen_truth);
  std::printf("precision %.4f\nprecision_within_one %.4f\nrecall %.4f\nrecall_within_one %.4f\nknown_volume_m3 %.1f\n",
              m.Precision(), m.PrecisionWithinOne(), m.Recall(), m.RecallWithinOne(), m.known_volume_m3);
  if (argc == 4) {
    FILE* out = std::fopen(argv[3], "w");
    if (!out) {
      std::fprintf(stderr, "rotors_map_compare: cannot write '%s'\n", argv[3]);
      return 2;
    }
    std::fprintf(out, "x,y,z,label\n");
    for (const auto& c : cells) std::fprintf(out, "%.3f,%.3f,%.3f,%d\n", c.p_W[0], c.p_W[1], c.p_W[2], c.label);
    std::fclose(out);
  }
  return 0;
}
