#include "rotors_core/rendering/tessellation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <tuple>

#include <Eigen/Geometry>
#include <octomap/OcTree.h>

#include "rotors_core/geometry/octree_cells.h"
#include "rotors_core/geometry/shapes.h"

namespace rotors_sim {
namespace rendering {

using Eigen::Vector3f;

namespace {
/// The sphere around the given vertices: centred on their bounding box.
template <typename VertexIds>
void SphereAround(const TriangleSoup& soup, const VertexIds& ids, Vector3f* centre_m, float* radius_m) {
  const Eigen::Map<const Eigen::Matrix3Xf> p(soup.positions_m.data(), 3, static_cast<Eigen::Index>(soup.VertexCount()));
  Vector3f lo = Vector3f::Constant(INFINITY), hi = Vector3f::Constant(-INFINITY);
  for (uint32_t v : ids) {
    lo = lo.cwiseMin(p.col(v));
    hi = hi.cwiseMax(p.col(v));
  }
  *centre_m = 0.5f * (lo + hi);
  float r2 = 0.0f;
  for (uint32_t v : ids) r2 = std::max(r2, (p.col(v) - *centre_m).squaredNorm());
  *radius_m = std::sqrt(r2);
}
}  // namespace

std::vector<Chunk> SortIntoChunks(TriangleSoup* soup, int cells_per_axis, size_t min_triangles) {
  const size_t n = soup->TriangleCount();
  if (n == 0) return {};
  const bool indexed = !soup->indices.empty();
  auto vertex = [&](size_t triangle, int corner) -> uint32_t {
    return indexed ? soup->indices[3 * triangle + corner] : static_cast<uint32_t>(3 * triangle + corner);
  };
  const Eigen::Map<const Eigen::Matrix3Xf> p(soup->positions_m.data(), 3,
                                             static_cast<Eigen::Index>(soup->VertexCount()));
  const Vector3f lo = p.rowwise().minCoeff(), extent = (p.rowwise().maxCoeff() - lo).cwiseMax(1e-9f);
  const int cells = n < min_triangles ? 1 : cells_per_axis;
  std::vector<int> cell(n);
  for (size_t t = 0; t < n; ++t) {
    const Vector3f centroid = (p.col(vertex(t, 0)) + p.col(vertex(t, 1)) + p.col(vertex(t, 2))) / 3.0f;
    const Eigen::Vector3i c = ((centroid - lo).cwiseQuotient(extent) * cells).cast<int>().cwiseMin(cells - 1);
    cell[t] = (c.z() * cells + c.y()) * cells + c.x();
  }
  std::vector<size_t> order(n);
  for (size_t t = 0; t < n; ++t) order[t] = t;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return cell[a] < cell[b]; });

  if (indexed) {
    std::vector<uint32_t> indices(soup->indices.size());
    for (size_t i = 0; i < n; ++i) std::copy_n(soup->indices.begin() + 3 * order[i], 3, indices.begin() + 3 * i);
    soup->indices.swap(indices);
  } else {
    // every per-vertex array moves with its triangle's three vertices
    auto permute = [&](std::vector<float>* values, int per_vertex) {
      if (values->empty()) return;
      std::vector<float> sorted(values->size());
      const size_t per_triangle = 3 * per_vertex;
      for (size_t i = 0; i < n; ++i)
        std::copy_n(values->begin() + per_triangle * order[i], per_triangle, sorted.begin() + per_triangle * i);
      values->swap(sorted);
    };
    permute(&soup->positions_m, 3);
    permute(&soup->normals, 3);
    permute(&soup->colours, 3);
    permute(&soup->uvs, 2);
  }

  std::vector<Chunk> chunks;
  for (size_t begin = 0; begin < n;) {
    size_t end = begin;
    while (end < n && cell[order[end]] == cell[order[begin]]) ++end;
    Chunk chunk;
    chunk.first_triangle = begin;
    chunk.triangles = end - begin;
    std::vector<uint32_t> ids;
    ids.reserve(3 * chunk.triangles);
    for (size_t t = begin; t < end; ++t)
      for (int corner = 0; corner < 3; ++corner) ids.push_back(vertex(t, corner));
    SphereAround(*soup, ids, &chunk.centre_m, &chunk.radius_m);
    chunks.push_back(chunk);
    begin = end;
  }
  return chunks;
}

void TriangleSoup::Add(const Vector3f& a, const Vector3f& b, const Vector3f& c) {
  Vector3f n = (b - a).cross(c - a);
  const float norm = n.norm();
  n = norm > 0 ? Vector3f(n / norm) : Vector3f::UnitZ();
  Add(a, b, c, n, n, n);
}

void TriangleSoup::Add(const Vector3f& a, const Vector3f& b, const Vector3f& c, const Vector3f& na, const Vector3f& nb,
                       const Vector3f& nc) {
  for (const Vector3f* p : {&a, &b, &c}) positions_m.insert(positions_m.end(), {p->x(), p->y(), p->z()});
  for (const Vector3f* n : {&na, &nb, &nc}) normals.insert(normals.end(), {n->x(), n->y(), n->z()});
}

namespace {
/// Two triangles a b c, a c d (counter-clockwise seen from the outside), texture coordinates
/// (0, 0) (1, 0) (1, 1) (0, 1) at a b c d, as Gazebo's unit box and plane have them per face.
void AddQuad(TriangleSoup* soup, const Vector3f& a, const Vector3f& b, const Vector3f& c, const Vector3f& d) {
  soup->Add(a, b, c);
  soup->Add(a, c, d);
  soup->uvs.insert(soup->uvs.end(), {0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1});
}

/// The face of an axis-aligned cube (centre, half size h) whose outward normal is +-axis.
void AddCubeFace(TriangleSoup* soup, const Vector3f& centre, float h, int axis, int sign) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  Vector3f e_u = Vector3f::Zero(), e_v = Vector3f::Zero(), e_n = Vector3f::Zero();
  e_u[u] = h;
  e_v[v] = h;
  e_n[axis] = sign * h;
  const Vector3f f = centre + e_n;
  // u x v = axis, so (u, v) order is counter-clockwise seen from +axis
  if (sign > 0) AddQuad(soup, f - e_u - e_v, f + e_u - e_v, f + e_u + e_v, f - e_u + e_v);
  else AddQuad(soup, f - e_u - e_v, f - e_u + e_v, f + e_u + e_v, f + e_u - e_v);
}
}  // namespace

TriangleSoup UnitBox() {
  TriangleSoup soup;
  for (int axis = 0; axis < 3; ++axis)
    for (int sign : {-1, 1}) AddCubeFace(&soup, Vector3f::Zero(), 0.5f, axis, sign);
  return soup;
}

TriangleSoup UnitSphere(int slices, int stacks) {
  TriangleSoup soup;
  auto point = [&](int i, int j) {
    const double theta = M_PI * j / stacks, phi = 2 * M_PI * i / slices;
    return Vector3f(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
  };
  for (int j = 0; j < stacks; ++j)
    for (int i = 0; i < slices; ++i) {
      const Vector3f a = point(i, j), b = point(i, j + 1), c = point(i + 1, j + 1), d = point(i + 1, j);
      if (j > 0) soup.Add(a, b, d, a, b, d);
      if (j < stacks - 1) soup.Add(b, c, d, b, c, d);
    }
  return soup;
}

TriangleSoup UnitCylinder(int slices) {
  TriangleSoup soup;
  const Vector3f top(0, 0, 0.5f), bottom(0, 0, -0.5f);
  for (int i = 0; i < slices; ++i) {
    const double a0 = 2 * M_PI * i / slices, a1 = 2 * M_PI * (i + 1) / slices;
    const Vector3f r0(std::cos(a0), std::sin(a0), 0), r1(std::cos(a1), std::sin(a1), 0);
    soup.Add(bottom + r0, bottom + r1, top + r1, r0, r1, r1);
    soup.Add(bottom + r0, top + r1, top + r0, r0, r1, r0);
    soup.Add(top, top + r0, top + r1);
    soup.Add(bottom, bottom + r1, bottom + r0);
  }
  return soup;
}

TriangleSoup UnitSquare() {
  TriangleSoup soup;
  AddQuad(&soup, {-0.5f, -0.5f, 0}, {0.5f, -0.5f, 0}, {0.5f, 0.5f, 0}, {-0.5f, 0.5f, 0});
  return soup;
}

TriangleSoup FromMesh(const geometry::TriangleMesh& mesh) {
  geometry::MeshPart all;
  all.triangles = mesh.TriangleCount();
  return FromMesh(mesh, all);
}

TriangleSoup FromMesh(const geometry::TriangleMesh& mesh, const geometry::MeshPart& part) {
  TriangleSoup soup;
  const auto& v = mesh.vertices_m;
  auto vertex = [&](uint32_t i) { return Vector3f(v[3 * i], v[3 * i + 1], v[3 * i + 2]); };
  for (size_t t = part.first_triangle; t < part.first_triangle + part.triangles; ++t) {
    const uint32_t* index = &mesh.indices[3 * t];
    soup.Add(vertex(index[0]), vertex(index[1]), vertex(index[2]));
    for (int k = 0; k < 3; ++k) {
      if (!mesh.colours.empty())
        soup.colours.insert(soup.colours.end(), mesh.colours.begin() + 3 * index[k],
                            mesh.colours.begin() + 3 * index[k] + 3);
      if (!mesh.uvs.empty())
        soup.uvs.insert(soup.uvs.end(), mesh.uvs.begin() + 2 * index[k], mesh.uvs.begin() + 2 * index[k] + 2);
    }
  }
  return soup;
}

TriangleSoup Simplified(const geometry::TriangleMesh& mesh, float cell_m) {
  const size_t n = mesh.vertices_m.size() / 3;
  const Eigen::Matrix3Xf p =
      Eigen::Map<const Eigen::Matrix3Xd>(mesh.vertices_m.data(), 3, static_cast<Eigen::Index>(n)).cast<float>();
  const Vector3f lo = n ? Vector3f(p.rowwise().minCoeff()) : Vector3f::Zero();
  // each vertex's cell, and each cell's mean position
  std::map<std::tuple<int, int, int>, uint32_t> cell_ids;
  std::vector<uint32_t> cell_of(n);
  std::vector<Vector3f> sum;
  std::vector<int> count;
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3i c = ((p.col(i) - lo) / cell_m).array().floor().cast<int>();
    const auto [it, added] = cell_ids.emplace(std::make_tuple(c.x(), c.y(), c.z()), static_cast<uint32_t>(sum.size()));
    if (added) {
      sum.push_back(Vector3f::Zero());
      count.push_back(0);
    }
    cell_of[i] = it->second;
    sum[it->second] += p.col(i);
    ++count[it->second];
  }
  TriangleSoup soup;
  std::set<std::array<uint32_t, 3>> kept;
  for (size_t t = 0; t < mesh.indices.size() / 3; ++t) {
    std::array<uint32_t, 3> c = {cell_of[mesh.indices[3 * t]], cell_of[mesh.indices[3 * t + 1]],
                                 cell_of[mesh.indices[3 * t + 2]]};
    if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) continue;  // collapsed
    std::array<uint32_t, 3> key = c;
    std::sort(key.begin(), key.end());
    if (!kept.insert(key).second) continue;  // already there (either winding: a shadow has no side)
    soup.Add(sum[c[0]] / count[c[0]], sum[c[1]] / count[c[1]], sum[c[2]] / count[c[2]]);
  }
  return soup;
}

TriangleSoup FromHeightField(const geometry::HeightField& h) {
  // one shared vertex per sample (normal from the height gradient), two indexed triangles per cell
  TriangleSoup soup;
  const int n = h.n;
  const double dx = h.size_x_m / (n - 1), dy = h.size_y_m / (n - 1);
  auto at = [&](int r, int c) {
    const int rr = std::clamp(r, 0, n - 1), cc = std::clamp(c, 0, n - 1);
    return Vector3f(h.pos_x_m - h.size_x_m / 2 + cc * dx, h.pos_y_m + h.size_y_m / 2 - rr * dy,
                    h.heights_m[rr * n + cc]);
  };
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      // central differences; rows run towards -y
      const double dz_dx = (at(r, c + 1).z() - at(r, c - 1).z()) / (at(r, c + 1).x() - at(r, c - 1).x());
      const double dz_dy = (at(r - 1, c).z() - at(r + 1, c).z()) / (at(r - 1, c).y() - at(r + 1, c).y());
      const Vector3f p = at(r, c), normal = Eigen::Vector3d(-dz_dx, -dz_dy, 1.0).normalized().cast<float>();
      soup.positions_m.insert(soup.positions_m.end(), {p.x(), p.y(), p.z()});
      soup.normals.insert(soup.normals.end(), {normal.x(), normal.y(), normal.z()});
      soup.uvs.insert(soup.uvs.end(), {p.x(), p.y()});  // metres: a terrain texture repeats every <size>
    }
  auto index = [&](int r, int c) { return static_cast<uint32_t>(r * n + c); };
  for (int r = 0; r + 1 < n; ++r)
    for (int c = 0; c + 1 < n; ++c) {
      // (r+1, c) is south-west: counter-clockwise from above is sw, se, ne, nw
      const uint32_t sw = index(r + 1, c), se = index(r + 1, c + 1), ne = index(r, c + 1), nw = index(r, c);
      soup.indices.insert(soup.indices.end(), {sw, se, ne, sw, ne, nw});
    }
  return soup;
}

TriangleSoup FromOcTree(const octomap::OcTree& tree) {
  // Exposed cell faces, grouped by (axis, side, layer) into 2-D masks; each mask is covered by
  // greedy maximal rectangles, so a flat wall is a few quads instead of one per cell.
  const double res = tree.getResolution();
  auto index = [&](float c) { return static_cast<int>(std::floor(c / res)); };
  std::map<std::tuple<int, int, int>, std::set<std::pair<int, int>>> masks;
  geometry::ForEachOccupiedCell(tree, [&](const octomap::point3d& centre) {
    const int ijk[3] = {index(centre.x()), index(centre.y()), index(centre.z())};
    for (int axis = 0; axis < 3; ++axis)
      for (int sign : {-1, 1}) {
        octomap::point3d neighbour = centre;
        neighbour(axis) += static_cast<float>(sign * res);
        const octomap::OcTreeNode* node = tree.search(neighbour);
        if (node && tree.isNodeOccupied(node)) continue;
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        masks[{axis, sign, ijk[axis]}].insert({ijk[u], ijk[v]});
      }
  });
  TriangleSoup soup;
  for (auto& [key, cells] : masks) {
    const auto [axis, sign, layer] = key;
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    while (!cells.empty()) {
      // grow a rectangle from the smallest cell: along v first, then along u while every row is full
      const auto [i0, j0] = *cells.begin();
      int j1 = j0;
      while (cells.count({i0, j1 + 1})) ++j1;
      int i1 = i0;
      for (bool full = true; full;) {
        for (int j = j0; j <= j1 && full; ++j) full = cells.count({i1 + 1, j}) > 0;
        if (full) ++i1;
      }
      for (int i = i0; i <= i1; ++i)
        for (int j = j0; j <= j1; ++j) cells.erase({i, j});
      Vector3f lo, hi;
      lo[axis] = hi[axis] = static_cast<float>((layer + (sign > 0 ? 1 : 0)) * res);
      lo[u] = static_cast<float>(i0 * res);
      hi[u] = static_cast<float>((i1 + 1) * res);
      lo[v] = static_cast<float>(j0 * res);
      hi[v] = static_cast<float>((j1 + 1) * res);
      Vector3f a = lo, b = lo, c = hi, d = lo;
      b[u] = hi[u];
      d[v] = hi[v];
      // u x v = axis: a b c d is counter-clockwise seen from +axis
      if (sign > 0) AddQuad(&soup, a, b, c, d);
      else AddQuad(&soup, a, d, c, b);
    }
  }
  // texture coordinates in metres of the octree's frame, so that a material's texture keeps its
  // size on every face and runs on across neighbouring rectangles: (x, y) on horizontal faces,
  // (the horizontal coordinate, z) on walls
  const size_t n = soup.VertexCount();
  for (size_t i = 0; i < n; ++i) {
    const float* p = &soup.positions_m[3 * i];
    const float* normal = &soup.normals[3 * i];
    float* uv = &soup.uvs[2 * i];
    const bool horizontal = std::abs(normal[2]) > 0.5f, faces_x = std::abs(normal[0]) > 0.5f;
    uv[0] = horizontal || !faces_x ? p[0] : p[1];
    uv[1] = horizontal ? p[1] : p[2];
  }
  return soup;
}

}  // namespace rendering
}  // namespace rotors_sim
