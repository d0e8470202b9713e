// The renderer's uploaded geometry and textures, bounded (lru_cache.h): the GPU mesh of each shape
// (unit primitives scaled per visual; mesh files, heightmaps and octrees by their source object),
// simplified copies of large meshes for the sun's shadow map, and image files as mip-mapped
// textures. Every GL object is released when its entry is dropped; the context is current then.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "rendering/gl.h"
#include "rendering/lru_cache.h"
#include "rotors_core/rendering/tessellation.h"
#include "rotors_core/geometry/visual.h"

namespace rotors_sim {
namespace rendering {

/// Triangles drawn with one texture (a mesh's part), in compact runs each culled on its own.
struct GpuPart {
  std::string texture_file;  // "" for none; the texture is looked up when drawn (TextureCache)
  std::vector<Chunk> chunks;
};

/// A soup to upload as one part, and the image file of its texture ("" for none).
struct PartSoup {
  TriangleSoup soup;
  std::string texture_file;
};

/// Vertex and index buffers of one shape; owns its GL objects.
struct GpuMesh {
  GLuint vao = 0, vbo = 0, ebo = 0;    // ebo 0: not indexed
  bool own_colours = false;            // per-vertex colours from the mesh file
  std::vector<GpuPart> parts;          // one per texture of the mesh
  size_t triangles = 0;                // of all parts
  std::shared_ptr<const void> source;  // keeps the key's object alive (its address is the key)

  GpuMesh() = default;
  GpuMesh(GpuMesh&& other) noexcept { *this = std::move(other); }
  GpuMesh& operator=(GpuMesh&& other) noexcept;
  GpuMesh(const GpuMesh&) = delete;
  GpuMesh& operator=(const GpuMesh&) = delete;
  ~GpuMesh();
};

/// Image files as repeating, mip-mapped textures, by file and anisotropy.
class TextureCache {
 public:
  static constexpr size_t kCapacity = 256;
  TextureCache() : textures_(kCapacity) {}
  /// The image file as a texture, loaded on first use; 0 when it cannot be read (said once).
  GLuint For(const std::string& file, float max_anisotropy = 1.0f);
  void NextFrame() { textures_.NextFrame(); }
  size_t Size() const { return textures_.Size(); }

 private:
  /// One texture name; released with the entry.
  struct Texture {
    GLuint name = 0;
    explicit Texture(GLuint n = 0) : name(n) {}
    Texture(Texture&& other) noexcept : name(std::exchange(other.name, 0)) {}
    Texture& operator=(Texture&& other) noexcept {
      std::swap(name, other.name);
      return *this;
    }
    Texture(const Texture&) = delete;
    Texture& operator=(const Texture&) = delete;
    ~Texture() {
      if (name) glDeleteTextures(1, &name);
    }
  };
  LruCache<std::pair<std::string, float>, Texture> textures_;
};

/// The GPU mesh of each shape.
class MeshCache {
 public:
  static constexpr size_t kCapacity = 512;        // shapes with their own mesh
  static constexpr size_t kShadowCapacity = 128;  // simplified copies for the shadow map
  MeshCache() : meshes_(kCapacity), shadow_proxies_(kShadowCapacity) {}

  /// The GPU mesh of a shape and the scale S that takes the mesh's frame to the visual frame;
  /// nullptr for a shape with nothing to draw.
  const GpuMesh* For(const geometry::Shape& shape, Eigen::Matrix4d* S);
  /// What a visual's shadow is drawn from: the shape's mesh, or for a mesh of more than 4,096
  /// triangles (a vehicle's body) a simplified copy on a grid of 1/64 of its size: the shadow map's
  /// texels are centimetres, and every vehicle is drawn into it again each time it moves.
  const GpuMesh* ShadowFor(const geometry::Shape& shape, Eigen::Matrix4d* S);
  void NextFrame() {
    meshes_.NextFrame();
    shadow_proxies_.NextFrame();
  }
  /// Triangles of the meshes cached now.
  size_t Triangles() const;
  size_t Size() const { return meshes_.Size() + shadow_proxies_.Size(); }

 private:
  static GpuMesh Upload(std::shared_ptr<const void> source, std::vector<PartSoup> parts);
  static GpuMesh Upload(std::shared_ptr<const void> source, TriangleSoup soup) {
    std::vector<PartSoup> one(1);
    one[0].soup = std::move(soup);
    return Upload(std::move(source), std::move(one));
  }
  LruCache<const void*, GpuMesh> meshes_;
  LruCache<const void*, GpuMesh> shadow_proxies_;
};

}  // namespace rendering
}  // namespace rotors_sim
