#include "rendering/sun_shadow.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>

#include <Eigen/Geometry>

#include "physics/pose_math.h"
#include "rotors_core/error.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"

namespace rotors_sim {
namespace rendering {
namespace {

using geometry::Shape;

/// A hash of everything a shadow layer depends on: the pose of every visual's link of the static
/// models (or of the others), and the region.
size_t SceneKey(const physics::World& world, bool static_models, const Eigen::Vector3d& region_centre_L,
                double region_half_m) {
  size_t key = 0x9e3779b97f4a7c15ull;
  auto mix = [&key](double value) {
    uint64_t bits = 0;
    std::memcpy(&bits, &value, sizeof(bits));
    key ^= std::hash<uint64_t>()(bits) + 0x9e3779b97f4a7c15ull + (key << 6) + (key >> 2);
  };
  for (int i = 0; i < 3; ++i) mix(region_centre_L[i]);
  mix(region_half_m);
  for (const physics::ModelPtr& model : world.Models()) {
    if (model->IsStatic() != static_models) continue;
    for (const geometry::Visual& visual : model->Visuals()) {
      const ignition::math::Pose3d X_WL = visual.link->WorldPose();
      for (double v : {X_WL.Pos().X(), X_WL.Pos().Y(), X_WL.Pos().Z(), X_WL.Rot().W(), X_WL.Rot().X(), X_WL.Rot().Y(),
                       X_WL.Rot().Z()})
        mix(v);
    }
  }
  return key == 0 ? 1 : key;
}

}  // namespace

ShadowLayer::~ShadowLayer() {
  if (fbo) glDeleteFramebuffers(1, &fbo);
  if (depth) glDeleteTextures(1, &depth);
}

bool SunShadow::Update(const physics::World& world, const ignition::math::Pose3d& X_WC, const CameraIntrinsics& in) {
  const geometry::Lighting& light = world.GetLighting();
  if (!light.shadows) return false;
  // the sun's frame L: z towards the sun
  const Eigen::Vector3d to_sun_W =
      -Eigen::Vector3d(light.sun_direction_W.X(), light.sun_direction_W.Y(), light.sun_direction_W.Z()).normalized();
  const Eigen::Matrix3d R_WL =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), to_sun_W).toRotationMatrix();
  // the smallest sphere around the camera's view up to D: centred a along the optical axis, it
  // reaches the camera (radius a) and the far corners (radius^2 = (D - a)^2 + D^2 k)
  const double D = std::min(in.far_m, kViewDistance_m), f = in.FocalLengthPx();
  const double k = std::pow(in.width_px / (2 * f), 2) + std::pow(in.height_px / (2 * f), 2);
  const double a = std::min(D, D * (1 + k) / 2);
  const double radius = std::max(a, std::sqrt((D - a) * (D - a) + D * D * k));
  const Eigen::Isometry3d T_WC = ToIsometry(X_WC);
  const Eigen::Vector3d centre_L = R_WL.transpose() * (T_WC * Eigen::Vector3d(a, 0, 0));
  // the region: a little larger than the sphere, kept while the sphere fits in it (the texels stay put
  // in the world while the camera moves, so shadow edges do not crawl from frame to frame, and
  // cameras close together share the map); else centred on the sphere, snapped to a grid of
  // kSnapTexels texels
  const double half = radius / (1.0 - 2.0 * kSnapTexels / kTexels);
  const double grid = 2.0 * half * kSnapTexels / kTexels;
  if (region_half_m_ != half || (centre_L - region_centre_L_).cwiseAbs().maxCoeff() > half - radius) {
    region_centre_L_ = (centre_L / grid).array().round().matrix() * grid;
    region_half_m_ = half;
  }
  const Eigen::Vector3d snapped_L = region_centre_L_;
  // orthographic clip space: x, y over the region, depth from the top (towards the sun) to the bottom
  const double z_top = snapped_L.z() + half + kCastersAbove_m, z_bottom = snapped_L.z() - half;
  Eigen::Matrix4d T_clip_L = Eigen::Matrix4d::Identity();
  T_clip_L(0, 0) = T_clip_L(1, 1) = 1.0 / half;
  T_clip_L(0, 3) = -snapped_L.x() / half;
  T_clip_L(1, 3) = -snapped_L.y() / half;
  T_clip_L(2, 2) = -2.0 / (z_top - z_bottom);  // z_clip = (z_top + z_bottom - 2 z_L) / (z_top - z_bottom)
  T_clip_L(2, 3) = (z_top + z_bottom) / (z_top - z_bottom);
  Eigen::Matrix4d T_LW = Eigen::Matrix4d::Identity();
  T_LW.topLeftCorner<3, 3>() = R_WL.transpose();
  const Eigen::Matrix4d T_clip_W = T_clip_L * T_LW;
  Eigen::Matrix4d T_S_clip = Eigen::Matrix4d::Identity();  // clip -1..1 -> texture 0..1
  T_S_clip.topLeftCorner<3, 3>() *= 0.5;
  T_S_clip.topRightCorner<3, 1>().setConstant(0.5);
  T_SW_ = T_S_clip * T_clip_W;
  for (bool static_models : {true, false}) {
    ShadowLayer& layer = static_models ? fixed_ : moving_;
    const size_t key = SceneKey(world, static_models, snapped_L, half);
    if (layer.drawn_for == key) continue;
    DrawCasters(world, T_clip_W, static_models, &layer);
    layer.drawn_for = key;
  }
  glBindVertexArray(0);
  return true;
}

void SunShadow::DrawCasters(const physics::World& world, const Eigen::Matrix4d& T_clip_W, bool static_models,
                            ShadowLayer* layer) {
  if (!layer->fbo) {
    glGenTextures(1, &layer->depth);
    glBindTexture(GL_TEXTURE_2D, layer->depth);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, layer->texels, layer->texels, 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                 nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);  // with the compare: 2 x 2 filtering
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);  // lit where no caster is nearer the sun
    glGenFramebuffers(1, &layer->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, layer->fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, layer->depth, 0);
    glDrawBuffer(GL_NONE);
    glReadBuffer(GL_NONE);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw SimError("camera renderer: cannot make the sun's shadow map");
  }
  glBindFramebuffer(GL_FRAMEBUFFER, layer->fbo);
  glViewport(0, 0, layer->texels, layer->texels);
  glClear(GL_DEPTH_BUFFER_BIT);
  glUseProgram(programs_.shadow);
  glEnable(GL_POLYGON_OFFSET_FILL);  // the surface itself stays lit (no shadow acne), slope by slope
  glPolygonOffset(2.0f, 4.0f);
  glEnable(GL_DEPTH_CLAMP);  // casters beyond the top still cast
  layer->empty = true;
  for (const physics::ModelPtr& model : world.Models()) {
    if (model->IsStatic() != static_models) continue;
    for (const geometry::Visual& visual : model->Visuals()) {
      if (!visual.cast_shadows) continue;
      Eigen::Matrix4d S;
      const GpuMesh* mesh = meshes_.ShadowFor(visual.shape, &S);
      if (!mesh) continue;
      const Eigen::Matrix4d T_clip_V = T_clip_W * ToIsometry(visual.X_LV + visual.link->WorldPose()).matrix() * S;
      const double scale = T_clip_V.topLeftCorner<2, 3>().colwise().norm().maxCoeff();
      const Eigen::Matrix4f T = T_clip_V.cast<float>();
      bool bound = false;
      for (const GpuPart& part : mesh->parts)
        for (const Chunk& chunk : part.chunks) {
          const Eigen::Vector4d c =
              T_clip_V * Eigen::Vector4d(chunk.centre_m.x(), chunk.centre_m.y(), chunk.centre_m.z(), 1);
          const double r = scale * chunk.radius_m;
          if (std::abs(c.x()) > 1 + r || std::abs(c.y()) > 1 + r || c.z() > 1 + r) continue;  // beside or below
          if (!bound) {
            glUniformMatrix4fv(programs_.shadow_T_clip_V, 1, GL_FALSE, T.data());
            glBindVertexArray(mesh->vao);
            bound = true;
          }
          layer->empty = false;
          const auto first = static_cast<GLint>(3 * chunk.first_triangle);
          const auto count = static_cast<GLsizei>(3 * chunk.triangles);
          if (mesh->ebo)
            glDrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT, reinterpret_cast<void*>(first * sizeof(uint32_t)));
          else glDrawArrays(GL_TRIANGLES, first, count);
        }
    }
  }
  glDisable(GL_DEPTH_CLAMP);
  glDisable(GL_POLYGON_OFFSET_FILL);
}

}  // namespace rendering
}  // namespace rotors_sim
