// GPS, magnetometer and barometer models against independent computations: WGS84 by the textbook
// ECEF formulas, the standard-atmosphere table, and sample statistics of the declared noise.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "rotors_gazebo_plugins/models/navigation_sensor_models.h"

using namespace rotors_gazebo_plugins;

namespace {

constexpr double kA = 6378137.0, kF = 1.0 / 298.257223563, kE2 = kF * (2.0 - kF);  // WGS84
constexpr double kDeg = M_PI / 180.0;

Eigen::Vector3d EcefFromGeodetic(double lat_deg, double lon_deg, double h) {
  const double phi = lat_deg * kDeg, lambda = lon_deg * kDeg;
  const double N = kA / std::sqrt(1.0 - kE2 * std::sin(phi) * std::sin(phi));
  return {(N + h) * std::cos(phi) * std::cos(lambda), (N + h) * std::cos(phi) * std::sin(lambda),
          (N * (1.0 - kE2) + h) * std::sin(phi)};
}

/// Columns: east, north, up at (lat, lon).
Eigen::Matrix3d EnuAxesInEcef(double lat_deg, double lon_deg) {
  const double phi = lat_deg * kDeg, lambda = lon_deg * kDeg;
  Eigen::Matrix3d R;
  R.col(0) << -std::sin(lambda), std::cos(lambda), 0.0;
  R.col(1) << -std::sin(phi) * std::cos(lambda), -std::sin(phi) * std::sin(lambda), std::cos(phi);
  R.col(2) << std::cos(phi) * std::cos(lambda), std::cos(phi) * std::sin(lambda), std::sin(phi);
  return R;
}

const GeodeticOrigin kZurich{47.3667, 8.55, 500.0, 0.0};  // RotorS' worlds

Eigen::Vector3d EnuOf(const Eigen::Vector3d& lla) {
  const Eigen::Vector3d d = EcefFromGeodetic(lla.x(), lla.y(), lla.z()) -
                            EcefFromGeodetic(kZurich.latitude_deg, kZurich.longitude_deg, kZurich.elevation_m);
  return EnuAxesInEcef(kZurich.latitude_deg, kZurich.longitude_deg).transpose() * d;
}

TEST(GpsModel, KnownDisplacementsLandOnWgs84WithinOneCentimetre) {
  const Eigen::Vector3d origin_ecef =
      EcefFromGeodetic(kZurich.latitude_deg, kZurich.longitude_deg, kZurich.elevation_m);
  const Eigen::Matrix3d R_ecef_enu = EnuAxesInEcef(kZurich.latitude_deg, kZurich.longitude_deg);
  for (const Eigen::Vector3d& d : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(100, -50, 20),
                                   Eigen::Vector3d(1500, 2500, 100), Eigen::Vector3d(-20000, 8000, 300)}) {
    const Eigen::Vector3d lla = GeodeticFromWorld(kZurich, d);
    // the point the displacement reaches, by hand, against the point the GPS names
    const Eigen::Vector3d expected_ecef = origin_ecef + R_ecef_enu * d;
    const double error_m = (EcefFromGeodetic(lla.x(), lla.y(), lla.z()) - expected_ecef).norm();
    EXPECT_LT(error_m, 0.01) << "displacement " << d.transpose() << ": " << error_m << " m";
  }
  // 1 km north at elevation h is 1 km / ((M(phi) + h) pi / 180) degrees of latitude, M the meridian
  // radius of curvature
  const double phi = kZurich.latitude_deg * kDeg;
  const double M = kA * (1.0 - kE2) / std::pow(1.0 - kE2 * std::sin(phi) * std::sin(phi), 1.5);
  EXPECT_NEAR(GeodeticFromWorld(kZurich, {0, 1000, 0}).x() - kZurich.latitude_deg,
              1000.0 / ((M + kZurich.elevation_m) * kDeg), 1e-8);
}

TEST(GpsModel, NoiseHasTheDeclaredStandardDeviations) {
  GpsParams p;  // RotorS' default_gps: 3 m horizontal, 6 m vertical, 0.1 m/s
  GpsModel gps(p, kZurich, 7);
  const int n = 20000;
  Eigen::Vector3d sum_sq_p = Eigen::Vector3d::Zero(), sum_sq_v = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) {
    const GpsSample s = gps.Measure(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 2, 3));
    sum_sq_p += EnuOf(s.latitude_longitude_altitude).cwiseAbs2();
    sum_sq_v += (s.ground_speed_W - Eigen::Vector3d(1, 2, 3)).cwiseAbs2();
  }
  const Eigen::Vector3d sigma_p = (sum_sq_p / n).cwiseSqrt(), sigma_v = (sum_sq_v / n).cwiseSqrt();
  EXPECT_TRUE(sigma_p.isApprox(Eigen::Vector3d(3, 3, 6), 0.03)) << sigma_p.transpose();
  EXPECT_TRUE(sigma_v.isApprox(Eigen::Vector3d(0.1, 0.1, 0.1), 0.03)) << sigma_v.transpose();
  EXPECT_FALSE((GpsParams{-1.0, 6.0, 0.1, 0.1}).Validate().empty());
}

// PX4's Gazebo GPS integrated every step dt: b_{k+1} = (1 - 1/tau) b_k + sigma_rw dt^(3/2) n_k, so at
// steady state var(b) = sigma_rw^2 dt^3 / (1 - (1 - 1/tau)^2), and each fix is the reading of 0.12 s ago.
TEST(RandomWalkGpsModel, BiasHasThePx4StationaryVarianceAndFixesAreDelayed) {
  GpsParams p;
  p.noise_model = GpsNoiseModel::kRandomWalk;
  p.xy_noise_density = p.z_noise_density = p.vxy_noise_density = p.vz_noise_density = 0.0;
  const double dt = 0.004, tau = p.correlation_time_steps;
  RandomWalkGpsModel gps(p, kZurich, 3);
  const int warmup = 2000, n = 200000;
  Eigen::Vector3d sum_sq = Eigen::Vector3d::Zero();
  for (int k = 0; k < warmup + n; ++k) {
    gps.Step(k * dt, dt, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
    if (k >= warmup) sum_sq += gps.Bias().cwiseAbs2();
  }
  const double decay = 1.0 - 1.0 / tau;
  const double sigma_xy = 2.0 * std::pow(dt, 1.5) / std::sqrt(1.0 - decay * decay);
  const double sigma_z = 4.0 * std::pow(dt, 1.5) / std::sqrt(1.0 - decay * decay);
  const Eigen::Vector3d sigma = (sum_sq / n).cwiseSqrt();
  EXPECT_TRUE(sigma.isApprox(Eigen::Vector3d(sigma_xy, sigma_xy, sigma_z), 0.05))
      << sigma.transpose() << " against " << sigma_xy << ", " << sigma_z;
  EXPECT_NEAR(sigma_xy, 0.0028, 0.0002);  // about 3 mm: PX4's GPS at rest holds still

  // a vehicle moving along x at 1 m/s: the fix at t is the reading of t - 0.12 s
  p.xy_random_walk = p.z_random_walk = 0.0;
  RandomWalkGpsModel moving(p, kZurich, 3);
  GpsSample fix;
  EXPECT_FALSE(moving.Fix(0.0, &fix));
  for (int k = 1; k <= 250; ++k) moving.Step(k * dt, dt, Eigen::Vector3d(k * dt, 0, 0), Eigen::Vector3d(1, 0, 0));
  ASSERT_TRUE(moving.Fix(250 * dt, &fix));
  EXPECT_NEAR(EnuOf(fix.latitude_longitude_altitude).x(), 250 * dt - 0.12, 1e-6);
  p.correlation_time_steps = 0.5;
  EXPECT_FALSE(p.Validate().empty());
}

TEST(MagnetometerModel, FieldInTheBodyFrameWithTheDeclaredNoiseAndBias) {
  MagnetometerParams p;  // RotorS' default_magnetometer: sigma 8e-8 T, bias bound 4e-7 T
  p.noise_normal_T.setConstant(8e-8);
  p.noise_uniform_initial_bias_T.setConstant(4e-7);
  // ENU world: north is +y, down is -z
  EXPECT_TRUE(p.ReferenceWorld().isApprox(Eigen::Vector3d(8.15e-7, 2.1493e-5, -4.2795e-5)));
  // turned 90 degrees about z, the body's x axis points north
  const Eigen::Quaterniond yaw90(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  const Eigen::Vector3d expected_B(2.1493e-5, -8.15e-7, -4.2795e-5);
  MagnetometerModel mag(p, 11);
  const int n = 20000;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), sum_sq = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d e = mag.Measure(yaw90) - expected_B - mag.Bias();
    sum += e;
    sum_sq += e.cwiseAbs2();
  }
  EXPECT_LT((sum / n).cwiseAbs().maxCoeff(), 4.0 * 8e-8 / std::sqrt(n));
  EXPECT_TRUE((sum_sq / n).cwiseSqrt().isApprox(Eigen::Vector3d::Constant(8e-8), 0.03));
  // the bias is drawn once from U(-4e-7, 4e-7): over many sensors, variance b^2 / 3
  double bias_sq = 0.0, bias_max = 0.0;
  const int sensors = 3000;
  for (int s = 0; s < sensors; ++s) {
    const Eigen::Vector3d b = MagnetometerModel(p, 100 + s).Bias();
    bias_sq += b.squaredNorm() / 3.0;
    bias_max = std::max(bias_max, b.cwiseAbs().maxCoeff());
  }
  EXPECT_LE(bias_max, 4e-7);
  EXPECT_NEAR(std::sqrt(bias_sq / sensors), 4e-7 / std::sqrt(3.0), 0.03 * 4e-7 / std::sqrt(3.0));
}

TEST(PressureModel, StandardAtmosphereTable) {
  // ICAO standard atmosphere at geopotential heights [m] -> pressure [Pa]
  const double R_e = 6356766.0;
  const std::vector<std::pair<double, double>> table = {
      {0.0, 101325.0}, {500.0, 95460.8}, {1000.0, 89874.6}, {2000.0, 79495.2}, {5000.0, 54019.9}};
  for (const auto& [h_gp, p_table] : table) {
    const double h = R_e * h_gp / (R_e - h_gp);  // geometric height of that geopotential height
    EXPECT_NEAR(StandardAtmospherePressure(h), p_table, 2.0) << "h_gp " << h_gp;
  }
  // referenceAltitude 500 m (RotorS' default): the world origin reads about 95461 Pa, and 1 m up
  // is about 11.3 Pa less (dp/dh = -rho g, rho = 1.1673 kg/m^3 at 500 m)
  PressureModel baro(PressureParams{}, 1);
  EXPECT_NEAR(baro.Measure(0.0) - baro.Measure(1.0), 1.1673 * 9.80665, 0.02);
}

TEST(PressureModel, NoiseHasTheDeclaredVariance) {
  PressureModel baro(PressureParams{0.0, 4.0}, 3);
  const int n = 20000;
  double sum = 0.0, sum_sq = 0.0;
  for (int i = 0; i < n; ++i) {
    const double e = baro.Measure(0.0) - 101325.0;
    sum += e;
    sum_sq += e * e;
  }
  EXPECT_NEAR(sum / n, 0.0, 4.0 * 2.0 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(sum_sq / n), 2.0, 0.06);
  EXPECT_FALSE((PressureParams{0.0, -1.0}).Validate().empty());
}

}  // namespace
