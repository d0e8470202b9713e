#include "mesh_radius.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <assimp/Importer.hpp>
#include <assimp/scene.h>
#include <ros/package.h>

namespace rotors_planning {

double MeshRadius_m(const std::string& uri) {
  std::string path = uri;
  if (uri.rfind("package://", 0) == 0) {
    const std::string rest = uri.substr(10);
    const std::string package = rest.substr(0, rest.find('/'));
    const std::string root = ros::package::getPath(package);
    if (root.empty())
      throw std::invalid_argument("mesh '" + uri + "': no package '" + package + "' on ROS_PACKAGE_PATH");
    path = root + rest.substr(package.size());
  } else if (uri.rfind("file://", 0) == 0) {
    path = uri.substr(7);
  }
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, 0);
  if (!scene) throw std::invalid_argument("mesh '" + uri + "' cannot be read: " + importer.GetErrorString());
  double radius_sq = 0.0;
  // vertices through the node hierarchy's transforms, as they are drawn
  auto visit = [&](const aiNode* node, aiMatrix4x4 transform, auto&& self) -> void {
    transform = transform * node->mTransformation;
    for (unsigned m = 0; m < node->mNumMeshes; ++m) {
      const aiMesh* mesh = scene->mMeshes[node->mMeshes[m]];
      for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
        const aiVector3D p = transform * mesh->mVertices[v];
        radius_sq = std::max(radius_sq, static_cast<double>(p.SquareLength()));
      }
    }
    for (unsigned c = 0; c < node->mNumChildren; ++c) self(node->mChildren[c], transform, self);
  };
  visit(scene->mRootNode, aiMatrix4x4(), visit);
  return std::sqrt(radius_sq);
}

}  // namespace rotors_planning
