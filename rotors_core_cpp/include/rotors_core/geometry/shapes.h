// Geometry read from files: triangle meshes (assimp), heightmaps (grey images) and OctoMap
// octrees. Engine-free data: no ODE here; the collision builder turns them into ODE geoms and
// the visual publishers draw them.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace octomap {
class OcTree;
}

namespace rotors_sim {
namespace geometry {

/// A run of a mesh's triangles drawn with one diffuse texture (a Collada or OBJ file may hold several).
struct MeshPart {
  size_t first_triangle = 0, triangles = 0;
  std::string texture_file;  ///< resolved path (may not exist), or empty: no texture
};

/// Triangles in the mesh's own frame, already scaled.
struct TriangleMesh {
  std::vector<double> vertices_m;                     ///< x0 y0 z0 x1 y1 z1 ... [m]
  std::vector<uint32_t> indices;                      ///< three per triangle
  std::array<float, 4> rgba{0.7f, 0.7f, 0.7f, 1.0f};  ///< diffuse colour of the first material
  std::vector<float> colours;  ///< r g b per vertex (its material's diffuse or vertex colour), for renderers
  std::vector<float> uvs;      ///< u v per vertex when the file has texture coordinates, else empty
  /// The triangles by diffuse texture, in order and covering them all: one part per texture (and
  /// one for the untextured ones)
  std::vector<MeshPart> parts;
  size_t TriangleCount() const { return indices.size() / 3; }
};

/// Loads every mesh of a .dae/.stl/.obj/.ply file (node transforms applied) scaled per axis.
/// Cached by file and scale. Throws SimError naming the file and the problem.
std::shared_ptr<const TriangleMesh> LoadMesh(const std::string& path, const std::array<double, 3>& scale);

/// A heightmap: n x n samples over size_x x size_y, heights in [pos_z, pos_z + size_z].
/// Sample (row r, column c) lies at x = pos_x - size_x/2 + c size_x/(n-1),
/// y = pos_y + size_y/2 - r size_y/(n-1): the image seen from above, north (+y) up.
struct HeightField {
  int n = 0;
  double size_x_m = 0, size_y_m = 0, size_z_m = 0;
  double pos_x_m = 0, pos_y_m = 0, pos_z_m = 0;
  std::vector<double> heights_m;                  ///< row-major, n * n, absolute z [m]
  double HeightAt(double x_m, double y_m) const;  ///< bilinear between samples
};

/// Reads a grey (8- or 16-bit) image as SDF <heightmap>: value / max * size_z above pos_z. The
/// image must be square with 2^k + 1 pixels per side, as in Gazebo. Cached by file, size and pos.
std::shared_ptr<const HeightField> LoadHeightmap(const std::string& path, const std::array<double, 3>& size_m,
                                                 const std::array<double, 3>& pos_m);

/// Reads an OctoMap (.bt binary or .ot full). Cached by file. Throws SimError when the file is
/// missing or does not parse.
std::shared_ptr<const octomap::OcTree> LoadOcTree(const std::string& path);

/// True for file names the engine reads as an OctoMap rather than a mesh (.bt, .ot).
bool IsOcTreeFile(const std::string& path);

}  // namespace geometry
}  // namespace rotors_sim
