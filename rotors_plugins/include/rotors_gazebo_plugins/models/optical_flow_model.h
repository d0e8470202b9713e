// Optical flow from a downward camera's frames, as RotorS' optical flow plugin computes it with
// PX4's OpticalFlowOpenCV: Shi-Tomasi corners of the previous frame tracked into the new one with
// pyramidal Lucas-Kanade (OpenCV), the median displacement [px] turned into an angle by the focal
// length, integrated over the output interval. Engine-free (OpenCV only).
//
// Signs as MAVLink's OPTICAL_FLOW_RAD states them, in the image frame (x right, y down): linear
// motion along +y makes integrated_x negative, along +x makes integrated_y positive, i.e.
//   integrated_x = sum dy / f,   integrated_y = -sum dx / f   (dx, dy: the scene's image motion [px]).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace rotors_gazebo_plugins {

struct OpticalFlowParams {
  double focal_length_px = 0.0;  ///< f = (width / 2) / tan(hfov / 2)
  double output_rate_hz = 20.0;  ///< one integrated sample per 1 / rate (RotorS: 20 Hz)
  int max_features = 50;         ///< corners tracked per frame
  /// Empty when valid, else one line naming the bad value.
  std::string Validate() const;
};

struct OpticalFlowSample {
  uint32_t integration_time_us = 0;
  float integrated_x = 0.0f;  ///< [rad]
  float integrated_y = 0.0f;  ///< [rad]
  uint8_t quality = 0;        ///< 0: no valid flow, 255: every corner tracked in every frame
};

class OpticalFlowModel {
 public:
  explicit OpticalFlowModel(const OpticalFlowParams& params) : params_(params) {}

  /// A grey frame (8 bit, row-major, width * height) taken at t_s; a sample when the output
  /// interval is complete.
  std::optional<OpticalFlowSample> AddFrame(const uint8_t* grey, int width, int height, double t_s);

 private:
  OpticalFlowParams params_;
  cv::Mat previous_;
  double interval_start_s_ = 0.0;  ///< [s] start of the output interval under way
  double flow_x_rad_ = 0.0, flow_y_rad_ = 0.0, quality_sum_ = 0.0;
  int frames_ = 0;
};

}  // namespace rotors_gazebo_plugins
