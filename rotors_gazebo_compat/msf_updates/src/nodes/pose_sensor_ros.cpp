// msf_updates/pose_sensor: see pose_sensor_node.h.
#include "pose_sensor_node.h"

#include <cmath>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <boost/make_shared.hpp>
#include <ros/ros.h>
#include <sensor_fusion_comm/DoubleArrayStamped.h>
#include <sensor_fusion_comm/DoubleMatrixStamped.h>
#include <sensor_fusion_comm/InitHeight.h>
#include <sensor_fusion_comm/InitScale.h>
#include <sensor_msgs/Imu.h>
#include <tf2_ros/transform_broadcaster.h>

#include "msf_updates/ekf/pose_ekf.h"
#include "rotors_params/ros_param_reader.h"

namespace msf_updates {
namespace {

/// MSF's parameters all have defaults (as upstream): one that is absent is announced with the value
/// used, and a key below core/ or pose_sensor/ that nobody reads is reported by name.
class ParamReader {
 public:
  explicit ParamReader(const ros::NodeHandle& private_nh) : reader_(private_nh) {}
  template <typename T>
  T Get(const std::string& key, const T& fallback) {
    return reader_.Get(key, fallback);
  }
  void ReportDefaults() const {
    std::string list;
    for (const std::string& d : reader_.Defaults()) list += (list.empty() ? "" : ", ") + d;
    if (!list.empty()) ROS_INFO("[msf] not given, defaults used: %s", list.c_str());
  }
  void WarnUnread(const std::vector<std::string>& namespaces) const {
    for (const std::string& name : reader_.UnknownKeys(namespaces))
      ROS_WARN("[msf] parameter %s is not a parameter of this estimator and is ignored (check its spelling)",
               name.c_str());
  }

 private:
  rotors_params::RosParamReader reader_;
};

/// Throttles a warning on wall time (ROS_WARN_THROTTLE uses ros::Time, which stands still before
/// the simulator's first /clock, exactly when bad input is most worth reporting).
class WallThrottle {
 public:
  explicit WallThrottle(double period_s) : period_s_(period_s) {}
  bool Ready() {
    const ros::WallTime now = ros::WallTime::now();
    if (!last_.isZero() && (now - last_).toSec() < period_s_) return false;
    last_ = now;
    return true;
  }

 private:
  double period_s_;
  ros::WallTime last_;
};

template <typename XyzMsg>
XyzMsg ToXyz(const Eigen::Vector3d& v) {  // geometry_msgs Point / Vector3
  XyzMsg m;
  m.x = v.x();
  m.y = v.y();
  m.z = v.z();
  return m;
}

geometry_msgs::Quaternion ToMsg(const Eigen::Quaterniond& q) {
  geometry_msgs::Quaternion m;
  m.w = q.w();
  m.x = q.x();
  m.y = q.y();
  m.z = q.z();
  return m;
}

bool AllFinite(std::initializer_list<double> values) {
  for (double v : values)
    if (!std::isfinite(v)) return false;
  return true;
}

}  // namespace

class PoseSensorNode::Impl {
 public:
  Impl(ros::NodeHandle nh, ros::NodeHandle pnh) : nh_(nh), pnh_(pnh) {
    ParamReader p(pnh);
    CoreNoiseParams core;
    core.core_noise_acc = p.Get("core/core_noise_acc", core.core_noise_acc);
    core.core_noise_accbias = p.Get("core/core_noise_accbias", core.core_noise_accbias);
    core.core_noise_gyr = p.Get("core/core_noise_gyr", core.core_noise_gyr);
    core.core_noise_gyrbias = p.Get("core/core_noise_gyrbias", core.core_noise_gyrbias);
    core.core_fixed_bias = p.Get("core/core_fixed_bias", core.core_fixed_bias);
    core.gravity_m_s2 = p.Get("core/core_gravity", core.gravity_m_s2);
    InitialUncertainty init;
    init.sigma_v_m_s = p.Get("core/core_init_sigma_v", init.sigma_v_m_s);
    init.sigma_b_w_rad_s = p.Get("core/core_init_sigma_gyrbias", init.sigma_b_w_rad_s);
    init.sigma_b_a_m_s2 = p.Get("core/core_init_sigma_accbias", init.sigma_b_a_m_s2);
    const double buffer_s = p.Get("core/core_state_buffer_length", 3.0);
    p.Get("core/data_playback", false);  // MSF: take the stamps of the messages, not the arrival time (always)
    output_frame_ = p.Get<std::string>("core/msf_output_frame", "world");
    child_frame_ = p.Get<std::string>("core/odometry_child_frame", "imu");
    tf_target_frame_ = p.Get<std::string>("core/tf_target_frame", "state");
    const bool tcp_no_delay = p.Get("core/enable_tcp_no_delay", true);

    PoseSensorParams pose;
    pose.p_ic = Eigen::Vector3d(p.Get("pose_sensor/init/p_ic/x", 0.0), p.Get("pose_sensor/init/p_ic/y", 0.0),
                                p.Get("pose_sensor/init/p_ic/z", 0.0));
    pose.q_ic = Eigen::Quaterniond(p.Get("pose_sensor/init/q_ic/w", 1.0), p.Get("pose_sensor/init/q_ic/x", 0.0),
                                   p.Get("pose_sensor/init/q_ic/y", 0.0), p.Get("pose_sensor/init/q_ic/z", 0.0));
    pose.scale = p.Get("pose_sensor/pose_initial_scale", 1.0);
    pose.pose_noise_meas_p = p.Get("pose_sensor/pose_noise_meas_p", pose.pose_noise_meas_p);
    pose.pose_noise_meas_q = p.Get("pose_sensor/pose_noise_meas_q", pose.pose_noise_meas_q);
    pose.pose_delay_s = p.Get("pose_sensor/pose_delay", pose.pose_delay_s);
    pose.pose_use_fixed_covariance = p.Get("pose_sensor/pose_use_fixed_covariance", false);
    pose.pose_measurement_minimum_dt_s = p.Get("pose_sensor/pose_measurement_minimum_dt", 0.05);
    pose.enable_mah_outlier_rejection = p.Get("pose_sensor/enable_mah_outlier_rejection", false);
    pose.mah_threshold = p.Get("pose_sensor/mah_threshold", pose.mah_threshold);
    // What this estimator does not do (yet) is refused by name, not ignored.
    if (!p.Get("pose_sensor/pose_measurement_world_sensor", true))
      Refuse(
          "pose_sensor/pose_measurement_world_sensor: false (a sensor measuring the world in its own frame, "
          "PTAM style) is not supported; set it to true");
    if (!p.Get("pose_sensor/pose_absolute_measurements", true))
      Refuse("pose_sensor/pose_absolute_measurements: false (relative pose updates) is not supported; set it to true");
    for (const char* aux : {"scale", "p_ic", "q_ic", "p_wv", "q_wv"}) {
      const std::string fixed = std::string("pose_sensor/pose_fixed_") + aux;
      if (!p.Get(fixed, true))
        Refuse(fixed + ": false: estimating " + aux + " online is not supported; set it to true (" + aux +
               " is then held at its initial value)");
      p.Get(std::string("pose_sensor/pose_noise_") + aux, 0.0);  // process noise of a fixed state: unused
    }
    p.WarnUnread({"core", "pose_sensor"});
    p.ReportDefaults();

    ekf_ = std::make_unique<PoseEkf>(core, pose, init, buffer_s);
    ROS_INFO(
        "[msf] pose_sensor: p_ic (%.3f, %.3f, %.3f), q_ic (w %.4f, %.4f, %.4f, %.4f), pose_delay %.3f s, "
        "Mahalanobis gate %s; call %s to initialise",
        pose.p_ic.x(), pose.p_ic.y(), pose.p_ic.z(), pose.q_ic.w(), pose.q_ic.x(), pose.q_ic.y(), pose.q_ic.z(),
        pose.pose_delay_s, pose.enable_mah_outlier_rejection ? "on" : "off",
        pnh_.resolveName("pose_sensor/initialize_msf_scale").c_str());

    const ros::TransportHints hints = tcp_no_delay ? ros::TransportHints().tcpNoDelay() : ros::TransportHints();
    subs_.push_back(nh_.subscribe("msf_core/imu_state_input", 100, &Impl::OnImu, this, hints));
    subs_.push_back(
        nh_.subscribe("msf_updates/pose_with_covariance_input", 20, &Impl::OnPoseWithCovariance, this, hints));
    subs_.push_back(nh_.subscribe("msf_updates/pose_input", 20, &Impl::OnPose, this, hints));
    subs_.push_back(nh_.subscribe("msf_updates/transform_input", 20, &Impl::OnTransform, this, hints));
    subs_.push_back(nh_.subscribe("msf_updates/odometry_input", 20, &Impl::OnOdometry, this, hints));
    odometry_pub_ = nh_.advertise<nav_msgs::Odometry>("msf_core/odometry", 100);
    pose_pub_ = nh_.advertise<geometry_msgs::PoseWithCovarianceStamped>("msf_core/pose", 100);
    pose_after_update_pub_ = nh_.advertise<geometry_msgs::PoseWithCovarianceStamped>("msf_core/pose_after_update", 20);
    state_pub_ = nh_.advertise<sensor_fusion_comm::DoubleArrayStamped>("msf_core/state_out", 100);
    cov_pub_ = nh_.advertise<sensor_fusion_comm::DoubleMatrixStamped>("msf_core/cov_core", 100);
    init_scale_srv_ = pnh_.advertiseService("pose_sensor/initialize_msf_scale", &Impl::OnInitScale, this);
    init_height_srv_ = pnh_.advertiseService("pose_sensor/initialize_msf_height", &Impl::OnInitHeight, this);
  }

 private:
  /// A shared copy: in the simulator's process (a nodelet) the controller gets it at once, not when
  /// roscpp's poll thread gets to a serialized message.
  template <class M>
  static void Publish(const ros::Publisher& pub, const M& msg) {
    if (pub.getNumSubscribers() > 0) pub.publish(boost::make_shared<M>(msg));
  }

  [[noreturn]] static void Refuse(const std::string& why) { throw std::invalid_argument(why); }

  void OnImu(const sensor_msgs::ImuConstPtr& msg) {
    const auto& w = msg->angular_velocity;
    const auto& a = msg->linear_acceleration;
    if (!AllFinite({w.x, w.y, w.z, a.x, a.y, a.z})) {
      if (bad_imu_warning_.Ready())
        ROS_WARN("[msf] IMU message at t = %.3f s has non-finite values; dropped", msg->header.stamp.toSec());
      return;
    }
    ImuReading u;
    u.t_s = msg->header.stamp.toSec();
    u.omega_m_I = Eigen::Vector3d(w.x, w.y, w.z);
    u.a_m_I = Eigen::Vector3d(a.x, a.y, a.z);
    if (!ekf_->AddImu(u)) {
      if (!ekf_->Initialized())
        if (not_initialised_warning_.Ready())
          ROS_WARN("[msf] not initialised: call %s", pnh_.resolveName("pose_sensor/initialize_msf_scale").c_str());
      return;
    }
    PublishState(msg->header.stamp);
  }

  void OnPoseWithCovariance(const geometry_msgs::PoseWithCovarianceStampedConstPtr& msg) {
    AddPose(msg->header, msg->pose);
  }
  void OnPose(const geometry_msgs::PoseStampedConstPtr& msg) {
    AddPose(msg->header, msg->pose.position, msg->pose.orientation, nullptr);
  }
  void OnTransform(const geometry_msgs::TransformStampedConstPtr& msg) {
    const auto& t = msg->transform.translation;
    AddPose(msg->header, ToXyz<geometry_msgs::Point>(Eigen::Vector3d(t.x, t.y, t.z)), msg->transform.rotation, nullptr);
  }
  void OnOdometry(const nav_msgs::OdometryConstPtr& msg) { AddPose(msg->header, msg->pose); }

  void AddPose(const std_msgs::Header& header, const geometry_msgs::PoseWithCovariance& pose) {
    const Matrix6d R = Eigen::Map<const Eigen::Matrix<double, 6, 6, Eigen::RowMajor>>(pose.covariance.data());
    AddPose(header, pose.pose.position, pose.pose.orientation, &R);
  }

  void AddPose(const std_msgs::Header& header, const geometry_msgs::Point& p, const geometry_msgs::Quaternion& q,
               const Matrix6d* covariance) {
    PoseMeasurement z;
    z.t_s = header.stamp.toSec();
    z.p_m_W = Eigen::Vector3d(p.x, p.y, p.z);
    z.q_m_WC = Eigen::Quaterniond(q.w, q.x, q.y, q.z);
    if (!z.p_m_W.allFinite() || !z.q_m_WC.coeffs().allFinite() || std::abs(z.q_m_WC.norm() - 1.0) > 1e-2) {
      if (bad_pose_warning_.Ready())
        ROS_WARN(
            "[msf] pose at t = %.3f s has a non-finite position or a non-unit quaternion "
            "(norm %.3f); dropped",
            z.t_s, z.q_m_WC.norm());
      return;
    }
    z.q_m_WC.normalize();
    const PoseSensorParams& s = ekf_->PoseParams();
    const bool usable = covariance && covariance->allFinite() && (covariance->diagonal().array() > 0.0).all();
    if (usable) {
      z.R.setZero();
      z.R.topLeftCorner<3, 3>() = covariance->topLeftCorner<3, 3>();
      z.R.bottomRightCorner<3, 3>() = covariance->bottomRightCorner<3, 3>();
    } else {
      if (covariance && !s.pose_use_fixed_covariance)
        ROS_WARN_ONCE("[msf] pose covariance has a non-positive diagonal; using pose_noise_meas_p/q instead");
      z.R = s.FixedCovariance();
    }
    const PoseStatus status = ekf_->AddPose(z);
    if (status == PoseStatus::kApplied) {
      if (pose_after_update_pub_.getNumSubscribers() > 0) {
        geometry_msgs::PoseWithCovarianceStamped out;
        FillPose(ekf_->StateAt(z.t_s - s.pose_delay_s), header.stamp, &out);
        Publish(pose_after_update_pub_, out);
      }
    } else if ((status == PoseStatus::kTooOld && z.t_s >= init_time_s_) || status == PoseStatus::kRejectedOutlier) {
      if (refused_pose_warning_.Ready())
        ROS_WARN("[msf] pose at t = %.3f s %s (Mahalanobis distance %.1f)", z.t_s, ToString(status),
                 ekf_->LastMahalanobis());
    }
  }

  void FillPose(const CoreState& x, const ros::Time& stamp, geometry_msgs::PoseWithCovarianceStamped* out) const {
    out->header.stamp = stamp;
    out->header.frame_id = output_frame_;
    ToPose(x, &out->pose);
  }

  static void ToPose(const CoreState& x, geometry_msgs::PoseWithCovariance* out) {
    out->pose.position = ToXyz<geometry_msgs::Point>(x.p_W);
    out->pose.orientation = ToMsg(x.q_WI);
    // [p, theta] blocks of P; theta is the attitude error in the IMU frame
    const int rows[6] = {idx::kP, idx::kP + 1, idx::kP + 2, idx::kTheta, idx::kTheta + 1, idx::kTheta + 2};
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) out->covariance[i * 6 + j] = x.P(rows[i], rows[j]);
  }

  void PublishState(const ros::Time& stamp) {
    const CoreState& x = ekf_->State();
    const ImuReading& u = ekf_->LatestImu();
    if (odometry_pub_.getNumSubscribers() > 0) {
      nav_msgs::Odometry odom;
      odom.header.stamp = stamp;
      odom.header.frame_id = output_frame_;
      odom.child_frame_id = child_frame_;
      ToPose(x, &odom.pose);
      // twist in the IMU (body) frame, as RotorS' odometry: v_I = C(q)^T v_W, omega = omega_m - b_w
      const Eigen::Matrix3d C_T = x.q_WI.toRotationMatrix().transpose();
      const Eigen::Vector3d v_I = C_T * x.v_W, omega_I = u.omega_m_I - x.b_w;
      odom.twist.twist.linear = ToXyz<geometry_msgs::Vector3>(v_I);
      odom.twist.twist.angular = ToXyz<geometry_msgs::Vector3>(omega_I);
      const Eigen::Matrix3d P_v_I = C_T * x.P.block<3, 3>(idx::kV, idx::kV) * C_T.transpose();
      const Eigen::Matrix3d P_w = x.P.block<3, 3>(idx::kBw, idx::kBw);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          odom.twist.covariance[i * 6 + j] = P_v_I(i, j);
          odom.twist.covariance[(i + 3) * 6 + j + 3] = P_w(i, j);
        }
      Publish(odometry_pub_, odom);
    }
    if (pose_pub_.getNumSubscribers() > 0) {
      geometry_msgs::PoseWithCovarianceStamped pose;
      FillPose(x, stamp, &pose);
      Publish(pose_pub_, pose);
    }
    if (state_pub_.getNumSubscribers() > 0) {
      // MSF's full state in enum order: p, v, q(w,x,y,z), b_w, b_a, L, q_wv, p_wv, q_ic, p_ic (31)
      const PoseSensorParams& s = ekf_->PoseParams();
      sensor_fusion_comm::DoubleArrayStamped state;
      state.header.stamp = stamp;
      state.header.frame_id = output_frame_;
      auto& d = state.data;
      auto push3 = [&d](const Eigen::Vector3d& v) { d.insert(d.end(), {v.x(), v.y(), v.z()}); };
      auto push_q = [&d](const Eigen::Quaterniond& q) { d.insert(d.end(), {q.w(), q.x(), q.y(), q.z()}); };
      push3(x.p_W);
      push3(x.v_W);
      push_q(x.q_WI);
      push3(x.b_w);
      push3(x.b_a);
      d.push_back(s.scale);
      push_q(Eigen::Quaterniond::Identity());
      push3(Eigen::Vector3d::Zero());
      push_q(s.q_ic);
      push3(s.p_ic);
      Publish(state_pub_, state);
    }
    if (cov_pub_.getNumSubscribers() > 0) {
      sensor_fusion_comm::DoubleMatrixStamped cov;
      cov.header.stamp = stamp;
      cov.header.frame_id = output_frame_;
      cov.rows = cov.cols = 15;
      cov.data.resize(225);
      Eigen::Map<Eigen::Matrix<double, 15, 15, Eigen::RowMajor>>(cov.data.data()) = x.P;
      Publish(cov_pub_, cov);
    }
    geometry_msgs::TransformStamped tf;
    tf.header.stamp = stamp;
    tf.header.frame_id = output_frame_;
    tf.child_frame_id = tf_target_frame_;
    tf.transform.translation = ToXyz<geometry_msgs::Vector3>(x.p_W);
    tf.transform.rotation = ToMsg(x.q_WI);
    tf_broadcaster_.sendTransform(tf);
  }

  bool OnInitScale(sensor_fusion_comm::InitScale::Request& req, sensor_fusion_comm::InitScale::Response& res) {
    const std::string why = ekf_->InitializeScale(req.scale);
    if (why.empty()) init_time_s_ = ekf_->State().t_s;
    res.result = why.empty() ? "Initialized scale" : "Not initialized: " + why;
    if (why.empty()) ROS_INFO("[msf] initialised with scale %.3f", req.scale);
    else if (refused_init_warning_.Ready()) ROS_WARN("[msf] initialize_msf_scale: %s", why.c_str());
    return true;
  }

  bool OnInitHeight(sensor_fusion_comm::InitHeight::Request& req, sensor_fusion_comm::InitHeight::Response& res) {
    const std::string why = ekf_->InitializeHeight(req.height);
    if (why.empty()) init_time_s_ = ekf_->State().t_s;
    res.result = why.empty() ? "Initialized by known height" : "Not initialized: " + why;
    if (why.empty()) ROS_INFO("[msf] initialised at height %.3f m (scale %.3f)", req.height, ekf_->PoseParams().scale);
    else if (refused_init_warning_.Ready()) ROS_WARN("[msf] initialize_msf_height: %s", why.c_str());
    return true;
  }

  ros::NodeHandle nh_, pnh_;
  std::unique_ptr<PoseEkf> ekf_;
  std::string output_frame_, child_frame_, tf_target_frame_;
  std::vector<ros::Subscriber> subs_;
  ros::Publisher odometry_pub_, pose_pub_, pose_after_update_pub_, state_pub_, cov_pub_;
  ros::ServiceServer init_scale_srv_, init_height_srv_;
  WallThrottle bad_imu_warning_{1.0}, bad_pose_warning_{1.0}, refused_pose_warning_{1.0}, not_initialised_warning_{5.0},
      refused_init_warning_{1.0};  // the response carries every refusal; the log gets one a second
  double init_time_s_ = 0.0;       ///< poses captured before initialisation are old news, not worth a warning
  tf2_ros::TransformBroadcaster tf_broadcaster_;
};

PoseSensorNode::PoseSensorNode(ros::NodeHandle nh, ros::NodeHandle pnh) : impl_(std::make_unique<Impl>(nh, pnh)) {}

PoseSensorNode::~PoseSensorNode() = default;

}  // namespace msf_updates
