// The event camera model against its definition: a moving edge fires events only where it passes,
// with the polarity of the brightness change, as many per pixel as the log-intensity change holds
// the pixel's threshold (within one), at times between the two renders; the refractory period.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "rotors_gazebo_plugins/models/event_camera_model.h"

using namespace rotors_gazebo_plugins;

namespace {

constexpr int kW = 64, kH = 8;

/// A dark (0.2) region left of column `edge`, bright (0.8) right of it.
std::vector<uint8_t> Edge(int edge) {
  std::vector<uint8_t> image(kW * kH);
  for (int v = 0; v < kH; ++v)
    for (int u = 0; u < kW; ++u) image[v * kW + u] = u < edge ? 51 : 204;
  return image;
}

TEST(EventCamera, AMovingEdgeFiresOnlyAlongItWithThePolarityOfItsDirection) {
  EventCameraParams p;
  EventCameraModel model(p, kW, kH, 7);
  std::vector<DvsEvent> events;
  model.Process(Edge(20), 0.0, &events);
  EXPECT_TRUE(events.empty());  // the first render sets the levels
  // the edge moves right one column per millisecond: columns 20..29 go from bright to dark
  for (int k = 1; k <= 10; ++k) model.Process(Edge(20 + k), k * 1e-3, &events);
  std::vector<int> count(kW * kH, 0);
  for (const DvsEvent& e : events) {
    ASSERT_FALSE(e.polarity) << "darker: negative events only";
    ASSERT_GE(e.x, 20);
    ASSERT_LT(e.x, 30) << "only where the edge passed";
    // column c darkens between the renders at (c - 20) and (c - 19) ms
    EXPECT_GE(e.t_s, (e.x - 20) * 1e-3 - 1e-12);
    EXPECT_LE(e.t_s, (e.x - 19) * 1e-3 + 1e-12);
    ++count[e.y * kW + e.x];
  }
  const double delta_log = std::log(51 / 255.0 + p.log_epsilon) - std::log(204 / 255.0 + p.log_epsilon);
  int checked = 0;
  for (int v = 0; v < kH; ++v)
    for (int u = 20; u < 30; ++u) {
      const double expected = std::abs(delta_log) / model.ThresholdNegative(u, v);
      EXPECT_LE(std::abs(count[v * kW + u] - expected), 1.0) << u << " " << v;
      ++checked;
    }
  std::printf("moving edge: %zu events over %d pixels, %.2f per pixel for |dL| / C = %.2f\n", events.size(), checked,
              events.size() / double(checked), std::abs(delta_log) / p.contrast_threshold_neg);
  for (size_t i = 1; i < events.size(); ++i) ASSERT_LE(events[i - 1].t_s, events[i].t_s) << "in time order";

  // back the other way: brighter, positive events
  std::vector<DvsEvent> back;
  for (int k = 9; k >= 0; --k) model.Process(Edge(20 + k), (20 - k) * 1e-3, &back);
  ASSERT_FALSE(back.empty());
  for (const DvsEvent& e : back) ASSERT_TRUE(e.polarity);
}

TEST(EventCamera, ThresholdsScatterAsTheirSigmaAndTheRefractoryPeriodHoldsEvents) {
  EventCameraParams p;
  EventCameraModel model(p, kW, kH, 3);
  double sum = 0, sum2 = 0;
  for (int v = 0; v < kH; ++v)
    for (int u = 0; u < kW; ++u) {
      sum += model.ThresholdPositive(u, v);
      sum2 += model.ThresholdPositive(u, v) * model.ThresholdPositive(u, v);
    }
  const double n = kW * kH, mean = sum / n, sigma = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, p.contrast_threshold_pos, 4 * p.contrast_threshold_sigma / std::sqrt(n));
  EXPECT_NEAR(sigma, p.contrast_threshold_sigma, 0.15 * p.contrast_threshold_sigma);

  // a refractory period longer than the step: one event per pixel at most in it
  p.contrast_threshold_sigma = 0.0;
  p.refractory_period_s = 1.0;
  EventCameraModel slow(p, kW, kH, 3);
  std::vector<DvsEvent> events;
  slow.Process(Edge(20), 0.0, &events);
  slow.Process(Edge(21), 1e-3, &events);
  EXPECT_EQ(events.size(), static_cast<size_t>(kH)) << "the first of the column's events, then silence";
  p.refractory_period_s = -1.0;
  EXPECT_NE(p.Validate().find("<refractoryPeriod> -1 must be >= 0 s"), std::string::npos);
}

}  // namespace
