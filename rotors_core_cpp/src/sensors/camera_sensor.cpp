#include "rotors_core/sensors/camera_sensor.h"

#include <filesystem>
#include <functional>

#include "rotors_core/error.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "sensors/camera_image_sensor.h"

namespace rotors_sim {
namespace sensors {
namespace {

/// The <camera> elements of a sensor element; SimError "<label>: <problem>" for a bad one.
std::vector<rendering::CameraSpec> ParseCameras(const sdf::ElementPtr& sensor, const std::string& label) {
  std::vector<rendering::CameraSpec> cameras;
  if (sensor && sensor->HasElement("camera")) {
    for (sdf::ElementPtr c = sensor->GetElement("camera"); c; c = c->GetNextElement("camera")) {
      try {
        cameras.push_back(rendering::ParseCamera(c));
      } catch (const SimError& e) {
        throw SimError(label + ": " + e.what());
      }
    }
  }
  if (cameras.empty()) throw SimError(label + " has no <camera> element");
  return cameras;
}

}  // namespace

CameraSensor::CameraSensor(std::string name, std::string type, physics::LinkPtr parent,
                           const physics::Pose3d& pose_in_link, double update_rate_hz, const sdf::ElementPtr& sdf)
    : Sensor(std::move(name), std::move(type), std::move(parent), pose_in_link, update_rate_hz) {
  const std::string label = Type() + " sensor '" + Name() + "'";
  if (!(update_rate_hz >= 0.0)) throw SimError(label + ": update_rate must be >= 0");
  cameras_ = ParseCameras(sdf, label);
  if (Type() != "multicamera" && cameras_.size() > 1)
    throw SimError(label + " has " + std::to_string(cameras_.size()) + " <camera> elements; only a multicamera may");
  // what it will draw must be drawable: the textures of the meshes in the world so far
  auto check_textures = [&](const physics::Model& model) {
    for (const geometry::Visual& v : model.Visuals()) {
      if (!v.shape.mesh || v.shape.mesh->uvs.empty()) continue;
      for (const geometry::MeshPart& part : v.shape.mesh->parts)
        if (!part.texture_file.empty() && !std::filesystem::exists(part.texture_file))
          throw SimError(label + ": texture '" + part.texture_file + "' of visual '" + v.scoped_name +
                         "' does not exist");
    }
  };
  const physics::Model& own = *ParentLink()->GetModel();
  check_textures(own);
  for (const physics::ModelPtr& m : own.GetWorldRaw()->Models())
    if (m.get() != &own) check_textures(*m);
  frames_.resize(cameras_.size());
  rendered_update_.assign(cameras_.size(), 0);
  asked_update_.assign(cameras_.size(), kNever);
  seed_ = std::hash<std::string>()(ParentLink()->GetModel()->GetName() + "::" + Name());
}

void CameraSensor::CheckAll(const sdf::ElementPtr& element, const std::string& model) {
  if (!element) return;
  const std::string name = element->HasAttribute("name") ? element->Get<std::string>("name") : "";
  const std::string in_model = element->GetName() == "model" ? name : model;
  if (element->GetName() == "sensor" && element->HasAttribute("type") &&
      IsCameraType(element->Get<std::string>("type"))) {
    ParseCameras(element, "model '" + in_model + "', " + element->Get<std::string>("type") + " sensor '" + name + "'");
    return;
  }
  for (sdf::ElementPtr child = element->GetFirstElement(); child; child = child->GetNextElement())
    CheckAll(child, in_model);
}

CameraSensor::~CameraSensor() = default;

physics::Pose3d CameraSensor::CameraWorldPose(size_t i) const { return cameras_.at(i).X_SC + WorldPose(); }

void CameraSensor::OnUpdate(const common::Time& /*sim_time*/) { ++update_count_; }

void CameraSensor::SetGroundTruthDepth(bool on) {
  if (on == ground_truth_depth_) return;
  ground_truth_depth_ = on;
  rendered_update_.assign(cameras_.size(), 0);  // this update's frames again, with or without depth
}

const rendering::RenderedFrame& CameraSensor::Frame(size_t i) {
  if (rendered_update_.at(i) != update_count_) {
    // the cameras asked for at the last update too (a stereo pair's other one) are rendered with
    // this one, in one batch
    std::vector<size_t> wanted;
    for (size_t j = 0; j < cameras_.size(); ++j) {
      const bool asked_last = asked_update_[j] != kNever && asked_update_[j] + 1 == update_count_;
      if (j == i || (asked_last && rendered_update_[j] != update_count_)) wanted.push_back(j);
    }
    if (!image_sensors_.empty()) {
      RenderThroughImageSensor(wanted);
    } else {
      std::vector<rendering::FrameRequest> requests;
      for (size_t j : wanted)
        requests.push_back({CameraWorldPose(j), &cameras_[j], NoiseSeedOf(j), true, RendersDepth(), &frames_[j]});
      physics::World& world = *ParentLink()->GetModel()->GetWorldRaw();
      rendering::Renderer::Of(world).RenderAll(world, requests);
    }
    for (size_t j : wanted) rendered_update_[j] = update_count_;
  }
  asked_update_[i] = update_count_;
  return frames_[i];
}

}  // namespace sensors
}  // namespace rotors_sim
