// A pinhole camera as SDF declares it (<camera>: horizontal_fov, image, clip, noise, pose) and the
// intrinsics that follow from it. Engine-free: no GL, no ROS.
#pragma once

#include <string>

#include <Eigen/Core>
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

  /// f = W / (2 tan(hfov / 2)); square pixels.
  double FocalLengthPx() const;
  /// The optical axis meets the image centre; pixel (0, 0) is the centre of the top-left pixel
  /// (ROS / OpenCV convention), so c = ((W - 1) / 2, (H - 1) / 2).
  double Cx() const { return (width_px - 1) / 2.0; }
  double Cy() const { return (height_px - 1) / 2.0; }
  Eigen::Matrix3d K() const;
  /// False when a sphere (centre in the optical frame) lies wholly outside the view frustum, so
  /// that nothing of what it encloses can be seen; true when it may be seen.
  bool MaySee(const Eigen::Vector3d& centre_O_m, double radius_m) const;
  std::string Validate() const;  ///< empty when valid, else a one-line reason
};

/// One <camera> of a camera, multicamera or depth sensor.
struct CameraSpec {
  std::string name;             ///< <camera name="left">, may be empty
  ignition::math::Pose3d X_SC;  ///< camera frame (x forward, z up) in the sensor frame
  CameraIntrinsics intrinsics;
  PixelFormat format = PixelFormat::kR8G8B8;
  double noise_mean = 0.0, noise_stddev = 0.0;  ///< Gaussian, in units of full scale [0, 1]
};

/// Reads a <camera> element; throws SimError naming the element and the problem.
CameraSpec ParseCamera(const sdf::ElementPtr& camera);

/// The optical frame (x right, y down, z forward) in the camera frame (x forward, z up):
/// rotation rpy (-pi/2, 0, -pi/2), as RotorS' optical joints.
ignition::math::Pose3d OpticalInCamera();

}  // namespace rendering
}  // namespace rotors_sim
