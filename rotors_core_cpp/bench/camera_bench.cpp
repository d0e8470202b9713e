// Frames per second of the headless renderer: the VI-sensor's stereo pair (2 x 752 x 480 L8) and
// its depth camera (640 x 480, depth read back), in a world file given on the command line, with
// a firefly-sized scene in view. The rig moves 1 cm per frame, as in a flight: the sun's shadow map
// (when the world has shadows) is drawn again for each stereo pair. Prints one JSON line.
//   rotors_camera_bench <world file> [frames] [folder: writes left.pgm, right.pgm, depth.pgm] [--no-shadows]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/rendering/renderer.h"
#include "rotors_core/sensors/camera_sensor.h"
#include "rotors_core/world_loader.h"

using namespace rotors_sim;

namespace {

const char* kRig = R"(
<model name='bench_rig'><static>true</static><pose>-4 -3 2.5 0 0.25 0.6</pose><link name='link'>
  <sensor name='stereo' type='multicamera'><update_rate>30</update_rate>
    <camera name='left'><pose>0 0.055 0 0 0 0</pose><horizontal_fov>1.3962634</horizontal_fov>
      <image><width>752</width><height>480</height><format>L8</format></image><clip><near>0.02</near><far>30</far></clip>
      <noise><type>gaussian</type><mean>0</mean><stddev>0.007</stddev></noise></camera>
    <camera name='right'><pose>0 -0.055 0 0 0 0</pose><horizontal_fov>1.3962634</horizontal_fov>
      <image><width>752</width><height>480</height><format>L8</format></image><clip><near>0.02</near><far>30</far></clip>
      <noise><type>gaussian</type><mean>0</mean><stddev>0.007</stddev></noise></camera>
  </sensor>
  <sensor name='depth' type='depth'><update_rate>30</update_rate>
    <camera name='depth'><horizontal_fov>2</horizontal_fov>
      <image><width>640</width><height>480</height><format>L8</format></image><clip><near>0.01</near><far>10</far></clip></camera>
  </sensor>
</link></model>
<model name='box'><static>true</static><pose>0 0 0.5 0 0 0.3</pose><link name='link'><visual name='v'><geometry>
  <box><size>1 1 1</size></box></geometry></visual></link></model>)";

double Fps(const std::function<void()>& render, int frames) {
  render();  // first frame uploads meshes
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < frames; ++i) render();
  return frames / std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  const auto no_shadows = std::find(args.begin(), args.end(), "--no-shadows");
  const bool shadows = no_shadows == args.end();
  if (!shadows) args.erase(no_shadows);
  if (args.empty()) {
    std::fprintf(stderr, "usage: rotors_camera_bench <world file> [frames] [folder] [--no-shadows]\n");
    return 2;
  }
  const int frames = args.size() > 1 ? std::atoi(args[1].c_str()) : 100;
  std::ifstream in(args[0]);
  std::stringstream text;
  text << in.rdbuf();
  std::string world_sdf = text.str();
  if (!in || world_sdf.rfind("</world>") == std::string::npos) {
    std::fprintf(stderr, "rotors_camera_bench: '%s' is no world file (cannot be read or has no </world>)\n",
                 args[0].c_str());
    return 1;
  }
  world_sdf.insert(world_sdf.rfind("</world>"), kRig);
  physics::WorldPtr world;
  try {
    WorldLoadOptions options;  // as the server and the Python module: RotorS' ROS bridge has nothing to do here
    options.skipped_plugins["librotors_gazebo_ros_interface_plugin.so"] = "not needed for rendering";
    options.shadows = shadows;
    world = WorldLoader::LoadString(world_sdf, args[0], options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rotors_camera_bench: %s\n", e.what());
    return 1;
  }
  auto model = world->ModelByName("bench_rig");
  auto stereo = std::dynamic_pointer_cast<sensors::CameraSensor>(model->Sensors().at(0));
  auto depth = std::dynamic_pointer_cast<sensors::CameraSensor>(model->Sensors().at(1));
  world->Step(1);
  ignition::math::Pose3d X_WR = model->WorldPose();
  const double pair_fps = Fps(
      [&] {
        X_WR.Pos().X() += 0.01;
        model->SetWorldPose(X_WR);
        world->Step(34);  // one sensor period at 1 ms steps: a new update, new frames
        stereo->Frame(0);
        stereo->Frame(1);
      },
      frames);
  const double depth_fps = Fps(
      [&] {
        world->Step(34);
        depth->Frame(0);
      },
      frames);
  if (args.size() > 2) {
    auto write = [&](const std::string& name, int w, int h, const std::vector<uint8_t>& grey) {
      std::ofstream f(args[2] + "/" + name, std::ios::binary);
      f << "P5\n" << w << " " << h << "\n255\n";
      f.write(reinterpret_cast<const char*>(grey.data()), grey.size());
    };
    write("left.pgm", 752, 480, stereo->Frame(0).image);
    write("right.pgm", 752, 480, stereo->Frame(1).image);
    const auto& d = depth->Frame(0).depth_m;
    std::vector<uint8_t> grey(d.size());
    for (size_t i = 0; i < d.size(); ++i)
      grey[i] = std::isnan(d[i]) ? 0 : static_cast<uint8_t>(255 - std::min(d[i], 10.0f) * 25);
    write("depth.pgm", 640, 480, grey);
  }
  std::printf("{\"stereo_pairs_per_s\": %.1f, \"depth_frames_per_s\": %.1f, \"triangles\": %zu}\n", pair_fps, depth_fps,
              rendering::Renderer::Of(*world).CachedTriangles());
  world->Fini();
  return 0;
}
