#include "rotors_core/rendering/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "physics/pose_math.h"
#include "rendering/gl.h"
#include "rendering/gl_context.h"
#include "rendering/gpu_cache.h"
#include "rendering/lru_cache.h"
#include "rendering/render_targets.h"
#include "rendering/shader_programs.h"
#include "rendering/sun_shadow.h"
#include "rotors_core/error.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/rendering/distortion_map.h"
#include "rotors_core/rendering/tessellation.h"

namespace rotors_sim {
namespace rendering {
namespace {

/// One visual in a camera's view: its transforms, and its chunks in view (Impl::visible[first, end)).
struct VisualDraw {
  const geometry::Visual* visual = nullptr;
  const GpuMesh* mesh = nullptr;
  Eigen::Matrix4f T_OV, T_SV;
  Eigen::Matrix3f N_OV;
  size_t first = 0, end = 0;
};

constexpr int kTerrainUnit = 3;  // texture units 3..6: a heightmap's layers (0: a part's texture, 1, 2: shadows)

/// Sets a heightmap's texture layers for the shading pass (none for another visual); true when it has some.
bool SetTerrain(const geometry::Visual& visual, const FragmentUniforms& u, TextureCache* textures) {
  const size_t n = std::min<size_t>(visual.terrain_layers.size(), 4);
  glUniform1i(u.terrain_layers, static_cast<GLint>(n));
  if (n == 0) return false;
  float layers[4][4] = {};
  GLuint texture[4] = {};
  for (size_t i = 0; i < n; ++i) {  // all loaded first: loading binds a new texture to the active unit
    const geometry::TerrainLayer& layer = visual.terrain_layers[i];
    texture[i] = layer.diffuse_file.empty() ? 0 : textures->For(layer.diffuse_file);
    layers[i][0] = static_cast<float>(1.0 / layer.size_m);
    layers[i][1] = static_cast<float>(layer.min_height_m);
    layers[i][2] = static_cast<float>(layer.fade_m);
    layers[i][3] = texture[i] != 0 ? 1.0f : 0.0f;
  }
  for (size_t i = 0; i < n; ++i) {
    glActiveTexture(GL_TEXTURE0 + kTerrainUnit + static_cast<GLenum>(i));
    glBindTexture(GL_TEXTURE_2D, texture[i]);
  }
  glActiveTexture(GL_TEXTURE0);
  glUniform4fv(u.terrain_layer, 4, &layers[0][0]);
  return true;
}

}  // namespace

/// The renderer's parts, in the order they are made: the context first (released last, after
/// everything made in it), then the programs, the caches and the shadow map.
struct Renderer::Impl {
  static constexpr size_t kDistortionMapCapacity = 16;
  GlContext gl;  // current from here until the end of the constructor
  ShaderPrograms programs;
  MeshCache meshes;
  TextureCache textures;
  RenderTargets targets;
  SunShadow shadow{programs, &meshes};
  LruCache<std::string, std::unique_ptr<DistortionMap>> distortion_maps{kDistortionMapCapacity};  // by DistortionKey
  std::vector<VisualDraw> draws;                         // scratch of a frame: the visuals in view
  std::vector<std::pair<size_t, const Chunk*>> visible;  // and their chunks in view (part, chunk)
  RenderedFrame pinhole_frame;                           // scratch of distorted cameras

  Impl() {
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);  // meshes of unknown winding; the optical frame mirrors GL's anyway
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    eglMakeCurrent(gl.Display(), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);  // current only while rendering
  }
  /// A frame starts: the caches drop what has not been used for longest, beyond their capacity.
  void NextFrame() {
    meshes.NextFrame();
    textures.NextFrame();
    targets.NextFrame();
    distortion_maps.NextFrame();
  }
};

Renderer& Renderer::Of(physics::World& world) {
  std::shared_ptr<void>& state = world.PluginState("rotors_sim/renderer");
  if (!state) state = std::shared_ptr<Renderer>(new Renderer());
  return *std::static_pointer_cast<Renderer>(state);
}

// a start that fails halfway releases what it made: Impl's members are destroyed in reverse, the context last
Renderer::Renderer() : impl_(new Impl) {}

Renderer::~Renderer() {
  // what was made in the context (caches, programs) is released with it current, the context last
  const ContextBinding current(impl_->gl);
  impl_.reset();
}

size_t Renderer::CachedTriangles() const { return impl_->meshes.Triangles(); }

Renderer::CacheSizes Renderer::CachedObjects() const {
  return {impl_->meshes.Size(), impl_->textures.Size(), impl_->targets.Size(), impl_->distortion_maps.Size()};
}

namespace {
/// Everything a distortion map depends on, printed exactly.
std::string DistortionKey(const CameraSpec& camera) {
  const CameraIntrinsics& in = camera.intrinsics;
  const LensDistortion& d = camera.distortion;
  char key[256];
  std::snprintf(key, sizeof(key), "%d %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g", in.width_px, in.height_px,
                in.horizontal_fov_rad, in.center_u, in.center_v, d.k1, d.k2, d.k3, d.p1, d.p2);
  return key;
}

}  // namespace

void AddGaussianNoise(const CameraSpec& camera, uint64_t seed, std::vector<uint8_t>* image) {
  if (camera.noise_stddev <= 0.0 && camera.noise_mean == 0.0) return;
  std::mt19937_64 random(seed);
  std::normal_distribution<double> gaussian(camera.noise_mean, camera.noise_stddev);
  for (uint8_t& value : *image)
    value = static_cast<uint8_t>(std::clamp(std::lround(value + 255.0 * gaussian(random)), 0L, 255L));
}

void Renderer::Render(const physics::World& world, const ignition::math::Pose3d& X_WC, const CameraSpec& camera,
                      uint64_t noise_seed, bool want_image, bool want_depth, RenderedFrame* out) {
  const ContextBinding current(impl_->gl);
  Impl& r = *impl_;
  r.NextFrame();
  if (camera.distortion.IsIdentity()) {
    DrawPinhole(world, X_WC, camera, noise_seed, want_image, want_depth, 0);
    ReadPinhole(camera, want_image, want_depth, 0, out);
    return;
  }
  const std::string key = DistortionKey(camera);
  std::unique_ptr<DistortionMap>* found = r.distortion_maps.Find(key);
  const DistortionMap* map =
      (found ? *found : r.distortion_maps.Insert(key, std::make_unique<DistortionMap>(camera))).get();
  CameraSpec pinhole = camera;
  pinhole.intrinsics = map->Pinhole();
  pinhole.distortion = LensDistortion();
  pinhole.noise_mean = pinhole.noise_stddev = 0.0;
  DrawPinhole(world, X_WC, pinhole, 0, want_image, want_depth, 0);
  ReadPinhole(pinhole, want_image, want_depth, 0, &r.pinhole_frame);
  out->width_px = camera.intrinsics.width_px;
  out->height_px = camera.intrinsics.height_px;
  out->image.clear();
  out->depth_m.clear();
  if (want_image) {
    map->RemapImage(r.pinhole_frame.image, BytesPerPixel(camera.format), &out->image);
    AddGaussianNoise(camera, noise_seed, &out->image);
  }
  if (want_depth) map->RemapDepth(r.pinhole_frame.depth_m, &out->depth_m);
}

void Renderer::RenderAll(const physics::World& world, const std::vector<FrameRequest>& requests) {
  const ContextBinding current(impl_->gl);
  impl_->NextFrame();
  // each pinhole camera's drawing goes to the rasteriser (glFlush) before the next one is prepared,
  // and all are read back after: llvmpipe's threads draw one camera while this thread sets up the next
  std::vector<const FrameRequest*> pinholes;  // the slot of each is its index
  for (const FrameRequest& q : requests) {
    if (!q.camera->distortion.IsIdentity()) continue;
    DrawPinhole(world, q.X_WC, *q.camera, q.noise_seed, q.want_image, q.want_depth, pinholes.size());
    glFlush();
    pinholes.push_back(&q);
  }
  for (size_t slot = 0; slot < pinholes.size(); ++slot) {
    const FrameRequest& q = *pinholes[slot];
    ReadPinhole(*q.camera, q.want_image, q.want_depth, slot, q.out);
  }
  for (const FrameRequest& q : requests)
    if (!q.camera->distortion.IsIdentity())
      Render(world, q.X_WC, *q.camera, q.noise_seed, q.want_image, q.want_depth, q.out);
}

void Renderer::DrawPinhole(const physics::World& world, const ignition::math::Pose3d& X_WC, const CameraSpec& camera,
                           uint64_t noise_seed, bool want_image, bool want_depth, size_t slot) {
  Impl& r = *impl_;  // its context is current: Render and RenderAll bind it
  const CameraIntrinsics& in = camera.intrinsics;
  const int W = in.width_px, H = in.height_px;
  const PixelFormat format = camera.format;
  const bool shadows = want_image && r.shadow.Update(world, X_WC, in);  // depth needs no shadows
  const Target& target = r.targets.For(W, H, format, want_depth, slot);
  const ShaderPrograms& programs = r.programs;
  glBindFramebuffer(GL_FRAMEBUFFER, target.fbo);
  glViewport(0, 0, W, H);
  glClear(GL_DEPTH_BUFFER_BIT);  // to 1: the far plane

  const geometry::Lighting& light = world.GetLighting();
  const Eigen::Isometry3d T_OW = ToIsometry(OpticalInCamera() + X_WC).inverse();  // X_WO = X_WC X_CO
  Eigen::Vector3d to_sun_W(-light.sun_direction_W.X(), -light.sun_direction_W.Y(), -light.sun_direction_W.Z());
  const Eigen::Vector3f to_sun_O = (T_OW.linear() * to_sun_W.normalized()).cast<float>();
  const float f = static_cast<float>(in.FocalLengthPx());

  for (GLuint program : {programs.background, programs.mesh}) {
    const FragmentUniforms& u = program == programs.mesh ? programs.mesh_fragment : programs.background_fragment;
    glUseProgram(program);
    glUniform1i(u.use_vertex_colour, 0);
    glUniform1i(u.use_texture, 0);
    glUniform1i(u.texture_image, 0);
    glUniform3f(u.to_sun_O, to_sun_O.x(), to_sun_O.y(), to_sun_O.z());
    glUniform1f(u.ambient, light.ambient);
    glUniform1f(u.sun_diffuse, light.sun_diffuse);
    glUniform1i(u.use_shadows, shadows);
    glUniform1i(u.shadow_map, 1);
    glUniform1i(u.use_moving_shadows, shadows && !r.shadow.Moving().empty);
    glUniform1i(u.moving_shadow_map, 2);
    glUniform1i(u.terrain_layers, 0);
    for (int i = 0; i < 4; ++i) glUniform1i(u.terrain_texture[i], kTerrainUnit + i);
    glUniform1i(u.grey, format == PixelFormat::kL8);
    glUniform2f(u.noise, static_cast<float>(camera.noise_mean), static_cast<float>(camera.noise_stddev));
    glUniform2ui(u.seed, static_cast<GLuint>(noise_seed), static_cast<GLuint>(noise_seed >> 32));
    glUniform1i(u.background, program == programs.background);
  }

  // what is in view: each visual's transforms and its chunks in view, part by part (a vehicle's own
  // body behind its camera is skipped)
  std::vector<VisualDraw>& draws = r.draws;
  std::vector<std::pair<size_t, const Chunk*>>& visible = r.visible;  // part, chunk
  draws.clear();
  visible.clear();
  for (const physics::ModelPtr& model : world.Models()) {
    for (const geometry::Visual& visual : model->Visuals()) {
      Eigen::Matrix4d S;
      const GpuMesh* mesh = r.meshes.For(visual.shape, &S);
      if (!mesh) continue;
      const ignition::math::Pose3d X_WV = visual.X_LV + visual.link->WorldPose();
      const Eigen::Matrix4d T_WV = ToIsometry(X_WV).matrix() * S;
      const Eigen::Matrix4d T_OV = T_OW.matrix() * T_WV;
      const Eigen::Matrix3d A = T_OV.topLeftCorner<3, 3>();
      const double scale = A.colwise().norm().maxCoeff();
      VisualDraw draw;
      draw.first = visible.size();
      for (size_t p = 0; p < mesh->parts.size(); ++p)
        for (const Chunk& chunk : mesh->parts[p].chunks)
          if (in.MaySee(A * chunk.centre_m.cast<double>() + T_OV.topRightCorner<3, 1>(), scale * chunk.radius_m))
            visible.push_back({p, &chunk});
      if (visible.size() == draw.first) continue;
      draw.end = visible.size();
      draw.visual = &visual;
      draw.mesh = mesh;
      draw.T_OV = T_OV.cast<float>();
      draw.N_OV = A.inverse().transpose().cast<float>();
      if (shadows) draw.T_SV = (r.shadow.T_SW() * T_WV).cast<float>();
      draws.push_back(draw);
    }
  }
  auto draw_chunk = [](const GpuMesh& mesh, const Chunk& chunk) {
    const auto first = static_cast<GLint>(3 * chunk.first_triangle);
    const auto count = static_cast<GLsizei>(3 * chunk.triangles);
    if (mesh.ebo)
      glDrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT, reinterpret_cast<void*>(first * sizeof(uint32_t)));
    else glDrawArrays(GL_TRIANGLES, first, count);
  };

  // the pinhole projection, the same in both passes (kMeshVertexShader's projection and principal)
  auto set_projection = [&](GLint projection, GLint principal) {
    glUniform4f(projection, 2 * f / W, 2 * f / H, static_cast<float>(in.near_m), static_cast<float>(in.far_m));
    glUniform2f(principal, static_cast<float>(2.0 * (in.Cx() + 0.5) / W - 1.0),
                static_cast<float>(2.0 * (in.Cy() + 0.5) / H - 1.0));
  };

  // the depth pre-pass: the nearest surface's depth at each pixel, no shading
  glUseProgram(programs.depth);
  set_projection(programs.depth_vertex.projection, programs.depth_vertex.principal);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  for (const VisualDraw& draw : draws) {
    glUniformMatrix4fv(programs.depth_vertex.T_OV, 1, GL_FALSE, draw.T_OV.data());
    glBindVertexArray(draw.mesh->vao);
    for (size_t k = draw.first; k < draw.end; ++k) draw_chunk(*draw.mesh, *visible[k].second);
  }
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);

  // the shading pass: only the fragments at the pre-pass's depth (each pixel shaded once)
  glUseProgram(programs.mesh);
  glDepthFunc(GL_EQUAL);
  glDepthMask(GL_FALSE);
  const MeshUniforms& vertex = programs.mesh_vertex;
  set_projection(vertex.projection, vertex.principal);
  const FragmentUniforms& fragment = programs.mesh_fragment;
  if (shadows) {
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, r.shadow.Fixed().depth);
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, r.shadow.Moving().depth);
  }
  glActiveTexture(GL_TEXTURE0);
  bool terrain_drawn = false;  // the terrain uniforms are set (the visual before was a textured heightmap)
  for (const VisualDraw& draw : draws) {
    const geometry::Visual& visual = *draw.visual;
    const GpuMesh& mesh = *draw.mesh;
    glUniformMatrix4fv(vertex.T_OV, 1, GL_FALSE, draw.T_OV.data());
    glUniformMatrix3fv(vertex.N_OV, 1, GL_FALSE, draw.N_OV.data());
    if (shadows) glUniformMatrix4fv(vertex.T_SV, 1, GL_FALSE, draw.T_SV.data());
    // an SDF/URDF <material> colours the whole visual; else the mesh's own colours and texture
    const bool own = mesh.own_colours && !visual.has_material;
    if (!visual.terrain_layers.empty() || terrain_drawn) terrain_drawn = SetTerrain(visual, fragment, &r.textures);
    if (own) glUniform3f(fragment.albedo, 1.0f, 1.0f, 1.0f);
    else glUniform3f(fragment.albedo, visual.rgba[0], visual.rgba[1], visual.rgba[2]);
    glUniform1i(fragment.use_vertex_colour, own);
    // a material script's texture on a primitive replaces the mesh parts' own (an SDF/URDF colour removes them)
    const GLuint script_texture =
        visual.texture_file.empty() ? 0 : r.textures.For(visual.texture_file, visual.texture_max_anisotropy);
    glBindVertexArray(mesh.vao);
    for (size_t k = draw.first; k < draw.end; ++k) {
      const auto [p, chunk] = visible[k];
      if (k == draw.first || visible[k - 1].first != p) {  // a new part: its texture
        const std::string& part_texture = mesh.parts[p].texture_file;
        GLuint texture = visual.has_material || part_texture.empty() ? 0 : r.textures.For(part_texture);
        float repeat_u = 1.0f, repeat_v = 1.0f;
        if (!visual.texture_file.empty()) {
          texture = script_texture;
          repeat_u = 1.0f / visual.texture_scale[0];
          repeat_v = 1.0f / visual.texture_scale[1];
        }
        const bool textured = texture != 0;
        glUniform1i(fragment.use_texture, textured);
        if (textured) {
          glBindTexture(GL_TEXTURE_2D, texture);
          glUniform2f(fragment.uv_scale, repeat_u, repeat_v);
        }
      }
      draw_chunk(mesh, *chunk);
    }
  }
  // the sky last, on the far plane where nothing was drawn (early depth test: no overdraw), through
  // the same noise as everything else
  glUseProgram(programs.background);
  glUniform3f(programs.background_fragment.albedo, light.background[0], light.background[1], light.background[2]);
  glDepthFunc(GL_LEQUAL);
  glBindVertexArray(programs.empty_vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  glBindVertexArray(0);
}

void Renderer::ReadPinhole(const CameraSpec& camera, bool want_image, bool want_depth, size_t slot,
                           RenderedFrame* out) {
  const int W = camera.intrinsics.width_px, H = camera.intrinsics.height_px;
  const PixelFormat format = camera.format;
  glBindFramebuffer(GL_FRAMEBUFFER, impl_->targets.For(W, H, format, want_depth, slot).fbo);  // DrawPinhole's
  out->width_px = W;
  out->height_px = H;
  out->image.clear();
  out->depth_m.clear();
  if (want_image) {
    out->image.resize(static_cast<size_t>(W) * H * BytesPerPixel(format));
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    const GLenum gl_format = format == PixelFormat::kL8 ? GL_RED : format == PixelFormat::kR8G8B8 ? GL_RGB : GL_BGR;
    glReadPixels(0, 0, W, H, gl_format, GL_UNSIGNED_BYTE, out->image.data());
  }
  if (want_depth) {
    out->depth_m.resize(static_cast<size_t>(W) * H);
    glReadBuffer(GL_COLOR_ATTACHMENT1);
    glReadPixels(0, 0, W, H, GL_RED, GL_FLOAT, out->depth_m.data());
    for (float& z : out->depth_m)
      if (z < 0.0f) z = std::numeric_limits<float>::quiet_NaN();
  }
}

}  // namespace rendering
}  // namespace rotors_sim
