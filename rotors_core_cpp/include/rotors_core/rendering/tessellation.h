// Every visual shape as triangles with normals, for the renderer. Engine-free: no GL.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "rotors_core/geometry/visual.h"

namespace rotors_sim {
namespace rendering {

/// Triangles in the shape's own frame, each vertex with a normal: three vertices per triangle, or
/// shared vertices and three indices per triangle (smooth surfaces such as heightmaps).
struct TriangleSoup {
  std::vector<float> positions_m;  ///< x y z per vertex
  std::vector<float> normals;      ///< unit normal per vertex
  std::vector<float> colours;      ///< r g b per vertex (a mesh's own colours), or empty: white
  std::vector<float> uvs;          ///< u v per vertex (texture coordinates), or empty
  std::vector<uint32_t> indices;   ///< three per triangle, or empty: the vertices taken in threes
  size_t VertexCount() const { return positions_m.size() / 3; }
  size_t TriangleCount() const { return indices.empty() ? VertexCount() / 3 : indices.size() / 3; }
  void Add(const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& c);  ///< flat normal
  void Add(const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& c, const Eigen::Vector3f& na,
           const Eigen::Vector3f& nb, const Eigen::Vector3f& nc);
};

/// A run of triangles of a soup and a sphere around them, so that the renderer can skip the run
/// when the sphere is out of view.
struct Chunk {
  size_t first_triangle = 0, triangles = 0;
  Eigen::Vector3f centre_m = Eigen::Vector3f::Zero();
  float radius_m = 0.0f;
};

/// Reorders a soup's triangles by the cell of a grid over its bounding box (at most
/// cells_per_axis^3 cells; one cell for soups of fewer than min_triangles) and returns one chunk
/// per non-empty cell. The set of triangles and each triangle's vertices are unchanged.
std::vector<Chunk> SortIntoChunks(TriangleSoup* soup, int cells_per_axis = 4, size_t min_triangles = 1024);

/// Unit shapes, scaled by the renderer: a 1 m cube centred at the origin, a sphere of radius 1 m,
/// a cylinder of radius 1 m and length 1 m along z, a 1 x 1 m square in the xy plane.
TriangleSoup UnitBox();
TriangleSoup UnitSphere(int slices = 32, int stacks = 16);
TriangleSoup UnitCylinder(int slices = 32);
TriangleSoup UnitSquare();

TriangleSoup FromMesh(const geometry::TriangleMesh& mesh);
/// The triangles of one part of a mesh (those drawn with one texture).
TriangleSoup FromMesh(const geometry::TriangleMesh& mesh, const geometry::MeshPart& part);
/// One quad per pair of neighbouring samples, normals from the height gradient.
TriangleSoup FromHeightField(const geometry::HeightField& field);
/// A coarse copy of a mesh for drawing its shadow: vertex clustering (Rossignac and Borrel) on a
/// grid of cell_m, each cell's vertices merged into their mean, triangles that collapse dropped,
/// each remaining triangle once. Positions only (the normals are flat).
TriangleSoup Simplified(const geometry::TriangleMesh& mesh, float cell_m);
/// The occupied cells' faces that border free or unknown space (inner faces are never seen), with
/// texture coordinates in metres: (x, y) on horizontal faces, (x or y, z) on walls.
TriangleSoup FromOcTree(const octomap::OcTree& tree);

}  // namespace rendering
}  // namespace rotors_sim
