// A pinhole camera as SDF declares it (<camera>: horizontal_fov, image, clip, noise, pose) and the
// intrinsics that follow from it. Engine-free: no GL, no ROS.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <ignition/math/Vector2.hh>
#include <ignition/math/Pose3.hh>
#include <sdf/Element.hh>

namespace rotors_sim {
namespace rendering {

enum class PixelFormat { kL8, kR8G8B8, kB8G8R8 };

/// "L8", "R8G8B8", "B8G8R8" (Gazebo's names); throws SimError for any other.
PixelFormat ParsePixelFormat(const std::string& name);
int BytesPerPixel(PixelFormat format);
std::string RosEncoding(PixelFormat format);  ///< "mono8", "rgb8", "bgr8"

struct CameraIntrinsics {
  int width_px = 320, height_px = 240;
  double horizontal_fov_rad = 1.047;
  double near_m = 0.1, far_m = 100.0;  ///< clip planes along the optical axis
  /// Where the optical axis meets the image, as a fraction of its width and height (Gazebo's
  /// <distortion><center>); 0.5 0.5 is the image centre.
  double center_u = 0.5, center_v = 0.5;

  /// f = W / (2 tan(hfov / 2)); square pixels.
  double FocalLengthPx() const;
  /// The principal point in pixels; pixel (0, 0) is the centre of the top-left pixel (ROS /
  /// OpenCV convention), so c = (center_u W - 1/2, center_v H - 1/2): ((W - 1) / 2, (H - 1) / 2)
  /// for the image centre.
  double Cx() const { return center_u * width_px - 0.5; }
  double Cy() const { return center_v * height_px - 0.5; }
  Eigen::Matrix3d K() const;
  /// False when a sphere (centre in the optical frame) lies wholly outside the view frustum, so
  /// that nothing of what it encloses can be seen; true when it may be seen.
  bool MaySee(const Eigen::Vector3d& centre_O_m, double radius_m) const;
  std::string Validate() const;  ///< empty when valid, else a one-line reason
  /// How fast the image's fastest point may move [px/s] for a camera turning at omega [rad/s] and
  /// moving at speed [m/s] past a scene no nearer than near [m]: a turn moves a point at angle
  /// theta off the axis by f omega / cos^2 theta (at most the farthest corner's), a translation by
  /// f v / Z.
  double ImageSpeedBoundPxS(double omega_rad_s, double speed_m_s, double near_m) const;
};

/// Gazebo's <distortion>: the Brown-Conrady model of OpenCV and ROS' plumb_bob, in coordinates
/// normalised by the focal length around the principal point (x = (u - cx) / f, r^2 = x^2 + y^2):
///   x_d = x (1 + k1 r^2 + k2 r^4 + k3 r^6) + 2 p1 x y + p2 (r^2 + 2 x^2)
///   y_d = y (1 + k1 r^2 + k2 r^4 + k3 r^6) + p1 (r^2 + 2 y^2) + 2 p2 x y
struct LensDistortion {
  double k1 = 0.0, k2 = 0.0, k3 = 0.0, p1 = 0.0, p2 = 0.0;

  bool IsIdentity() const { return k1 == 0.0 && k2 == 0.0 && k3 == 0.0 && p1 == 0.0 && p2 == 0.0; }
  /// The radial factor 1 + k1 r^2 + k2 r^4 + k3 r^6 at r^2 = `r2`.
  double Radial(double r2) const { return 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3)); }
  /// An ideal (pinhole) point to where the lens shows it.
  Eigen::Vector2d Distort(const Eigen::Vector2d& x_ideal) const;
  /// The inverse of Distort by fixed-point iteration (as cv::undistortPoints); false when it does
  /// not converge to 1e-9 (the point has no preimage the model maps there).
  bool Undistort(const Eigen::Vector2d& x_distorted, Eigen::Vector2d* x_ideal) const;
  /// Empty when the model is one-to-one over the image (radial factor positive and r_d rising with
  /// r out to the farthest corner, at `max_radius` in normalised coordinates), else a one-line reason.
  std::string Validate(double max_radius) const;
  /// D as camera_info's plumb_bob orders it: k1, k2, p1, p2, k3.
  std::vector<double> PlumbBob() const { return {k1, k2, p1, p2, k3}; }
};

/// One <camera> of a camera, multicamera or depth sensor.
struct CameraSpec {
  std::string name;             ///< <camera name="left">, may be empty
  ignition::math::Pose3d X_SC;  ///< camera frame (x forward, z up) in the sensor frame
  CameraIntrinsics intrinsics;
  PixelFormat format = PixelFormat::kR8G8B8;
  double noise_mean = 0.0, noise_stddev = 0.0;  ///< Gaussian, in units of full scale [0, 1]
  LensDistortion distortion;                    ///< identity unless <distortion> says otherwise
};

/// Reads a <camera> element; throws SimError naming the element and the problem.
CameraSpec ParseCamera(const sdf::ElementPtr& camera);

/// The optical frame (x right, y down, z forward) in the camera frame (x forward, z up):
/// rotation rpy (-pi/2, 0, -pi/2), as RotorS' optical joints.
ignition::math::Pose3d OpticalInCamera();

}  // namespace rendering
}  // namespace rotors_sim
