// Rays from one origin cast 16 at a time through Embree 3's ray packets (a lidar's column, a depth
// camera's image): what RayScene::CastFan and the batch's obstacle scenes share.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include <embree3/rtcore.h>
#include <Eigen/Core>

namespace rotors_sim {
namespace raycast {

/// Casts the n unit rays origin_W + t dirs_W[k], t in [near_m, far_m], into `scene` with `context`
/// (its flags and filter as the caller set them), and calls on_hit(k, packet, lane) for each ray k
/// with the packet and lane that hold its result (packet.hit.geomID[lane] is
/// RTC_INVALID_GEOMETRY_ID where nothing was hit; packet.ray.tfar[lane] is the distance otherwise).
template <class OnHit>
void CastPackets16(RTCScene scene, RTCIntersectContext* context, const Eigen::Vector3d& origin_W,
                   const Eigen::Vector3d* dirs_W, size_t n, double near_m, double far_m, uint32_t ray_mask,
                   OnHit&& on_hit) {
  for (size_t first = 0; first < n; first += 16) {
    const size_t count = std::min<size_t>(16, n - first);
    alignas(64) int valid[16];
    alignas(64) RTCRayHit16 rh;
    for (size_t k = 0; k < 16; ++k) {
      valid[k] = k < count ? -1 : 0;
      const Eigen::Vector3d& d = dirs_W[first + std::min(k, count - 1)];
      rh.ray.org_x[k] = static_cast<float>(origin_W.x());
      rh.ray.org_y[k] = static_cast<float>(origin_W.y());
      rh.ray.org_z[k] = static_cast<float>(origin_W.z());
      rh.ray.dir_x[k] = static_cast<float>(d.x());
      rh.ray.dir_y[k] = static_cast<float>(d.y());
      rh.ray.dir_z[k] = static_cast<float>(d.z());
      rh.ray.tnear[k] = static_cast<float>(near_m);
      rh.ray.tfar[k] = static_cast<float>(far_m);
      rh.ray.time[k] = 0.0f;
      rh.ray.mask[k] = ray_mask;
      rh.ray.id[k] = static_cast<unsigned>(k);
      rh.ray.flags[k] = 0;
      rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect16(valid, scene, context, &rh);
    for (size_t k = 0; k < count; ++k) on_hit(first + k, rh, k);
  }
}

}  // namespace raycast
}  // namespace rotors_sim
