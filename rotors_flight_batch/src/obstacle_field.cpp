#include "rotors_flight_batch/obstacle_field.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <embree3/rtcore.h>
#include <octomap/OcTree.h>
#include <Eigen/Geometry>

#include "rotors_core/error.h"
#include "rotors_core/raycast/ray_packets.h"
#include "rotors_core/raycast/ray_scene.h"
#include "rotors_core/rendering/tessellation.h"

namespace rotors_flight_batch {

using rotors_sim::SimError;

namespace {

/// Slices of a cylinder's triangles for the rays: the chord lies r (1 - cos(pi / 128)) = 3e-4 r
/// inside the circle (0.03 mm at r = 0.1 m); the collision test uses the exact circle.
constexpr int kCylinderSlices = 128;
/// The collision grid's cell [m].
constexpr double kCellM = 1.0;

bool Finite(const Eigen::Vector3d& v) { return v.allFinite(); }

}  // namespace

std::string Obstacle::Validate() const {
  if (!Finite(center_W) || !Finite(half_extents_m) || !std::isfinite(yaw_rad)) return "a value is not finite";
  if ((half_extents_m.array() <= 0.0).any()) return "a size is <= 0 (every half extent must be > 0)";
  if (shape == Shape::kCylinder && half_extents_m.x() != half_extents_m.y())
    return "a cylinder's first two half extents are its radius and must be equal";
  return "";
}

double Obstacle::Distance(const Eigen::Vector3d& c_W) const {
  const Eigen::Vector3d d = c_W - center_W;
  if (shape == Shape::kCylinder) {
    // d = |(max(rho - r, 0), max(|dz| - h, 0))|, rho the distance from the axis
    const double rho = std::hypot(d.x(), d.y());
    return std::hypot(std::max(rho - half_extents_m.x(), 0.0), std::max(std::abs(d.z()) - half_extents_m.z(), 0.0));
  }
  // the point in the box frame (turned by -yaw), then the distance to the box: |max(|p| - e, 0)|
  const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
  const Eigen::Vector3d p(c * d.x() + s * d.y(), -s * d.x() + c * d.y(), d.z());
  return (p.cwiseAbs() - half_extents_m).cwiseMax(0.0).norm();
}

/// One environment: its obstacles, their grid of 1 m cells (each cell lists the obstacles within
/// the largest sphere's radius of it) and their Embree scene.
struct ObstacleField::Set_ {
  std::vector<Obstacle> obstacles;
  double x0 = 0.0, y0 = 0.0;  ///< the grid's corner [m]
  int nx = 0, ny = 0;
  std::vector<uint32_t> cell_start;  ///< nx * ny + 1
  std::vector<uint32_t> cell_items;
  RTCScene scene = nullptr;
};

/// The world's occupied cells on a dense grid of the octree's resolution, and beside them the cells
/// "near" one: within the largest sphere's radius of an occupied cell (cube to cube), where the
/// exact test runs. Bits, x fastest.
struct ObstacleField::CellGrid {
  double cell_m = 0.0;
  Eigen::Vector3d origin_W = Eigen::Vector3d::Zero();  ///< the corner of cell (0, 0, 0)
  int nx = 0, ny = 0, nz = 0;
  std::vector<bool> occupied, near;
  size_t Index(int i, int j, int k) const { return (static_cast<size_t>(k) * ny + j) * nx + i; }
  bool Inside(int i, int j, int k) const { return i >= 0 && j >= 0 && k >= 0 && i < nx && j < ny && k < nz; }
};

struct ObstacleField::Embree {
  RTCDevice device = nullptr;
  Embree() {
    device = rtcNewDevice("threads=1");  // scenes are small and built on the caller's thread
    if (!device) throw SimError("ObstacleField: Embree could not make a device");
  }
  ~Embree() { rtcReleaseDevice(device); }
  RTCScene Build(const std::vector<Obstacle>& obstacles) const;
};

RTCScene ObstacleField::Embree::Build(const std::vector<Obstacle>& obstacles) const {
  static const rotors_sim::rendering::TriangleSoup kBox = rotors_sim::rendering::UnitBox();
  static const rotors_sim::rendering::TriangleSoup kCylinder = rotors_sim::rendering::UnitCylinder(kCylinderSlices);
  std::vector<float> vertices;
  std::vector<unsigned> indices;
  for (const Obstacle& o : obstacles) {
    const auto& soup = o.shape == Obstacle::Shape::kBox ? kBox : kCylinder;
    // the unit shape (1 m cube, or radius 1 m and length 1 m along z, centred) scaled, turned, placed
    const Eigen::Vector3d scale =
        o.shape == Obstacle::Shape::kBox
            ? Eigen::Vector3d(2.0 * o.half_extents_m)
            : Eigen::Vector3d(o.half_extents_m.x(), o.half_extents_m.x(), 2.0 * o.half_extents_m.z());
    const Eigen::Matrix3d R = Eigen::AngleAxisd(o.yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const unsigned first = static_cast<unsigned>(vertices.size() / 3);
    for (size_t v = 0; v < soup.VertexCount(); ++v) {
      const Eigen::Vector3d p(soup.positions_m[3 * v], soup.positions_m[3 * v + 1], soup.positions_m[3 * v + 2]);
      const Eigen::Vector3d p_W = o.center_W + R * p.cwiseProduct(scale);
      for (int c = 0; c < 3; ++c) vertices.push_back(static_cast<float>(p_W[c]));
    }
    for (size_t t = 0; t < 3 * soup.TriangleCount(); ++t)
      indices.push_back(first + (soup.indices.empty() ? static_cast<unsigned>(t) : soup.indices[t]));
  }
  RTCScene scene = rtcNewScene(device);
  if (!indices.empty()) {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* p = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), vertices.size() / 3));
    std::copy(vertices.begin(), vertices.end(), p);
    auto* ix = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                              3 * sizeof(unsigned), indices.size() / 3));
    std::copy(indices.begin(), indices.end(), ix);
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(scene);
  return scene;
}

ObstacleField::ObstacleField(int environments, double max_sphere_radius_m)
    : max_sphere_radius_m_(max_sphere_radius_m), embree_(std::make_unique<Embree>()) {
  if (environments < 1)
    throw SimError("ObstacleField: environments = " + std::to_string(environments) + " must be >= 1");
  if (!(max_sphere_radius_m >= 0.0 && std::isfinite(max_sphere_radius_m)))
    throw SimError("ObstacleField: the largest sphere's radius must be finite and >= 0");
  sets_.resize(environments);
  for (auto& s : sets_) {
    s = std::make_unique<Set_>();
    s->cell_start.assign(1, 0);
    s->scene = embree_->Build({});
  }
}

ObstacleField::~ObstacleField() {
  for (auto& s : sets_)
    if (s->scene) rtcReleaseScene(s->scene);
}

void ObstacleField::Set(int env, std::vector<Obstacle> obstacles) {
  if (env < 0 || env >= Environments())
    throw SimError("ObstacleField: environment " + std::to_string(env) + " is not in 0.." +
                   std::to_string(Environments() - 1));
  for (size_t k = 0; k < obstacles.size(); ++k) {
    const std::string why = obstacles[k].Validate();
    if (!why.empty())
      throw SimError("ObstacleField: environment " + std::to_string(env) + ", obstacle " + std::to_string(k) + ": " +
                     why);
  }
  Set_& s = *sets_[env];
  // each obstacle's footprint: a circle around its centre that holds it (box: its half diagonal)
  std::vector<double> reach(obstacles.size());
  double x_min = 0, x_max = 0, y_min = 0, y_max = 0;
  for (size_t k = 0; k < obstacles.size(); ++k) {
    const Obstacle& o = obstacles[k];
    reach[k] = (o.shape == Obstacle::Shape::kBox ? o.half_extents_m.head<2>().norm() : o.half_extents_m.x()) +
               max_sphere_radius_m_;
    const double lo_x = o.center_W.x() - reach[k], hi_x = o.center_W.x() + reach[k];
    const double lo_y = o.center_W.y() - reach[k], hi_y = o.center_W.y() + reach[k];
    x_min = k == 0 ? lo_x : std::min(x_min, lo_x), x_max = k == 0 ? hi_x : std::max(x_max, hi_x);
    y_min = k == 0 ? lo_y : std::min(y_min, lo_y), y_max = k == 0 ? hi_y : std::max(y_max, hi_y);
  }
  s.x0 = x_min, s.y0 = y_min;
  s.nx = obstacles.empty() ? 0 : static_cast<int>(std::floor((x_max - x_min) / kCellM)) + 1;
  s.ny = obstacles.empty() ? 0 : static_cast<int>(std::floor((y_max - y_min) / kCellM)) + 1;
  // a cell lists an obstacle whose reach circle meets the cell's square (tested by the square's
  // nearest point to the centre)
  std::vector<std::vector<uint32_t>> cells(static_cast<size_t>(s.nx) * s.ny);
  for (size_t k = 0; k < obstacles.size(); ++k) {
    const Obstacle& o = obstacles[k];
    const int ix0 = static_cast<int>(std::floor((o.center_W.x() - reach[k] - s.x0) / kCellM));
    const int ix1 = static_cast<int>(std::floor((o.center_W.x() + reach[k] - s.x0) / kCellM));
    const int iy0 = static_cast<int>(std::floor((o.center_W.y() - reach[k] - s.y0) / kCellM));
    const int iy1 = static_cast<int>(std::floor((o.center_W.y() + reach[k] - s.y0) / kCellM));
    for (int ix = std::max(ix0, 0); ix <= std::min(ix1, s.nx - 1); ++ix)
      for (int iy = std::max(iy0, 0); iy <= std::min(iy1, s.ny - 1); ++iy) {
        const double cx = std::clamp(o.center_W.x(), s.x0 + ix * kCellM, s.x0 + (ix + 1) * kCellM);
        const double cy = std::clamp(o.center_W.y(), s.y0 + iy * kCellM, s.y0 + (iy + 1) * kCellM);
        if (std::hypot(cx - o.center_W.x(), cy - o.center_W.y()) <= reach[k])
          cells[static_cast<size_t>(ix) * s.ny + iy].push_back(static_cast<uint32_t>(k));
      }
  }
  s.cell_start.assign(cells.size() + 1, 0);
  s.cell_items.clear();
  for (size_t c = 0; c < cells.size(); ++c) {
    s.cell_items.insert(s.cell_items.end(), cells[c].begin(), cells[c].end());
    s.cell_start[c + 1] = static_cast<uint32_t>(s.cell_items.size());
  }
  RTCScene scene = embree_->Build(obstacles);
  if (s.scene) rtcReleaseScene(s.scene);
  s.scene = scene;
  s.obstacles = std::move(obstacles);
}

void ObstacleField::SetWorld(std::shared_ptr<const rotors_sim::raycast::RayScene> scene,
                             const octomap::OcTree* occupied, std::shared_ptr<const void> keep_alive) {
  world_grid_.reset();
  world_cells_ = 0;
  world_scene_ = std::move(scene);
  world_keep_alive_ = std::move(keep_alive);
  if (!world_scene_ || !occupied) return;
  // the occupied leaves (a leaf may span several cells of the finest size)
  auto grid = std::make_unique<CellGrid>();
  const double res = occupied->getResolution();
  grid->cell_m = res;
  double lo[3], hi[3];
  bool any = false;
  for (auto it = occupied->begin_leafs(); it != occupied->end_leafs(); ++it) {
    if (!occupied->isNodeOccupied(*it)) continue;
    const double half = it.getSize() / 2.0;
    const double c[3] = {it.getX(), it.getY(), it.getZ()};
    for (int a = 0; a < 3; ++a) {
      lo[a] = any ? std::min(lo[a], c[a] - half) : c[a] - half;
      hi[a] = any ? std::max(hi[a], c[a] + half) : c[a] + half;
    }
    any = true;
  }
  if (!any) return;
  const int pad = static_cast<int>(std::ceil(max_sphere_radius_m_ / res)) + 1;
  for (int a = 0; a < 3; ++a) grid->origin_W[a] = lo[a] - pad * res;
  grid->nx = static_cast<int>(std::llround((hi[0] - lo[0]) / res)) + 2 * pad;
  grid->ny = static_cast<int>(std::llround((hi[1] - lo[1]) / res)) + 2 * pad;
  grid->nz = static_cast<int>(std::llround((hi[2] - lo[2]) / res)) + 2 * pad;
  const size_t cells = static_cast<size_t>(grid->nx) * grid->ny * grid->nz;
  if (cells > (size_t{1} << 33))
    throw SimError("ObstacleField: the world's occupancy spans " + std::to_string(cells) + " cells of " +
                   std::to_string(res) + " m; use a coarser leaf or a smaller box");
  grid->occupied.assign(cells, false);
  grid->near.assign(cells, false);
  std::vector<std::array<int, 3>> filled;
  for (auto it = occupied->begin_leafs(); it != occupied->end_leafs(); ++it) {
    if (!occupied->isNodeOccupied(*it)) continue;
    const int n = static_cast<int>(std::llround(it.getSize() / res));
    const int i0 = static_cast<int>(std::floor((it.getX() - it.getSize() / 2.0 - grid->origin_W.x()) / res + 0.5));
    const int j0 = static_cast<int>(std::floor((it.getY() - it.getSize() / 2.0 - grid->origin_W.y()) / res + 0.5));
    const int k0 = static_cast<int>(std::floor((it.getZ() - it.getSize() / 2.0 - grid->origin_W.z()) / res + 0.5));
    for (int k = k0; k < k0 + n; ++k)
      for (int j = j0; j < j0 + n; ++j)
        for (int i = i0; i < i0 + n; ++i)
          if (grid->Inside(i, j, k) && !grid->occupied[grid->Index(i, j, k)]) {
            grid->occupied[grid->Index(i, j, k)] = true;
            filled.push_back({i, j, k});
          }
  }
  world_cells_ = filled.size();
  // near: cells whose cube lies within the largest radius of an occupied cube (gap per axis
  // max(|d| - 1, 0) cells); only occupied cells with a free neighbour need spreading
  const int reach = static_cast<int>(std::ceil(max_sphere_radius_m_ / res));
  std::vector<std::array<int, 3>> offsets;
  for (int dk = -reach - 1; dk <= reach + 1; ++dk)
    for (int dj = -reach - 1; dj <= reach + 1; ++dj)
      for (int di = -reach - 1; di <= reach + 1; ++di) {
        const double gx = std::max(std::abs(di) - 1, 0), gy = std::max(std::abs(dj) - 1, 0),
                     gz = std::max(std::abs(dk) - 1, 0);
        if (res * std::sqrt(gx * gx + gy * gy + gz * gz) <= max_sphere_radius_m_) offsets.push_back({di, dj, dk});
      }
  for (const auto& c : filled) {
    bool surface = false;
    for (int a = 0; a < 3 && !surface; ++a)
      for (int step : {-1, 1}) {
        std::array<int, 3> n = c;
        n[a] += step;
        if (!grid->Inside(n[0], n[1], n[2]) || !grid->occupied[grid->Index(n[0], n[1], n[2])]) surface = true;
      }
    grid->near[grid->Index(c[0], c[1], c[2])] = true;
    if (!surface) continue;
    for (const auto& o : offsets) {
      const int i = c[0] + o[0], j = c[1] + o[1], k = c[2] + o[2];
      if (grid->Inside(i, j, k)) grid->near[grid->Index(i, j, k)] = true;
    }
  }
  world_grid_ = std::move(grid);
}

bool ObstacleField::WorldSphereTouches(const Eigen::Vector3d& c_W, double r_m) const {
  const CellGrid& g = *world_grid_;
  const Eigen::Vector3d u = (c_W - g.origin_W) / g.cell_m;
  const int i = static_cast<int>(std::floor(u.x())), j = static_cast<int>(std::floor(u.y())),
            k = static_cast<int>(std::floor(u.z()));
  if (!g.Inside(i, j, k) || !g.near[g.Index(i, j, k)]) return false;
  // the exact distance to each occupied cube around: |max(|c - centre| - cell / 2, 0)|
  const int reach = static_cast<int>(std::ceil(r_m / g.cell_m)) + 1;
  for (int dk = -reach; dk <= reach; ++dk)
    for (int dj = -reach; dj <= reach; ++dj)
      for (int di = -reach; di <= reach; ++di) {
        if (!g.Inside(i + di, j + dj, k + dk) || !g.occupied[g.Index(i + di, j + dj, k + dk)]) continue;
        const Eigen::Vector3d centre =
            g.origin_W + g.cell_m * Eigen::Vector3d(i + di + 0.5, j + dj + 0.5, k + dk + 0.5);
        if (((c_W - centre).cwiseAbs().array() - g.cell_m / 2.0).cwiseMax(0.0).matrix().norm() <= r_m) return true;
      }
  return false;
}

const std::vector<Obstacle>& ObstacleField::Get(int env) const { return sets_.at(env)->obstacles; }

bool ObstacleField::SphereTouches(int env, const Eigen::Vector3d& c_W, double r_m) const {
  if (world_grid_ && WorldSphereTouches(c_W, r_m)) return true;
  const Set_& s = *sets_[env];
  const int ix = static_cast<int>(std::floor((c_W.x() - s.x0) / kCellM));
  const int iy = static_cast<int>(std::floor((c_W.y() - s.y0) / kCellM));
  if (ix < 0 || iy < 0 || ix >= s.nx || iy >= s.ny) return false;  // farther than any reach
  const size_t cell = static_cast<size_t>(ix) * s.ny + iy;
  for (uint32_t k = s.cell_start[cell]; k < s.cell_start[cell + 1]; ++k)
    if (s.obstacles[s.cell_items[k]].Distance(c_W) <= r_m) return true;
  return false;
}

void ObstacleField::Cast(int env, const Eigen::Vector3d& origin_W, const Eigen::Vector3d* dirs_W, size_t n,
                         double near_m, double far_m, double* t_m) const {
  RTCScene scene = sets_[env]->scene;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // one origin, neighbouring directions
  rotors_sim::raycast::CastPackets16(scene, &context, origin_W, dirs_W, n, near_m, far_m, 0xFFFFFFFFu,
                                     [&](size_t k, const RTCRayHit16& rh, size_t lane) {
                                       t_m[k] = rh.hit.geomID[lane] == RTC_INVALID_GEOMETRY_ID
                                                    ? std::numeric_limits<double>::infinity()
                                                    : static_cast<double>(rh.ray.tfar[lane]);
                                     });
  if (!world_scene_) return;
  thread_local std::vector<rotors_sim::raycast::RayHit> hits;
  hits.resize(n);
  world_scene_->CastFan(origin_W, dirs_W, n, near_m, far_m, nullptr, rotors_sim::raycast::RayScene::kAllVisuals,
                        hits.data());
  for (size_t k = 0; k < n; ++k) t_m[k] = std::min(t_m[k], hits[k].distance_m);
}

}  // namespace rotors_flight_batch
