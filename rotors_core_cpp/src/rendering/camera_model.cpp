#include "rotors_core/rendering/camera_model.h"

#include <cmath>

#include "rotors_core/error.h"

namespace rotors_sim {
namespace rendering {

PixelFormat ParsePixelFormat(const std::string& name) {
  if (name == "L8" || name == "L_INT8") return PixelFormat::kL8;
  if (name == "R8G8B8" || name == "RGB_INT8") return PixelFormat::kR8G8B8;
  if (name == "B8G8R8" || name == "BGR_INT8") return PixelFormat::kB8G8R8;
  throw SimError("unknown image format '" + name + "' (known: L8, R8G8B8, B8G8R8)");
}

int BytesPerPixel(PixelFormat format) { return format == PixelFormat::kL8 ? 1 : 3; }

std::string RosEncoding(PixelFormat format) {
  switch (format) {
    case PixelFormat::kL8: return "mono8";
    case PixelFormat::kR8G8B8: return "rgb8";
    case PixelFormat::kB8G8R8: return "bgr8";
  }
  return "mono8";
}

double CameraIntrinsics::FocalLengthPx() const { return width_px / (2.0 * std::tan(horizontal_fov_rad / 2.0)); }

Eigen::Matrix3d CameraIntrinsics::K() const {
  const double f = FocalLengthPx();
  Eigen::Matrix3d K;
  K << f, 0, Cx(), 0, f, Cy(), 0, 0, 1;
  return K;
}

bool CameraIntrinsics::MaySee(const Eigen::Vector3d& c_O, double r) const {
  if (c_O.z() < near_m - r || c_O.z() > far_m + r) return false;
  // side planes through the optical centre and the image edges: a point is inside when
  // |x| f <= z W/2 and |y| f <= z H/2 (a pixel of margin)
  const double f = FocalLengthPx();
  const double half_w = width_px / 2.0 + 1.0, half_h = height_px / 2.0 + 1.0;
  // signed distance of the centre beyond each side plane; the sphere is outside when beyond by r
  auto beyond = [&](double lateral_m, double half_px) {
    return (std::abs(lateral_m) * f - c_O.z() * half_px) / std::hypot(f, half_px) > r;
  };
  return !beyond(c_O.x(), half_w) && !beyond(c_O.y(), half_h);
}

std::string CameraIntrinsics::Validate() const {
  if (width_px <= 0 || height_px <= 0)
    return "image size " + std::to_string(width_px) + " x " + std::to_string(height_px) + " must be positive";
  if (!(horizontal_fov_rad > 0.0 && horizontal_fov_rad < M_PI))
    return "horizontal_fov " + std::to_string(horizontal_fov_rad) + " rad must be in (0, pi)";
  if (!(near_m > 0.0 && far_m > near_m))
    return "clip near " + std::to_string(near_m) + " m, far " + std::to_string(far_m) + " m: need 0 < near < far";
  return "";
}

namespace {
template <typename T>
T Child(const sdf::ElementPtr& parent, const char* name, const T& fallback) {
  if (!parent || !parent->HasElement(name)) return fallback;
  return parent->GetElement(name)->Get<T>();
}
}  // namespace

CameraSpec ParseCamera(const sdf::ElementPtr& camera) {
  CameraSpec spec;
  spec.name = camera->HasAttribute("name") ? camera->Get<std::string>("name") : "";
  const std::string label = "camera '" + spec.name + "'";
  if (camera->HasElement("pose")) spec.X_SC = camera->GetElement("pose")->Get<ignition::math::Pose3d>();
  CameraIntrinsics& in = spec.intrinsics;
  in.horizontal_fov_rad = Child<double>(camera, "horizontal_fov", in.horizontal_fov_rad);
  sdf::ElementPtr image = camera->HasElement("image") ? camera->GetElement("image") : nullptr;
  in.width_px = Child<int>(image, "width", in.width_px);
  in.height_px = Child<int>(image, "height", in.height_px);
  try {
    spec.format = ParsePixelFormat(Child<std::string>(image, "format", "R8G8B8"));
  } catch (const SimError& e) {
    throw SimError(label + ": " + e.what());
  }
  sdf::ElementPtr clip = camera->HasElement("clip") ? camera->GetElement("clip") : nullptr;
  in.near_m = Child<double>(clip, "near", in.near_m);
  in.far_m = Child<double>(clip, "far", in.far_m);
  const std::string why = in.Validate();
  if (!why.empty()) throw SimError(label + ": " + why);
  if (camera->HasElement("noise")) {
    sdf::ElementPtr noise = camera->GetElement("noise");
    const std::string type = Child<std::string>(noise, "type", "none");
    if (type == "gaussian") {
      spec.noise_mean = Child<double>(noise, "mean", 0.0);
      spec.noise_stddev = Child<double>(noise, "stddev", 0.0);
      if (!(spec.noise_stddev >= 0.0)) throw SimError(label + ": noise stddev must be >= 0");
    } else if (type != "none") {
      throw SimError(label + ": noise type '" + type + "' is not supported (gaussian or none)");
    }
  }
  return spec;
}

ignition::math::Pose3d OpticalInCamera() { return ignition::math::Pose3d(0, 0, 0, -M_PI / 2, 0, -M_PI / 2); }

}  // namespace rendering
}  // namespace rotors_sim
