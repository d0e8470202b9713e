// Rays per second of the laser caster in a world given on the command line (the power plant for
// `make bench`), against Embree's own figure for the same rays in the same run: the caster
// (RayScene::Cast: ray set-up, the filter that skips the sensor's own link, the hit's world normal)
// and a bare rtcIntersect1 loop on the same Embree scene; and the packet caster the sensors use
// (RayScene::CastFan, a column of 16 beams per packet; its trigonometry for the directions
// included). The rays are a VLP-16's 16 x 1800 beams from a few places in the world. Also: a VLP-16 and an OS1-64
// sensor stepping with the world (their whole per-step cost). Prints one JSON line.
//   rotors_ray_bench <world file> [sweeps]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <sstream>
#include <vector>

#include <embree3/rtcore.h>
#include <Eigen/Geometry>

#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/raycast/ray_scene.h"
#include "rotors_core/sensors/ray_sensor.h"
#include "rotors_core/world_loader.h"

using namespace rotors_sim;

namespace {

std::string Lidar(const std::string& name, const std::string& pose, int columns, int rings, double half_fov_rad) {
  std::ostringstream s;
  s.precision(17);
  s << "<model name='" << name << "'><static>true</static><pose>" << pose << "</pose><link name='link'>"
    << "<sensor name='lidar' type='ray'><update_rate>10</update_rate><ray><scan><horizontal><samples>" << columns
    << "</samples><min_angle>" << -M_PI << "</min_angle><max_angle>" << M_PI * (1 - 2.0 / columns)
    << "</max_angle></horizontal><vertical><samples>" << rings << "</samples><min_angle>" << -half_fov_rad
    << "</min_angle><max_angle>" << half_fov_rad << "</max_angle></vertical></scan><range><min>0.3</min><max>100</max>"
    << "</range></ray></sensor></link></model>";
  return s.str();
}

double Seconds(const std::function<void()>& work) {
  const auto t0 = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: rotors_ray_bench <world file> [sweeps]\n");
    return 2;
  }
  const int sweeps = argc > 2 ? std::atoi(argv[2]) : 20;
  std::ifstream in(argv[1]);
  std::stringstream text;
  text << in.rdbuf();
  std::string sdf = text.str();
  if (!in || sdf.rfind("</world>") == std::string::npos) {
    std::fprintf(stderr, "rotors_ray_bench: '%s' is no world file (cannot be read or has no </world>)\n", argv[1]);
    return 1;
  }
  // a VLP-16 over the plant (10 m up, where it sees structure all round)
  auto load = [&](const std::string& lidar) {
    std::string with = sdf;
    with.insert(with.rfind("</world>"), lidar);
    return WorldLoader::LoadString(with, argv[1]);
  };
  physics::WorldPtr world;
  try {
    world = load(Lidar("vlp16", "2 -6 10 0 0 0", 1800, 16, 15 * M_PI / 180));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rotors_ray_bench: %s\n", e.what());
    return 1;
  }
  raycast::RayScene& rays = world->Rays();
  rays.Sync();
  // the same rays for both: a VLP-16's beams from five places
  const auto vlp16 = std::dynamic_pointer_cast<sensors::RaySensor>(world->ModelByName("vlp16")->Sensors().at(0));
  const sensors::RayScanSpec& spec = vlp16->Spec();
  std::vector<Eigen::Vector3d> origins = {{2, -6, 10}, {-5, 3, 4}, {10, 0, 15}, {0, -15, 2}, {6, 6, 8}};
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> beams;
  for (const auto& o : origins)
    for (int j = 0; j < spec.vertical_count; ++j)
      for (int i = 0; i < spec.horizontal_count; ++i) beams.emplace_back(o, spec.Direction_S(i, j));
  size_t hits = 0;
  const double caster_s = Seconds([&] {
    for (int k = 0; k < sweeps; ++k)
      for (const auto& [o, d] : beams) hits += rays.Cast(o, d, 0.0, 100.0, vlp16->ParentLink().get()).Hit();
  });
  RTCScene scene = static_cast<RTCScene>(rays.EmbreeScene());
  size_t embree_hits = 0;
  const double embree_s = Seconds([&] {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (int k = 0; k < sweeps; ++k)
      for (const auto& [o, d] : beams) {
        RTCRayHit rh;
        rh.ray.org_x = static_cast<float>(o.x()), rh.ray.org_y = static_cast<float>(o.y());
        rh.ray.org_z = static_cast<float>(o.z());
        rh.ray.dir_x = static_cast<float>(d.x()), rh.ray.dir_y = static_cast<float>(d.y());
        rh.ray.dir_z = static_cast<float>(d.z());
        rh.ray.tnear = 0.0f, rh.ray.tfar = 100.0f, rh.ray.time = 0.0f;
        rh.ray.mask = 0xFFFFFFFFu, rh.ray.id = 0, rh.ray.flags = 0;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &context, &rh);
        embree_hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
      }
  });
  // the same rays again, a column (16 rings) at a time through the packet caster the sensors use
  std::vector<Eigen::Vector3d> column(spec.vertical_count);
  std::vector<raycast::RayHit> column_hits(spec.vertical_count);
  size_t fan_hits = 0;
  const uint32_t mask = rays.SkipMask(vlp16->ParentLink().get());
  rays.Sync();
  const double fan_s = Seconds([&] {
    for (int k = 0; k < sweeps; ++k)
      for (const auto& o : origins)
        for (int i = 0; i < spec.horizontal_count; ++i) {
          for (int j = 0; j < spec.vertical_count; ++j) column[j] = spec.Direction_S(i, j);
          rays.CastFan(o, column.data(), column.size(), 0.0, 100.0, vlp16->ParentLink().get(), mask,
                       column_hits.data());
          for (const auto& h : column_hits) fan_hits += h.Hit();
        }
  });
  const double n_rays = static_cast<double>(beams.size()) * sweeps;
  const size_t triangles = rays.TriangleCount(), instances = rays.InstanceCount();
  world->Fini();
  // each sensor stepping with the world alone (the world's step, swept over time): sim s per wall s
  auto sensor_rtf = [&](const std::string& lidar) {
    physics::WorldPtr w = load(lidar);
    std::dynamic_pointer_cast<sensors::RaySensor>(w->Models().back()->Sensors().at(0))->SetScanOverTime(true);
    const unsigned steps = static_cast<unsigned>(std::lround(5.0 / w->Physics().max_step_size_s));  // 5 s
    w->Step(steps / 10);
    const double s = Seconds([&] { w->Step(steps); });
    w->Fini();
    return 5.0 / s;
  };
  const double vlp16_rtf = sensor_rtf(Lidar("vlp16", "2 -6 10 0 0 0", 1800, 16, 15 * M_PI / 180));
  const double os1_rtf = sensor_rtf(Lidar("os1_64", "2 -6 10 0 0 0", 1024, 64, 16.6 * M_PI / 180));
  std::printf(
      "{\"rays\": %.0f, \"hit_share\": %.3f, \"caster_rays_per_s\": %.0f, \"embree_rays_per_s\": %.0f, "
      "\"caster_over_embree\": %.3f, \"caster_fan_rays_per_s\": %.0f, \"hits_agree\": %s, \"scene_triangles\": %zu, "
      "\"instances\": %zu, "
      "\"world_with_vlp16_sim_s_per_wall_s\": %.2f, \"world_with_os1_64_sim_s_per_wall_s\": %.2f}\n",
      n_rays, hits / n_rays, n_rays / caster_s, n_rays / embree_s, (n_rays / caster_s) / (n_rays / embree_s),
      n_rays / fan_s, hits == embree_hits && hits == fan_hits ? "true" : "false", triangles, instances, vlp16_rtf,
      os1_rtf);
  return 0;
}
