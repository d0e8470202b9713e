#include "rotors_core/sensors/ray_sensor.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>

#include <Eigen/Geometry>

#include "rotors_core/error.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/raycast/ray_scene.h"
#include "physics/pose_math.h"

namespace rotors_sim {
namespace sensors {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

std::string Text(double value) {
  std::ostringstream s;
  s << value;
  return s.str();
}

/// <child> of `e` as T, or `fallback` when it is absent.
template <typename T>
T Child(const sdf::ElementPtr& e, const std::string& child, T fallback) {
  return e && e->HasElement(child) ? e->GetElement(child)->Get<T>() : fallback;
}

/// One axis of <scan>: count = samples x resolution beams from min_angle to max_angle.
void ParseAxis(const sdf::ElementPtr& scan, const std::string& axis, int* count, double* lo, double* hi) {
  if (!scan || !scan->HasElement(axis)) return;  // absent: one beam at 0 rad
  const sdf::ElementPtr e = scan->GetElement(axis);
  const std::string where = "<" + axis + ">";
  const double samples = Child(e, "samples", 0.0), resolution = Child(e, "resolution", 1.0);
  if (!(samples >= 1.0) || samples != std::floor(samples))
    throw SimError(where + "<samples> is " + Text(samples) + "; a scan needs a whole number of samples >= 1");
  if (!(resolution > 0.0)) throw SimError(where + "<resolution> is " + Text(resolution) + "; it must be > 0");
  *count = static_cast<int>(std::lround(samples * resolution));
  if (*count < 1)
    throw SimError(where + " samples x resolution = " + Text(samples * resolution) + " gives no beam; make it >= 1");
  *lo = Child(e, "min_angle", 0.0);
  *hi = Child(e, "max_angle", 0.0);
  if (!std::isfinite(*lo) || !std::isfinite(*hi) || *lo > *hi)
    throw SimError(where + "<min_angle> " + Text(*lo) + " is above <max_angle> " + Text(*hi) +
                   " (angles in rad, min <= max)");
}

/// The pose a fraction alpha of the way from X0 to X1: position linear, attitude by slerp.
Eigen::Isometry3d Interpolate(const physics::Pose3d& X0, const physics::Pose3d& X1, double alpha) {
  const Eigen::Isometry3d T0 = ToIsometry(X0), T1 = ToIsometry(X1);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(T0.linear()).slerp(alpha, Eigen::Quaterniond(T1.linear())).toRotationMatrix();
  T.translation() = (1.0 - alpha) * T0.translation() + alpha * T1.translation();
  return T;
}

}  // namespace

RayScanSpec RayScanSpec::Parse(const sdf::ElementPtr& sensor) {
  sdf::ElementPtr ray;
  if (sensor && sensor->HasElement("ray")) ray = sensor->GetElement("ray");
  else if (sensor && sensor->HasElement("lidar")) ray = sensor->GetElement("lidar");
  if (!ray) throw SimError("has no <ray> element (the beams and ranges of a laser)");
  RayScanSpec spec;
  if (!ray->HasElement("scan") || !ray->GetElement("scan")->HasElement("horizontal"))
    throw SimError("has no <scan><horizontal> element (samples, min_angle, max_angle)");
  const sdf::ElementPtr scan = ray->GetElement("scan");
  ParseAxis(scan, "horizontal", &spec.horizontal_count, &spec.horizontal_min_rad, &spec.horizontal_max_rad);
  ParseAxis(scan, "vertical", &spec.vertical_count, &spec.vertical_min_rad, &spec.vertical_max_rad);
  if (!ray->HasElement("range") || !ray->GetElement("range")->HasElement("max"))
    throw SimError("has no <range><max> element (the longest range, m)");
  const sdf::ElementPtr range = ray->GetElement("range");
  spec.range_min_m = Child(range, "min", 0.0);
  spec.range_max_m = Child(range, "max", 0.0);
  spec.range_resolution_m = Child(range, "resolution", 0.0);
  if (!(spec.range_min_m >= 0.0)) throw SimError("<range><min> " + Text(spec.range_min_m) + " must be >= 0 m");
  if (!(spec.range_max_m > spec.range_min_m) || !std::isfinite(spec.range_max_m))
    throw SimError("<range><min> " + Text(spec.range_min_m) + " m is not below <range><max> " + Text(spec.range_max_m) +
                   " m");
  if (!(spec.range_resolution_m >= 0.0))
    throw SimError("<range><resolution> " + Text(spec.range_resolution_m) + " must be >= 0 m");
  if (ray->HasElement("noise")) {
    const sdf::ElementPtr noise = ray->GetElement("noise");
    const std::string type = Child<std::string>(noise, "type", "none");
    if (type == "gaussian") {
      spec.noise_mean_m = Child(noise, "mean", 0.0);
      spec.noise_stddev_m = Child(noise, "stddev", 0.0);
      if (!(spec.noise_stddev_m >= 0.0) || !std::isfinite(spec.noise_mean_m))
        throw SimError("<noise> mean " + Text(spec.noise_mean_m) + ", stddev " + Text(spec.noise_stddev_m) +
                       ": the mean must be finite and the stddev >= 0 m");
    } else if (type != "none") {
      throw SimError("<noise><type> '" + type + "' is not supported for lasers (gaussian or none)");
    }
  }
  return spec;
}

double RayScanSpec::HorizontalAngle(int i) const {
  if (horizontal_count < 2) return horizontal_min_rad;
  return horizontal_min_rad + i * (horizontal_max_rad - horizontal_min_rad) / (horizontal_count - 1);
}

double RayScanSpec::VerticalAngle(int j) const {
  if (vertical_count < 2) return vertical_min_rad;
  return vertical_min_rad + j * (vertical_max_rad - vertical_min_rad) / (vertical_count - 1);
}

Eigen::Vector3d RayScanSpec::Direction_S(int i, int j) const {
  const double h = HorizontalAngle(i), v = VerticalAngle(j);
  return Eigen::Vector3d(std::cos(v) * std::cos(h), std::cos(v) * std::sin(h), std::sin(v));
}

std::vector<Eigen::Vector3d> RayScanSpec::Directions_S() const {
  std::vector<Eigen::Vector3d> d;
  d.reserve(BeamCount());
  for (int j = 0; j < vertical_count; ++j)
    for (int i = 0; i < horizontal_count; ++i) d.push_back(Direction_S(i, j));
  return d;
}

RaySensor::RaySensor(std::string name, std::string type, physics::LinkPtr parent, const physics::Pose3d& pose_in_link,
                     double update_rate_hz, const sdf::ElementPtr& sdf)
    : Sensor(std::move(name), std::move(type), std::move(parent), pose_in_link, update_rate_hz) {
  const std::string label = Type() + " sensor '" + Name() + "'";
  if (!(update_rate_hz >= 0.0)) throw SimError(label + ": update_rate must be >= 0");
  try {
    spec_ = RayScanSpec::Parse(sdf);
  } catch (const SimError& e) {
    throw SimError(label + ": " + e.what());
  }
  seed_ = std::hash<std::string>()(ParentLink()->GetModel()->GetName() + "::" + Name());
  d_S_ = spec_.Directions_S();
}

void RaySensor::CheckAll(const sdf::ElementPtr& element, const std::string& model) {
  if (!element) return;
  const std::string name = element->HasAttribute("name") ? element->Get<std::string>("name") : "";
  const std::string in_model = element->GetName() == "model" ? name : model;
  if (element->GetName() == "sensor" && element->HasAttribute("type") && IsRayType(element->Get<std::string>("type"))) {
    try {
      RayScanSpec::Parse(element);
    } catch (const SimError& e) {
      throw SimError("model '" + in_model + "', " + element->Get<std::string>("type") + " sensor '" + name +
                     "': " + e.what());
    }
    return;
  }
  for (sdf::ElementPtr child = element->GetFirstElement(); child; child = child->GetNextElement())
    CheckAll(child, in_model);
}

float RaySensor::Measure(double r) {
  // REP 117: +inf nothing within max range, -inf closer than min range
  if (!(r <= spec_.range_max_m)) return kInf;
  if (r < spec_.range_min_m) return -kInf;
  if (spec_.noise_stddev_m > 0.0 || spec_.noise_mean_m != 0.0)
    r += spec_.noise_mean_m + spec_.noise_stddev_m * unit_normal_(rng_);
  if (spec_.range_resolution_m > 0.0) r = std::round(r / spec_.range_resolution_m) * spec_.range_resolution_m;
  return static_cast<float>(std::clamp(r, spec_.range_min_m, spec_.range_max_m));
}

void RaySensor::StartScan(const common::Time& start) {
  const size_t beams = spec_.BeamCount();
  building_.start = start;
  building_.ranges_m.assign(beams, kInf);
  building_.intensities.assign(beams, 0.0f);
  building_.column_time_s.assign(spec_.horizontal_count, 0.0f);
  next_column_ = 0;
  scanning_ = true;
  // a noise stream per scan, from the sensor's seed and the scan's number: same seed, same scans
  rng_.seed(seed_ ^ ((scan_count_ + 1) * 0x9E3779B97F4A7C15ull));
  unit_normal_.reset();
}

void RaySensor::CastColumn(int i, const Eigen::Isometry3d& T_WS, double time_s) {
  const raycast::RayScene& rays = ParentLink()->GetModel()->GetWorldRaw()->Rays();
  const physics::Link* own = ParentLink().get();  // the sensor's housing is not in its view
  const int rows = spec_.vertical_count, columns = spec_.horizontal_count;
  column_d_W_.resize(rows);
  column_hits_.resize(rows);
  for (int j = 0; j < rows; ++j) column_d_W_[j] = T_WS.linear() * d_S_[static_cast<size_t>(j) * columns + i];
  rays.CastFan(T_WS.translation(), column_d_W_.data(), rows, 0.0, spec_.range_max_m, own, skip_own_mask_,
               column_hits_.data());
  for (int j = 0; j < rows; ++j) {
    const size_t k = static_cast<size_t>(j) * columns + i;
    const raycast::RayHit& hit = column_hits_[j];
    building_.ranges_m[k] = Measure(hit.distance_m);
    // Lambertian return strength: the cosine between beam and surface normal
    building_.intensities[k] =
        hit.Hit() ? static_cast<float>(255.0 * std::abs(hit.normal_W.dot(column_d_W_[j]))) : 0.0f;
  }
  building_.column_time_s[i] = static_cast<float>(time_s);
}

void RaySensor::FinishScan() {
  last_.start = building_.start;
  last_.ranges_m.swap(building_.ranges_m);
  last_.intensities.swap(building_.intensities);
  last_.column_time_s.swap(building_.column_time_s);
  ++scan_count_;
  scanning_ = false;
}

bool RaySensor::SweepsOverTime() const { return over_time_ && UpdateRate() > 0.0; }

void RaySensor::SyncScene() {
  raycast::RayScene& rays = ParentLink()->GetModel()->GetWorldRaw()->Rays();
  if (skip_own_mask_ == raycast::RayScene::kAllVisuals) skip_own_mask_ = rays.SkipMask(ParentLink().get());
  rays.Sync();
}

void RaySensor::OnStep(const common::Time& sim_time) {
  const physics::Pose3d X_WS = WorldPose();
  if (SweepsOverTime() && scanning_) {
    SyncScene();
    // the columns due since the last step, each from the pose at its own time
    const double t = sim_time.Double(), t_prev = previous_step_time_.Double(), t0 = building_.start.Double();
    const double column_period_s = 1.0 / (UpdateRate() * spec_.horizontal_count);
    for (; next_column_ < spec_.horizontal_count; ++next_column_) {
      const double t_column = t0 + next_column_ * column_period_s;
      if (t_column > t + 1e-9) break;
      const double alpha = t > t_prev ? std::clamp((t_column - t_prev) / (t - t_prev), 0.0, 1.0) : 1.0;
      CastColumn(next_column_, Interpolate(previous_X_WS_, X_WS, alpha), t_column - t0);
    }
  }
  previous_step_time_ = sim_time;
  previous_X_WS_ = X_WS;
}

void RaySensor::OnUpdate(const common::Time& sim_time) {
  SyncScene();
  const Eigen::Isometry3d T_WS = ToIsometry(WorldPose());
  if (SweepsOverTime()) {
    if (scanning_) {
      // columns left by rounding of the column times are cast now
      const double column_period_s = 1.0 / (UpdateRate() * spec_.horizontal_count);
      for (; next_column_ < spec_.horizontal_count; ++next_column_)
        CastColumn(next_column_, T_WS, next_column_ * column_period_s);
      FinishScan();
    }
    StartScan(sim_time);
    CastColumn(0, T_WS, 0.0);
    next_column_ = 1;
    return;
  }
  StartScan(sim_time);
  for (int i = 0; i < spec_.horizontal_count; ++i) CastColumn(i, T_WS, 0.0);
  FinishScan();
}

void RaySensor::OnReset() {
  scanning_ = false;
  next_column_ = 0;
  scan_count_ = 0;  // the noise of scan n is seeded by n: a reset world scans as after load
}

}  // namespace sensors
}  // namespace rotors_sim
