// msf_ekf_bench: cost of the estimator on this machine (make bench). A 100 Hz IMU, a 10 Hz pose
// arriving 100 ms late (each update re-propagates 10 buffered states), 60 s of data, noise-free
// hover (the cost does not depend on the values). Prints "<us per IMU sample> <us per pose update>".
#include <chrono>
#include <cstdio>

#include "msf_updates/ekf/pose_ekf.h"

int main() {
  using Clock = std::chrono::steady_clock;
  msf_updates::PoseSensorParams sensor;
  sensor.pose_delay_s = 0.0;
  msf_updates::PoseEkf ekf(msf_updates::CoreNoiseParams{}, sensor, msf_updates::InitialUncertainty{});
  const auto imu = [](int k) {
    return msf_updates::ImuReading{k * 0.01, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 9.81)};
  };
  msf_updates::PoseMeasurement z;
  z.R = msf_updates::Matrix6d::Identity() * 1e-4;
  ekf.AddImu(imu(0));
  ekf.AddPose(z);
  ekf.InitializeScale(1.0);
  const int steps = 6000, runs = 20;
  double imu_s = 0.0, pose_s = 0.0;
  int poses = 0;
  for (int run = 0; run < runs; ++run) {
    for (int k = 1; k <= steps; ++k) {
      const int step = run * steps + k;
      auto t0 = Clock::now();
      ekf.AddImu(imu(step));
      imu_s += std::chrono::duration<double>(Clock::now() - t0).count();
      if (step % 10 == 0 && step > 10) {
        z.t_s = (step - 10) * 0.01;  // captured 100 ms ago
        t0 = Clock::now();
        ekf.AddPose(z);
        pose_s += std::chrono::duration<double>(Clock::now() - t0).count();
        ++poses;
      }
    }
  }
  std::printf("%.3f %.3f\n", 1e6 * imu_s / (steps * runs), 1e6 * pose_s / poses);
  return 0;
}
