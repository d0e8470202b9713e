// An event camera (DVS) after ESIM's model (Rebecq, Gehrig, Scaramuzza, "ESIM: an Open Event Camera
// Simulator", CoRL 2018), free of any engine: a pixel fires an event each time its log intensity has
// moved by its contrast threshold from the level of its last event, L(t) - L_ref = +-C; the event's
// time is where the straight line between two renders crosses the level (renders sampled closely
// enough that the log intensity is near linear between them: the plugin's adaptive sampling).
// docs/sensor_realism.md gives the parameters and their sources.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rotors_gazebo_plugins {

struct EventCameraParams {
  double contrast_threshold_pos = 0.15;  ///< C+ [log intensity] (<contrastThresholdPositive>)
  double contrast_threshold_neg = 0.15;  ///< C- [log intensity] (<contrastThresholdNegative>)
  /// sigma of each pixel's thresholds around C+ and C- [log intensity], drawn once per pixel
  /// (<contrastThresholdSigma>)
  double contrast_threshold_sigma = 0.021;
  double refractory_period_s = 0.0;  ///< a pixel fires no event sooner after its last (<refractoryPeriod>)
  double log_epsilon = 1e-3;         ///< L = ln(I + eps), I in [0, 1] (<logEpsilon>): no log of 0
  /// Empty when valid, else one line naming the bad parameter.
  std::string Validate() const;
};

struct DvsEvent {
  uint16_t x, y;
  double t_s;
  bool polarity;  ///< true: brighter
};

class EventCameraModel {
 public:
  /// width x height pixels; `seed` draws the per-pixel thresholds.
  EventCameraModel(const EventCameraParams& p, int width_px, int height_px, uint64_t seed);

  /// A render at time t_s (grey, W x H bytes, 0..255, linear in the scene's light): the events since
  /// the last render, in time order, appended to `events`. The first render sets the levels.
  void Process(const std::vector<uint8_t>& grey, double t_s, std::vector<DvsEvent>* events);
  bool Started() const { return started_; }
  void Reset() { started_ = false; }
  /// C+ and C- of pixel (u, v), with its mismatch.
  double ThresholdPositive(int u, int v) const { return c_pos_[static_cast<size_t>(v) * width_ + u]; }
  double ThresholdNegative(int u, int v) const { return c_neg_[static_cast<size_t>(v) * width_ + u]; }

 private:
  EventCameraParams p_;
  int width_, height_;
  bool started_ = false;
  double t_last_s_ = 0.0;
  std::vector<float> log_last_, log_ref_, c_pos_, c_neg_;
  std::vector<double> last_event_s_;
};

}  // namespace rotors_gazebo_plugins
