#include "physics/octree_geom.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <new>
#include <vector>

#include <octomap/OcTree.h>

namespace rotors_sim {
namespace {

struct OcTreeGeomData {
  std::shared_ptr<const octomap::OcTree> tree;
  double p_W[3];
  dGeomID leaf_box;                         ///< scratch cube, in no space, moved onto each leaf under test
  std::vector<dContactGeom> found, chosen;  ///< scratch of Collide, kept to reuse their memory
};

int g_class = -1;

OcTreeGeomData* DataOf(dGeomID g) { return static_cast<OcTreeGeomData*>(dGeomGetClassData(g)); }

void Aabb(dGeomID g, dReal aabb[6]) {
  const OcTreeGeomData* d = DataOf(g);
  double min[3], max[3];
  d->tree->getMetricMin(min[0], min[1], min[2]);
  d->tree->getMetricMax(max[0], max[1], max[2]);
  for (int k = 0; k < 3; ++k) {
    aabb[2 * k] = min[k] + d->p_W[k];
    aabb[2 * k + 1] = max[k] + d->p_W[k];
  }
}

dContactGeom* At(dContactGeom* contacts, int i, int skip) {
  return reinterpret_cast<dContactGeom*>(reinterpret_cast<char*>(contacts) + static_cast<size_t>(i) * skip);
}

/// A contact on a face the leaf shares with another occupied leaf is an artefact of cutting the
/// solid into cubes (a body sliding over a floor of leaves would catch on their seams): dropped.
bool OnInternalFace(const octomap::OcTree& tree, const octomap::point3d& centre, double size, const dContactGeom& c,
                    const double p_W[3]) {
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(c.normal[k]) > std::abs(c.normal[axis])) axis = k;
  if (std::abs(c.normal[axis]) < 0.99) return false;  // an edge or corner contact
  const double offset = c.pos[axis] - p_W[axis] - centre(axis);
  octomap::point3d neighbour = centre;
  neighbour(axis) += offset > 0 ? size : -size;
  const octomap::OcTreeNode* node = tree.search(neighbour);
  return node && tree.isNodeOccupied(node);
}

/// Up to `max` contacts of the cubes of the occupied leaves in o2's bounding box with o2. When
/// there are more, the deepest one and then, one by one, the one farthest from those chosen: a
/// body resting on several leaves keeps its support polygon.
int Collide(dGeomID o1, dGeomID o2, int flags, dContactGeom* contacts, int skip) {
  OcTreeGeomData* d = DataOf(o1);
  const int max = flags & 0xffff;
  dReal box[6];
  dGeomGetAABB(o2, box);
  const octomap::point3d min(box[0] - d->p_W[0], box[2] - d->p_W[1], box[4] - d->p_W[2]);
  const octomap::point3d max_corner(box[1] - d->p_W[0], box[3] - d->p_W[1], box[5] - d->p_W[2]);
  std::vector<dContactGeom>& found = d->found;
  found.clear();
  dContactGeom leaf_contacts[8];
  for (auto it = d->tree->begin_leafs_bbx(min, max_corner), end = d->tree->end_leafs_bbx(); it != end; ++it) {
    if (!d->tree->isNodeOccupied(*it)) continue;
    const double size = it.getSize();
    const octomap::point3d c = it.getCoordinate();
    dGeomBoxSetLengths(d->leaf_box, size, size, size);
    dGeomSetPosition(d->leaf_box, c.x() + d->p_W[0], c.y() + d->p_W[1], c.z() + d->p_W[2]);
    const int n = dCollide(d->leaf_box, o2, 8, leaf_contacts, sizeof(dContactGeom));
    for (int i = 0; i < n; ++i) {
      if (OnInternalFace(*d->tree, c, size, leaf_contacts[i], d->p_W)) continue;
      leaf_contacts[i].g1 = o1;
      leaf_contacts[i].g2 = o2;
      leaf_contacts[i].side1 = -1;
      found.push_back(leaf_contacts[i]);
    }
  }
  if (static_cast<int>(found.size()) > max) {
    std::vector<dContactGeom>& chosen = d->chosen;
    chosen.clear();
    auto deepest = std::max_element(found.begin(), found.end(),
                                    [](const dContactGeom& a, const dContactGeom& b) { return a.depth < b.depth; });
    chosen.push_back(*deepest);
    found.erase(deepest);
    while (static_cast<int>(chosen.size()) < max) {
      auto distance = [&](const dContactGeom& c) {
        double best = 1e300;
        for (const auto& s : chosen) {
          double d2 = 0;
          for (int k = 0; k < 3; ++k) d2 += (c.pos[k] - s.pos[k]) * (c.pos[k] - s.pos[k]);
          best = std::min(best, d2);
        }
        return best;
      };
      auto farthest = std::max_element(found.begin(), found.end(), [&](const dContactGeom& a, const dContactGeom& b) {
        return distance(a) < distance(b);
      });
      chosen.push_back(*farthest);
      found.erase(farthest);
    }
    found.swap(chosen);
  }
  for (size_t i = 0; i < found.size(); ++i) *At(contacts, static_cast<int>(i), skip) = found[i];
  return static_cast<int>(found.size());
}

dColliderFn* ColliderFor(int other_class) { return other_class == g_class ? nullptr : &Collide; }

void Destroy(dGeomID g) {
  OcTreeGeomData* d = DataOf(g);
  dGeomDestroy(d->leaf_box);
  d->~OcTreeGeomData();
}

int ClassNumber() {
  static std::once_flag once;
  std::call_once(once, [] {
    dGeomClass c{};
    c.bytes = sizeof(OcTreeGeomData);
    c.collider = &ColliderFor;
    c.aabb = &Aabb;
    c.aabb_test = nullptr;
    c.dtor = &Destroy;
    g_class = dCreateGeomClass(&c);
  });
  return g_class;
}

}  // namespace

dGeomID CreateOcTreeGeom(dSpaceID space, std::shared_ptr<const octomap::OcTree> tree, const double p_W[3]) {
  dGeomID g = dCreateGeom(ClassNumber());
  new (dGeomGetClassData(g))
      OcTreeGeomData{std::move(tree), {p_W[0], p_W[1], p_W[2]}, dCreateBox(nullptr, 1, 1, 1), {}, {}};
  if (space) dSpaceAdd(space, g);
  return g;
}

bool IsOcTreeGeom(dGeomID g) { return g_class >= 0 && dGeomGetClass(g) == g_class; }

bool OcTreeGeomOverlapsBox(dGeomID g, const double centre_W[3], const double lengths[3]) {
  const OcTreeGeomData* d = DataOf(g);
  double lo[3], hi[3];  // the box in the tree's frame
  for (int k = 0; k < 3; ++k) {
    lo[k] = centre_W[k] - lengths[k] / 2 - d->p_W[k];
    hi[k] = centre_W[k] + lengths[k] / 2 - d->p_W[k];
  }
  const octomap::point3d min(lo[0], lo[1], lo[2]), max(hi[0], hi[1], hi[2]);
  for (auto it = d->tree->begin_leafs_bbx(min, max), end = d->tree->end_leafs_bbx(); it != end; ++it) {
    if (!d->tree->isNodeOccupied(*it)) continue;
    const octomap::point3d c = it.getCoordinate();
    const double half = it.getSize() / 2;
    bool overlap = true;
    for (int k = 0; k < 3; ++k) overlap = overlap && c(k) - half < hi[k] && c(k) + half > lo[k];
    if (overlap) return true;
  }
  return false;
}

}  // namespace rotors_sim
