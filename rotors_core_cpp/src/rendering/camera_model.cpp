#include "rotors_core/rendering/camera_model.h"

#include <algorithm>
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
  // side planes through the optical centre and the image edges (a pixel of margin): a point is
  // inside when -(c + 1/2 + 1) <= f x / z <= (W - 1/2 - c) + 1, likewise for y
  const double f = FocalLengthPx();
  // signed distance of the centre beyond the plane of an edge `edge_px` pixels from the principal
  // point; the sphere is outside when beyond by r
  auto beyond = [&](double lateral_m, double edge_px) {
    return (lateral_m * f - c_O.z() * edge_px) / std::hypot(f, edge_px) > r;
  };
  return !beyond(c_O.x(), width_px - 0.5 - Cx() + 1.0) && !beyond(-c_O.x(), Cx() + 1.5) &&
         !beyond(c_O.y(), height_px - 0.5 - Cy() + 1.0) && !beyond(-c_O.y(), Cy() + 1.5);
}

double CameraIntrinsics::ImageSpeedBoundPxS(double omega_rad_s, double speed_m_s, double near_m) const {
  const double f = FocalLengthPx();
  const double du = std::max(Cx(), width_px - 1 - Cx()), dv = std::max(Cy(), height_px - 1 - Cy());
  const double corner2 = (du * du + dv * dv) / (f * f);  // tan^2 theta of the farthest corner
  return f * omega_rad_s * (1.0 + corner2) + f * speed_m_s / near_m;
}

std::string CameraIntrinsics::Validate() const {
  if (width_px <= 0 || height_px <= 0)
    return "image size " + std::to_string(width_px) + " x " + std::to_string(height_px) + " must be positive";
  if (!(horizontal_fov_rad > 0.0 && horizontal_fov_rad < M_PI))
    return "horizontal_fov " + std::to_string(horizontal_fov_rad) + " rad must be in (0, pi)";
  if (!(near_m > 0.0 && far_m > near_m))
    return "clip near " + std::to_string(near_m) + " m, far " + std::to_string(far_m) + " m: need 0 < near < far";
  if (!(center_u > 0.0 && center_u < 1.0 && center_v > 0.0 && center_v < 1.0))
    return "distortion center " + std::to_string(center_u) + " " + std::to_string(center_v) +
           " must lie inside the image (each in (0, 1))";
  return "";
}

Eigen::Vector2d LensDistortion::Distort(const Eigen::Vector2d& x_ideal) const {
  const double x = x_ideal.x(), y = x_ideal.y();
  const double r2 = x * x + y * y;
  // the radial factor, then the tangential (decentring) terms
  const double radial = Radial(r2);
  return {x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x),
          y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y};
}

bool LensDistortion::Undistort(const Eigen::Vector2d& x_distorted, Eigen::Vector2d* x_ideal) const {
  // x = (x_d - tangential(x)) / radial(x), iterated from x = x_d
  Eigen::Vector2d x = x_distorted;
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector2d residual = Distort(x) - x_distorted;
    if (residual.norm() < 1e-9) {
      *x_ideal = x;
      return true;
    }
    const double radial = Radial(x.squaredNorm());
    if (!(radial > 0.0)) return false;
    x -= residual / radial;
  }
  return false;
}

std::string LensDistortion::Validate(double max_radius) const {
  auto radial = [&](double r) { return Radial(r * r); };
  // r_d = r radial(r) must rise from 0 until it covers the image's farthest corner
  const double dr = 1e-3;
  double r_d = 0.0;
  for (double r = dr; r_d < max_radius; r += dr) {
    const double next = r * radial(r);
    if (!(radial(r) > 0.0) || next <= r_d)
      return "distortion k1 " + std::to_string(k1) + " k2 " + std::to_string(k2) + " k3 " + std::to_string(k3) +
             " folds the image over at r = " + std::to_string(r) + " (r_d stops rising at " + std::to_string(r_d) +
             ", the farthest corner is at r_d = " + std::to_string(max_radius) + "): coefficients out of range";
    if (r > 100.0) return "distortion: the image corners have no undistorted preimage (r > 100): out of range";
    r_d = next;
  }
  if (std::abs(p1) > 0.1 || std::abs(p2) > 0.1)
    return "distortion p1 " + std::to_string(p1) + " p2 " + std::to_string(p2) +
           ": tangential coefficients beyond +-0.1 are out of range for a real lens";
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
  if (camera->HasElement("distortion")) {
    sdf::ElementPtr d = camera->GetElement("distortion");
    LensDistortion& lens = spec.distortion;
    lens.k1 = Child<double>(d, "k1", 0.0);
    lens.k2 = Child<double>(d, "k2", 0.0);
    lens.k3 = Child<double>(d, "k3", 0.0);
    lens.p1 = Child<double>(d, "p1", 0.0);
    lens.p2 = Child<double>(d, "p2", 0.0);
    const auto center = Child<ignition::math::Vector2d>(d, "center", ignition::math::Vector2d(0.5, 0.5));
    in.center_u = center.X();
    in.center_v = center.Y();
  }
  const std::string why = in.Validate();
  if (!why.empty()) throw SimError(label + ": " + why);
  if (!spec.distortion.IsIdentity()) {
    // the farthest image corner from the principal point, in coordinates normalised by f
    const double f = in.FocalLengthPx();
    const double dx = std::max(in.Cx() + 0.5, in.width_px - 0.5 - in.Cx());
    const double dy = std::max(in.Cy() + 0.5, in.height_px - 0.5 - in.Cy());
    const std::string lens_why = spec.distortion.Validate(std::hypot(dx, dy) / f);
    if (!lens_why.empty()) throw SimError(label + ": " + lens_why);
  }
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
