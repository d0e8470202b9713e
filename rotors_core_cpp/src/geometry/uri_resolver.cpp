#include "rotors_core/geometry/uri_resolver.h"

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <sstream>

#include "rotors_core/error.h"

namespace fs = std::filesystem;

namespace rotors_sim {
namespace geometry {
namespace {

std::mutex& Mutex() {
  static std::mutex m;
  return m;
}

std::vector<std::string>& ExtraPaths() {
  static std::vector<std::string> paths;
  return paths;
}

std::vector<std::string> SplitPathList(const char* value) {
  std::vector<std::string> out;
  if (!value) return out;
  std::stringstream s(value);
  std::string item;
  while (std::getline(s, item, ':'))
    if (!item.empty()) out.push_back(item);
  return out;
}

bool StartsWith(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

std::string Join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& i : items) out += (out.empty() ? "" : ":") + i;
  return out.empty() ? "(none)" : out;
}

/// package://NAME: <entry>/NAME or a package.xml two levels down naming it, for each
/// ROS_PACKAGE_PATH entry.
std::string FindPackage(const std::string& name, std::vector<std::string>* searched) {
  for (const auto& entry : SplitPathList(std::getenv("ROS_PACKAGE_PATH"))) {
    searched->push_back(entry);
    const fs::path direct = fs::path(entry) / name;
    if (fs::exists(direct / "package.xml")) return direct.string();
    if (fs::path(entry).filename() == name && fs::exists(fs::path(entry) / "package.xml")) return entry;
  }
  return "";
}

}  // namespace

void UriResolver::AddModelPath(const std::string& folder) {
  std::lock_guard<std::mutex> lock(Mutex());
  for (const auto& p : ExtraPaths())
    if (p == folder) return;
  ExtraPaths().push_back(folder);
}

std::vector<std::string> UriResolver::ModelPaths() {
  std::vector<std::string> paths;
  for (const char* env : {"GAZEBO_MODEL_PATH", "ROTORS_MODEL_PATH"})
    for (const auto& p : SplitPathList(std::getenv(env))) paths.push_back(p);
  std::lock_guard<std::mutex> lock(Mutex());
  for (const auto& p : ExtraPaths()) paths.push_back(p);
  return paths;
}

std::vector<std::string> UriResolver::ResourcePaths() {
  std::vector<std::string> paths = SplitPathList(std::getenv("GAZEBO_RESOURCE_PATH"));
  paths.push_back(ROTORS_CORE_RESOURCE_DIR);
  return paths;
}

std::string UriResolver::Resolve(const std::string& uri, const std::string& base_file) {
  std::vector<std::string> searched;
  std::string candidate;
  if (StartsWith(uri, "model://")) {
    const std::string rest = uri.substr(8);
    for (const auto& folder : ModelPaths()) {
      searched.push_back(folder);
      const fs::path p = fs::path(folder) / rest;
      if (fs::exists(p)) return p.string();
    }
    // sdformat turns a URDF's package://NAME/... into model://NAME/...: NAME may be a ROS package.
    const std::string package = rest.substr(0, rest.find('/'));
    std::vector<std::string> package_paths;
    const std::string dir = FindPackage(package, &package_paths);
    if (!dir.empty()) {
      const fs::path p = fs::path(dir) / rest.substr(std::min(rest.size(), package.size() + 1));
      if (fs::exists(p)) return p.string();
    }
    throw SimError("'" + uri + "' cannot be resolved: no such file under the model paths " + Join(searched) +
                   (dir.empty() ? std::string(" nor a ROS package '") + package + "'"
                                : std::string(" nor in package '") + package + "' at " + dir) +
                   " (set GAZEBO_MODEL_PATH or export gazebo_model_path from a package)");
  }
  if (StartsWith(uri, "package://")) {
    const std::string rest = uri.substr(10);
    const std::string package = rest.substr(0, rest.find('/'));
    const std::string dir = FindPackage(package, &searched);
    if (dir.empty())
      throw SimError("'" + uri + "' cannot be resolved: package '" + package + "' is not on ROS_PACKAGE_PATH " +
                     Join(searched));
    candidate = (fs::path(dir) / rest.substr(std::min(rest.size(), package.size() + 1))).string();
  } else if (StartsWith(uri, "file://")) {
    candidate = uri.substr(7);
    // Gazebo reads a relative file:// (file://media/materials/scripts/gazebo.material) under its
    // resource paths: GAZEBO_RESOURCE_PATH, then this engine's own media (Gazebo's built-in materials)
    if (!candidate.empty() && candidate[0] != '/' && !fs::exists(candidate)) {
      for (const auto& folder : ResourcePaths()) {
        searched.push_back(folder);
        if (fs::exists(fs::path(folder) / candidate)) return (fs::path(folder) / candidate).string();
      }
      throw SimError("'" + uri + "' cannot be resolved: no such file under the resource paths " + Join(searched) +
                     " (set GAZEBO_RESOURCE_PATH)");
    }
  } else if (!uri.empty() && uri[0] == '/') {
    candidate = uri;
  } else {
    candidate = (base_file.empty() ? fs::path(uri) : fs::path(base_file).parent_path() / uri).string();
  }
  if (!fs::exists(candidate)) throw SimError("'" + uri + "': file '" + candidate + "' does not exist");
  return candidate;
}

}  // namespace geometry
}  // namespace rotors_sim
