// Estimator tests against physics and statistics: exact IMU integration where it is exact,
// filter consistency (NEES inside chi-square bounds over Monte Carlo runs), delayed poses fused
// as if on time, bias estimation, outages, outlier rejection.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "truth_simulator.h"

namespace msf_updates {
namespace {

CoreNoiseParams SimulatorNoise() {  // msf_simulator.yaml: the ADIS16448 model of the simulated IMU
  CoreNoiseParams p;
  p.core_noise_acc = 0.004;
  p.core_noise_accbias = 0.006;
  p.core_noise_gyr = 0.0003394;
  p.core_noise_gyrbias = 0.000038785;
  p.gravity_m_s2 = 9.8;
  return p;
}

PoseSensorParams MountedSensor() {  // firefly_generic_pose_sensor: xyz (0.03, -0.07, 0.1), rpy (0.2, -0.1, 0.3)
  PoseSensorParams p;
  p.p_ic = Eigen::Vector3d(0.03, -0.07, 0.1);
  p.q_ic = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(-0.1, Eigen::Vector3d::UnitY()) *
           Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX());
  p.pose_noise_meas_p = 0.01;
  p.pose_noise_meas_q = 0.017;
  p.pose_delay_s = 0.0;
  return p;
}

struct RunOptions {
  int steps = 3000;                 ///< 100 Hz IMU
  int pose_divisor = 10;            ///< 10 Hz pose
  int delivery_delay_steps = 0;     ///< the pose reaches the filter this many IMU steps after capture
  bool stamp_with_arrival = false;  ///< a filter that ignores the delay: stamp = arrival time
  double outage_from_s = -1, outage_to_s = -1;
  double motion_scale = 1.0;
  double compare_at_s = 29.95;
};

struct RunResult {
  std::vector<double> t_s, nees;
  std::vector<Vector15d> error;
  std::vector<Matrix15d> P;
  CoreState final_truth, final_estimate;
  CoreState estimate_at_compare;  ///< buffered estimate at RunOptions::compare_at_s, read after the run
  double min_eigenvalue = 1e300, max_asymmetry = 0.0;
};

RunResult Fly(uint64_t seed, const RunOptions& o, const PoseSensorParams& sensor = MountedSensor()) {
  const InitialUncertainty init;
  TruthSimulator truth(SimulatorNoise(), sensor, init, seed, o.motion_scale);
  PoseEkf ekf(SimulatorNoise(), sensor, init);
  std::deque<std::pair<int, PoseMeasurement>> in_flight;  // (arrival step, measurement)
  RunResult r;
  for (int k = 0; k <= o.steps; ++k) {
    const TruthSample s = truth.Step(k);
    const double t = s.x.t_s;
    const bool outage = t >= o.outage_from_s && t < o.outage_to_s;
    ekf.AddImu(s.imu);
    if (k == 0) {  // initialised on the first pose, as the init service does
      ekf.AddPose(truth.Measure(s.x));
      EXPECT_EQ(ekf.InitializeScale(1.0), "");
    } else if (k % o.pose_divisor == 0 && !outage) {
      in_flight.push_back({k + o.delivery_delay_steps, truth.Measure(s.x)});
    }
    while (!in_flight.empty() && in_flight.front().first <= k) {
      PoseMeasurement z = in_flight.front().second;
      if (o.stamp_with_arrival) z.t_s = t;
      in_flight.pop_front();
      ekf.AddPose(z);
    }
    const CoreState& x = ekf.State();
    const Vector15d e = ErrorState(s.x, x);
    r.t_s.push_back(t);
    r.error.push_back(e);
    r.P.push_back(x.P);
    r.nees.push_back(e.dot(x.P.ldlt().solve(e)));
    if (k % 50 == 0) {
      r.min_eigenvalue = std::min(r.min_eigenvalue, Eigen::SelfAdjointEigenSolver<Matrix15d>(x.P).eigenvalues()(0));
      r.max_asymmetry = std::max(r.max_asymmetry, (x.P - x.P.transpose()).cwiseAbs().maxCoeff());
    }
    r.final_truth = s.x;
    r.final_estimate = x;
  }
  r.estimate_at_compare = ekf.StateAt(o.compare_at_s);
  return r;
}

double Rms(const RunResult& r, int block, double from_s, double to_s) {
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < r.t_s.size(); ++i)
    if (r.t_s[i] >= from_s && r.t_s[i] < to_s) {
      sum += r.error[i].segment<3>(block).squaredNorm();
      ++n;
    }
  return std::sqrt(sum / n);
}

TEST(ImuPropagation, AtRestNothingMovesAndVelocityVarianceGrowsAsSigmaASquaredT) {
  CoreNoiseParams noise = SimulatorNoise();
  ImuPropagation prop(noise);
  CoreState x;
  x.p_W = Eigen::Vector3d(1, 2, 3);
  ImuReading u{0.0, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 9.8)};
  for (int k = 1; k <= 1000; ++k) {
    ImuReading u1 = u;
    u1.t_s = k * 0.01;
    x = prop.Propagate(x, u, u1);
    u = u1;
  }
  EXPECT_NEAR((x.p_W - Eigen::Vector3d(1, 2, 3)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(x.v_W.norm(), 0.0, 1e-12);
  // d(dv)/dt = -C (db_a + n_a) with db_a a random walk: P_vz(T) = sigma_a^2 T + sigma_ba^2 T^3 / 3
  // (tilt errors from the gyro move only x and y at rest)
  const double T = 10.0;
  const double P_vz = std::pow(noise.core_noise_acc, 2) * T + std::pow(noise.core_noise_accbias, 2) * T * T * T / 3.0;
  EXPECT_NEAR(x.P(idx::kV + 2, idx::kV + 2), P_vz, 1e-3 * P_vz);
  // attitude about z likewise: P_theta_z(T) = sigma_w^2 T + sigma_bw^2 T^3 / 3
  EXPECT_NEAR(x.P(idx::kTheta + 2, idx::kTheta + 2),
              std::pow(noise.core_noise_gyr, 2) * T + std::pow(noise.core_noise_gyrbias, 2) * T * T * T / 3.0,
              1e-3 * std::pow(noise.core_noise_gyr, 2) * T);
}

TEST(ImuPropagation, ConstantRateAndAccelerationIntegrateExactly) {
  ImuPropagation prop(SimulatorNoise());
  CoreState x;
  const Eigen::Vector3d omega(0.0, 0.0, 0.7);
  // specific force of a body accelerating at a_W = (0, 0, 1.2) while spinning about z: C^T (a - g)
  ImuReading u{0.0, omega, Eigen::Vector3d(0, 0, 1.2 + 9.8)};
  for (int k = 1; k <= 500; ++k) {
    ImuReading u1 = u;
    u1.t_s = k * 0.01;
    x = prop.Propagate(x, u, u1);
    u = u1;
  }
  const double T = 5.0;
  EXPECT_LT(QuaternionLog(x.q_WI.conjugate() * Eigen::Quaterniond(Eigen::AngleAxisd(0.7 * T, Eigen::Vector3d::UnitZ())))
                .norm(),
            1e-12);
  EXPECT_NEAR(x.v_W.z(), 1.2 * T, 1e-10);            // v = a t
  EXPECT_NEAR(x.p_W.z(), 0.5 * 1.2 * T * T, 1e-10);  // p = a t^2 / 2
}

TEST(PoseEkf, ConsistentNeesOverMonteCarloRunsWithinChiSquareBounds) {
  // M runs; the average NEES at each time is chi^2(15 M)/M distributed for a consistent filter.
  const int M = 25;
  RunOptions o;
  std::vector<RunResult> runs;
  for (int m = 0; m < M; ++m) runs.push_back(Fly(1000 + m, o));
  const double lower = ChiSquareQuantile(15.0 * M, -1.959964) / M, upper = ChiSquareQuantile(15.0 * M, 1.959964) / M;
  int inside = 0, samples = 0;
  double mean = 0.0;
  for (std::size_t i = 100; i < runs[0].nees.size(); i += 10) {  // every 0.1 s after the first second
    double avg = 0.0;
    for (const auto& r : runs) avg += r.nees[i] / M;
    inside += (avg >= lower && avg <= upper);
    mean += avg;
    ++samples;
  }
  mean /= samples;
  std::printf("average NEES %.2f (15 expected), %.1f %% of times inside [%.2f, %.2f]\n", mean, 100.0 * inside / samples,
              lower, upper);
  EXPECT_GE(static_cast<double>(inside) / samples, 0.90);
  EXPECT_NEAR(mean, 15.0, 1.5);
  for (const auto& r : runs) {
    EXPECT_GT(r.min_eigenvalue, 0.0);
    EXPECT_LT(r.max_asymmetry, 1e-15);
  }
}

TEST(PoseEkf, PoseDelayedBy100msGivesTheSameEstimateAsAnOnTimePose) {
  RunOptions on_time, delayed;
  delayed.delivery_delay_steps = 10;  // 100 ms at 100 Hz, stamped with the capture time
  const RunResult a = Fly(7, on_time), b = Fly(7, delayed);
  // re-propagation after the late update reproduces the on-time estimate
  // (29.95 s: both have fused the poses up to 29.9 s there)
  const CoreState &x_a = a.estimate_at_compare, &x_b = b.estimate_at_compare;
  EXPECT_LT((x_a.p_W - x_b.p_W).norm(), 1e-9);
  EXPECT_LT(QuaternionLog(x_a.q_WI.conjugate() * x_b.q_WI).norm(), 1e-9);
  EXPECT_LT((x_a.b_a - x_b.b_a).norm(), 1e-9);
  EXPECT_LT((x_a.P - x_b.P).cwiseAbs().maxCoeff(), 1e-12);
  // ...while the present between two arrivals is still dead-reckoned: small error, consistent
  const double rms_delayed = Rms(b, idx::kP, 5, 30);
  EXPECT_LT(rms_delayed, 1.5 * Rms(a, idx::kP, 5, 30));
  // a filter that takes the delayed pose as current is clearly worse in motion
  RunOptions naive = delayed;
  naive.stamp_with_arrival = true;
  const RunResult c = Fly(7, naive);
  std::printf("position RMS: on time %.4f m, 100 ms late %.4f m, late but taken as current %.4f m\n",
              Rms(a, idx::kP, 5, 30), rms_delayed, Rms(c, idx::kP, 5, 30));
  EXPECT_GT(Rms(c, idx::kP, 5, 30), 3.0 * rms_delayed);
}

TEST(PoseEkf, BiasesAreEstimatedWithin20PercentAfter30s) {
  for (uint64_t seed : {11u, 12u, 13u}) {
    const RunResult r = Fly(seed, RunOptions{});
    const Eigen::Vector3d gyr_err = r.final_truth.b_w - r.final_estimate.b_w;
    const Eigen::Vector3d acc_err = r.final_truth.b_a - r.final_estimate.b_a;
    EXPECT_LT(gyr_err.norm(), 0.2 * r.final_truth.b_w.norm())
        << "seed " << seed << " b_w " << r.final_truth.b_w.transpose();
    EXPECT_LT(acc_err.norm(), 0.2 * r.final_truth.b_a.norm())
        << "seed " << seed << " b_a " << r.final_truth.b_a.transpose();
  }
}

TEST(PoseEkf, SurvivesA2sPoseOutageAndReconverges) {
  RunOptions o;
  o.outage_from_s = 15.0;
  o.outage_to_s = 17.0;
  const RunResult r = Fly(21, o);
  double worst_sigma_ratio = 0.0, worst_error = 0.0;
  for (std::size_t i = 0; i < r.t_s.size(); ++i) {
    if (r.t_s[i] < o.outage_from_s || r.t_s[i] >= o.outage_to_s) continue;
    const double e = r.error[i].segment<3>(idx::kP).norm();
    const double sigma = std::sqrt(r.P[i].block<3, 3>(idx::kP, idx::kP).trace());
    worst_error = std::max(worst_error, e);
    worst_sigma_ratio = std::max(worst_sigma_ratio, e / sigma);
  }
  std::printf("outage: worst position error %.3f m, %.2f sigma\n", worst_error, worst_sigma_ratio);
  EXPECT_LT(worst_error, 0.1);        // dead reckoning on estimated biases for 2 s
  EXPECT_LT(worst_sigma_ratio, 4.0);  // and the filter knows it
  // covariance grew during the outage and shrinks back after
  const auto at = [&](double t) { return static_cast<std::size_t>(std::lround((t - r.t_s[0]) / 0.01)); };
  EXPECT_GT(r.P[at(16.99)](0, 0), 10.0 * r.P[at(14.99)](0, 0));
  EXPECT_LT(Rms(r, idx::kP, 19, 30), 0.01);
  EXPECT_LT(r.P[at(20.0)](0, 0), 2.0 * r.P[at(14.99)](0, 0));
}

TEST(PoseEkf, MahalanobisGateRejectsAnOutlierOnlyWhenEnabled) {
  for (bool enabled : {true, false}) {
    PoseSensorParams sensor = MountedSensor();
    sensor.enable_mah_outlier_rejection = enabled;
    sensor.mah_threshold = 5.0;
    TruthSimulator truth(SimulatorNoise(), sensor, InitialUncertainty(), 3);
    PoseEkf ekf(SimulatorNoise(), sensor, InitialUncertainty());
    TruthSample s = truth.Step(0);
    ekf.AddImu(s.imu);
    ekf.AddPose(truth.Measure(s.x));
    ASSERT_EQ(ekf.InitializeScale(1.0), "");
    for (int k = 1; k <= 500; ++k) {
      s = truth.Step(k);
      ekf.AddImu(s.imu);
      if (k % 10 == 0) {
        ASSERT_EQ(ekf.AddPose(truth.Measure(s.x)), PoseStatus::kApplied);
      }
    }
    for (int k = 501; k <= 506; ++k) {  // beyond pose_measurement_minimum_dt
      s = truth.Step(k);
      ekf.AddImu(s.imu);
    }
    PoseMeasurement outlier = truth.Measure(s.x);
    outlier.p_m_W.x() += 1.0;  // a 1 m jump, 100 sigma
    const Eigen::Vector3d before = ekf.State().p_W;
    const PoseStatus status = ekf.AddPose(outlier);
    EXPECT_GT(ekf.LastMahalanobis(), 50.0);
    if (enabled) {
      EXPECT_EQ(status, PoseStatus::kRejectedOutlier);
      EXPECT_EQ(ekf.State().p_W, before);
    } else {
      EXPECT_EQ(status, PoseStatus::kApplied);
      EXPECT_GT((ekf.State().p_W - before).norm(), 0.1);  // pulled towards the jump
    }
  }
}

TEST(PoseEkf, InitialisationNeedsMeasurementsAndRecoversThePoseOfTheImu) {
  PoseEkf ekf(SimulatorNoise(), MountedSensor(), InitialUncertainty());
  EXPECT_EQ(ekf.InitializeScale(1.0), "no pose measurement received yet");
  PoseMeasurement z;
  const Eigen::Quaterniond q_WI(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()));
  const Eigen::Vector3d p_W(1, -2, 0.5);
  z.p_m_W = p_W + q_WI * MountedSensor().p_ic;
  z.q_m_WC = q_WI * MountedSensor().q_ic;
  z.R = Matrix6d::Identity() * 1e-4;
  EXPECT_EQ(ekf.AddPose(z), PoseStatus::kStoredForInit);
  EXPECT_EQ(ekf.InitializeScale(1.0), "no IMU measurement received yet");
  ekf.AddImu(ImuReading{0.0, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 9.8)});
  EXPECT_EQ(ekf.InitializeScale(-1.0), "scale -1 must be > 0");
  EXPECT_EQ(ekf.InitializeHeight(0.001), "height 0.001 m is below the minimum of 0.01 m");
  ASSERT_EQ(ekf.InitializeScale(1.0), "");
  EXPECT_LT((ekf.State().p_W - p_W).norm(), 1e-12);
  EXPECT_LT(QuaternionLog(ekf.State().q_WI.conjugate() * q_WI).norm(), 1e-12);
  // InitHeight: the scale that maps the measured position to the given height
  ASSERT_EQ(ekf.InitializeHeight(z.p_m_W.norm() / 2.0), "");
  EXPECT_NEAR(ekf.PoseParams().scale, 2.0, 1e-12);
}

TEST(PoseEkf, MeasurementsOlderThanTheBufferAreRefused) {
  PoseEkf ekf(SimulatorNoise(), MountedSensor(), InitialUncertainty(), /*buffer_length_s=*/1.0);
  PoseMeasurement z;
  z.p_m_W = MountedSensor().p_ic;
  z.q_m_WC = MountedSensor().q_ic;
  z.R = Matrix6d::Identity() * 1e-4;
  ekf.AddImu(ImuReading{0.0, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 9.8)});
  ekf.AddPose(z);
  ASSERT_EQ(ekf.InitializeScale(1.0), "");
  for (int k = 1; k <= 300; ++k) ekf.AddImu(ImuReading{k * 0.01, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 9.8)});
  z.t_s = 1.0;  // 2 s old, buffer holds 1 s
  EXPECT_EQ(ekf.AddPose(z), PoseStatus::kTooOld);
  z.t_s = 3.5;  // ahead of the IMU: waits for it
  EXPECT_EQ(ekf.AddPose(z), PoseStatus::kPending);
}

TEST(Params, BadValuesAreNamed) {
  CoreNoiseParams core;
  core.core_noise_acc = -1.0;
  EXPECT_EQ(core.Validate(), "core/core_noise_acc = -1 must be a positive noise density");
  PoseSensorParams pose;
  pose.q_ic = Eigen::Quaterniond(2.0, 0.0, 0.0, 0.0);
  EXPECT_EQ(pose.Validate(), "pose_sensor/init/q_ic (w, x, y, z) = (2, 0, 0, 0) must be a unit quaternion");
  EXPECT_THROW(ImuPropagation{core}, std::invalid_argument);
}

}  // namespace
}  // namespace msf_updates
