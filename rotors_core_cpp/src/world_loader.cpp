#include "rotors_core/world_loader.h"

#include "rotors_core/sensors/camera_sensor.h"
#include "rotors_core/sensors/ray_sensor.h"
#include "sdf_console.h"

#include <cstdlib>
#include <iostream>

#include <sdf/Model.hh>
#include <sdf/ParserConfig.hh>
#include <sdf/Physics.hh>
#include <sdf/Root.hh>
#include <sdf/SDFImpl.hh>
#include <sdf/World.hh>
#include <ignition/math/SphericalCoordinates.hh>
#include <sdf/Light.hh>
#include <sdf/Scene.hh>

#include "rotors_core/error.h"
#include "rotors_core/event.h"
#include "rotors_core/geometry/uri_resolver.h"
#include "rotors_core/model_builder.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/plugin_loader.h"

namespace rotors_sim {
namespace {

template <typename T>
T Child(const sdf::ElementPtr& element, const std::vector<std::string>& path, T fallback) {
  sdf::ElementPtr e = element;
  for (const auto& name : path) {
    if (!e || !e->HasElement(name)) return fallback;
    e = e->GetElement(name);
  }
  return e->Get<T>();
}

physics::PhysicsParams ReadPhysics(const sdf::World& world) {
  physics::PhysicsParams p;
  const sdf::Physics* physics = world.PhysicsDefault();
  if (physics) {
    p.max_step_size_s = physics->MaxStepSize();
    p.real_time_factor = physics->RealTimeFactor();
    sdf::ElementPtr e = physics->Element();
    p.real_time_update_rate_hz = Child<double>(e, {"real_time_update_rate"}, p.real_time_update_rate_hz);
    p.quick_solver = Child<std::string>(e, {"ode", "solver", "type"}, "quick") == "quick";
    p.quick_iterations = Child<int>(e, {"ode", "solver", "iters"}, p.quick_iterations);
    p.sor = Child<double>(e, {"ode", "solver", "sor"}, p.sor);
    p.cfm = Child<double>(e, {"ode", "constraints", "cfm"}, p.cfm);
    p.erp = Child<double>(e, {"ode", "constraints", "erp"}, p.erp);
    p.contact_max_correcting_vel_m_s =
        Child<double>(e, {"ode", "constraints", "contact_max_correcting_vel"}, p.contact_max_correcting_vel_m_s);
    p.contact_surface_layer_m =
        Child<double>(e, {"ode", "constraints", "contact_surface_layer"}, p.contact_surface_layer_m);
  }
  p.gravity_W = world.Gravity();
  return p;
}

/// The first directional light is the sun; <scene> gives ambient and background (grey levels) and
/// whether the sun's shadows are drawn (Gazebo's default: yes, if the sun casts them).
geometry::Lighting ReadLighting(const sdf::World& world, const WorldLoadOptions& options) {
  geometry::Lighting lighting;
  bool sun_casts_shadows = false, scene_shadows = true;
  for (uint64_t i = 0; i < world.LightCount(); ++i) {
    const sdf::Light& light = *world.LightByIndex(i);
    if (light.Type() != sdf::LightType::DIRECTIONAL) continue;
    lighting.sun_direction_W = light.Direction();
    const auto d = light.Diffuse();
    lighting.sun_diffuse = static_cast<float>((d.R() + d.G() + d.B()) / 3.0);
    sun_casts_shadows = light.CastShadows();
    break;
  }
  if (const sdf::Scene* scene = world.Scene()) {
    const auto a = scene->Ambient(), b = scene->Background();
    lighting.ambient = static_cast<float>((a.R() + a.G() + a.B()) / 3.0);
    lighting.background = {static_cast<float>(b.R()), static_cast<float>(b.G()), static_cast<float>(b.B())};
    scene_shadows = scene->Shadows();
  }
  lighting.shadows = sun_casts_shadows && scene_shadows && options.shadows;
  return lighting;
}

physics::WorldPtr Build(const sdf::Root& root, const sdf::Errors& errors, const std::string& source,
                        const WorldLoadOptions& options) {
  for (const auto& e : errors) {
    if (IsCheckedByTheEngine(e)) continue;
    // name a bad camera or laser better than sdformat does
    sensors::CameraSensor::CheckAll(root.Element());
    sensors::RaySensor::CheckAll(root.Element());
    throw SimError("world '" + source + "' does not parse: " + Describe(e));
  }
  if (root.WorldCount() == 0) throw SimError("world '" + source + "' holds no <world> element");
  const sdf::World& sdf_world = *root.WorldByIndex(0);
  physics::WorldPtr world = physics::World::Create(sdf_world.Name(), ReadPhysics(sdf_world));
  if (const auto* sc = sdf_world.SphericalCoordinates()) {
    physics::SphericalCoordinates origin;
    origin.latitude_deg = sc->LatitudeReference().Degree();
    origin.longitude_deg = sc->LongitudeReference().Degree();
    origin.elevation_m = sc->ElevationReference();
    origin.heading_deg = sc->HeadingOffset().Degree();
    world->SetOrigin(origin);
  }
  world->SetLighting(ReadLighting(sdf_world, options));
  try {
    for (uint64_t i = 0; i < sdf_world.ModelCount(); ++i) {
      const sdf::Model& m = *sdf_world.ModelByIndex(i);
      ModelBuilder::BuildTree(world, m, m.Name(), m.RawPose(), options.skip_broken_sensors);
    }
    sdf::ElementPtr element = sdf_world.Element();
    if (element->HasElement("plugin")) {
      event::ScopedCurrentEvents scope(&world->Events());
      for (sdf::ElementPtr p = element->GetElement("plugin"); p; p = p->GetNextElement("plugin")) {
        const std::string filename = p->Get<std::string>("filename");
        const auto skipped = options.skipped_plugins.find(filename);
        if (skipped != options.skipped_plugins.end()) {
          std::cerr << "[rotors_sim] world '" << source << "': " << filename << " skipped: " << skipped->second << "\n";
          continue;
        }
        try {
          auto plugin = PluginLoader::CreateWorldPlugin(filename);
          plugin->SetIdentity(p->Get<std::string>("name"), filename);
          LoadPlugin(*plugin, world, p);
          world->AddPlugin(std::move(plugin));
        } catch (const std::exception& e) {
          throw SimError("world '" + source + "', plugin '" + p->Get<std::string>("name") + "' (" + filename +
                         "): " + e.what());
        }
      }
    }
  } catch (...) {
    world->Fini();
    throw;
  }
  return world;
}

sdf::ParserConfig Config() {
  SilenceSdformatConsole();
  sdf::ParserConfig config;
  for (const auto& folder : geometry::UriResolver::ModelPaths()) config.AddURIPath("model://", folder);
  // includes inside an included model (RotorS' pallet_full includes europallet and small_box) are
  // looked up by sdformat 12 through its process-wide find callback, not the parser's: both ask
  // the UriResolver (itself process-wide: the model paths)
  auto find = [](const std::string& uri) {
    try {
      return geometry::UriResolver::Resolve(uri);
    } catch (const SimError&) {
      return std::string();
    }
  };
  config.SetFindCallback(find);
  sdf::setFindCallback(find);
  return config;
}

}  // namespace

physics::WorldPtr WorldLoader::LoadFile(const std::string& path, const WorldLoadOptions& options) {
  sdf::Root root;
  sdf::Errors errors = root.Load(path, Config());
  return Build(root, errors, path, options);
}

physics::WorldPtr WorldLoader::LoadString(const std::string& sdf_text, const std::string& source_name,
                                          const WorldLoadOptions& options) {
  sdf::Root root;
  sdf::Errors errors = root.LoadSdfString(sdf_text, Config());
  return Build(root, errors, source_name, options);
}

}  // namespace rotors_sim
