#include "rotors_gazebo_plugins/models/event_camera_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>

namespace rotors_gazebo_plugins {

std::string EventCameraParams::Validate() const {
  std::ostringstream why;
  auto positive = [&why](const char* name, double v) {
    if (why.str().empty() && !(std::isfinite(v) && v > 0.0)) why << "<" << name << "> " << v << " must be > 0";
  };
  positive("contrastThresholdPositive", contrast_threshold_pos);
  positive("contrastThresholdNegative", contrast_threshold_neg);
  positive("logEpsilon", log_epsilon);
  if (why.str().empty() && !(std::isfinite(contrast_threshold_sigma) && contrast_threshold_sigma >= 0.0))
    why << "<contrastThresholdSigma> " << contrast_threshold_sigma << " must be >= 0";
  if (why.str().empty() && !(std::isfinite(refractory_period_s) && refractory_period_s >= 0.0))
    why << "<refractoryPeriod> " << refractory_period_s << " must be >= 0 s";
  return why.str();
}

EventCameraModel::EventCameraModel(const EventCameraParams& p, int width_px, int height_px, uint64_t seed)
    : p_(p), width_(width_px), height_(height_px) {
  const size_t n = static_cast<size_t>(width_px) * height_px;
  log_last_.assign(n, 0.0f);
  log_ref_.assign(n, 0.0f);
  last_event_s_.assign(n, -std::numeric_limits<double>::infinity());
  c_pos_.resize(n);
  c_neg_.resize(n);
  std::mt19937_64 random(seed);
  std::normal_distribution<double> pos(p.contrast_threshold_pos, p.contrast_threshold_sigma),
      neg(p.contrast_threshold_neg, p.contrast_threshold_sigma);
  // a threshold below a tenth of its mean would fire on rounding; ESIM clamps it likewise
  for (size_t i = 0; i < n; ++i) {
    c_pos_[i] = static_cast<float>(std::max(pos(random), 0.1 * p.contrast_threshold_pos));
    c_neg_[i] = static_cast<float>(std::max(neg(random), 0.1 * p.contrast_threshold_neg));
  }
}

void EventCameraModel::Process(const std::vector<uint8_t>& grey, double t_s, std::vector<DvsEvent>* events) {
  const size_t n = log_last_.size();
  const size_t first = events->size();
  auto log_of = [this](uint8_t value) { return static_cast<float>(std::log(value / 255.0 + p_.log_epsilon)); };
  if (!started_) {
    for (size_t i = 0; i < n; ++i) log_last_[i] = log_ref_[i] = log_of(grey[i]);
    t_last_s_ = t_s;
    started_ = true;
    return;
  }
  const double dt = t_s - t_last_s_;
  for (size_t i = 0; i < n; ++i) {
    const float L0 = log_last_[i], L1 = log_of(grey[i]);
    log_last_[i] = L1;
    if (L1 == L0) continue;
    const bool up = L1 > L0;
    const float C = up ? c_pos_[i] : c_neg_[i];
    float& ref = log_ref_[i];
    // every level ref +- k C between L0 and L1 is crossed: an event where the line crosses it
    while (up ? L1 - ref >= C : ref - L1 >= C) {
      ref += up ? C : -C;
      const double t = t_last_s_ + dt * (ref - L0) / (L1 - L0);
      if (t - last_event_s_[i] < p_.refractory_period_s) continue;  // the level moves, no event
      last_event_s_[i] = t;
      events->push_back({static_cast<uint16_t>(i % width_), static_cast<uint16_t>(i / width_), t, up});
    }
  }
  t_last_s_ = t_s;
  std::stable_sort(events->begin() + static_cast<std::ptrdiff_t>(first), events->end(),
                   [](const DvsEvent& a, const DvsEvent& b) { return a.t_s < b.t_s; });
}

}  // namespace rotors_gazebo_plugins
