// Frames per second of the headless renderer: the VI-sensor's stereo pair (2 x 752 x 480 L8) and
// its depth camera (640 x 480, depth read back), in a world file given on the command line, with
// a firefly-sized scene in view. The rig moves 1 cm per frame, as in a flight: the sun's shadow map
// (when the world has shadows) is drawn again for each stereo pair. Prints one JSON line.
//   rotors_camera_bench <world file> [frames] [folder: writes left.pgm, right.pgm, depth.pgm] [--no-shadows]
//                       [--image-sensor off|blur|blur_subframes|auto_exposure|noise|rolling_shutter|all]
// --image-sensor: the stereo pair through the image sensor model (docs/sensor_realism.md) while the
// rig moves at 1 m/s and turns at 0.75 rad/s (a medium VIO flight): each effect alone, or all of the
// VI-sensor's (auto exposure and its blur, photon noise, cos^4 vignetting; rolling shutter apart).
// The blur is the velocity buffer's, as sensor_realism's; blur_subframes the sub-frame reference.
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

/// The preset's image sensor; false for an unknown name.
bool ImageSensorPreset(const std::string& name, rendering::ImageSensorParams* p) {
  *p = rendering::ImageSensorParams();
  auto mt9v034 = [p] {  // the xacro's image_sensor_params "mt9v034"
    p->auto_exposure = true;
    p->noise = true;
    p->full_well_e = 5888.0;
    p->read_noise_e = 10.47;
    p->blur_method = rendering::ImageSensorParams::BlurMethod::kVelocityBuffer;
  };
  if (name == "off") return true;
  if (name == "blur" || name == "blur_subframes") {
    p->exposure_s = 0.01;
    p->reference_exposure_s = 0.01;
    if (name == "blur") p->blur_method = rendering::ImageSensorParams::BlurMethod::kVelocityBuffer;
  } else if (name == "auto_exposure") {
    p->auto_exposure = true;
    p->blur_method = rendering::ImageSensorParams::BlurMethod::kVelocityBuffer;
  } else if (name == "noise") {
    p->noise = true;
    p->full_well_e = 5888.0;
    p->read_noise_e = 10.47;
  } else if (name == "rolling_shutter") {
    p->line_delay_s = 30e-6;
    p->blur_method = rendering::ImageSensorParams::BlurMethod::kVelocityBuffer;
  } else if (name == "all") {
    mt9v034();
    p->vignetting = rendering::ImageSensorParams::Vignetting::kCos4;
  } else {
    return false;
  }
  return true;
}

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
  std::string image_sensor;
  const auto sensor_flag = std::find(args.begin(), args.end(), "--image-sensor");
  if (sensor_flag != args.end()) {
    if (sensor_flag + 1 == args.end()) {
      std::fprintf(stderr, "rotors_camera_bench: --image-sensor needs a preset\n");
      return 2;
    }
    image_sensor = *(sensor_flag + 1);
    args.erase(sensor_flag, sensor_flag + 2);
  }
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
  std::string rig = kRig;
  if (!image_sensor.empty())  // a body that can move: the image sensor reads the link's twist
    rig.replace(rig.find("<static>true</static>"), 21, "<static>false</static>");
  world_sdf.insert(world_sdf.rfind("</world>"), rig);
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
  if (!image_sensor.empty()) {
    rendering::ImageSensorParams p;
    if (!ImageSensorPreset(image_sensor, &p)) {
      std::fprintf(stderr,
                   "rotors_camera_bench: --image-sensor '%s' is not known: off, blur, blur_subframes, "
                   "auto_exposure, noise, rolling_shutter or all\n",
                   image_sensor.c_str());
      return 2;
    }
    stereo->SetImageSensor(p);
  }
  world->Step(1);
  ignition::math::Pose3d X_WR = model->WorldPose();
  int subframes = 0, pairs = 0;
  const double pair_fps = Fps(
      [&] {
        X_WR.Pos().X() += 0.01;
        model->SetWorldPose(X_WR);
        if (!image_sensor.empty()) {  // a moving rig (a non-static one in the world file's gravity)
          model->SetWorldTwist({1.0, 0.0, 0.0}, {0.0, 0.0, 0.75});
        }
        world->Step(34);  // one sensor period at 1 ms steps: a new update, new frames
        stereo->Frame(0);
        stereo->Frame(1);
        subframes += stereo->SubframesOf(0) + stereo->SubframesOf(1);
        pairs += 1;
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
  std::printf(
      "{\"stereo_pairs_per_s\": %.1f, \"depth_frames_per_s\": %.1f, \"triangles\": %zu, "
      "\"renders_per_frame\": %.2f}\n",
      pair_fps, depth_fps, rendering::Renderer::Of(*world).CachedTriangles(), pairs ? subframes / (2.0 * pairs) : 1.0);
  world->Fini();
  return 0;
}
