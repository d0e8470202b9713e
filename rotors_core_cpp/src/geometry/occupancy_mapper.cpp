#include "rotors_core/geometry/occupancy_mapper.h"

#include <cmath>
#include <sstream>

#include <ode/ode.h>
#include <octomap/OcTree.h>

#include "physics/octree_geom.h"
#include "physics/ode_handles.h"
#include "rotors_core/error.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"

namespace rotors_sim {
namespace geometry {
namespace {

struct Probe {
  dGeomID cube;
  bool hit = false;
};

void ProbeCallback(void* data, dGeomID o1, dGeomID o2) {
  auto* probe = static_cast<Probe*>(data);
  if (probe->hit) return;
  dGeomID other = o1 == probe->cube ? o2 : o1;
  if (dGeomGetBody(other) || !dGeomGetData(other)) return;  // static collision geometry only
  if (IsOcTreeGeom(other)) {
    dVector3 lengths;
    dGeomBoxGetLengths(probe->cube, lengths);
    const dReal* p = dGeomGetPosition(probe->cube);
    const double centre[3] = {p[0], p[1], p[2]}, length[3] = {lengths[0], lengths[1], lengths[2]};
    probe->hit = OcTreeGeomOverlapsBox(other, centre, length);
    return;
  }
  dContactGeom contact;
  if (dCollide(probe->cube, other, 1, &contact, sizeof(dContactGeom)) > 0) probe->hit = true;
}

class Mapper {
 public:
  Mapper(const physics::World& world, octomap::OcTree* tree, const octomap::OcTreeKey& lo, const octomap::OcTreeKey& hi)
      : space_(Ode(world.Space())), tree_(tree), lo_(lo), hi_(hi), cube_(dCreateBox(nullptr, 1, 1, 1)) {}
  ~Mapper() { dGeomDestroy(cube_); }

  /// The block of cells [start, start + size) per axis (clipped to the request).
  void Visit(const int start[3], int size) {
    int a[3], b[3];  // clipped key range, inclusive
    for (int k = 0; k < 3; ++k) {
      a[k] = std::max(start[k], static_cast<int>(lo_[k]));
      b[k] = std::min(start[k] + size - 1, static_cast<int>(hi_[k]));
      if (a[k] > b[k]) return;
    }
    if (!Overlaps(a, b)) return;
    if (size == 1) {
      octomap::OcTreeKey key(a[0], a[1], a[2]);
      tree_->updateNode(key, tree_->getClampingThresMaxLog(), true);
      return;
    }
    const int half = size / 2;
    for (int i = 0; i < 8; ++i) {
      const int child[3] = {start[0] + ((i & 1) ? half : 0), start[1] + ((i & 2) ? half : 0),
                            start[2] + ((i & 4) ? half : 0)};
      Visit(child, half);
    }
  }

 private:
  bool Overlaps(const int a[3], const int b[3]) {
    const double r = tree_->getResolution();
    const double shrink = 1e-6 * r;  // cells that only touch a surface are not occupied
    double centre[3], length[3];
    for (int k = 0; k < 3; ++k) {
      const double lo = tree_->keyToCoord(a[k]) - r / 2, hi = tree_->keyToCoord(b[k]) + r / 2;
      centre[k] = (lo + hi) / 2;
      length[k] = hi - lo - 2 * shrink;
    }
    dGeomBoxSetLengths(cube_, length[0], length[1], length[2]);
    dGeomSetPosition(cube_, centre[0], centre[1], centre[2]);
    Probe probe{cube_};
    dSpaceCollide2(cube_, reinterpret_cast<dGeomID>(space_), &probe, &ProbeCallback);
    return probe.hit;
  }

  dSpaceID space_;
  octomap::OcTree* tree_;
  octomap::OcTreeKey lo_, hi_;
  dGeomID cube_;
};

}  // namespace

std::string OccupancyRequest::Validate() const {
  std::ostringstream why;
  if (!(leaf_size_m > 0.0) || !std::isfinite(leaf_size_m)) why << "leaf size " << leaf_size_m << " m must be > 0";
  else if (!(lengths_m.X() > 0) || !(lengths_m.Y() > 0) || !(lengths_m.Z() > 0) || !lengths_m.IsFinite())
    why << "bounding box lengths " << lengths_m << " m must all be > 0";
  else if (!center_W.IsFinite()) why << "bounding box origin " << center_W << " must be finite";
  else if (lengths_m.Max() / leaf_size_m > 65536.0)
    why << "bounding box of " << lengths_m.Max() << " m is more than 65536 leaves of " << leaf_size_m << " m";
  return why.str();
}

std::unique_ptr<octomap::OcTree> BuildOccupancy(const physics::World& world, const OccupancyRequest& request) {
  const std::string why = request.Validate();
  if (!why.empty()) throw SimError("octomap request: " + why);
  auto tree = std::make_unique<octomap::OcTree>(request.leaf_size_m);
  const ignition::math::Vector3d lo_W = request.center_W - request.lengths_m / 2;
  const ignition::math::Vector3d hi_W = request.center_W + request.lengths_m / 2;
  octomap::OcTreeKey lo, hi;
  // the cells whose centres lie in the box
  const double r = request.leaf_size_m;
  if (!tree->coordToKeyChecked(octomap::point3d(lo_W.X() + r / 2, lo_W.Y() + r / 2, lo_W.Z() + r / 2), lo) ||
      !tree->coordToKeyChecked(octomap::point3d(hi_W.X() - r / 2, hi_W.Y() - r / 2, hi_W.Z() - r / 2), hi))
    throw SimError("octomap request: the bounding box does not fit an octree of that resolution");
  int size = 1;
  int extent = 1;
  for (int k = 0; k < 3; ++k) extent = std::max(extent, static_cast<int>(hi[k]) - static_cast<int>(lo[k]) + 1);
  while (size < extent) size *= 2;
  Mapper mapper(world, tree.get(), lo, hi);
  const int start[3] = {lo[0], lo[1], lo[2]};
  mapper.Visit(start, size);
  tree->updateInnerOccupancy();
  tree->prune();
  return tree;
}

}  // namespace geometry
}  // namespace rotors_sim
