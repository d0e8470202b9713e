#include "rotors_gazebo_plugins/models/optical_flow_model.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

namespace rotors_gazebo_plugins {

std::string OpticalFlowParams::Validate() const {
  std::ostringstream why;
  if (!(focal_length_px > 0.0) || !std::isfinite(focal_length_px))
    why << "focal length " << focal_length_px << " px must be > 0 (the camera's horizontal_fov)";
  else if (!(output_rate_hz > 0.0) || !std::isfinite(output_rate_hz))
    why << "outputRate = " << output_rate_hz << " must be > 0 Hz";
  else if (max_features < 1) why << "maxFeatures = " << max_features << " must be >= 1";
  return why.str();
}

namespace {
double Median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}
}  // namespace

std::optional<OpticalFlowSample> OpticalFlowModel::AddFrame(const uint8_t* grey, int width, int height, double t_s) {
  const cv::Mat frame = cv::Mat(height, width, CV_8UC1, const_cast<uint8_t*>(grey)).clone();
  if (previous_.empty() || previous_.size() != frame.size()) {
    previous_ = frame;
    interval_start_s_ = t_s;
    return std::nullopt;
  }
  std::vector<cv::Point2f> corners, tracked;
  cv::goodFeaturesToTrack(previous_, corners, params_.max_features, 0.01, 4.0);
  double quality = 0.0;
  if (!corners.empty()) {
    std::vector<uchar> status;
    std::vector<float> error;
    cv::calcOpticalFlowPyrLK(previous_, frame, corners, tracked, status, error, cv::Size(15, 15), 2);
    std::vector<double> dx, dy;
    for (size_t i = 0; i < corners.size(); ++i) {
      if (!status[i]) continue;
      dx.push_back(tracked[i].x - corners[i].x);
      dy.push_back(tracked[i].y - corners[i].y);
    }
    if (!dx.empty()) {
      // the scene's image motion as angles: integrated_x = dy / f, integrated_y = -dx / f
      flow_x_rad_ += std::atan2(Median(dy), params_.focal_length_px);
      flow_y_rad_ -= std::atan2(Median(dx), params_.focal_length_px);
      quality = static_cast<double>(dx.size()) / params_.max_features;
    }
  }
  quality_sum_ += std::min(quality, 1.0);
  ++frames_;
  previous_ = frame;
  if (t_s - interval_start_s_ + 1e-9 < 1.0 / params_.output_rate_hz) return std::nullopt;
  OpticalFlowSample sample;
  sample.integration_time_us = static_cast<uint32_t>(std::lround((t_s - interval_start_s_) * 1e6));
  sample.integrated_x = static_cast<float>(flow_x_rad_);
  sample.integrated_y = static_cast<float>(flow_y_rad_);
  sample.quality = static_cast<uint8_t>(std::lround(255.0 * quality_sum_ / frames_));
  interval_start_s_ = t_s;
  flow_x_rad_ = flow_y_rad_ = quality_sum_ = 0.0;
  frames_ = 0;
  return sample;
}

}  // namespace rotors_gazebo_plugins
