#include "rendering/gpu_cache.h"

#include <algorithm>
#include <cstring>
#include <iostream>

#include <Eigen/Geometry>
#include <stb/stb_image.h>

#include "rotors_core/error.h"

namespace rotors_sim {
namespace rendering {
namespace {

using geometry::Shape;

bool HasExtension(const char* name) {
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i)
    if (std::strcmp(reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, i)), name) == 0) return true;
  return false;
}

// the unit primitives' keys: addresses no source object has
const int kUnitBox = 0, kUnitSphere = 0, kUnitCylinder = 0, kUnitSquare = 0;

}  // namespace

GpuMesh& GpuMesh::operator=(GpuMesh&& other) noexcept {
  std::swap(vao, other.vao);
  std::swap(vbo, other.vbo);
  std::swap(ebo, other.ebo);
  std::swap(own_colours, other.own_colours);
  std::swap(parts, other.parts);
  std::swap(triangles, other.triangles);
  std::swap(source, other.source);
  return *this;
}

GpuMesh::~GpuMesh() {
  if (ebo) glDeleteBuffers(1, &ebo);
  if (vbo) glDeleteBuffers(1, &vbo);
  if (vao) glDeleteVertexArrays(1, &vao);
}

/// A grey image is kept as one channel read as (g, g, g): the same colours, a third of the
/// filtering work. Mip-mapped (trilinear) and anisotropically filtered up to max_anisotropy (a
/// material's "filtering anisotropic"): distant texture does not shimmer from frame to frame.
GLuint TextureCache::For(const std::string& file, float max_anisotropy) {
  const auto key = std::make_pair(file, max_anisotropy);
  if (const Texture* found = textures_.Find(key)) return found->name;
  int w = 0, h = 0, channels = 0;
  // grey (with or without alpha) as one channel, the rest as RGB; the alpha is not drawn
  const bool grey = stbi_info(file.c_str(), &w, &h, &channels) && channels <= 2;
  const int kept = grey ? 1 : 3;
  unsigned char* pixels = stbi_load(file.c_str(), &w, &h, &channels, kept);
  if (!pixels) {
    // CameraSensor checks textures when it is created; a model spawned later is drawn without
    std::cerr << "[rotors_sim] camera renderer: texture '" << file << "' cannot be read (" << stbi_failure_reason()
              << "); drawn without it\n";
    return textures_.Insert(key, Texture(0)).name;
  }
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  // image row 0 is the top; texture coordinate v = 0 is the bottom
  const size_t row = static_cast<size_t>(w) * kept;
  std::vector<unsigned char> flipped(row * h);
  for (int r = 0; r < h; ++r) std::copy(pixels + r * row, pixels + (r + 1) * row, flipped.begin() + (h - 1 - r) * row);
  stbi_image_free(pixels);
  if (grey) {
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, w, h, 0, GL_RED, GL_UNSIGNED_BYTE, flipped.data());
    const GLint rrr1[] = {GL_RED, GL_RED, GL_RED, GL_ONE};
    glTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_SWIZZLE_RGBA, rrr1);
  } else {
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, w, h, 0, GL_RGB, GL_UNSIGNED_BYTE, flipped.data());
  }
  glGenerateMipmap(GL_TEXTURE_2D);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  // anisotropic filtering (OGRE's "filtering anisotropic", max_anisotropy 16) where the driver has it
  constexpr GLenum kMaxAnisotropy = 0x84FE;  // GL_TEXTURE_MAX_ANISOTROPY(_EXT), core in OpenGL 4.6
  if (max_anisotropy > 1.0f &&
      (HasExtension("GL_EXT_texture_filter_anisotropic") || HasExtension("GL_ARB_texture_filter_anisotropic")))
    glTexParameterf(GL_TEXTURE_2D, kMaxAnisotropy, max_anisotropy);
  return textures_.Insert(key, Texture(texture)).name;
}

GpuMesh MeshCache::Upload(std::shared_ptr<const void> source, std::vector<PartSoup> parts) {
  GpuMesh mesh;
  mesh.source = std::move(source);
  bool any_colours = false;
  for (const PartSoup& p : parts) any_colours = any_colours || !p.soup.colours.empty();
  if (parts.size() > 1)
    for (const PartSoup& p : parts)
      if (!p.soup.indices.empty()) throw SimError("camera renderer: only an unindexed soup may come in parts");
  mesh.own_colours = any_colours;
  constexpr int kFloats = 11;  // position, normal, colour, uv
  std::vector<float> interleaved;
  size_t first_triangle = 0;
  for (PartSoup& p : parts) {
    TriangleSoup& soup = p.soup;
    GpuPart part;
    part.chunks = SortIntoChunks(&soup);
    for (Chunk& chunk : part.chunks) chunk.first_triangle += first_triangle;  // in the one buffer of all parts
    for (size_t i = 0; i < soup.VertexCount(); ++i) {
      interleaved.insert(interleaved.end(), soup.positions_m.begin() + 3 * i, soup.positions_m.begin() + 3 * i + 3);
      interleaved.insert(interleaved.end(), soup.normals.begin() + 3 * i, soup.normals.begin() + 3 * i + 3);
      if (!soup.colours.empty())
        interleaved.insert(interleaved.end(), soup.colours.begin() + 3 * i, soup.colours.begin() + 3 * i + 3);
      else interleaved.insert(interleaved.end(), {1.0f, 1.0f, 1.0f});
      if (!soup.uvs.empty())
        interleaved.insert(interleaved.end(), soup.uvs.begin() + 2 * i, soup.uvs.begin() + 2 * i + 2);
      else interleaved.insert(interleaved.end(), {0.0f, 0.0f});
    }
    if (!soup.uvs.empty()) part.texture_file = p.texture_file;
    first_triangle += soup.TriangleCount();
    mesh.parts.push_back(std::move(part));
  }
  mesh.triangles = first_triangle;
  glGenVertexArrays(1, &mesh.vao);
  glBindVertexArray(mesh.vao);
  glGenBuffers(1, &mesh.vbo);
  glBindBuffer(GL_ARRAY_BUFFER, mesh.vbo);
  glBufferData(GL_ARRAY_BUFFER, interleaved.size() * sizeof(float), interleaved.data(), GL_STATIC_DRAW);
  const GLsizei stride = kFloats * sizeof(float);
  const int sizes[] = {3, 3, 3, 2};
  for (int a = 0, offset = 0; a < 4; offset += sizes[a], ++a) {
    glVertexAttribPointer(a, sizes[a], GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offset * sizeof(float)));
    glEnableVertexAttribArray(a);
  }
  if (parts.size() == 1 && !parts[0].soup.indices.empty()) {
    const std::vector<uint32_t>& indices = parts[0].soup.indices;
    glGenBuffers(1, &mesh.ebo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mesh.ebo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, indices.size() * sizeof(uint32_t), indices.data(), GL_STATIC_DRAW);
  }
  glBindVertexArray(0);
  return mesh;
}

const GpuMesh* MeshCache::For(const Shape& shape, Eigen::Matrix4d* S) {
  S->setIdentity();
  // a unit primitive (pinned), or the shape's own source object's mesh
  auto unit = [&](const int* key, auto make) -> const GpuMesh* {
    if (const GpuMesh* mesh = meshes_.Find(key)) return mesh;
    return &meshes_.Insert(key, Upload(nullptr, make()), true);
  };
  auto own = [&](const std::shared_ptr<const void>& source, auto make) -> const GpuMesh* {
    if (!source) return nullptr;
    if (const GpuMesh* mesh = meshes_.Find(source.get())) return mesh;
    return &meshes_.Insert(source.get(), make());
  };
  switch (shape.type) {
    case Shape::Type::kBox:
      *S = Eigen::Vector4d(shape.box_size_m.X(), shape.box_size_m.Y(), shape.box_size_m.Z(), 1).asDiagonal();
      return unit(&kUnitBox, [] { return UnitBox(); });
    case Shape::Type::kSphere:
      *S = Eigen::Vector4d(shape.radius_m, shape.radius_m, shape.radius_m, 1).asDiagonal();
      return unit(&kUnitSphere, [] { return UnitSphere(); });
    case Shape::Type::kCylinder:
      *S = Eigen::Vector4d(shape.radius_m, shape.radius_m, shape.length_m, 1).asDiagonal();
      return unit(&kUnitCylinder, [] { return UnitCylinder(); });
    case Shape::Type::kPlane: {
      const Eigen::Vector3d n(shape.plane_normal.X(), shape.plane_normal.Y(), shape.plane_normal.Z());
      S->topLeftCorner<3, 3>() =
          Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), n.normalized()).toRotationMatrix() *
          Eigen::Vector3d(shape.plane_size_m.X(), shape.plane_size_m.Y(), 1).asDiagonal();
      return unit(&kUnitSquare, [] { return UnitSquare(); });
    }
    case Shape::Type::kMesh:
      return own(shape.mesh, [&] {
        std::vector<PartSoup> parts;
        for (const geometry::MeshPart& part : shape.mesh->parts)
          parts.push_back({FromMesh(*shape.mesh, part), part.texture_file});
        return Upload(shape.mesh, std::move(parts));
      });
    case Shape::Type::kHeightmap:
      return own(shape.heightfield, [&] { return Upload(shape.heightfield, FromHeightField(*shape.heightfield)); });
    case Shape::Type::kOcTree:
      return own(shape.octree, [&] { return Upload(shape.octree, FromOcTree(*shape.octree)); });
  }
  return nullptr;
}

const GpuMesh* MeshCache::ShadowFor(const Shape& shape, Eigen::Matrix4d* S) {
  constexpr size_t kMaxTriangles = 4096;
  if (shape.type != Shape::Type::kMesh || !shape.mesh || shape.mesh->TriangleCount() <= kMaxTriangles)
    return For(shape, S);
  S->setIdentity();
  if (const GpuMesh* found = shadow_proxies_.Find(shape.mesh.get())) return found;
  const geometry::TriangleMesh& mesh = *shape.mesh;
  const Eigen::Map<const Eigen::Matrix3Xd> p(mesh.vertices_m.data(), 3,
                                             static_cast<Eigen::Index>(mesh.vertices_m.size() / 3));
  const auto size_m = static_cast<float>((p.rowwise().maxCoeff() - p.rowwise().minCoeff()).norm());
  return &shadow_proxies_.Insert(shape.mesh.get(),
                                 Upload(shape.mesh, Simplified(mesh, std::max(size_m / 64.0f, 1e-4f))));
}

size_t MeshCache::Triangles() const {
  size_t sum = 0;
  meshes_.ForEach([&sum](const void*, const GpuMesh& mesh) { sum += mesh.triangles; });
  shadow_proxies_.ForEach([&sum](const void*, const GpuMesh& mesh) { sum += mesh.triangles; });
  return sum;
}

}  // namespace rendering
}  // namespace rotors_sim
