// The batched flight engine: N copies of one multirotor, their state in structure of arrays, all
// stepped by one call on a pool of threads. Per vehicle and physics step it does what the full
// world does with the same models: the motor plugins' RotorModel forces (book eqs. 1-5) from the
// rotor speeds of the last step, then their first-order speed dynamics; the wind plugin's WindModel
// (and field or profile); the rotors' spin moments of the kinematic joints; gravity; the solver's
// free-body step (free_body_step.h: ODE's, to rounding); then the odometry plugin (divisor, delay,
// OdometryNoise) and the IMU plugin (ImuNoiseModel). A controller of rotors_control (Lee position,
// roll-pitch-yawrate-thrust, attitude-thrust, rate-thrust) answers every new odometry message, as
// World.attach_controller does. What it leaves out: collisions other than its corners on the
// ground plane z = 0 (a penalty contact), cameras, lasers and the plugins that only measure. What it
// adds for learning: static obstacles per vehicle (obstacle_field.h), a collision flag when the
// vehicle's sphere touches one, and a low-resolution depth camera cast against them and the ground.
// No ROS, no engine: see vehicle_description.h for where its numbers come from.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include "rotors_control/attitude_controllers.h"
#include "rotors_control/lee_controller.h"
#include "rotors_flight_batch/flight_kernel.h"
#include "rotors_flight_batch/obstacle_field.h"
#include "rotors_gazebo_plugins/models/depth_noise_model.h"
#include "rotors_flight_batch/vehicle_description.h"

namespace rotors_flight_batch {

/// The allocator of a vector whose data starts on a cache line (64 bytes). The batch's per-vehicle
/// arrays use it: a group's kGroupLanes values of a component, or their rows of doubles, then fill
/// whole lines, so the pool's threads (which step whole groups) never write the same line.
template <class T>
struct CacheLineAllocator {
  using value_type = T;
  CacheLineAllocator() = default;
  template <class U>
  explicit CacheLineAllocator(const CacheLineAllocator<U>&) {}
  T* allocate(size_t n) { return static_cast<T*>(::operator new (n * sizeof(T), std::align_val_t{64})); }
  void deallocate(T* p, size_t) { ::operator delete (p, std::align_val_t{64}); }
  template <class U>
  bool operator==(const CacheLineAllocator<U>&) const {
    return true;
  }
  template <class U>
  bool operator!=(const CacheLineAllocator<U>&) const {
    return false;
  }
};
template <class T>
using LineVector = std::vector<T, CacheLineAllocator<T>>;

/// What the `commands` array holds, one row per vehicle.
enum class CommandMode {
  kRotorSpeeds,             ///< rotor speeds [rad/s] (R columns), every step
  kNormalizedThrust,        ///< thrust of each rotor as a fraction of its maximum, 0..1 (R columns)
  kLeePosition,             ///< x, y, z [m], yaw [rad]: Lee's controller at every odometry; a row of
                            ///< NaN: no set point yet (rotors stopped until the first, as the node)
  kRollPitchYawrateThrust,  ///< roll, pitch [rad], yaw rate [rad/s], thrust [N]
  kAttitudeThrust,          ///< q_WD (x, y, z, w), thrust [N]
  kRateThrust,              ///< body rates [rad/s] (3), thrust [N]
};

/// The mode of a name: rotor_speeds, normalized_thrust, lee_position, roll_pitch_yawrate_thrust,
/// attitude_thrust, rate_thrust; SimError listing them for any other.
CommandMode ParseCommandMode(const std::string& name);
int CommandColumns(CommandMode mode, int rotors);

/// What may differ between the vehicles of a batch, as the xacro's values would set them in the
/// full world: the solver body's mass, inertia (the lumped body's, about its CoG, body frame) and
/// CoG (in the model frame: moving it moves every point of the vehicle relative to the body's
/// origin, as the solver sees it) and each motor plugin's constants. The rotors' and sensors'
/// places in the model frame and the rotor axes are the description's for every vehicle.
struct Airframe {
  double mass_kg = 0.0;
  Eigen::Matrix3d inertia_B_kg_m2 = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p_M_cog = Eigen::Vector3d::Zero();  ///< [m]
  /// The motors get the rotor speed commanded this many physics steps ago (an ESC's and link's
  /// latency; 0: the same step, as RotorS' motor plugin). After a reset, 0 (stopped) until then.
  int actuator_delay_steps = 0;
  /// The wind plugin's parameters (when the vehicle has one; its field or profile stays the
  /// description's): mean and variance of the wind force and speed, the gust's window, force and
  /// direction. A reset draws the wind from them.
  rotors_gazebo_plugins::WindParams wind;
  /// by motor number: motorConstant, momentConstant, rotorDragCoefficient, rollingMomentCoefficient,
  /// timeConstantUp/Down, maxRotVelocity (0: a failed motor; turningDirection stays the description's)
  std::vector<rotors_gazebo_plugins::RotorParams> rotors;
  /// The odometry plugin's noise (noiseNormalPosition, ...) and the IMU plugin's (gyroscopeNoiseDensity,
  /// ...; when the vehicle has one): each reset draws the vehicle's noise from them and its seed.
  rotors_gazebo_plugins::OdometryNoiseParams odometry_noise;
  rotors_gazebo_plugins::ImuNoiseParams imu_noise;
};

/// The airframe `d` describes (the xacro's).
Airframe AirframeOf(const VehicleDescription& d);

constexpr int kMaxActuatorDelaySteps = 1000;

/// Range rays on every vehicle (a rangefinder's beam, a ring of them): unit directions in the model
/// frame from p_M_m; each reads the distance to the first obstacle, world surface or ground point
/// along it, +inf outside [min_range_m, max_range_m] (REP 117's "no return"). No noise.
struct RangeRays {
  std::vector<Eigen::Vector3d> dirs_M;
  Eigen::Vector3d p_M_m = Eigen::Vector3d::Zero();
  double min_range_m = 0.0, max_range_m = 10.0;
};

/// A depth camera on every vehicle of a batch, looking along the model frame's x axis from p_M_m
/// (a pinhole with the pixel centres of ROS' camera_info: fx = W / (2 tan(hfov / 2)),
/// fy = H / (2 tan(vfov / 2)), so the pixels need not be square). A pixel holds the depth along the
/// optical axis [m] of the first obstacle or ground point its centre's ray meets, with the depth
/// noise model's noise; NaN where that depth is outside (min_range_m, max_range_m). The defaults
/// are the project's RealSense D435 (rgbd_base.xacro: 91.2 deg over 848 x 480, so 60.0 deg
/// vertically; depth from 0.195 m; Intel's D435 noise sigma = z^2 e / (f b) with e = 0.25 px over
/// the 848 px imager, b = 50 mm) at 64 x 48 pixels, to Intel's approximate 10 m maximum range.
struct DepthCameraParams {
  int width_px = 64, height_px = 48;
  double horizontal_fov_rad = 1.59174, vertical_fov_rad = 1.04724;
  double min_range_m = 0.195, max_range_m = 10.0;
  Eigen::Vector3d p_M_m = Eigen::Vector3d::Zero();  ///< where it sits in the model (base_link) frame [m]
  bool noise = true;
  rotors_gazebo_plugins::DepthNoiseParams noise_params = D435Noise();
  static rotors_gazebo_plugins::DepthNoiseParams D435Noise();
  /// "" or why not (sizes < 1 or above 4096, a field of view outside (0, pi), 0 <= min < max, the noise's own check).
  std::string Validate() const;
};

struct FlightBatchOptions {
  int count = 1;
  int threads = 0;  ///< 0: one per core
  CommandMode mode = CommandMode::kRotorSpeeds;
  rotors_control::LeeControllerParameters lee;                    ///< kLeePosition
  std::vector<rotors_control::LeeControllerParameters> lee_each;  ///< per vehicle instead (sweeps)
  rotors_control::AttitudeControllerParameters attitude;          ///< the attitude-level modes
  bool imu = true;    ///< simulate the IMU (with its noise unless noise is false)
  bool noise = true;  ///< sensor and wind noise as the description gives it
  /// Per vehicle, as the xacro's random_seed: each plugin's seed keeps its offset from
  /// `description_seed`, the random_seed the description was spawned with (the odometry draws from
  /// random_seed + 1). Empty: every vehicle the description's seeds.
  std::vector<uint64_t> seeds;
  uint64_t description_seed = 0;
  double contact_stiffness_scale = 1.0;  ///< of the ground contact's spring (see Contact())
  /// The kernels' instruction set: "" the fastest this CPU runs, or avx512, avx2, sse2 (x86-64),
  /// neon (arm64), scalar
  /// (the same step bit for bit; ChooseKernels).
  std::string kernel;
};

class FlightBatch {
 public:
  FlightBatch(VehicleDescription description, FlightBatchOptions options);
  ~FlightBatch();
  FlightBatch(const FlightBatch&) = delete;
  FlightBatch& operator=(const FlightBatch&) = delete;

  int Count() const { return n_; }
  int Rotors() const { return r_; }
  CommandMode Mode() const { return options_.mode; }
  int CommandColumns() const { return command_columns_; }
  int Threads() const { return threads_; }
  /// The instruction set the kernels step with: avx512, avx2, sse2, neon or scalar.
  std::string Kernel() const { return kernels_.instruction_set; }
  const VehicleDescription& Description() const { return d_; }
  double StepSize() const { return dt_; }

  /// Checks every command (finite, in range, a reference for the controllers), then advances every
  /// vehicle `steps` physics steps. On a bad command: SimError naming the vehicle and the value,
  /// and no vehicle moves.
  void Step(long steps);
  /// The description's airframe (every vehicle's until SetAirframe).
  Airframe NominalAirframe() const;
  const Airframe& GetAirframe(int i) const;
  /// Vehicle i flies `airframe` from its next step on (its state is kept: set it at a reset). SimError
  /// naming the vehicle and the bad value (the motor plugin's own checks; mass > 0; an inertia that
  /// is symmetric positive definite), and nothing changes.
  void SetAirframe(int i, const Airframe& airframe);
  /// Vehicle indices[j] flies airframes[j], each checked as SetAirframe checks it; on the first bad
  /// one, SimError naming its vehicle, and no vehicle's airframe changes.
  void SetAirframes(const std::vector<int>& indices, const std::vector<Airframe>& airframes);

  /// Vehicle i flies among environment i's obstacles of `field` (nullptr: none): after every
  /// physics step, Collided()[i] becomes 1 when the vehicle's collision sphere (the sphere around
  /// its collision bounding box, CollisionRadius()) touches one, until its next Reset. SimError when the
  /// field has fewer environments than the batch has vehicles or tests smaller spheres.
  void SetObstacles(std::shared_ptr<const ObstacleField> field);
  const std::shared_ptr<const ObstacleField>& Obstacles() const { return obstacles_; }
  uint8_t* Collided() { return collided_.data(); }
  double CollisionRadius() const { return sphere_radius_m_; }
  /// Every vehicle carries `camera` from now on (std::nullopt: none); its noise is seeded per vehicle
  /// at each Reset, as the other sensors are. SimError naming the bad value.
  void SetDepthCamera(std::optional<DepthCameraParams> camera);
  const std::optional<DepthCameraParams>& DepthCamera() const { return depth_camera_; }
  /// The depth images of `vehicles` now (one H x W image each, in their order, row-major; on the
  /// pool's threads). SimError without a camera or for a vehicle not in the batch.
  void RenderDepth(const std::vector<int>& vehicles, float* out);

  /// Every vehicle carries `rays` from now on (std::nullopt: none); SimError naming a bad direction or range.
  void SetRangeRays(std::optional<RangeRays> rays);
  const std::optional<RangeRays>& GetRangeRays() const { return range_rays_; }
  /// Each vehicle's range per ray now (N x rays [m], +inf: no return; on the pool's threads).
  void CastRanges(double* out);

  /// Vehicle i's random_seed from its next Reset on (a new episode's sensor and wind noise).
  void SetSeed(int i, uint64_t seed);

  /// Vehicles `indices` back to rest at position_M (N x 3, the model frame's origin, as spawned) and
  /// yaw, their time at 0, rotors stopped, sensor and wind noise at their seeds again.
  void Reset(const std::vector<int>& indices, const double* positions_M, const double* yaws);

  // --- arrays shared with Python (row per vehicle) ---
  double* Commands() { return commands_.data(); }  ///< N x CommandColumns()
  /// The last odometry message: position_W (3), orientation (x, y, z, w), velocity_B (3),
  /// angular_velocity_B (3) and its stamp [s]: N x 14.
  double* Odometry() { return odometry_out_.data(); }
  uint64_t* OdometryCount() { return odometry_count_.data(); }
  double* Imu() { return imu_out_.data(); }  ///< N x 6: angular_velocity_I, linear_acceleration_I
  /// Ground truth of the model frame (base_link), N x 13: position_W, orientation (x, y, z, w),
  /// velocity_W (3), angular_velocity_B (3); written by Truth().
  double* Truth();
  double* RotorSpeeds();  ///< N x R signed [rad/s], written at this call
  const uint64_t* Steps() const { return steps_.data(); }
  uint8_t* InContact() { return in_contact_.data(); }
  /// Bytes of per-vehicle state (structure of arrays, the shared arrays included; not the
  /// controllers' and noise models' objects, which ControllerBytes / NoiseBytes report).
  size_t StateBytesPerVehicle() const;
  size_t ControllerBytesPerVehicle() const;
  size_t NoiseBytesPerVehicle() const;

 private:
  struct Controller;
  struct Sensors;
  class Pool;
  void CheckCommands() const;
  uint64_t SeedFor(uint64_t plugin_seed, int i) const;
  static constexpr int kLanes = static_cast<int>(kGroupLanes);  ///< vehicles stepped together by the kernel
  /// Fewer vehicle-steps than this in one call run on the calling thread. The pool's threads spin
  /// between calls, so handing a call to them costs microseconds; 256 vehicle-steps (about 60 ns
  /// each) is where sharing starts to pay on two cores (64 environments' 320 vehicle-steps per
  /// FlightBatchEnv.step ran about a fifth faster on two threads than on one).
  static constexpr long kPoolMinVehicleSteps = 256;
  void BuildKernelModel();
  /// `airframe` as vehicle i flies it (the description's turning directions), or SimError naming the bad value.
  Airframe CheckedAirframe(int i, const Airframe& airframe) const;
  void WriteAirframe(size_t i, const Airframe& airframe);  ///< into the kernel's arrays
  void ParkPaddingLanes();
  void StepRange(int begin, int end, long steps);
  void StepGroup(int i0);
  /// The motors' command of vehicle i for this step; `answered`: its controller has just answered
  /// new odometry in the group's lanes (RunLeeGroup).
  void ApplyCommand(int i, bool answered);
  void RunController(int i);  ///< the controller of vehicle i on its latest odometry
  /// The Lee controllers of the whole group i0 .. i0 + kLanes - 1 in lanes, for the vehicles with new
  /// odometry (each lane equal to its vehicle's RunController); a bit per vehicle that got a new target.
  unsigned RunLeeGroup(int i0);
  rotors_control::VehicleState OdometryState(int i) const;  ///< the latest odometry message, as the node reads it
  void SetLeeReference(int i);  ///< vehicle i's command row as its Lee controller's set point (a row of NaN: none)
  /// The sensors of vehicle i after its step; `before` holds the state before it in row `lane`.
  void Observe(int i, const KernelBefore& before, int lane);
  /// Observe's measurements at odometry step `step` (the IMU, the odometry when due, the queue).
  void Measure(int i, const KernelBefore& before, int lane, uint64_t step, bool odometry_due);
  /// The odometry plugin's Publish: the noise drawn, the message written to the vehicle's row.
  void Publish(int i, double stamp_s, const rotors_gazebo_plugins::OdometryMeasurement& truth);

  VehicleDescription d_;
  FlightBatchOptions options_;
  int n_, r_, command_columns_, threads_;
  size_t n_pad_ = 0;  ///< n_ rounded up to whole groups of lanes (the structure of arrays' stride)
  KernelModel kernel_model_;
  KernelArrays kernel_arrays_{};
  Kernels kernels_{};
  double dt_;
  // constants
  int64_t dt_ns_ = 0;
  Eigen::Matrix3d R_BI_ = Eigen::Matrix3d::Identity();
  // state, structure of arrays: component k of vehicle i at [k * n_pad_ + i]
  LineVector<double> p_W_, v_W_, q_WB_, R_WB_, omega_W_;           ///< the body (CoG), as the solver keeps it
  LineVector<double> omega_rotor_, qdot_applied_, motor_command_;  ///< R per vehicle
  LineVector<double> command_target_;             ///< R per vehicle: what the controller or the commands ask now
  std::vector<std::vector<double>> delay_rings_;  ///< per vehicle: the last actuator_delay_steps commands
  std::vector<int> delay_heads_;
  LineVector<double> wind_velocity_W_;  ///< the wind speed the motors see
  // each vehicle's airframe (KernelAirframes), and as set
  LineVector<double> mass_, inv_mass_, I_B_, inv_I_B_, contact_k_, contact_c_;
  LineVector<double> motor_constant_, rotor_drag_coefficient_, rolling_moment_coefficient_, reaction_factor_;
  LineVector<double> max_rot_velocity_, a_up_, a_down_;
  LineVector<double> p_origin_B_, p_cog_B_, corner_B_, contact_reach_m_;
  std::vector<RotorColumnsOfOne> rotor_columns_;  ///< the same, per vehicle, for the lone-vehicle kernel
  std::vector<Airframe> airframes_;
  /// Each vehicle's points in its body frame that the scalar code reads (the CoG's move applied).
  struct BodyPoints {
    Eigen::Vector3d imu, odometry, wind_link, wind_force;
  };
  std::vector<BodyPoints> points_;
  double contact_w_ = 0.0;      ///< the ground contact's natural frequency [rad/s]
  LineVector<uint64_t> steps_;  ///< steps since the vehicle's reset
  LineVector<uint8_t> has_motor_command_, in_contact_;
  // shared with Python
  LineVector<double> commands_, odometry_out_, imu_out_, truth_out_, rotor_speed_out_;
  LineVector<uint64_t> odometry_count_, controller_seen_;
  std::vector<std::unique_ptr<Controller>> controllers_;
  std::vector<LeeGroupConstants> lee_groups_;  ///< per whole group, its controllers' constants in lanes
  std::vector<std::unique_ptr<Sensors>> sensors_;
  std::unique_ptr<Pool> pool_;
  // obstacles and the depth camera
  std::shared_ptr<const ObstacleField> obstacles_;
  LineVector<uint8_t> collided_;
  Eigen::Vector3d sphere_center_M_ = Eigen::Vector3d::Zero();  ///< the collision sphere's centre, model frame
  double sphere_radius_m_ = 0.0;
  std::optional<DepthCameraParams> depth_camera_;
  std::vector<Eigen::Vector3d> depth_dirs_M_;  ///< per pixel: its ray, a unit vector in the model frame
  std::vector<double> depth_per_distance_;     ///< per pixel: depth along the axis per metre of ray
  std::vector<std::unique_ptr<rotors_gazebo_plugins::DepthNoiseModel>> depth_noise_;
  std::optional<RangeRays> range_rays_;
  void SeedDepthNoise(int i);
  /// Casts dirs_M (model frame) of vehicle i from p_M against its obstacles and the ground: the
  /// distances t_m (+inf: nothing within far_m), the directions in the world in *dirs_W.
  void CastFromVehicle(int i, const Eigen::Vector3d& p_M, const std::vector<Eigen::Vector3d>& dirs_M, double far_m,
                       std::vector<Eigen::Vector3d>* dirs_W, double* t_m) const;
  /// work(begin, end) over 0..count - 1 (vehicles or a list of them), split across the pool's threads.
  void Split(int count, const std::function<void(int, int)>& work);
};

}  // namespace rotors_flight_batch
