#include "rotors_core/geometry/shapes.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <octomap/OcTree.h>
#include <stb/stb_image.h>

#include "rotors_core/error.h"

namespace rotors_sim {
namespace geometry {
namespace {

std::string Extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  return ext;
}

template <typename T>
struct Cache {
  std::mutex mutex;
  std::map<std::string, std::weak_ptr<const T>> entries;
};

}  // namespace

bool IsOcTreeFile(const std::string& path) {
  const std::string ext = Extension(path);
  return ext == ".bt" || ext == ".ot";
}

std::shared_ptr<const TriangleMesh> LoadMesh(const std::string& path, const std::array<double, 3>& scale) {
  static Cache<TriangleMesh> cache;
  std::ostringstream key;
  key << path << '|' << scale[0] << ',' << scale[1] << ',' << scale[2];
  std::lock_guard<std::mutex> lock(cache.mutex);
  if (auto hit = cache.entries[key.str()].lock()) return hit;

  if (!std::filesystem::exists(path)) throw SimError("mesh '" + path + "' does not exist");
  Assimp::Importer importer;
  // a Collada file's <up_axis> is ignored, as Gazebo's and rviz' loaders do (assimp would turn a
  // Z_UP file, RotorS' warehouse models, on its side to make Y up)
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  // node transforms baked into the vertices
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                                     aiProcess_PreTransformVertices | aiProcess_SortByPType);
  if (!scene || !scene->mRootNode) throw SimError("mesh '" + path + "' does not parse: " + importer.GetErrorString());
  auto mesh = std::make_shared<TriangleMesh>();
  bool any_uv = false;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) any_uv = any_uv || scene->mMeshes[m]->HasTextureCoords(0);
  // each assimp mesh's diffuse texture; the meshes are appended texture by texture, so that each
  // texture's triangles form one part
  auto material_of = [&](const aiMesh* am) -> const aiMaterial* {
    return scene->mNumMaterials > am->mMaterialIndex ? scene->mMaterials[am->mMaterialIndex] : nullptr;
  };
  std::map<std::string, std::vector<unsigned>> by_texture;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* am = scene->mMeshes[m];
    const aiMaterial* material = material_of(am);
    aiString texture;
    std::string file;
    if (material && am->HasTextureCoords(0) && material->GetTexture(aiTextureType_DIFFUSE, 0, &texture) == AI_SUCCESS &&
        texture.length > 0 && texture.C_Str()[0] != '*')  // '*n': embedded, not supported
      file = (std::filesystem::path(path).parent_path() / texture.C_Str()).lexically_normal().string();
    by_texture[file].push_back(m);
  }
  for (const auto& [texture_file, meshes] : by_texture) {
    MeshPart part;
    part.first_triangle = mesh->indices.size() / 3;
    part.texture_file = texture_file;
    for (unsigned m : meshes) {
      const aiMesh* am = scene->mMeshes[m];
      const aiMaterial* material = material_of(am);
      aiColor4D diffuse(0.7f, 0.7f, 0.7f, 1.0f);
      if (material) material->Get(AI_MATKEY_COLOR_DIFFUSE, diffuse);
      const uint32_t base = static_cast<uint32_t>(mesh->vertices_m.size() / 3);
      for (unsigned v = 0; v < am->mNumVertices; ++v) {
        for (int k = 0; k < 3; ++k) mesh->vertices_m.push_back(am->mVertices[v][k] * scale[k]);
        // a textured material's diffuse colour is what the texture shows through (white unless set)
        const aiColor4D c = am->HasVertexColors(0) ? am->mColors[0][v] : diffuse;
        mesh->colours.insert(mesh->colours.end(), {c.r, c.g, c.b});
        if (any_uv) {
          const bool has = am->HasTextureCoords(0);
          mesh->uvs.insert(mesh->uvs.end(),
                           {has ? am->mTextureCoords[0][v].x : 0.0f, has ? am->mTextureCoords[0][v].y : 0.0f});
        }
      }
      for (unsigned f = 0; f < am->mNumFaces; ++f) {
        if (am->mFaces[f].mNumIndices != 3) continue;  // points and lines
        for (int k = 0; k < 3; ++k) mesh->indices.push_back(base + am->mFaces[f].mIndices[k]);
      }
    }
    part.triangles = mesh->indices.size() / 3 - part.first_triangle;
    if (part.triangles > 0) mesh->parts.push_back(part);
  }
  if (mesh->indices.empty()) throw SimError("mesh '" + path + "' holds no triangles");
  if (scene->mNumMaterials > 0 && scene->mNumMeshes > 0) {
    aiColor4D c;
    if (scene->mMaterials[scene->mMeshes[0]->mMaterialIndex]->Get(AI_MATKEY_COLOR_DIFFUSE, c) == AI_SUCCESS)
      mesh->rgba = {c.r, c.g, c.b, c.a};
  }
  cache.entries[key.str()] = mesh;
  return mesh;
}

double HeightField::HeightAt(double x_m, double y_m) const {
  const double u = std::clamp((x_m - (pos_x_m - size_x_m / 2)) / size_x_m * (n - 1), 0.0, n - 1.0);
  const double v = std::clamp(((pos_y_m + size_y_m / 2) - y_m) / size_y_m * (n - 1), 0.0, n - 1.0);
  const int c = std::min(static_cast<int>(u), n - 2), r = std::min(static_cast<int>(v), n - 2);
  const double fu = u - c, fv = v - r;
  auto h = [&](int rr, int cc) { return heights_m[rr * n + cc]; };
  return (1 - fv) * ((1 - fu) * h(r, c) + fu * h(r, c + 1)) + fv * ((1 - fu) * h(r + 1, c) + fu * h(r + 1, c + 1));
}

std::shared_ptr<const HeightField> LoadHeightmap(const std::string& path, const std::array<double, 3>& size_m,
                                                 const std::array<double, 3>& pos_m) {
  static Cache<HeightField> cache;
  std::ostringstream key;
  key << path << '|' << size_m[0] << ',' << size_m[1] << ',' << size_m[2] << '|' << pos_m[0] << ',' << pos_m[1] << ','
      << pos_m[2];
  std::lock_guard<std::mutex> lock(cache.mutex);
  if (auto hit = cache.entries[key.str()].lock()) return hit;
  if (!std::filesystem::exists(path)) throw SimError("heightmap image '" + path + "' does not exist");
  if (!(size_m[0] > 0) || !(size_m[1] > 0) || !(size_m[2] >= 0))
    throw SimError("heightmap '" + path + "': <size> must be positive");
  int w = 0, h = 0, channels = 0;
  const bool sixteen = stbi_is_16_bit(path.c_str());
  void* pixels = sixteen ? static_cast<void*>(stbi_load_16(path.c_str(), &w, &h, &channels, 1))
                         : static_cast<void*>(stbi_load(path.c_str(), &w, &h, &channels, 1));
  if (!pixels) throw SimError("heightmap image '" + path + "' does not parse: " + stbi_failure_reason());
  const bool power_of_two_plus_one = w >= 3 && ((w - 1) & (w - 2)) == 0;
  if (w != h || !power_of_two_plus_one) {
    stbi_image_free(pixels);
    throw SimError("heightmap image '" + path + "' is " + std::to_string(w) + " x " + std::to_string(h) +
                   " pixels; it must be square with 2^k + 1 pixels per side (e.g. 129, 257, 513)");
  }
  auto field = std::make_shared<HeightField>();
  field->n = w;
  field->size_x_m = size_m[0];
  field->size_y_m = size_m[1];
  field->size_z_m = size_m[2];
  field->pos_x_m = pos_m[0];
  field->pos_y_m = pos_m[1];
  field->pos_z_m = pos_m[2];
  field->heights_m.resize(static_cast<size_t>(w) * h);
  const double full_scale = sixteen ? 65535.0 : 255.0;
  for (size_t i = 0; i < field->heights_m.size(); ++i) {
    const double value = sixteen ? static_cast<uint16_t*>(pixels)[i] : static_cast<uint8_t*>(pixels)[i];
    field->heights_m[i] = pos_m[2] + value / full_scale * size_m[2];
  }
  stbi_image_free(pixels);
  cache.entries[key.str()] = field;
  return field;
}

std::shared_ptr<const octomap::OcTree> LoadOcTree(const std::string& path) {
  static Cache<octomap::OcTree> cache;
  std::lock_guard<std::mutex> lock(cache.mutex);
  if (auto hit = cache.entries[path].lock()) return hit;
  if (!std::filesystem::exists(path)) throw SimError("octomap '" + path + "' does not exist");
  std::shared_ptr<octomap::OcTree> tree;
  if (Extension(path) == ".bt") {
    std::ifstream in(path, std::ios::binary);
    tree = std::make_shared<octomap::OcTree>(0.1);
    // readBinary checks the header; a truncated body leaves the stream failed
    if (!tree->readBinary(in) || in.bad())
      throw SimError("octomap '" + path + "' does not parse as a binary OcTree (.bt)");
  } else {
    std::unique_ptr<octomap::AbstractOcTree> any(octomap::AbstractOcTree::read(path));
    auto* as_octree = dynamic_cast<octomap::OcTree*>(any.get());
    if (!as_octree) throw SimError("octomap '" + path + "' does not parse as an OcTree (.ot)");
    any.release();
    tree.reset(as_octree);
  }
  if (tree->size() == 0) throw SimError("octomap '" + path + "' holds no nodes");
  cache.entries[path] = tree;
  return tree;
}

}  // namespace geometry
}  // namespace rotors_sim
