// librotors_gazebo_noisydepth_plugin.so (RotorS): a depth camera with axial noise,
// <depthNoiseModelName> Kinect (default), D435 or PMD (models/depth_noise_model.h); for D435 also
// <horizontal_fov>, <baseline>, <D435NoiseSubpixelErr>, <D435MaxStdev>; <depthNoiseMinDist> and
// <depthNoiseMaxDist> [m] bound the valid depths (NaN outside). Its defaults: image on
// ir/image_raw + ir/camera_info, cloud on points, depth on depth/image_raw, cutoff 0.4-5 m.
// <randomEngineSeed> makes the noise repeatable.
#include "depth_camera_ros_plugin.h"
#include "rotors_gazebo_plugins/models/depth_noise_model.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/seeded_model.h"

namespace rotors_gazebo_plugins {

class GazeboNoisyDepth : public DepthCameraRosPlugin {
 protected:
  CameraRosParams ReadParams(rotors_sim::SdfParams& params) override {
    CameraRosParams p = CameraRosParams::Read(params, *sensor_, true);
    if (!Params().Has("imageTopicName")) p.image_topic = "ir/image_raw";
    if (!Params().Has("cameraInfoTopicName")) p.info_topic = "ir/camera_info";
    if (!Params().Has("pointCloudTopicName")) p.points_topic = "points";
    if (!Params().Has("pointCloudCutoff")) p.cloud_cutoff_min_m = 0.4;
    if (!Params().Has("pointCloudCutoffMax")) p.cloud_cutoff_max_m = 5.0;
    DepthNoiseParams noise;
    std::string model = "Kinect";
    ReadParam(Params(), "depthNoiseModelName", &model);
    noise.model = DepthNoiseParams::ParseModel(model);
    // RotorS: depths outside [depthNoiseMinDist, depthNoiseMaxDist] are invalid (NaN); by default
    // the point cloud's cutoff
    noise.min_depth_m = p.cloud_cutoff_min_m;
    noise.max_depth_m = p.cloud_cutoff_max_m;
    ReadParam(Params(), "depthNoiseMinDist", &noise.min_depth_m);
    ReadParam(Params(), "depthNoiseMaxDist", &noise.max_depth_m);
    noise.width_px = sensor_->Camera(0).intrinsics.width_px;
    noise.horizontal_fov_rad = sensor_->Camera(0).intrinsics.horizontal_fov_rad;
    ReadParam(Params(), "horizontal_fov", &noise.horizontal_fov_rad);
    if (p.baseline_m > 0) noise.baseline_m = p.baseline_m;
    ReadParam(Params(), "D435NoiseSubpixelErr", &noise.subpixel_error_px);
    ReadParam(Params(), "D435MaxStdev", &noise.max_stdev_m);
    ThrowIfInvalid(noise.Validate());
    noise_.Emplace(noise, ReadSeed(Params()));
    return p;
  }

  const rotors_sim::rendering::RenderedFrame& Measured(const rotors_sim::rendering::RenderedFrame& rendered,
                                                       rotors_sim::rendering::RenderedFrame* scratch) override {
    scratch->width_px = rendered.width_px;
    scratch->height_px = rendered.height_px;
    scratch->depth_m = rendered.depth_m;
    noise_->Apply(&scratch->depth_m);
    return *scratch;
  }

  void Reset() override { noise_.Reset(); }

 private:
  SeededModel<DepthNoiseModel> noise_;
};

}  // namespace rotors_gazebo_plugins

RSIM_REGISTER_SENSOR_PLUGIN(rotors_gazebo_plugins::GazeboNoisyDepth)
