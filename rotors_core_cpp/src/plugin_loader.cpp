#include "rotors_core/plugin_loader.h"

#include <dlfcn.h>
#include <sys/stat.h>

#include <cctype>
#include <cstdlib>
#include <sstream>

#include "rotors_core/error.h"

namespace rotors_sim {
namespace {

bool IsFile(const std::string& path) {
  struct stat st;
  return stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

void AppendPathList(const char* env_name, std::vector<std::string>* out) {
  const char* value = std::getenv(env_name);
  if (!value) return;
  std::stringstream ss(value);
  std::string dir;
  while (std::getline(ss, dir, ':'))
    if (!dir.empty()) out->push_back(dir);
}

void* OpenLibrary(const std::string& filename) {
  const std::string path = PluginLoader::Resolve(filename);
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);  // never closed: plugins live with the process
  if (!handle) throw SimError("cannot load plugin library '" + path + "': " + dlerror());
  return handle;
}

template <typename PluginT>
std::unique_ptr<PluginT> Create(const std::string& filename, const char* symbol, const char* kind) {
  void* handle = OpenLibrary(filename);
  using Factory = PluginT* (*)();
  auto factory = reinterpret_cast<Factory>(dlsym(handle, symbol));
  if (!factory) {
    for (const char* other : {"model", "world", "sensor"}) {
      const std::string other_symbol =
          std::string("RotorsSimCreate") + char(std::toupper(other[0])) + (other + 1) + "Plugin";
      if (dlsym(handle, other_symbol.c_str()))
        throw SimError("plugin '" + filename + "' is a " + other + " plugin and cannot be used as a " + kind +
                       " plugin");
    }
    std::string macro = kind;
    for (char& c : macro) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    throw SimError("'" + filename + "' is not a rotors_sim plugin (it exports no " + symbol +
                   "; register the class with GZ_REGISTER_" + macro + "_PLUGIN)");
  }
  return std::unique_ptr<PluginT>(factory());
}

}  // namespace

std::vector<std::string> PluginLoader::SearchPath() {
  std::vector<std::string> dirs;
  AppendPathList("GAZEBO_PLUGIN_PATH", &dirs);
  AppendPathList("ROTORS_PLUGIN_PATH", &dirs);
  AppendPathList("LD_LIBRARY_PATH", &dirs);
  return dirs;
}

std::string PluginLoader::Resolve(const std::string& filename) {
  if (filename.empty()) throw SimError("a <plugin> has an empty filename attribute");
  if (filename.find('/') != std::string::npos) {
    if (IsFile(filename)) return filename;
    throw SimError("plugin library '" + filename + "' does not exist");
  }
  const std::vector<std::string> dirs = SearchPath();
  for (const auto& dir : dirs) {
    const std::string candidate = dir + "/" + filename;
    if (IsFile(candidate)) return candidate;
  }
  std::string searched;
  for (const auto& dir : dirs) searched += (searched.empty() ? "" : ":") + dir;
  throw SimError("plugin library '" + filename +
                 "' not found in GAZEBO_PLUGIN_PATH, ROTORS_PLUGIN_PATH or LD_LIBRARY_PATH (" +
                 (searched.empty() ? std::string("all empty") : searched) + "); is the workspace built and sourced?");
}

std::unique_ptr<ModelPlugin> PluginLoader::CreateModelPlugin(const std::string& filename) {
  return Create<ModelPlugin>(filename, "RotorsSimCreateModelPlugin", "model");
}

std::unique_ptr<WorldPlugin> PluginLoader::CreateWorldPlugin(const std::string& filename) {
  return Create<WorldPlugin>(filename, "RotorsSimCreateWorldPlugin", "world");
}

std::unique_ptr<SensorPlugin> PluginLoader::CreateSensorPlugin(const std::string& filename) {
  return Create<SensorPlugin>(filename, "RotorsSimCreateSensorPlugin", "sensor");
}

}  // namespace rotors_sim
