#include "rotors_flight_batch/flight_batch.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <iterator>
#include <limits>
#include <mutex>
#include <sstream>

#include <Eigen/Eigenvalues>
#include <thread>

#include "rotors_core/error.h"
#include "rotors_core/physics/free_body_step.h"
#include "rotors_flight_batch/flight_kernel.h"

namespace rotors_flight_batch {

using rotors_sim::SimError;
using rotors_sim::physics::FreeBodyState;
using rotors_sim::physics::RotationFromQuaternion;
namespace rgp = rotors_gazebo_plugins;

namespace {

const char* kModeNames[] = {"rotor_speeds",    "normalized_thrust", "lee_position", "roll_pitch_yawrate_thrust",
                            "attitude_thrust", "rate_thrust"};

inline void Cross(const double a[3], const double b[3], double out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}
/// out = R v (R row-major)
inline void Rotate(const double R[9], const Eigen::Vector3d& v, double out[3]) {
  for (int k = 0; k < 3; ++k) out[k] = R[k * 3 + 0] * v[0] + R[k * 3 + 1] * v[1] + R[k * 3 + 2] * v[2];
}
/// out = R^T v
inline void RotateBack(const double R[9], const double v[3], double out[3]) {
  for (int k = 0; k < 3; ++k) out[k] = R[0 * 3 + k] * v[0] + R[1 * 3 + k] * v[1] + R[2 * 3 + k] * v[2];
}

/// The world's sim time after `steps` steps of dt: whole nanoseconds, read as seconds the way
/// common::Time::Double() does (so that a gust starts at the same step in both engines).
inline double SimTimeS(uint64_t steps, int64_t dt_ns) {
  const int64_t t_ns = static_cast<int64_t>(steps) * dt_ns;
  return static_cast<double>(t_ns / 1000000000) + static_cast<double>(t_ns % 1000000000) * 1e-9;
}

}  // namespace

CommandMode ParseCommandMode(const std::string& name) {
  for (int m = 0; m < 6; ++m)
    if (name == kModeNames[m]) return static_cast<CommandMode>(m);
  throw SimError("command mode '" + name +
                 "' is not known; use rotor_speeds, normalized_thrust, lee_position, roll_pitch_yawrate_thrust, "
                 "attitude_thrust or rate_thrust");
}

int CommandColumns(CommandMode mode, int rotors) {
  switch (mode) {
    case CommandMode::kRotorSpeeds:
    case CommandMode::kNormalizedThrust: return rotors;
    case CommandMode::kAttitudeThrust: return 5;
    default: return 4;
  }
}

// ---------------------------------------------------------------------------------------------
/// A T on cache lines of its own (64-byte aligned, its size rounded up to whole lines): the
/// per-vehicle objects a step writes (controllers, noise generators) are allocated one vehicle
/// after the other, and two threads stepping neighbours must not write one line.
template <class T>
struct alignas(64) OwnLines : T {
  using T::T;
};

struct alignas(64) FlightBatch::Controller {
  std::unique_ptr<OwnLines<rotors_control::LeeController>> lee;
  std::unique_ptr<OwnLines<rotors_control::AttitudeLevelController>> attitude;
};

/// A vehicle's seeded models (the plugins' classes) and its odometry sensor's queue.
struct alignas(64) FlightBatch::Sensors {
  struct Pending {
    uint64_t publish_at_step;
    double stamp_s;
    rgp::OdometryMeasurement truth;
  };
  std::unique_ptr<OwnLines<rgp::OdometryNoise>> odometry_noise;  ///< none when every sigma and bound is 0
  std::unique_ptr<OwnLines<rgp::ImuNoiseModel>> imu_noise;
  std::unique_ptr<OwnLines<rgp::WindModel>> wind;
  std::deque<Pending> queue;
  uint64_t odometry_step = 0;
  int steps_to_odometry = 0;  ///< odometry_step % divisor counted down (no division per step)
};

namespace {
/// A hint to the core that this thread is spinning (x86's pause, arm64's yield; nothing elsewhere).
inline void CpuRelax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__)
  __asm__ __volatile__("yield");
#endif
}

/// Spins until done() or `budget` has passed; whether done().
template <class Done>
bool SpinUntil(const Done& done, std::chrono::nanoseconds budget) {
  const auto deadline = std::chrono::steady_clock::now() + budget;
  for (;;) {
    for (int i = 0; i < 64; ++i) {
      if (done()) return true;
      CpuRelax();
    }
    if (std::chrono::steady_clock::now() >= deadline) return done();
  }
}
}  // namespace

/// The step's threads. A call wakes the workers and waits for them; both sides spin briefly before
/// they block, because an RL loop calls the batch again within a fraction of a millisecond (its
/// Python between two control periods) and a futex wake-up on each side costs about as much as
/// a short call's work. A worker blocks after kWorkerSpin without a call, so an idle batch takes no CPU.
class FlightBatch::Pool {
 public:
  static constexpr std::chrono::microseconds kWorkerSpin{400}, kCallerSpin{2000};

  explicit Pool(int threads) {
    for (int t = 1; t < threads; ++t) workers_.emplace_back([this, t] { Loop(t); });
  }
  ~Pool() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_.store(true, std::memory_order_release);
    }
    wake_.notify_all();
    for (auto& w : workers_) w.join();
  }
  /// task(t) for t = 0 .. threads - 1, task 0 on the calling thread; rethrows the first exception.
  void Run(const std::function<void(int)>& task) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      task_ = &task;
      error_ = nullptr;
      pending_.store(static_cast<int>(workers_.size()), std::memory_order_relaxed);
      generation_.fetch_add(1, std::memory_order_release);  // publishes task_ to spinning workers
    }
    wake_.notify_all();
    try {
      task(0);
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!error_) error_ = std::current_exception();
    }
    const auto finished = [this] { return pending_.load(std::memory_order_acquire) == 0; };
    if (!SpinUntil(finished, kCallerSpin)) {
      std::unique_lock<std::mutex> lock(mutex_);
      done_.wait(lock, finished);
    }
    std::lock_guard<std::mutex> lock(mutex_);
    task_ = nullptr;
    if (error_) std::rethrow_exception(error_);
  }

 private:
  void Loop(int t) {
    uint64_t seen = 0;
    for (;;) {
      const auto called = [&] {
        return stop_.load(std::memory_order_acquire) || generation_.load(std::memory_order_acquire) != seen;
      };
      if (!SpinUntil(called, kWorkerSpin)) {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, called);
      }
      if (stop_.load(std::memory_order_acquire)) return;
      seen = generation_.load(std::memory_order_acquire);
      const std::function<void(int)>* task = task_;
      std::exception_ptr error;
      try {
        (*task)(t);
      } catch (...) {
        error = std::current_exception();
      }
      if (error) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!error_) error_ = error;
      }
      if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
        std::lock_guard<std::mutex> lock(mutex_);  // the caller is spinning, or waiting under the mutex
        done_.notify_one();
      }
    }
  }
  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(int)>* task_ = nullptr;  ///< written before generation_'s release
  std::atomic<uint64_t> generation_{0};
  std::atomic<int> pending_{0};
  std::atomic<bool> stop_{false};
  std::exception_ptr error_;  ///< under mutex_
};

// ---------------------------------------------------------------------------------------------
FlightBatch::FlightBatch(VehicleDescription description, FlightBatchOptions options)
    : d_(std::move(description)), options_(std::move(options)) {
  n_ = options_.count;
  if (n_ < 1) throw SimError("FlightBatch: count = " + std::to_string(n_) + " must be >= 1");
  r_ = static_cast<int>(d_.rotors.size());
  command_columns_ = rotors_flight_batch::CommandColumns(options_.mode, r_);
  dt_ = d_.step_s;
  if (!(dt_ > 0.0)) throw SimError("FlightBatch: the physics step must be > 0");
  if (!options_.seeds.empty() && static_cast<int>(options_.seeds.size()) != n_)
    throw SimError("FlightBatch: " + std::to_string(options_.seeds.size()) + " seeds for " + std::to_string(n_) +
                   " vehicles; give one per vehicle or none");
  const int cores = std::max(1u, std::thread::hardware_concurrency());
  threads_ = std::clamp(options_.threads > 0 ? options_.threads : cores, 1, n_);

  dt_ns_ = std::llround(dt_ * 1e9);
  if (d_.imu) R_BI_ = d_.imu->mount.q_BS.toRotationMatrix();

  n_pad_ = (n_ + kLanes - 1) / kLanes * kLanes;
  const size_t n = n_pad_;
  p_W_.assign(3 * n, 0.0);
  v_W_.assign(3 * n, 0.0);
  q_WB_.assign(4 * n, 0.0);
  R_WB_.assign(9 * n, 0.0);
  omega_W_.assign(3 * n, 0.0);
  omega_rotor_.assign(r_ * n, 0.0);
  qdot_applied_.assign(r_ * n, 0.0);
  motor_command_.assign(r_ * n, 0.0);
  command_target_.assign(r_ * n, 0.0);
  delay_rings_.assign(n, {});
  delay_heads_.assign(n, 0);
  wind_velocity_W_.assign(3 * n, 0.0);
  for (auto* v : {&mass_, &inv_mass_, &contact_k_, &contact_c_, &contact_reach_m_}) v->assign(n, 0.0);
  for (auto* v : {&p_origin_B_, &p_cog_B_}) v->assign(3 * r_ * n, 0.0);
  corner_B_.assign(3 * kMaxContacts * n, 0.0);
  rotor_columns_.assign(n, RotorColumnsOfOne{});
  points_.resize(n);
  for (auto* v : {&I_B_, &inv_I_B_}) v->assign(9 * n, 0.0);
  for (auto* v : {&motor_constant_, &rotor_drag_coefficient_, &rolling_moment_coefficient_, &reaction_factor_,
                  &max_rot_velocity_, &a_up_, &a_down_})
    v->assign(r_ * n, 0.0);
  const size_t count = n_;
  steps_.assign(count, 0);
  in_contact_.assign(count, 0);
  commands_.assign(command_columns_ * count, 0.0);
  if (options_.mode == CommandMode::kAttitudeThrust)
    for (size_t i = 0; i < count; ++i) commands_[i * 5 + 3] = 1.0;  // identity attitude
  odometry_out_.assign(14 * count, 0.0);
  imu_out_.assign(6 * count, 0.0);
  truth_out_.assign(13 * count, 0.0);
  rotor_speed_out_.assign(r_ * count, 0.0);
  odometry_count_.assign(count, 0);
  controller_seen_.assign(count, 0);
  BuildKernelModel();
  kernel_arrays_ = {n_pad_,
                    p_W_.data(),
                    v_W_.data(),
                    q_WB_.data(),
                    R_WB_.data(),
                    omega_W_.data(),
                    omega_rotor_.data(),
                    qdot_applied_.data(),
                    motor_command_.data(),
                    wind_velocity_W_.data(),
                    KernelAirframes{mass_.data(), inv_mass_.data(), I_B_.data(), inv_I_B_.data(), contact_k_.data(),
                                    contact_c_.data(), rotor_columns_.data(), p_origin_B_.data(), p_cog_B_.data(),
                                    corner_B_.data(), contact_reach_m_.data(), motor_constant_.data(),
                                    rotor_drag_coefficient_.data(), rolling_moment_coefficient_.data(),
                                    reaction_factor_.data(), max_rot_velocity_.data(), a_up_.data(), a_down_.data()}};
  // the collision sphere: about the description's CoG, holding every visual and collision (model frame)
  collided_.assign(count, 0);
  sphere_center_M_ = d_.p_M_cog;
  sphere_radius_m_ = d_.reach_m;
  const Airframe nominal = NominalAirframe();
  airframes_.assign(count, nominal);
  for (size_t i = 0; i < n; ++i) WriteAirframe(i, nominal);  // the padding lanes too
  kernels_ = ChooseKernels(options_.kernel);

  if (!options_.lee_each.empty() && static_cast<int>(options_.lee_each.size()) != n_)
    throw SimError("FlightBatch: " + std::to_string(options_.lee_each.size()) + " controller parameter sets for " +
                   std::to_string(n_) + " vehicles; give one per vehicle or one for all");
  if (options_.mode != CommandMode::kRotorSpeeds && options_.mode != CommandMode::kNormalizedThrust) {
    const auto& vehicle = options_.mode == CommandMode::kLeePosition ? options_.lee.vehicle : options_.attitude.vehicle;
    if (static_cast<int>(vehicle.rotors.size()) != r_)
      throw SimError("FlightBatch: the controller's vehicle parameters have " + std::to_string(vehicle.rotors.size()) +
                     " rotors, the model '" + d_.model_name + "' has " + std::to_string(r_) +
                     "; give the controller the vehicle's yaml");
    for (size_t i = 0; i < count; ++i) {
      auto c = std::make_unique<Controller>();
      try {
        if (options_.mode == CommandMode::kLeePosition) {
          c->lee = std::make_unique<OwnLines<rotors_control::LeeController>>(
              options_.lee_each.empty() ? options_.lee : options_.lee_each[i]);
        } else {
          c->attitude = std::make_unique<OwnLines<rotors_control::AttitudeLevelController>>(options_.attitude);
        }
      } catch (const std::exception& e) {
        throw SimError(std::string("FlightBatch: controller parameters: ") + e.what());
      }
      controllers_.push_back(std::move(c));
    }
  }
  if (options_.mode == CommandMode::kLeePosition) {  // whole groups run their controllers in lanes
    lee_groups_.resize(count / kLanes);
    for (size_t g = 0; g < lee_groups_.size(); ++g) {
      LeeConstantsT<double> each[kLanes];
      for (int l = 0; l < kLanes; ++l) each[l] = controllers_[g * kLanes + l]->lee->Constants();
      kernels_.pack_lee(each, &lee_groups_[g]);
    }
  }
  for (size_t i = 0; i < count; ++i) sensors_.push_back(std::make_unique<Sensors>());
  std::vector<int> all(count);
  std::vector<double> origin(3 * count, 0.0), yaw(count, 0.0);
  for (size_t i = 0; i < count; ++i) all[i] = static_cast<int>(i);
  Reset(all, origin.data(), yaw.data());
  ParkPaddingLanes();
  if (threads_ > 1) pool_ = std::make_unique<Pool>(threads_);
}

FlightBatch::~FlightBatch() = default;

size_t FlightBatch::StateBytesPerVehicle() const {
  const size_t doubles = (3 + 3 + 4 + 9 + 3) + 3 * r_ + 3 + command_columns_ + 14 + 6 + 13 + r_;
  return doubles * sizeof(double) + 3 * sizeof(uint64_t) + 2 * sizeof(uint8_t);
}

size_t FlightBatch::ControllerBytesPerVehicle() const {
  if (controllers_.empty()) return 0;
  const auto& vehicle = options_.mode == CommandMode::kLeePosition ? options_.lee.vehicle : options_.attitude.vehicle;
  // the object and its heap: rotor parameters, the allocation matrix and its inverse (4 x R each)
  const size_t heap =
      vehicle.rotors.size() * (sizeof(rotors_control::RotorGeometry) + 2 * 4 * sizeof(double) + 2 * sizeof(double));
  // a Lee controller's share of its group's constants in lanes besides
  return sizeof(Controller) + heap +
         (options_.mode == CommandMode::kLeePosition
              ? sizeof(OwnLines<rotors_control::LeeController>) + sizeof(LeeGroupConstants) / kLanes
              : sizeof(OwnLines<rotors_control::AttitudeLevelController>));
}

size_t FlightBatch::NoiseBytesPerVehicle() const {
  const Sensors& s = *sensors_.front();
  return sizeof(Sensors) + (s.odometry_noise ? sizeof(OwnLines<rgp::OdometryNoise>) : 0) +
         (s.imu_noise ? sizeof(OwnLines<rgp::ImuNoiseModel>) : 0) + (s.wind ? sizeof(OwnLines<rgp::WindModel>) : 0);
}

rgp::DepthNoiseParams DepthCameraParams::D435Noise() {
  rgp::DepthNoiseParams p;
  p.model = rgp::DepthNoiseParams::Model::kD435;
  p.horizontal_fov_rad = 1.59174;  // the imager's: the error is a disparity error at its resolution
  p.width_px = 848;
  p.baseline_m = 0.05;
  p.subpixel_error_px = 0.25;
  p.max_stdev_m = 3.0;
  return p;
}

std::string DepthCameraParams::Validate() const {
  if (width_px < 1 || height_px < 1 || width_px > 4096 || height_px > 4096)
    return "width and height must be 1..4096 pixels (got " + std::to_string(width_px) + " x " +
           std::to_string(height_px) + ")";
  if (!(horizontal_fov_rad > 0.0 && horizontal_fov_rad < M_PI && vertical_fov_rad > 0.0 && vertical_fov_rad < M_PI))
    return "horizontal_fov = " + std::to_string(horizontal_fov_rad) +
           " and vertical_fov = " + std::to_string(vertical_fov_rad) + " rad must be in (0, pi)";
  if (!(min_range_m >= 0.0 && max_range_m > min_range_m && std::isfinite(max_range_m)))
    return "need 0 <= min_range < max_range < inf (got " + std::to_string(min_range_m) + ", " +
           std::to_string(max_range_m) + ")";
  if (!p_M_m.allFinite()) return "the mount p_M must be finite";
  if (noise) {
    const std::string why = noise_params.Validate();
    if (!why.empty()) return "noise: " + why;
  }
  return "";
}

void FlightBatch::SetObstacles(std::shared_ptr<const ObstacleField> field) {
  if (field && field->Environments() < n_)
    throw SimError("FlightBatch.set_obstacles: the field has " + std::to_string(field->Environments()) +
                   " environments for " + std::to_string(n_) + " vehicles; give one per vehicle");
  if (field && field->MaxSphereRadius() < sphere_radius_m_)
    throw SimError("FlightBatch.set_obstacles: the field tests spheres up to " +
                   std::to_string(field->MaxSphereRadius()) + " m, the vehicle's is " +
                   std::to_string(sphere_radius_m_) + " m; make the field for it");
  obstacles_ = std::move(field);
  std::fill(collided_.begin(), collided_.end(), 0);
}

void FlightBatch::SetDepthCamera(std::optional<DepthCameraParams> camera) {
  if (camera) {
    const std::string why = camera->Validate();
    if (!why.empty()) throw SimError("FlightBatch.set_depth_camera: " + why);
  }
  depth_camera_ = std::move(camera);
  depth_dirs_M_.clear();
  depth_per_distance_.clear();
  depth_noise_.clear();
  if (!depth_camera_) return;
  const DepthCameraParams& c = *depth_camera_;
  // pixel (u, v) looks along (x, y, 1) in the optical frame, x = (u - (W-1)/2) / fx, y = (v - (H-1)/2) / fy;
  // the optical frame's z, x, y are the model frame's x, -y, -z
  const double fx = c.width_px / (2.0 * std::tan(c.horizontal_fov_rad / 2.0));
  const double fy = c.height_px / (2.0 * std::tan(c.vertical_fov_rad / 2.0));
  for (int v = 0; v < c.height_px; ++v)
    for (int u = 0; u < c.width_px; ++u) {
      const double x = (u - (c.width_px - 1) / 2.0) / fx, y = (v - (c.height_px - 1) / 2.0) / fy;
      const Eigen::Vector3d ray_M(1.0, -x, -y);
      depth_dirs_M_.push_back(ray_M.normalized());
      depth_per_distance_.push_back(1.0 / ray_M.norm());
    }
  depth_noise_.resize(n_);
  for (int i = 0; i < n_; ++i) SeedDepthNoise(i);
}

void FlightBatch::SeedDepthNoise(int i) {
  // its own stream beside the odometry's (description seed + 1) and the wind's: the vehicle's random_seed + 7
  const uint64_t seed = (options_.seeds.empty() ? options_.description_seed : options_.seeds[i]) + 7;
  depth_noise_[i] =
      depth_camera_->noise ? std::make_unique<rgp::DepthNoiseModel>(depth_camera_->noise_params, seed) : nullptr;
}

void FlightBatch::CastFromVehicle(int i, const Eigen::Vector3d& p_M, const std::vector<Eigen::Vector3d>& dirs_M,
                                  double far_m, std::vector<Eigen::Vector3d>* dirs_W, double* t_m) const {
  const size_t n = n_pad_, rays = dirs_M.size();
  Eigen::Matrix3d R;
  for (int r = 0; r < 3; ++r)
    for (int col = 0; col < 3; ++col) R(r, col) = R_WB_[(3 * r + col) * n + i];
  const Eigen::Vector3d origin_W =
      Eigen::Vector3d(p_W_[i], p_W_[n + i], p_W_[2 * n + i]) + R * (p_M - airframes_[i].p_M_cog);
  dirs_W->resize(rays);
  for (size_t k = 0; k < rays; ++k) (*dirs_W)[k] = R * dirs_M[k];
  if (obstacles_) {
    obstacles_->Cast(i, origin_W, dirs_W->data(), rays, 0.0, far_m, t_m);
  } else {
    std::fill(t_m, t_m + rays, std::numeric_limits<double>::infinity());
  }
  for (size_t k = 0; k < rays; ++k) {  // the ground plane z = 0, seen from above
    const Eigen::Vector3d& d = (*dirs_W)[k];
    if (d.z() < 0.0 && origin_W.z() > 0.0) t_m[k] = std::min(t_m[k], -origin_W.z() / d.z());
  }
}

void FlightBatch::Split(int count, const std::function<void(int, int)>& work) {
  if (!pool_ || count < 2) {
    work(0, count);
    return;
  }
  const int threads = threads_;
  pool_->Run([&](int t) { work(count * t / threads, count * (t + 1) / threads); });
}

void FlightBatch::RenderDepth(const std::vector<int>& vehicles, float* out) {
  if (!depth_camera_) throw SimError("FlightBatch.render_depth: no depth camera; set one with set_depth_camera");
  for (int i : vehicles)
    if (i < 0 || i >= n_)
      throw SimError("FlightBatch.render_depth: vehicle " + std::to_string(i) + " is not in 0.." +
                     std::to_string(n_ - 1));
  const DepthCameraParams& c = *depth_camera_;
  const size_t pixels = depth_dirs_M_.size();
  const double far_ray = c.max_range_m / *std::min_element(depth_per_distance_.begin(), depth_per_distance_.end());
  Split(static_cast<int>(vehicles.size()), [&](int begin, int end) {
    std::vector<Eigen::Vector3d> dirs_W;
    std::vector<double> t(pixels);
    std::vector<float> depth(pixels);
    for (int j = begin; j < end; ++j) {
      const int i = vehicles[j];
      CastFromVehicle(i, c.p_M_m, depth_dirs_M_, far_ray, &dirs_W, t.data());
      for (size_t k = 0; k < pixels; ++k) {
        const double z = t[k] * depth_per_distance_[k];
        depth[k] =
            z > c.min_range_m && z < c.max_range_m ? static_cast<float>(z) : std::numeric_limits<float>::quiet_NaN();
      }
      if (depth_noise_[i]) depth_noise_[i]->Apply(&depth);  // NaN stays NaN; noise may not leave the range
      std::copy(depth.begin(), depth.end(), out + static_cast<size_t>(j) * pixels);
    }
  });
}

void FlightBatch::SetRangeRays(std::optional<RangeRays> rays) {
  if (rays) {
    if (rays->dirs_M.empty() || rays->dirs_M.size() > 4096)
      throw SimError("FlightBatch.set_range_rays: give 1..4096 directions (got " + std::to_string(rays->dirs_M.size()) +
                     ")");
    for (size_t k = 0; k < rays->dirs_M.size(); ++k) {
      if (!rays->dirs_M[k].allFinite() || rays->dirs_M[k].norm() < 1e-9)
        throw SimError("FlightBatch.set_range_rays: direction " + std::to_string(k) + " is not finite or is zero");
      rays->dirs_M[k].normalize();
    }
    if (!(rays->min_range_m >= 0.0 && rays->max_range_m > rays->min_range_m && std::isfinite(rays->max_range_m)) ||
        !rays->p_M_m.allFinite())
      throw SimError("FlightBatch.set_range_rays: need 0 <= min_range < max_range < inf (got " +
                     std::to_string(rays->min_range_m) + ", " + std::to_string(rays->max_range_m) +
                     ") and a finite xyz");
  }
  range_rays_ = std::move(rays);
}

void FlightBatch::CastRanges(double* out) {
  if (!range_rays_) throw SimError("FlightBatch.cast_ranges: no range rays; set them with set_range_rays");
  const RangeRays& r = *range_rays_;
  const size_t rays = r.dirs_M.size();
  Split(n_, [&](int begin, int end) {
    std::vector<Eigen::Vector3d> dirs_W;
    for (int i = begin; i < end; ++i) {
      double* t = out + static_cast<size_t>(i) * rays;
      CastFromVehicle(i, r.p_M_m, r.dirs_M, r.max_range_m, &dirs_W, t);
      for (size_t k = 0; k < rays; ++k)
        if (!(t[k] >= r.min_range_m && t[k] <= r.max_range_m)) t[k] = std::numeric_limits<double>::infinity();
    }
  });
}

uint64_t FlightBatch::SeedFor(uint64_t plugin_seed, int i) const {
  return options_.seeds.empty() ? plugin_seed : options_.seeds[i] + (plugin_seed - options_.description_seed);
}

void FlightBatch::SetSeed(int i, uint64_t seed) {
  if (i < 0 || i >= n_)
    throw SimError("FlightBatch.set_seed: vehicle " + std::to_string(i) + " is not in 0.." + std::to_string(n_ - 1));
  if (options_.seeds.empty()) options_.seeds.assign(n_, options_.description_seed);
  options_.seeds[i] = seed;
}

void FlightBatch::Reset(const std::vector<int>& indices, const double* positions_M, const double* yaws) {
  for (size_t k = 0; k < indices.size(); ++k) {
    const int i = indices[k];
    if (i < 0 || i >= n_)
      throw SimError("FlightBatch.reset: vehicle " + std::to_string(i) + " is not in 0.." + std::to_string(n_ - 1));
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(positions_M[3 * k + c]))
        throw SimError("FlightBatch.reset: vehicle " + std::to_string(i) + ": position must be finite");
    if (!std::isfinite(yaws[k]))
      throw SimError("FlightBatch.reset: vehicle " + std::to_string(i) + ": yaw must be finite");
  }
  const size_t n = n_pad_;
  for (size_t k = 0; k < indices.size(); ++k) {
    const size_t i = indices[k];
    const double yaw = yaws[k];
    const double q[4] = {std::cos(yaw / 2), 0.0, 0.0, std::sin(yaw / 2)};
    double R[9];
    RotationFromQuaternion(q, R);
    double r_cog[3];
    Rotate(R, airframes_[i].p_M_cog, r_cog);
    for (int c = 0; c < 3; ++c) {
      p_W_[c * n + i] = positions_M[3 * k + c] + r_cog[c];
      v_W_[c * n + i] = 0.0;
      omega_W_[c * n + i] = 0.0;
      wind_velocity_W_[c * n + i] = 0.0;
    }
    for (int c = 0; c < 4; ++c) q_WB_[c * n + i] = q[c];
    for (int c = 0; c < 9; ++c) R_WB_[c * n + i] = R[c];
    for (int r = 0; r < r_; ++r) {
      omega_rotor_[r * n + i] = 0.0;
      qdot_applied_[r * n + i] = 0.0;
      motor_command_[r * n + i] = 0.0;
      command_target_[r * n + i] = 0.0;
      rotor_speed_out_[i * r_ + r] = 0.0;
    }
    steps_[i] = 0;
    in_contact_[i] = 0;
    collided_[i] = 0;
    if (depth_camera_) SeedDepthNoise(static_cast<int>(i));
    // no command in flight: the motors get 0 (stopped) for the first actuator_delay_steps steps
    delay_rings_[i].assign(static_cast<size_t>(airframes_[i].actuator_delay_steps) * r_, 0.0);
    delay_heads_[i] = 0;
    Sensors& s = *sensors_[i];
    const uint64_t seed_odometry = SeedFor(d_.odometry->seed, i);
    s.queue.clear();
    s.odometry_step = 0;
    s.steps_to_odometry = 0;
    const auto& on = airframes_[i].odometry_noise;
    const bool odometry_noisy =
        options_.noise &&
        (on.normal_position_m.any() || on.normal_quaternion_rad.any() || on.normal_linear_velocity_m_s.any() ||
         on.normal_angular_velocity_rad_s.any() || on.uniform_position_m.any() || on.uniform_quaternion_rad.any() ||
         on.uniform_linear_velocity_m_s.any() || on.uniform_angular_velocity_rad_s.any());
    s.odometry_noise = odometry_noisy ? std::make_unique<OwnLines<rgp::OdometryNoise>>(on, seed_odometry) : nullptr;
    if (d_.imu && options_.imu && options_.noise)
      s.imu_noise = std::make_unique<OwnLines<rgp::ImuNoiseModel>>(airframes_[i].imu_noise, SeedFor(d_.imu->seed, i));
    if (d_.wind) {
      rgp::WindParams wp = airframes_[i].wind;
      if (!options_.noise) wp.wind_speed_variance = wp.wind_force_variance = wp.wind_gust_force_variance = 0.0;
      s.wind = std::make_unique<OwnLines<rgp::WindModel>>(wp, SeedFor(d_.wind->seed, i));
    }
    // until the sensor's first message the odometry row holds the reset state, noise-free
    double* o = &odometry_out_[i * 14];
    const Mount& m = d_.odometry->mount;
    double r_s[3];
    Rotate(R, points_[i].odometry, r_s);
    const Eigen::Quaterniond q_WS = Eigen::Quaterniond(q[0], q[1], q[2], q[3]) * m.q_BS;
    for (int c = 0; c < 3; ++c) o[c] = p_W_[c * n + i] + r_s[c];
    o[3] = q_WS.x(), o[4] = q_WS.y(), o[5] = q_WS.z(), o[6] = q_WS.w();
    for (int c = 7; c < 14; ++c) o[c] = 0.0;
    controller_seen_[i] = odometry_count_[i];
    for (int c = 0; c < 6; ++c) imu_out_[i * 6 + c] = 0.0;
  }
}

void FlightBatch::CheckCommands() const {
  const int cols = command_columns_;
  for (int i = 0; i < n_; ++i) {
    const double* c = &commands_[i * cols];
    if (options_.mode == CommandMode::kLeePosition && std::isnan(c[0]) && std::isnan(c[1]) && std::isnan(c[2]) &&
        std::isnan(c[3]))
      continue;  // no set point yet
    for (int k = 0; k < cols; ++k) {
      std::string why;
      if (!std::isfinite(c[k])) {
        why = "is not finite";
      } else if (options_.mode == CommandMode::kRotorSpeeds && c[k] < 0.0) {
        why = "is a negative rotor speed";
      } else if (options_.mode == CommandMode::kNormalizedThrust && (c[k] < 0.0 || c[k] > 1.0)) {
        why = "is outside 0..1 (a fraction of the rotor's maximum thrust)";
      } else if (k == cols - 1 && c[k] < 0.0 &&
                 (options_.mode == CommandMode::kRollPitchYawrateThrust ||
                  options_.mode == CommandMode::kAttitudeThrust || options_.mode == CommandMode::kRateThrust)) {
        why = "is a negative thrust";
      }
      if (!why.empty()) {
        std::ostringstream msg;
        msg << "FlightBatch.step: commands[" << i << ", " << k << "] = " << c[k] << " " << why << " ("
            << kModeNames[static_cast<int>(options_.mode)] << "); no vehicle was stepped";
        throw SimError(msg.str());
      }
    }
    if (options_.mode == CommandMode::kAttitudeThrust && c[0] * c[0] + c[1] * c[1] + c[2] * c[2] + c[3] * c[3] < 1e-18)
      throw SimError("FlightBatch.step: commands[" + std::to_string(i) +
                     ", 0:4] is a zero quaternion (x, y, z, w); no vehicle was stepped");
  }
}

void FlightBatch::Step(long steps) {
  if (steps < 0) throw SimError("FlightBatch.step: n = " + std::to_string(steps) + " must be >= 0");
  CheckCommands();
  if (steps == 0) return;
  ParkPaddingLanes();
  // a short call (an environment's control period over few vehicles) is cheaper on this thread
  // than handing it to the pool: below kPoolMinVehicleSteps vehicle-steps the workers are not
  // called, nor for one group (a thread steps whole groups: the others would only wait)
  const int threads = threads_, groups = static_cast<int>(n_pad_ / kLanes);
  if (!pool_ || groups < 2 || static_cast<long>(n_) * steps < kPoolMinVehicleSteps) {
    StepRange(0, n_, steps);
    return;
  }
  // whole groups of lanes per thread
  pool_->Run([&](int t) {
    StepRange(groups * t / threads * kLanes, std::min(n_, groups * (t + 1) / threads * kLanes), steps);
  });
}

void FlightBatch::BuildKernelModel() {
  KernelModel& k = kernel_model_;
  k.rotors = r_;
  for (int r = 0; r < r_; ++r) {
    const RotorMount& rotor = d_.rotors[r];
    KernelModel::Rotor& kr = k.rotor[r];
    for (int c = 0; c < 3; ++c) kr.axis_B[c] = rotor.axis_B[c];
    kr.cog_on_origin = rotor.p_B_cog == rotor.p_B_origin;
    kr.spin_inertia = rotor.spin_inertia_kg_m2;
    kr.direction = rotor.params.turning_direction;
    kr.slowdown = rotor.slowdown;
  }
  FillRotorColumns(k);
  k.contacts = static_cast<int>(std::min<size_t>(d_.contact_points_B.size(), kMaxContacts));
  // Ground contact: a spring and damper at each corner below z = 0, stiff enough that the vehicle
  // sinks g / w^2 (0.4 mm at 500 Hz), soft enough for the explicit step (w dt = 0.3); per vehicle
  // with its own mass (WriteAirframe).
  contact_w_ = 0.3 / dt_ * std::sqrt(options_.contact_stiffness_scale);
  k.dt = dt_;
  k.inv_dt = 1.0 / dt_;
  for (int c = 0; c < 3; ++c) k.gravity_W[c] = d_.gravity_W[c];
  k.has_wind = d_.wind.has_value();
  k.keep_state_before = d_.imu && options_.imu;
  k.wind_before_motors = d_.wind && d_.wind->before_motors;
}

Airframe AirframeOf(const VehicleDescription& d) {
  Airframe a;
  a.mass_kg = d.mass_kg;
  a.inertia_B_kg_m2 = d.inertia_B_kg_m2;
  a.p_M_cog = d.p_M_cog;
  if (d.wind) a.wind = d.wind->params;
  for (const RotorMount& rotor : d.rotors) a.rotors.push_back(rotor.params);
  if (d.odometry) a.odometry_noise = d.odometry->noise;
  if (d.imu) a.imu_noise = d.imu->noise;
  return a;
}

Airframe FlightBatch::NominalAirframe() const { return AirframeOf(d_); }

const Airframe& FlightBatch::GetAirframe(int i) const {
  if (i < 0 || i >= n_)
    throw SimError("FlightBatch.airframe: vehicle " + std::to_string(i) + " is not in 0.." + std::to_string(n_ - 1));
  return airframes_[i];
}

void FlightBatch::SetAirframe(int i, const Airframe& airframe) {
  const Airframe checked = CheckedAirframe(i, airframe);
  airframes_[i] = checked;
  WriteAirframe(i, checked);
}

void FlightBatch::SetAirframes(const std::vector<int>& indices, const std::vector<Airframe>& airframes) {
  if (indices.size() != airframes.size())
    throw SimError("FlightBatch.set_airframes: " + std::to_string(indices.size()) + " vehicles for " +
                   std::to_string(airframes.size()) + " airframes");
  std::vector<Airframe> checked;
  checked.reserve(airframes.size());
  for (size_t j = 0; j < airframes.size(); ++j) checked.push_back(CheckedAirframe(indices[j], airframes[j]));
  for (size_t j = 0; j < checked.size(); ++j) {
    airframes_[indices[j]] = checked[j];
    WriteAirframe(indices[j], checked[j]);
  }
}

Airframe FlightBatch::CheckedAirframe(int i, const Airframe& airframe) const {
  const std::string who = "FlightBatch.set_airframe: vehicle " + std::to_string(i);
  if (i < 0 || i >= n_) throw SimError(who + " is not in 0.." + std::to_string(n_ - 1));
  if (!(airframe.mass_kg > 0.0) || !std::isfinite(airframe.mass_kg))
    throw SimError(who + ": mass = " + std::to_string(airframe.mass_kg) + " kg must be > 0");
  const Eigen::Matrix3d& I = airframe.inertia_B_kg_m2;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(I);
  if (!I.allFinite() || (I - I.transpose()).cwiseAbs().maxCoeff() > 1e-12 * I.cwiseAbs().maxCoeff() ||
      !(eigen.eigenvalues().minCoeff() > 0.0)) {
    std::ostringstream msg;
    msg << who << ": inertia [" << I.row(0) << "; " << I.row(1) << "; " << I.row(2)
        << "] kg m^2 is not symmetric positive definite";
    throw SimError(msg.str());
  }
  if (!airframe.p_M_cog.allFinite()) throw SimError(who + ": the CoG must be finite");
  if (airframe.actuator_delay_steps < 0 || airframe.actuator_delay_steps > kMaxActuatorDelaySteps)
    throw SimError(who + ": actuatorDelay = " + std::to_string(airframe.actuator_delay_steps) +
                   " steps must be in 0.." + std::to_string(kMaxActuatorDelaySteps));
  if (d_.wind) {
    const rgp::WindParams& w = airframe.wind;
    std::string why = w.Validate();
    const double values[] = {w.wind_speed_mean_m_s, w.wind_force_mean_n, w.wind_gust_start_s, w.wind_gust_force_mean_n};
    if (why.empty() && !(std::all_of(std::begin(values), std::end(values), [](double v) { return std::isfinite(v); }) &&
                         w.wind_direction.allFinite() && w.wind_gust_direction.allFinite()))
      why = "the wind's means, gust start and directions must be finite";
    if (!why.empty()) throw SimError(who + ", wind: " + why);
  }
  if (static_cast<int>(airframe.rotors.size()) != r_)
    throw SimError(who + ": " + std::to_string(airframe.rotors.size()) + " rotors given, the vehicle has " +
                   std::to_string(r_));
  // the noise as the odometry and IMU plugins check theirs
  std::string why_noise = airframe.odometry_noise.Validate();
  if (why_noise.empty() && d_.imu) why_noise = airframe.imu_noise.Validate();
  if (!why_noise.empty()) throw SimError(who + ": " + why_noise);
  Airframe checked = airframe;
  for (int r = 0; r < r_; ++r) {
    checked.rotors[r].turning_direction = d_.rotors[r].params.turning_direction;
    // maxRotVelocity 0 is a failed motor (it turns no more); every other value as the plugin checks it
    rgp::RotorParams as_plugin = checked.rotors[r];
    if (as_plugin.max_rot_velocity == 0.0) as_plugin.max_rot_velocity = 1.0;
    const std::string why = as_plugin.Validate();
    if (!why.empty()) throw SimError(who + ", rotor " + std::to_string(r) + ": " + why);
  }
  return checked;
}

void FlightBatch::WriteAirframe(size_t i, const Airframe& a) {
  const size_t n = n_pad_;
  mass_[i] = a.mass_kg;
  inv_mass_[i] = 1.0 / a.mass_kg;
  const Eigen::Matrix3d inv_I = a.inertia_B_kg_m2.inverse();
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) {
      I_B_[(row * 3 + col) * n + i] = a.inertia_B_kg_m2(row, col);
      inv_I_B_[(row * 3 + col) * n + i] = inv_I(row, col);
    }
  contact_k_[i] = a.mass_kg * contact_w_ * contact_w_ / 4.0;
  contact_c_[i] = a.mass_kg * contact_w_ / 2.0;
  // every point in the body frame moves against the CoG: p_B = p_M - p_M_cog (0 for the description's)
  const Eigen::Vector3d cog_move = a.p_M_cog - d_.p_M_cog;
  auto in_body = [&](const Eigen::Vector3d& p_B) -> Eigen::Vector3d { return p_B - cog_move; };
  for (int r = 0; r < r_; ++r) {
    const RotorMount& rotor = d_.rotors[r];
    const Eigen::Vector3d p_o = in_body(rotor.p_B_origin);
    const Eigen::Vector3d p_c = rotor.p_B_cog == rotor.p_B_origin ? p_o : in_body(rotor.p_B_cog);
    for (int c = 0; c < 3; ++c) {
      p_origin_B_[(c * r_ + r) * n + i] = p_o[c];
      p_cog_B_[(c * r_ + r) * n + i] = p_c[c];
    }
  }
  contact_reach_m_[i] = 0.0;  // no corner is farther from the CoG: above it, no contact
  for (int k = 0; k < kernel_model_.contacts; ++k) {
    const Eigen::Vector3d corner = in_body(d_.contact_points_B[k]);
    for (int c = 0; c < 3; ++c) corner_B_[(3 * k + c) * n + i] = corner[c];
    contact_reach_m_[i] = std::max(contact_reach_m_[i], corner.norm());
  }
  BodyPoints& points = points_[i];
  if (d_.imu) points.imu = in_body(d_.imu->mount.p_B);
  if (d_.odometry) points.odometry = in_body(d_.odometry->mount.p_B);
  if (d_.wind) {
    points.wind_link = in_body(d_.wind->p_B_link);
    points.wind_force = in_body(d_.wind->p_B_force);
  }
  for (int r = 0; r < r_; ++r) {
    const rgp::RotorParams& p = a.rotors[r];
    motor_constant_[r * n + i] = p.motor_constant;
    rotor_drag_coefficient_[r * n + i] = p.rotor_drag_coefficient;
    rolling_moment_coefficient_[r * n + i] = p.rolling_moment_coefficient;
    reaction_factor_[r * n + i] = -d_.rotors[r].params.turning_direction * p.moment_constant;  // -epsilon C_M
    max_rot_velocity_[r * n + i] = p.max_rot_velocity;
    a_up_[r * n + i] = std::exp(-dt_ / p.time_constant_up_s);  // FirstOrderFilter's factors, once
    a_down_[r * n + i] = std::exp(-dt_ / p.time_constant_down_s);
  }
  RotorColumnsOfOne& own = rotor_columns_[i];
  for (int r = 0; r < r_; ++r) {
    own.motor_constant[r] = motor_constant_[r * n + i];
    own.rotor_drag_coefficient[r] = rotor_drag_coefficient_[r * n + i];
    own.rolling_moment_coefficient[r] = rolling_moment_coefficient_[r * n + i];
    own.reaction_factor[r] = reaction_factor_[r * n + i];
    own.max_rot_velocity[r] = max_rot_velocity_[r * n + i];
    own.a_up[r] = a_up_[r * n + i];
    own.a_down[r] = a_down_[r * n + i];
    for (int c = 0; c < 3; ++c) {
      own.p_origin_B[c][r] = p_origin_B_[(c * r_ + r) * n + i];
      own.p_cog_B[c][r] = p_cog_B_[(c * r_ + r) * n + i];
    }
  }
}

void FlightBatch::ParkPaddingLanes() {
  // lanes past the last vehicle fill the last group: at rest far above the ground, unpowered
  const size_t n = n_pad_;
  for (size_t i = n_; i < n; ++i) {
    const double q[4] = {1.0, 0.0, 0.0, 0.0};
    double R[9];
    RotationFromQuaternion(q, R);
    for (int c = 0; c < 3; ++c) {
      p_W_[c * n + i] = c == 2 ? 1e6 : 0.0;
      v_W_[c * n + i] = omega_W_[c * n + i] = wind_velocity_W_[c * n + i] = 0.0;
    }
    for (int c = 0; c < 4; ++c) q_WB_[c * n + i] = q[c];
    for (int c = 0; c < 9; ++c) R_WB_[c * n + i] = R[c];
    for (int r = 0; r < r_; ++r) omega_rotor_[r * n + i] = qdot_applied_[r * n + i] = motor_command_[r * n + i] = 0.0;
  }
}

void FlightBatch::StepRange(int begin, int end, long steps) {
  // groups of kLanes vehicles; blocks of groups stay in cache for all the steps
  constexpr int kBlock = 4 * kLanes;
  for (int b = begin; b < end; b += kBlock) {
    const int e = std::min(end, b + kBlock);
    for (long s = 0; s < steps; ++s)
      for (int i0 = b; i0 < e; i0 += kLanes) StepGroup(i0);
  }
}

// the early return of most steps inlined into the group's loop; the measurements are Measure
inline void FlightBatch::Observe(int i, const KernelBefore& before, int lane) {
  Sensors& sensors = *sensors_[i];
  const uint64_t step = sensors.odometry_step++;
  const bool odometry_due = sensors.steps_to_odometry == 0;  // step % divisor == 0
  sensors.steps_to_odometry = (odometry_due ? d_.odometry->divisor : sensors.steps_to_odometry) - 1;
  const bool imu = d_.imu && options_.imu;
  if (!imu && !odometry_due && sensors.queue.empty()) return;  // most steps: nothing to measure
  Measure(i, before, lane, step, odometry_due);
}

void FlightBatch::StepGroup(int i0) {
  const size_t n = n_pad_;
  const int lanes = std::min(kLanes, n_ - i0);  // vehicles in this group (the rest are padding)
  double wind_force[3 * kLanes], wind_moment[3 * kLanes], wind_velocity[3 * kLanes];  // read only with a wind
  double v_before[3 * kLanes], w_before[3 * kLanes], R_before[9 * kLanes];
  const unsigned answered = lanes == kLanes && !lee_groups_.empty() ? RunLeeGroup(i0) : 0u;
  for (int l = 0; l < lanes; ++l) {
    const int i = i0 + l;
    ApplyCommand(i, (answered >> l) & 1u);
    if (!d_.wind) continue;
    // the wind plugin: a force on its link and the wind speed the rotors see (this step's sample)
    const WindDescription& wd = *d_.wind;
    double R[9], p[3];
    for (int c = 0; c < 9; ++c) R[c] = R_WB_[c * n + i];
    for (int c = 0; c < 3; ++c) p[c] = p_W_[c * n + i];
    const double t_s = SimTimeS(steps_[i], dt_ns_);
    rgp::WindSample ws = sensors_[i]->wind->Sample(t_s);
    if (wd.profile) ws.velocity_W = wd.profile->Velocity(t_s);
    if (wd.field) {
      double r_link[3];
      Rotate(R, points_[i].wind_link, r_link);
      Eigen::Vector3d v_field;
      if (wd.field->Velocity({p[0] + r_link[0], p[1] + r_link[1], p[2] + r_link[2]}, &v_field)) ws.velocity_W = v_field;
    }
    double r_f[3], moment[3];
    Rotate(R, points_[i].wind_force, r_f);
    const double f[3] = {ws.force_W[0], ws.force_W[1], ws.force_W[2]};
    Cross(r_f, f, moment);
    for (int c = 0; c < 3; ++c) {
      wind_force[c * kLanes + l] = f[c];
      wind_moment[c * kLanes + l] = moment[c];
      wind_velocity[c * kLanes + l] = ws.velocity_W[c];
    }
  }
  const KernelWind wind{wind_force, wind_moment, wind_velocity};
  const KernelBefore before{v_before, w_before, R_before};
  unsigned touching = 0;
  if (lanes == kLanes) {
    touching = kernels_.group(kernel_model_, kernel_arrays_, i0, wind, before);
  } else {  // a last group of fewer vehicles: each alone (the same step as a lane's, bit for bit)
    for (int l = 0; l < lanes; ++l)
      touching |= StepOneOfGroup(kernels_, kernel_model_, kernel_arrays_, i0 + l, l, wind, before);
  }
  for (int l = 0; l < lanes; ++l) {
    const int i = i0 + l;
    // flags of eight vehicles share a cache line with other groups' (another thread's): written
    // only when they change
    const uint8_t touches = (touching >> l) & 1u;
    if (in_contact_[i] != touches) in_contact_[i] = touches;
    ++steps_[i];
    Observe(i, before, l);
    if (obstacles_ && !collided_[i]) {
      // the sphere's centre: the CoG plus R (c_M - p_M_cog)
      double r_c[3], R[9];
      for (int c = 0; c < 9; ++c) R[c] = R_WB_[c * n + i];
      const Eigen::Vector3d c_B = sphere_center_M_ - airframes_[i].p_M_cog;
      Rotate(R, c_B, r_c);
      const Eigen::Vector3d c_W(p_W_[i] + r_c[0], p_W_[n + i] + r_c[1], p_W_[2 * n + i] + r_c[2]);
      if (obstacles_->SphereTouches(i, c_W, sphere_radius_m_)) collided_[i] = 1;
    }
  }
}

void FlightBatch::ApplyCommand(int i, bool answered) {
  const size_t n = n_pad_;
  const double* c = &commands_[i * command_columns_];
  bool new_target = true;
  switch (options_.mode) {
    case CommandMode::kRotorSpeeds:
      for (int r = 0; r < r_; ++r) command_target_[r * n + i] = c[r];
      break;
    case CommandMode::kNormalizedThrust:
      // thrust = u T_max = u C_T omega_max^2  ->  omega = omega_max sqrt(u)
      for (int r = 0; r < r_; ++r) command_target_[r * n + i] = max_rot_velocity_[r * n + i] * std::sqrt(c[r]);
      break;
    default:
      // a controller answers a new odometry message, as World.attach_controller (and the ROS node) does
      new_target = answered || odometry_count_[i] != controller_seen_[i];
      if (new_target && !answered) RunController(i);
      break;
  }
  // the motors get the command of actuator_delay_steps steps ago (the ring holds the last ones)
  std::vector<double>& ring = delay_rings_[i];
  if (ring.empty()) {
    if (new_target)
      for (int r = 0; r < r_; ++r) motor_command_[r * n + i] = command_target_[r * n + i];
    return;
  }
  double* oldest = &ring[delay_heads_[i] * r_];
  for (int r = 0; r < r_; ++r) {
    motor_command_[r * n + i] = oldest[r];
    oldest[r] = command_target_[r * n + i];
  }
  delay_heads_[i] = (delay_heads_[i] + 1) % airframes_[i].actuator_delay_steps;
}

rotors_control::VehicleState FlightBatch::OdometryState(int i) const {
  const double* o = &odometry_out_[i * 14];
  rotors_control::VehicleState state;
  state.position_W = {o[0], o[1], o[2]};
  const Eigen::Quaterniond q(o[6], o[3], o[4], o[5]);  // as mav_msgs: normalised, identity when ~0
  state.orientation_W_B = q.norm() >= 1.e-6 ? q.normalized() : Eigen::Quaterniond::Identity();
  state.velocity_B = {o[7], o[8], o[9]};
  state.angular_velocity_B = {o[10], o[11], o[12]};
  return state;
}

void FlightBatch::SetLeeReference(int i) {
  const double* c = &commands_[i * command_columns_];
  if (std::isnan(c[0])) return;  // a row of NaN: no set point yet, or the last one kept
  rotors_control::TrajectoryPoint point;
  point.position_W = {c[0], c[1], c[2]};
  point.yaw_rad = c[3];
  controllers_[i]->lee->SetTrajectoryPoint(point);
}

unsigned FlightBatch::RunLeeGroup(int i0) {
  unsigned due = 0;
  for (int l = 0; l < kLanes; ++l)
    if (odometry_count_[i0 + l] != controller_seen_[i0 + l]) due |= 1u << l;
  if (due == 0) return 0;
  LeeInputsT<double> in[kLanes];
  const int first = __builtin_ctz(due);
  for (int l = 0; l < kLanes; ++l) {
    const int i = i0 + l;
    if (!((due >> l) & 1u)) continue;
    SetLeeReference(i);
    in[l] = controllers_[i]->lee->Inputs(OdometryState(i));
  }
  for (int l = 0; l < kLanes; ++l)  // a lane not due computes on the first due lane's inputs, unused
    if (!((due >> l) & 1u)) in[l] = in[first];
  LeeGroupSpeeds omega;
  kernels_.lee_group(r_, lee_groups_[i0 / kLanes], in, omega);
  const size_t n = n_pad_;
  for (int l = 0; l < kLanes; ++l) {
    if (!((due >> l) & 1u)) continue;
    const int i = i0 + l;
    controller_seen_[i] = odometry_count_[i];
    const bool has_reference = controllers_[i]->lee->HasReference();  // none yet: the rotors stay stopped
    for (int r = 0; r < r_; ++r) command_target_[r * n + i] = has_reference ? std::max(0.0, omega[r][l]) : 0.0;
  }
  return due;
}

void FlightBatch::RunController(int i) {
  const size_t n = n_pad_;
  const double* c = &commands_[i * command_columns_];
  controller_seen_[i] = odometry_count_[i];
  const rotors_control::VehicleState state = OdometryState(i);
  Controller& ctrl = *controllers_[i];
  rotors_control::RotorVector speeds;
  switch (options_.mode) {
    case CommandMode::kLeePosition:
      SetLeeReference(i);
      speeds = ctrl.lee->RotorSpeeds(state);
      break;
    case CommandMode::kRollPitchYawrateThrust:
      ctrl.attitude->SetRollPitchYawrateThrust(c[0], c[1], c[2], c[3]);
      speeds = ctrl.attitude->RotorSpeeds(state);
      break;
    case CommandMode::kAttitudeThrust:
      ctrl.attitude->SetAttitudeThrust(Eigen::Quaterniond(c[3], c[0], c[1], c[2]).normalized(), c[4]);
      speeds = ctrl.attitude->RotorSpeeds(state);
      break;
    case CommandMode::kRateThrust:
      ctrl.attitude->SetRateThrust(Eigen::Vector3d(c[0], c[1], c[2]), c[3]);
      speeds = ctrl.attitude->RotorSpeeds(state);
      break;
    default: break;
  }
  for (int r = 0; r < r_; ++r) command_target_[r * n + i] = std::max(0.0, speeds[r]);
}

void FlightBatch::Measure(int i, const KernelBefore& before, int lane, uint64_t step, bool odometry_due) {
  const size_t n = n_pad_;
  Sensors& sensors = *sensors_[i];
  const OdometryDescription& od = *d_.odometry;
  const bool imu = d_.imu && options_.imu;
  double p[3], v[3], w[3], R[9];
  for (int c = 0; c < 3; ++c) {
    p[c] = p_W_[c * n + i];
    v[c] = v_W_[c * n + i];
    w[c] = omega_W_[c * n + i];
  }
  for (int c = 0; c < 9; ++c) R[c] = R_WB_[c * n + i];

  // the IMU plugin: specific force from the velocity change of its point over the step
  if (imu) {
    double v_before_W[3], omega_before_W[3], R_before[9];
    for (int c = 0; c < 3; ++c) {
      v_before_W[c] = before.v_W[c * kLanes + lane];
      omega_before_W[c] = before.omega_W[c * kLanes + lane];
    }
    for (int c = 0; c < 9; ++c) R_before[c] = before.R_WB[c * kLanes + lane];
    double r_now[3], r_then[3], wxr_now[3], wxr_then[3];
    Rotate(R, points_[i].imu, r_now);
    Rotate(R_before, points_[i].imu, r_then);
    Cross(w, r_now, wxr_now);
    Cross(omega_before_W, r_then, wxr_then);
    const Eigen::Matrix3d R_WI = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(R) * R_BI_;
    Eigen::Vector3d a_W;
    for (int c = 0; c < 3; ++c) a_W[c] = ((v[c] + wxr_now[c]) - (v_before_W[c] + wxr_then[c])) / dt_;
    rgp::ImuSample sample{R_WI.transpose() * Eigen::Vector3d(w[0], w[1], w[2]),
                          R_WI.transpose() * (a_W - d_.gravity_W)};
    if (sensors.imu_noise) sample = sensors.imu_noise->Corrupt(sample, dt_);
    for (int c = 0; c < 3; ++c) {
      imu_out_[i * 6 + c] = sample.angular_velocity_I[c];
      imu_out_[i * 6 + 3 + c] = sample.linear_acceleration_I[c];
    }
  }

  // the odometry plugin: every divisor-th step, published delay steps later
  if (odometry_due) {
    const Eigen::Quaterniond q_WB(q_WB_[0 * n + i], q_WB_[1 * n + i], q_WB_[2 * n + i], q_WB_[3 * n + i]);
    const double t_s = SimTimeS(steps_[i], dt_ns_);
    rgp::OdometryMeasurement m;
    double r_s[3], wxr[3], v_s[3], v_S[3], w_S[3];
    Rotate(R, points_[i].odometry, r_s);
    Cross(w, r_s, wxr);
    for (int c = 0; c < 3; ++c) v_s[c] = v[c] + wxr[c];
    m.q_WS = q_WB * od.mount.q_BS;
    const Eigen::Matrix3d R_WS = m.q_WS.toRotationMatrix();
    m.p_W = {p[0] + r_s[0], p[1] + r_s[1], p[2] + r_s[2]};
    for (int c = 0; c < 3; ++c) {
      v_S[c] = R_WS(0, c) * v_s[0] + R_WS(1, c) * v_s[1] + R_WS(2, c) * v_s[2];
      w_S[c] = R_WS(0, c) * w[0] + R_WS(1, c) * w[1] + R_WS(2, c) * w[2];
    }
    m.v_S = {v_S[0], v_S[1], v_S[2]};
    m.omega_S = {w_S[0], w_S[1], w_S[2]};
    const Sensors::Pending pending{step + od.delay_steps, t_s + od.unknown_delay_s, m};
    if (od.delay_steps == 0 && sensors.queue.empty()) {
      Publish(i, pending.stamp_s, pending.truth);  // due now: no queue
    } else {
      sensors.queue.push_back(pending);
    }
  }
  while (!sensors.queue.empty() && sensors.queue.front().publish_at_step <= step) {
    Publish(i, sensors.queue.front().stamp_s, sensors.queue.front().truth);
    sensors.queue.pop_front();
  }
}

void FlightBatch::Publish(int i, double stamp_s, const rgp::OdometryMeasurement& truth) {
  Sensors& sensors = *sensors_[i];
  const rgp::OdometryMeasurement m = sensors.odometry_noise ? sensors.odometry_noise->Corrupt(truth) : truth;
  double* o = &odometry_out_[i * 14];
  o[0] = m.p_W.x(), o[1] = m.p_W.y(), o[2] = m.p_W.z();
  o[3] = m.q_WS.x(), o[4] = m.q_WS.y(), o[5] = m.q_WS.z(), o[6] = m.q_WS.w();
  o[7] = m.v_S.x(), o[8] = m.v_S.y(), o[9] = m.v_S.z();
  o[10] = m.omega_S.x(), o[11] = m.omega_S.y(), o[12] = m.omega_S.z();
  o[13] = stamp_s;
  ++odometry_count_[i];
}

double* FlightBatch::RotorSpeeds() {
  const size_t n = n_pad_;
  for (int i = 0; i < n_; ++i)
    for (int r = 0; r < r_; ++r)
      rotor_speed_out_[i * r_ + r] = d_.rotors[r].params.turning_direction * omega_rotor_[r * n + i];
  return rotor_speed_out_.data();
}

double* FlightBatch::Truth() {
  const size_t n = n_pad_;
  for (size_t i = 0; i < static_cast<size_t>(n_); ++i) {
    double R[9], r_cog[3], w[3], wxr[3], w_B[3];
    for (int c = 0; c < 9; ++c) R[c] = R_WB_[c * n + i];
    for (int c = 0; c < 3; ++c) w[c] = omega_W_[c * n + i];
    Rotate(R, airframes_[i].p_M_cog, r_cog);
    const double r_m[3] = {-r_cog[0], -r_cog[1], -r_cog[2]};  // the model origin from the CoG
    Cross(w, r_m, wxr);
    RotateBack(R, w, w_B);
    double* t = &truth_out_[i * 13];
    for (int c = 0; c < 3; ++c) {
      t[c] = p_W_[c * n + i] + r_m[c];
      t[7 + c] = v_W_[c * n + i] + wxr[c];
      t[10 + c] = w_B[c];
    }
    t[3] = q_WB_[1 * n + i], t[4] = q_WB_[2 * n + i], t[5] = q_WB_[3 * n + i], t[6] = q_WB_[0 * n + i];
  }
  return truth_out_.data();
}

}  // namespace rotors_flight_batch
