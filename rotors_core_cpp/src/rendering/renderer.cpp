#include "rotors_core/rendering/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <tuple>

#include <iostream>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>
#include <Eigen/Geometry>
#include <stb/stb_image.h>

#include "rotors_core/error.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/rendering/distortion_map.h"
#include "rotors_core/rendering/tessellation.h"
#include "physics/pose_math.h"

namespace rotors_sim {
namespace rendering {
namespace {

using geometry::Shape;

const char* kMeshVertexShader = R"(#version 330 core
layout(location = 0) in vec3 p_V;
layout(location = 1) in vec3 n_V;
layout(location = 2) in vec3 colour_V;
layout(location = 3) in vec2 uv_V;
uniform mat4 T_OV;        // visual frame -> optical frame (x right, y down, z forward)
uniform mat3 N_OV;        // normals visual -> optical: inverse transpose of T_OV's linear part
uniform vec4 projection;  // 2 f / W, 2 f / H, near, far
uniform vec2 principal;   // the principal point in NDC: 2 (c + 1/2) / W - 1, 2 (c_y + 1/2) / H - 1
uniform mat4 T_SV;        // visual frame -> shadow-map coordinates (s, t, depth in 0..1)
out vec3 p_O;
out vec3 n_O;
out vec3 vertex_colour;
out vec2 uv;
out vec3 p_S;
invariant gl_Position;  // the depth pre-pass and the shading pass give the same depth, bit for bit
void main() {
  vec4 p = T_OV * vec4(p_V, 1.0);
  p_O = p.xyz;
  p_S = (T_SV * vec4(p_V, 1.0)).xyz;
  n_O = N_OV * n_V;
  vertex_colour = colour_V;
  uv = uv_V;
  float near = projection.z, far = projection.w;
  // x_ndc = 2 f x / (W z) + principal.x, likewise y: pixel u = f x / z + c_x, rows top down
  gl_Position = vec4(projection.x * p.x + principal.x * p.z, projection.y * p.y + principal.y * p.z,
                     (far + near) / (far - near) * p.z - 2.0 * far * near / (far - near), p.z);
})";

const char* kBackgroundVertexShader = R"(#version 330 core
out vec3 p_O;
out vec3 n_O;
out vec3 vertex_colour;
out vec2 uv;
out vec3 p_S;
void main() {
  // one triangle covering the viewport, on the far plane
  vec2 corner = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
  p_O = vec3(0.0);
  n_O = vec3(0.0);
  vertex_colour = vec3(1.0);
  uv = vec2(0.0);
  p_S = vec3(0.0);
  gl_Position = vec4(corner, 1.0, 1.0);
})";

// The sun's shadow map: depth only, in the sun's orthographic view
const char* kShadowVertexShader = R"(#version 330 core
layout(location = 0) in vec3 p_V;
uniform mat4 T_clip_V;  // visual frame -> the sun's clip space
void main() { gl_Position = T_clip_V * vec4(p_V, 1.0); })";

const char* kShadowFragmentShader = R"(#version 330 core
void main() {})";

// The depth pre-pass draws the meshes with this (and kMeshVertexShader): depth only, so that the
// shading pass then shades each pixel once, for the nearest surface (no overdraw)
const char* kDepthOnlyFragmentShader = kShadowFragmentShader;

const char* kFragmentShader = R"(#version 330 core
in vec3 p_O;
in vec3 n_O;
in vec3 vertex_colour;
in vec2 uv;
in vec3 p_S;
uniform vec3 albedo;
uniform bool use_vertex_colour;
uniform bool use_texture;
uniform sampler2D texture_image;
uniform vec2 uv_scale;    // texture repeats per unit of uv (1 / an OGRE texture_unit's scale)
uniform vec3 to_sun_O;
uniform float ambient;
uniform float sun_diffuse;
uniform bool use_shadows;
uniform sampler2DShadow shadow_map;         // static models' casters
uniform bool use_moving_shadows;
uniform sampler2DShadow moving_shadow_map;  // the other models' (vehicles), same region
uniform bool background;
uniform bool grey;
uniform vec2 noise;       // mean, stddev (full scale 1)
uniform uvec2 seed;
layout(location = 0) out vec4 colour;
layout(location = 1) out float depth_m;

uint Hash(uint x) {  // lowbias32
  x ^= x >> 16; x *= 0x7feb352du; x ^= x >> 15; x *= 0x846ca68bu; x ^= x >> 16;
  return x;
}
float Uniform01(uint k) { return (float(Hash(k) >> 8) + 0.5) / 16777216.0; }
float Gaussian(uint channel) {  // Box-Muller from two hashed uniforms
  uint k = Hash(uint(gl_FragCoord.x) * 73856093u ^ uint(gl_FragCoord.y) * 19349663u ^ seed.x) ^ seed.y;
  k = Hash(k + channel * 0x9e3779b9u);
  return sqrt(-2.0 * log(Uniform01(k))) * cos(6.28318530718 * Uniform01(k ^ 0x68e31da4u));
}

// The share of the sun this fragment gets: 1 outside the shadow maps, else the comparison with the
// 2 x 2 nearest texels, interpolated (one lookup per map: more taps cost a third of the frame rate on llvmpipe)
float SunLit() {
  if (!use_shadows || any(lessThan(p_S, vec3(0.0))) || any(greaterThan(p_S, vec3(1.0)))) return 1.0;
  float lit = texture(shadow_map, p_S);
  if (use_moving_shadows) lit = min(lit, texture(moving_shadow_map, p_S));
  return lit;
}

void main() {
  vec3 c = albedo;
  if (use_vertex_colour) c *= vertex_colour;
  if (use_texture) c *= texture(texture_image, uv * uv_scale).rgb;
  if (!background) {
    vec3 n = normalize(n_O);
    if (dot(n, p_O) > 0.0) n = -n;  // light the side the camera sees
    float n_dot_sun = dot(n, to_sun_O);
    c *= ambient + sun_diffuse * max(n_dot_sun, 0.0) * (n_dot_sun > 0.0 ? SunLit() : 1.0);
  }
  if (grey) c = vec3(dot(c, vec3(0.299, 0.587, 0.114)));
  if (noise.y > 0.0 || noise.x != 0.0) {
    c.r += noise.x + noise.y * Gaussian(0u);
    if (grey) { c.g = c.r; c.b = c.r; }
    else { c.g += noise.x + noise.y * Gaussian(1u); c.b += noise.x + noise.y * Gaussian(2u); }
  }
  colour = vec4(clamp(c, 0.0, 1.0), 1.0);
  depth_m = background ? -1.0 : p_O.z;
})";

bool HasExtension(const char* name) {
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i)
    if (std::strcmp(reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, i)), name) == 0) return true;
  return false;
}

GLuint Compile(GLenum type, const char* source) {
  GLuint shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetShaderInfoLog(shader, sizeof(log), nullptr, log);
    throw SimError(std::string("camera renderer: shader does not compile: ") + log);
  }
  return shader;
}

GLuint Link(const char* vertex, const char* fragment) {
  GLuint program = glCreateProgram();
  glAttachShader(program, Compile(GL_VERTEX_SHADER, vertex));
  glAttachShader(program, Compile(GL_FRAGMENT_SHADER, fragment));
  glBindFragDataLocation(program, 0, "colour");
  glBindFragDataLocation(program, 1, "depth_m");
  glLinkProgram(program);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) throw SimError("camera renderer: shader program does not link");
  return program;
}

/// A uniform's location; throws when the program has none of that name (misspelt, or unused and
/// optimised away), which glUniform* calls would otherwise ignore silently.
GLint RequireUniform(GLuint program, const char* name) {
  const GLint location = glGetUniformLocation(program, name);
  if (location < 0)
    throw SimError(std::string("camera renderer: the shader program has no uniform '") + name +
                   "' (misspelt, or unused and optimised away)");
  return location;
}

/// The fragment shader's uniforms in one program, resolved once. The background program draws
/// one flat, unlit colour, so the compiler drops the lighting and mesh colouring there: those are
/// looked up without the check (-1: setting them does nothing, as intended).
struct FragmentUniforms {
  GLint albedo = -1, use_vertex_colour = -1, use_texture = -1, texture_image = -1, uv_scale = -1, to_sun_O = -1,
        ambient = -1, sun_diffuse = -1, use_shadows = -1, shadow_map = -1, use_moving_shadows = -1,
        moving_shadow_map = -1, background = -1, grey = -1, noise = -1, seed = -1;
  FragmentUniforms() = default;
  FragmentUniforms(GLuint program, bool draws_meshes) {
    auto mesh_only = [&](const char* name) {
      return draws_meshes ? RequireUniform(program, name) : glGetUniformLocation(program, name);
    };
    albedo = RequireUniform(program, "albedo");
    background = RequireUniform(program, "background");
    grey = RequireUniform(program, "grey");
    noise = RequireUniform(program, "noise");
    seed = RequireUniform(program, "seed");
    use_vertex_colour = mesh_only("use_vertex_colour");
    use_texture = mesh_only("use_texture");
    texture_image = mesh_only("texture_image");
    uv_scale = mesh_only("uv_scale");
    to_sun_O = mesh_only("to_sun_O");
    ambient = mesh_only("ambient");
    sun_diffuse = mesh_only("sun_diffuse");
    use_shadows = mesh_only("use_shadows");
    shadow_map = mesh_only("shadow_map");
    use_moving_shadows = mesh_only("use_moving_shadows");
    moving_shadow_map = mesh_only("moving_shadow_map");
  }
};

/// The mesh vertex shader's uniforms, resolved once.
struct MeshUniforms {
  GLint T_OV = -1, N_OV = -1, projection = -1, principal = -1, T_SV = -1;
  explicit MeshUniforms(GLuint program = 0) {
    if (!program) return;
    T_OV = RequireUniform(program, "T_OV");
    T_SV = RequireUniform(program, "T_SV");
    N_OV = RequireUniform(program, "N_OV");
    projection = RequireUniform(program, "projection");
    principal = RequireUniform(program, "principal");
  }
};

/// The depth pre-pass program's uniforms (kMeshVertexShader's that set the position), resolved once.
struct DepthUniforms {
  GLint T_OV = -1, projection = -1, principal = -1;
  explicit DepthUniforms(GLuint program = 0) {
    if (!program) return;
    T_OV = RequireUniform(program, "T_OV");
    projection = RequireUniform(program, "projection");
    principal = RequireUniform(program, "principal");
  }
};

/// Triangles drawn with one texture (a mesh's part), in compact runs each culled on its own.
struct GpuPart {
  GLuint texture = 0;  // 0: none
  std::vector<Chunk> chunks;
};

/// A soup to upload as one part, and the image file of its texture ("" for none).
struct PartSoup {
  TriangleSoup soup;
  std::string texture_file;
};

struct GpuMesh {
  GLuint vao = 0, vbo = 0, ebo = 0;    // ebo 0: not indexed
  bool own_colours = false;            // per-vertex colours from the mesh file
  std::vector<GpuPart> parts;          // one per texture of the mesh
  std::shared_ptr<const void> source;  // keeps the key's object alive
};

/// One visual in a camera's view: its transforms, and its chunks in view (Impl::visible[first, end)).
struct VisualDraw {
  const geometry::Visual* visual = nullptr;
  const GpuMesh* mesh = nullptr;
  Eigen::Matrix4f T_OV, T_SV;
  Eigen::Matrix3f N_OV;
  size_t first = 0, end = 0;
};

struct Target {
  GLuint fbo = 0, colour = 0, depth_out = 0, depth_buffer = 0;
};

/// Depth seen from the sun over a shadow map's region, drawn from some of the models' visuals.
struct ShadowLayer {
  int texels = 0;  // per side
  GLuint fbo = 0, depth = 0;
  size_t drawn_for = 0;  // SceneKey of what it was last drawn from; 0: nothing yet
  bool empty = true;     // no caster in the region
};

/// The sun's shadow map around a camera's view: depth seen from the sun (orthographic), and the
/// transform from the world to its coordinates (s, t, depth, each 0..1 over the map). Static
/// models' casters are drawn into one layer, again only when the region moves or one of them is
/// moved; the other models' (vehicles) into a second, coarser layer, again whenever they move.
struct ShadowMap {
  static constexpr int kTexels = 2048;              // per side, the static layer
  static constexpr int kMovingTexels = 1024;        // per side, the layer of the other models
  static constexpr double kViewDistance_m = 30.0;   // shadows are drawn up to this far from a camera
  static constexpr double kCastersAbove_m = 200.0;  // casters this far towards the sun beyond the view still count
  static constexpr int kSnapTexels = 32;            // the map moves in steps of this many texels
  ShadowLayer fixed{kTexels}, moving{kMovingTexels};
  Eigen::Vector3d region_centre_L = Eigen::Vector3d::Zero();  // in the sun's frame
  double region_half_m = 0.0;                                 // 0: no region yet
  Eigen::Matrix4d T_SW = Eigen::Matrix4d::Identity();
};

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

struct Renderer::Impl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  GLuint mesh_program = 0, background_program = 0, shadow_program = 0, depth_program = 0, empty_vao = 0;
  GLint shadow_T_clip_V = -1;
  FragmentUniforms mesh_fragment, background_fragment;
  MeshUniforms mesh_vertex;
  DepthUniforms depth_vertex;
  ShadowMap shadow;
  std::vector<VisualDraw> draws;                             // scratch of a frame: the visuals in view
  std::vector<std::pair<size_t, const Chunk*>> visible;      // and their chunks in view (part, chunk)
  std::map<const void*, GpuMesh> meshes;                     // by source object
  std::map<std::pair<std::string, float>, GLuint> textures;  // by image file and anisotropy (0: unreadable)
  // by width, height, format, depth, slot (each camera of a batch draws into its own)
  std::map<std::tuple<int, int, int, bool, size_t>, Target> targets;
  std::map<std::string, std::unique_ptr<DistortionMap>> distortion_maps;  // by DistortionKey
  RenderedFrame pinhole_frame;                                            // scratch of distorted cameras
  size_t triangles = 0;

  void CreateContext();
  const GpuMesh& Upload(const void* key, std::shared_ptr<const void> source, std::vector<PartSoup> parts,
                        std::map<const void*, GpuMesh>* into = nullptr);
  const GpuMesh& Upload(const void* key, std::shared_ptr<const void> source, TriangleSoup soup,
                        std::map<const void*, GpuMesh>* into = nullptr) {
    std::vector<PartSoup> one(1);
    one[0].soup = std::move(soup);
    return Upload(key, std::move(source), std::move(one), into);
  }
  const GpuMesh* MeshFor(const Shape& shape, Eigen::Matrix4d* S);
  GLuint TextureFor(const std::string& file, float max_anisotropy = 1.0f);
  Target& TargetFor(int width, int height, PixelFormat format, bool depth, size_t slot);
  const ShadowMap* ShadowFor(const physics::World& world, const ignition::math::Pose3d& X_WC,
                             const CameraIntrinsics& in);
  void DrawCasters(const physics::World& world, const Eigen::Matrix4d& T_clip_W, bool static_models,
                   ShadowLayer* layer);
  const GpuMesh* ShadowMeshFor(const Shape& shape, Eigen::Matrix4d* S);
  std::map<const void*, GpuMesh> shadow_proxies;  // simplified copies of large meshes, by source object
};

/// Makes a renderer's context current on this thread for one render call and releases it after.
/// A context left current on a thread that has ended cannot be made current on another one (Mesa
/// answers EGL_BAD_ACCESS unless the new thread happens to get the old one's bookkeeping address),
/// and a world may step from any thread. Nested calls (a distorted camera in a batch) reuse it.
class Renderer::ContextBinding {
 public:
  explicit ContextBinding(const Impl& r) : display_(r.display), bound_here_(eglGetCurrentContext() != r.context) {
    if (bound_here_ && !eglMakeCurrent(r.display, EGL_NO_SURFACE, EGL_NO_SURFACE, r.context))
      throw SimError("camera renderer: cannot make its OpenGL context current (EGL error 0x" + Hex(eglGetError()) +
                     ")");
  }
  ~ContextBinding() {
    if (bound_here_) eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
  ContextBinding(const ContextBinding&) = delete;
  ContextBinding& operator=(const ContextBinding&) = delete;

 private:
  static std::string Hex(EGLint code) {
    char text[16];
    std::snprintf(text, sizeof(text), "%04x", static_cast<unsigned>(code));
    return text;
  }
  EGLDisplay display_;
  bool bound_here_;
};

void Renderer::Impl::CreateContext() {
  auto get_platform_display =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  const std::string fix = " (headless rendering needs Mesa's EGL: apt install libegl-mesa0 libgl1-mesa-dri)";
  if (!get_platform_display) throw SimError("camera renderer: EGL has no eglGetPlatformDisplayEXT" + fix);
  display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  EGLint major = 0, minor = 0;
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor))
    throw SimError("camera renderer: no surfaceless EGL display" + fix);
  if (!eglBindAPI(EGL_OPENGL_API)) throw SimError("camera renderer: EGL cannot bind OpenGL" + fix);
  const EGLint attributes[] = {
      EGL_CONTEXT_MAJOR_VERSION,           3,       EGL_CONTEXT_MINOR_VERSION, 3, EGL_CONTEXT_OPENGL_PROFILE_MASK,
      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
  if (context == EGL_NO_CONTEXT || !eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
    throw SimError("camera renderer: no OpenGL 3.3 core context" + fix);
  mesh_program = Link(kMeshVertexShader, kFragmentShader);
  background_program = Link(kBackgroundVertexShader, kFragmentShader);
  mesh_fragment = FragmentUniforms(mesh_program, true);
  background_fragment = FragmentUniforms(background_program, false);
  mesh_vertex = MeshUniforms(mesh_program);
  depth_program = Link(kMeshVertexShader, kDepthOnlyFragmentShader);
  depth_vertex = DepthUniforms(depth_program);
  shadow_program = Link(kShadowVertexShader, kShadowFragmentShader);
  shadow_T_clip_V = RequireUniform(shadow_program, "T_clip_V");
  glGenVertexArrays(1, &empty_vao);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);  // meshes of unknown winding; the optical frame mirrors GL's anyway
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);  // current only while rendering
}

const GpuMesh& Renderer::Impl::Upload(const void* key, std::shared_ptr<const void> source, std::vector<PartSoup> parts,
                                      std::map<const void*, GpuMesh>* into) {
  GpuMesh mesh;
  mesh.source = std::move(source);
  bool any_colours = false;
  for (const PartSoup& p : parts) any_colours = any_colours || !p.soup.colours.empty();
  if (parts.size() > 1)
    for (const PartSoup& p : parts)
      if (!p.soup.indices.empty()) throw SimError("camera renderer: only an unindexed soup may come in parts");
  mesh.own_colours = any_colours;
  constexpr int kFloats = 11;  // position, normal, colour, uv
  std::vector<float> interleaved;
  size_t first_triangle = 0;
  for (PartSoup& p : parts) {
    TriangleSoup& soup = p.soup;
    GpuPart part;
    part.chunks = SortIntoChunks(&soup);
    for (Chunk& chunk : part.chunks) chunk.first_triangle += first_triangle;  // in the one buffer of all parts
    for (size_t i = 0; i < soup.VertexCount(); ++i) {
      interleaved.insert(interleaved.end(), soup.positions_m.begin() + 3 * i, soup.positions_m.begin() + 3 * i + 3);
      interleaved.insert(interleaved.end(), soup.normals.begin() + 3 * i, soup.normals.begin() + 3 * i + 3);
      if (!soup.colours.empty())
        interleaved.insert(interleaved.end(), soup.colours.begin() + 3 * i, soup.colours.begin() + 3 * i + 3);
      else interleaved.insert(interleaved.end(), {1.0f, 1.0f, 1.0f});
      if (!soup.uvs.empty())
        interleaved.insert(interleaved.end(), soup.uvs.begin() + 2 * i, soup.uvs.begin() + 2 * i + 2);
      else interleaved.insert(interleaved.end(), {0.0f, 0.0f});
    }
    if (!p.texture_file.empty() && !soup.uvs.empty()) part.texture = TextureFor(p.texture_file);
    first_triangle += soup.TriangleCount();
    mesh.parts.push_back(std::move(part));
  }
  glGenVertexArrays(1, &mesh.vao);
  glBindVertexArray(mesh.vao);
  glGenBuffers(1, &mesh.vbo);
  glBindBuffer(GL_ARRAY_BUFFER, mesh.vbo);
  glBufferData(GL_ARRAY_BUFFER, interleaved.size() * sizeof(float), interleaved.data(), GL_STATIC_DRAW);
  const GLsizei stride = kFloats * sizeof(float);
  const int sizes[] = {3, 3, 3, 2};
  for (int a = 0, offset = 0; a < 4; offset += sizes[a], ++a) {
    glVertexAttribPointer(a, sizes[a], GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offset * sizeof(float)));
    glEnableVertexAttribArray(a);
  }
  if (parts.size() == 1 && !parts[0].soup.indices.empty()) {
    const std::vector<uint32_t>& indices = parts[0].soup.indices;
    glGenBuffers(1, &mesh.ebo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mesh.ebo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, indices.size() * sizeof(uint32_t), indices.data(), GL_STATIC_DRAW);
  }
  glBindVertexArray(0);
  triangles += first_triangle;
  return (into ? into : &meshes)->emplace(key, std::move(mesh)).first->second;
}

/// The image file as a mip-mapped (trilinear), repeating texture, anisotropically filtered up to
/// max_anisotropy (a material's "filtering anisotropic"): distant texture does not shimmer from frame
/// to frame. A grey image is kept as one channel read as (g, g, g): the same colours, a third of the
/// filtering work. Loaded once; 0 when it cannot be read (said once).
GLuint Renderer::Impl::TextureFor(const std::string& file, float max_anisotropy) {
  const auto key = std::make_pair(file, max_anisotropy);
  const auto found = textures.find(key);
  if (found != textures.end()) return found->second;
  GLuint texture = 0;
  int w = 0, h = 0, channels = 0;
  // grey (with or without alpha) as one channel, the rest as RGB; the alpha is not drawn
  const bool grey = stbi_info(file.c_str(), &w, &h, &channels) && channels <= 2;
  const int kept = grey ? 1 : 3;
  unsigned char* pixels = stbi_load(file.c_str(), &w, &h, &channels, kept);
  if (!pixels) {
    // CameraSensor checks textures when it is created; a model spawned later is drawn without
    std::cerr << "[rotors_sim] camera renderer: texture '" << file << "' cannot be read (" << stbi_failure_reason()
              << "); drawn without it\n";
    return textures[key] = 0;
  }
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  // image row 0 is the top; texture coordinate v = 0 is the bottom
  const size_t row = static_cast<size_t>(w) * kept;
  std::vector<unsigned char> flipped(row * h);
  for (int r = 0; r < h; ++r) std::copy(pixels + r * row, pixels + (r + 1) * row, flipped.begin() + (h - 1 - r) * row);
  if (grey) {
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, w, h, 0, GL_RED, GL_UNSIGNED_BYTE, flipped.data());
    const GLint rrr1[] = {GL_RED, GL_RED, GL_RED, GL_ONE};
    glTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_SWIZZLE_RGBA, rrr1);
  } else {
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, w, h, 0, GL_RGB, GL_UNSIGNED_BYTE, flipped.data());
  }
  glGenerateMipmap(GL_TEXTURE_2D);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  // anisotropic filtering (OGRE's "filtering anisotropic", max_anisotropy 16) where the driver has it
  constexpr GLenum kMaxAnisotropy = 0x84FE;  // GL_TEXTURE_MAX_ANISOTROPY(_EXT), core in OpenGL 4.6
  if (max_anisotropy > 1.0f &&
      (HasExtension("GL_EXT_texture_filter_anisotropic") || HasExtension("GL_ARB_texture_filter_anisotropic")))
    glTexParameterf(GL_TEXTURE_2D, kMaxAnisotropy, max_anisotropy);
  stbi_image_free(pixels);
  return textures[key] = texture;
}

/// The GPU mesh of a shape and the scale S that takes the mesh's frame to the visual frame.
const GpuMesh* Renderer::Impl::MeshFor(const Shape& shape, Eigen::Matrix4d* S) {
  static const int kUnitBox = 0, kUnitSphere = 0, kUnitCylinder = 0, kUnitSquare = 0;
  S->setIdentity();
  auto cached = [&](const void* key) -> const GpuMesh* {
    auto it = meshes.find(key);
    return it == meshes.end() ? nullptr : &it->second;
  };
  const GpuMesh* mesh = nullptr;
  switch (shape.type) {
    case Shape::Type::kBox:
      *S = Eigen::Vector4d(shape.box_size_m.X(), shape.box_size_m.Y(), shape.box_size_m.Z(), 1).asDiagonal();
      return (mesh = cached(&kUnitBox)) ? mesh : &Upload(&kUnitBox, nullptr, UnitBox());
    case Shape::Type::kSphere:
      *S = Eigen::Vector4d(shape.radius_m, shape.radius_m, shape.radius_m, 1).asDiagonal();
      return (mesh = cached(&kUnitSphere)) ? mesh : &Upload(&kUnitSphere, nullptr, UnitSphere());
    case Shape::Type::kCylinder:
      *S = Eigen::Vector4d(shape.radius_m, shape.radius_m, shape.length_m, 1).asDiagonal();
      return (mesh = cached(&kUnitCylinder)) ? mesh : &Upload(&kUnitCylinder, nullptr, UnitCylinder());
    case Shape::Type::kPlane: {
      const Eigen::Vector3d n(shape.plane_normal.X(), shape.plane_normal.Y(), shape.plane_normal.Z());
      S->topLeftCorner<3, 3>() =
          Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), n.normalized()).toRotationMatrix() *
          Eigen::Vector3d(shape.plane_size_m.X(), shape.plane_size_m.Y(), 1).asDiagonal();
      return (mesh = cached(&kUnitSquare)) ? mesh : &Upload(&kUnitSquare, nullptr, UnitSquare());
    }
    case Shape::Type::kMesh: {
      if (!shape.mesh) return nullptr;
      if ((mesh = cached(shape.mesh.get()))) return mesh;
      std::vector<PartSoup> parts;
      for (const geometry::MeshPart& part : shape.mesh->parts)
        parts.push_back({FromMesh(*shape.mesh, part), part.texture_file});
      return &Upload(shape.mesh.get(), shape.mesh, std::move(parts));
    }
    case Shape::Type::kHeightmap:
      if (!shape.heightfield) return nullptr;
      return (mesh = cached(shape.heightfield.get()))
                 ? mesh
                 : &Upload(shape.heightfield.get(), shape.heightfield, FromHeightField(*shape.heightfield));
    case Shape::Type::kOcTree:
      if (!shape.octree) return nullptr;
      return (mesh = cached(shape.octree.get())) ? mesh
                                                 : &Upload(shape.octree.get(), shape.octree, FromOcTree(*shape.octree));
  }
  return nullptr;
}

Target& Renderer::Impl::TargetFor(int width, int height, PixelFormat format, bool depth, size_t slot) {
  const auto key = std::make_tuple(width, height, static_cast<int>(format), depth, slot);
  auto it = targets.find(key);
  if (it != targets.end()) return it->second;
  Target t;
  glGenFramebuffers(1, &t.fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
  auto renderbuffer = [&](GLenum internal_format, GLenum attachment) {
    GLuint rb = 0;
    glGenRenderbuffers(1, &rb);
    glBindRenderbuffer(GL_RENDERBUFFER, rb);
    glRenderbufferStorage(GL_RENDERBUFFER, internal_format, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, attachment, GL_RENDERBUFFER, rb);
    return rb;
  };
  // L8 renders into one channel, so that the read-back is a copy
  t.colour = renderbuffer(format == PixelFormat::kL8 ? GL_R8 : GL_RGBA8, GL_COLOR_ATTACHMENT0);
  // the float depth output only for depth cameras: a plain camera does not pay for writing it
  if (depth) t.depth_out = renderbuffer(GL_R32F, GL_COLOR_ATTACHMENT1);
  t.depth_buffer = renderbuffer(GL_DEPTH_COMPONENT32F, GL_DEPTH_ATTACHMENT);
  const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glDrawBuffers(depth ? 2 : 1, buffers);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw SimError("camera renderer: cannot make a " + std::to_string(width) + " x " + std::to_string(height) +
                   " render target");
  return targets.emplace(key, t).first->second;
}

/// The shadow map for a camera at X_WC, drawn unless the one drawn last covers the same region of
/// the same scene (the other camera of a stereo pair, usually); nullptr when the world has no shadows.
const ShadowMap* Renderer::Impl::ShadowFor(const physics::World& world, const ignition::math::Pose3d& X_WC,
                                           const CameraIntrinsics& in) {
  const geometry::Lighting& light = world.GetLighting();
  if (!light.shadows) return nullptr;
  // the sun's frame L: z towards the sun
  const Eigen::Vector3d to_sun_W =
      -Eigen::Vector3d(light.sun_direction_W.X(), light.sun_direction_W.Y(), light.sun_direction_W.Z()).normalized();
  const Eigen::Matrix3d R_WL =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), to_sun_W).toRotationMatrix();
  // the smallest sphere around the camera's view up to D: centred a along the optical axis, it
  // reaches the camera (radius a) and the far corners (radius^2 = (D - a)^2 + D^2 k)
  const double D = std::min(in.far_m, ShadowMap::kViewDistance_m), f = in.FocalLengthPx();
  const double k = std::pow(in.width_px / (2 * f), 2) + std::pow(in.height_px / (2 * f), 2);
  const double a = std::min(D, D * (1 + k) / 2);
  const double radius = std::max(a, std::sqrt((D - a) * (D - a) + D * D * k));
  const Eigen::Isometry3d T_WC = ToIsometry(X_WC);
  const Eigen::Vector3d centre_L = R_WL.transpose() * (T_WC * Eigen::Vector3d(a, 0, 0));
  // the region: a little larger than the sphere, kept while the sphere fits in it (the texels stay put
  // in the world while the camera moves, so shadow edges do not crawl from frame to frame, and
  // cameras close together share the map); else centred on the sphere, snapped to a grid of
  // kSnapTexels texels
  const double half = radius / (1.0 - 2.0 * ShadowMap::kSnapTexels / ShadowMap::kTexels);
  const double grid = 2.0 * half * ShadowMap::kSnapTexels / ShadowMap::kTexels;
  if (shadow.region_half_m != half || (centre_L - shadow.region_centre_L).cwiseAbs().maxCoeff() > half - radius) {
    shadow.region_centre_L = (centre_L / grid).array().round().matrix() * grid;
    shadow.region_half_m = half;
  }
  const Eigen::Vector3d snapped_L = shadow.region_centre_L;
  // orthographic clip space: x, y over the region, depth from the top (towards the sun) to the bottom
  const double z_top = snapped_L.z() + half + ShadowMap::kCastersAbove_m, z_bottom = snapped_L.z() - half;
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
  shadow.T_SW = T_S_clip * T_clip_W;
  for (bool static_models : {true, false}) {
    ShadowLayer& layer = static_models ? shadow.fixed : shadow.moving;
    const size_t key = SceneKey(world, static_models, snapped_L, half);
    if (layer.drawn_for == key) continue;
    DrawCasters(world, T_clip_W, static_models, &layer);
    layer.drawn_for = key;
  }
  glBindVertexArray(0);
  return &shadow;
}

/// Clears a shadow layer and draws the casting visuals of the static models (or of the others) into it.
void Renderer::Impl::DrawCasters(const physics::World& world, const Eigen::Matrix4d& T_clip_W, bool static_models,
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
  glUseProgram(shadow_program);
  glEnable(GL_POLYGON_OFFSET_FILL);  // the surface itself stays lit (no shadow acne), slope by slope
  glPolygonOffset(2.0f, 4.0f);
  glEnable(GL_DEPTH_CLAMP);  // casters beyond the top still cast
  layer->empty = true;
  for (const physics::ModelPtr& model : world.Models()) {
    if (model->IsStatic() != static_models) continue;
    for (const geometry::Visual& visual : model->Visuals()) {
      if (!visual.cast_shadows) continue;
      Eigen::Matrix4d S;
      const GpuMesh* mesh = ShadowMeshFor(visual.shape, &S);
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
            glUniformMatrix4fv(shadow_T_clip_V, 1, GL_FALSE, T.data());
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

/// What a visual's shadow is drawn from: the shape's mesh, or for a mesh of more than 4,096 triangles
/// (a vehicle's body) a simplified copy on a grid of 1/64 of its size: the shadow map's texels are
/// centimetres, and every vehicle is drawn into it again each time it moves.
const GpuMesh* Renderer::Impl::ShadowMeshFor(const Shape& shape, Eigen::Matrix4d* S) {
  constexpr size_t kMaxTriangles = 4096;
  if (shape.type != Shape::Type::kMesh || !shape.mesh || shape.mesh->TriangleCount() <= kMaxTriangles)
    return MeshFor(shape, S);
  S->setIdentity();
  const auto found = shadow_proxies.find(shape.mesh.get());
  if (found != shadow_proxies.end()) return &found->second;
  const geometry::TriangleMesh& mesh = *shape.mesh;
  const Eigen::Map<const Eigen::Matrix3Xd> p(mesh.vertices_m.data(), 3,
                                             static_cast<Eigen::Index>(mesh.vertices_m.size() / 3));
  const auto size_m = static_cast<float>((p.rowwise().maxCoeff() - p.rowwise().minCoeff()).norm());
  return &Upload(shape.mesh.get(), shape.mesh, Simplified(mesh, std::max(size_m / 64.0f, 1e-4f)), &shadow_proxies);
}

Renderer& Renderer::Of(physics::World& world) {
  std::shared_ptr<void>& state = world.PluginState("rotors_sim/renderer");
  if (!state) state = std::shared_ptr<Renderer>(new Renderer());
  return *std::static_pointer_cast<Renderer>(state);
}

Renderer::Renderer() : impl_(new Impl) { impl_->CreateContext(); }

Renderer::~Renderer() {
  if (impl_->display != EGL_NO_DISPLAY) {
    eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (impl_->context != EGL_NO_CONTEXT) eglDestroyContext(impl_->display, impl_->context);
    // no eglTerminate: the surfaceless display is one per process, shared with other worlds' renderers
  }
}

size_t Renderer::CachedTriangles() const { return impl_->triangles; }

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

/// Gaussian pixel noise on a remapped image (the shader's noise would be blurred by the remap):
/// deterministic in the seed.
void AddNoise(const CameraSpec& camera, uint64_t seed, std::vector<uint8_t>* image) {
  if (camera.noise_stddev <= 0.0 && camera.noise_mean == 0.0) return;
  std::mt19937_64 random(seed);
  std::normal_distribution<double> gaussian(camera.noise_mean, camera.noise_stddev);
  for (uint8_t& value : *image)
    value = static_cast<uint8_t>(std::clamp(std::lround(value + 255.0 * gaussian(random)), 0L, 255L));
}
}  // namespace

void Renderer::Render(const physics::World& world, const ignition::math::Pose3d& X_WC, const CameraSpec& camera,
                      uint64_t noise_seed, bool want_image, bool want_depth, RenderedFrame* out) {
  const ContextBinding current(*impl_);
  if (camera.distortion.IsIdentity()) {
    DrawPinhole(world, X_WC, camera, noise_seed, want_image, want_depth, 0);
    ReadPinhole(camera, want_image, want_depth, 0, out);
    return;
  }
  Impl& r = *impl_;
  std::unique_ptr<DistortionMap>& map = r.distortion_maps[DistortionKey(camera)];
  if (!map) map = std::make_unique<DistortionMap>(camera);
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
    AddNoise(camera, noise_seed, &out->image);
  }
  if (want_depth) map->RemapDepth(r.pinhole_frame.depth_m, &out->depth_m);
}

void Renderer::RenderAll(const physics::World& world, const std::vector<FrameRequest>& requests) {
  const ContextBinding current(*impl_);
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
  const ShadowMap* shadow = want_image ? r.ShadowFor(world, X_WC, in) : nullptr;  // depth needs no shadows
  Target& target = r.TargetFor(W, H, format, want_depth, slot);
  glBindFramebuffer(GL_FRAMEBUFFER, target.fbo);
  glViewport(0, 0, W, H);
  glClear(GL_DEPTH_BUFFER_BIT);  // to 1: the far plane

  const geometry::Lighting& light = world.GetLighting();
  const Eigen::Isometry3d T_OW = ToIsometry(OpticalInCamera() + X_WC).inverse();  // X_WO = X_WC X_CO
  Eigen::Vector3d to_sun_W(-light.sun_direction_W.X(), -light.sun_direction_W.Y(), -light.sun_direction_W.Z());
  const Eigen::Vector3f to_sun_O = (T_OW.linear() * to_sun_W.normalized()).cast<float>();
  const float f = static_cast<float>(in.FocalLengthPx());

  for (GLuint program : {r.background_program, r.mesh_program}) {
    const FragmentUniforms& u = program == r.mesh_program ? r.mesh_fragment : r.background_fragment;
    glUseProgram(program);
    glUniform1i(u.use_vertex_colour, 0);
    glUniform1i(u.use_texture, 0);
    glUniform1i(u.texture_image, 0);
    glUniform3f(u.to_sun_O, to_sun_O.x(), to_sun_O.y(), to_sun_O.z());
    glUniform1f(u.ambient, light.ambient);
    glUniform1f(u.sun_diffuse, light.sun_diffuse);
    glUniform1i(u.use_shadows, shadow != nullptr);
    glUniform1i(u.shadow_map, 1);
    glUniform1i(u.use_moving_shadows, shadow != nullptr && !shadow->moving.empty);
    glUniform1i(u.moving_shadow_map, 2);
    glUniform1i(u.grey, format == PixelFormat::kL8);
    glUniform2f(u.noise, static_cast<float>(camera.noise_mean), static_cast<float>(camera.noise_stddev));
    glUniform2ui(u.seed, static_cast<GLuint>(noise_seed), static_cast<GLuint>(noise_seed >> 32));
    glUniform1i(u.background, program == r.background_program);
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
      const GpuMesh* mesh = r.MeshFor(visual.shape, &S);
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
      if (shadow) draw.T_SV = (shadow->T_SW * T_WV).cast<float>();
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
  glUseProgram(r.depth_program);
  set_projection(r.depth_vertex.projection, r.depth_vertex.principal);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  for (const VisualDraw& draw : draws) {
    glUniformMatrix4fv(r.depth_vertex.T_OV, 1, GL_FALSE, draw.T_OV.data());
    glBindVertexArray(draw.mesh->vao);
    for (size_t k = draw.first; k < draw.end; ++k) draw_chunk(*draw.mesh, *visible[k].second);
  }
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);

  // the shading pass: only the fragments at the pre-pass's depth (each pixel shaded once)
  glUseProgram(r.mesh_program);
  glDepthFunc(GL_EQUAL);
  glDepthMask(GL_FALSE);
  set_projection(r.mesh_vertex.projection, r.mesh_vertex.principal);
  const GLint loc_albedo = r.mesh_fragment.albedo, loc_vertex_colour = r.mesh_fragment.use_vertex_colour;
  const GLint loc_texture = r.mesh_fragment.use_texture, loc_uv_scale = r.mesh_fragment.uv_scale;
  if (shadow) {
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, shadow->fixed.depth);
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, shadow->moving.depth);
  }
  glActiveTexture(GL_TEXTURE0);
  for (const VisualDraw& draw : draws) {
    const geometry::Visual& visual = *draw.visual;
    const GpuMesh& mesh = *draw.mesh;
    glUniformMatrix4fv(r.mesh_vertex.T_OV, 1, GL_FALSE, draw.T_OV.data());
    glUniformMatrix3fv(r.mesh_vertex.N_OV, 1, GL_FALSE, draw.N_OV.data());
    if (shadow) glUniformMatrix4fv(r.mesh_vertex.T_SV, 1, GL_FALSE, draw.T_SV.data());
    // an SDF/URDF <material> colours the whole visual; else the mesh's own colours and texture
    const bool own = mesh.own_colours && !visual.has_material;
    if (own) glUniform3f(loc_albedo, 1.0f, 1.0f, 1.0f);
    else glUniform3f(loc_albedo, visual.rgba[0], visual.rgba[1], visual.rgba[2]);
    glUniform1i(loc_vertex_colour, own);
    // a material script's texture on a primitive replaces the mesh parts' own (an SDF/URDF colour removes them)
    const GLuint script_texture =
        visual.texture_file.empty() ? 0 : r.TextureFor(visual.texture_file, visual.texture_max_anisotropy);
    glBindVertexArray(mesh.vao);
    for (size_t k = draw.first; k < draw.end; ++k) {
      const auto [p, chunk] = visible[k];
      if (k == draw.first || visible[k - 1].first != p) {  // a new part: its texture
        GLuint texture = visual.has_material ? 0 : mesh.parts[p].texture;
        float repeat_u = 1.0f, repeat_v = 1.0f;
        if (!visual.texture_file.empty()) {
          texture = script_texture;
          repeat_u = 1.0f / visual.texture_scale[0];
          repeat_v = 1.0f / visual.texture_scale[1];
        }
        const bool textured = texture != 0;
        glUniform1i(loc_texture, textured);
        if (textured) {
          glBindTexture(GL_TEXTURE_2D, texture);
          glUniform2f(loc_uv_scale, repeat_u, repeat_v);
        }
      }
      draw_chunk(mesh, *chunk);
    }
  }
  // the sky last, on the far plane where nothing was drawn (early depth test: no overdraw), through
  // the same noise as everything else
  glUseProgram(r.background_program);
  glUniform3f(r.background_fragment.albedo, light.background[0], light.background[1], light.background[2]);
  glDepthFunc(GL_LEQUAL);
  glBindVertexArray(r.empty_vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  glBindVertexArray(0);
}

void Renderer::ReadPinhole(const CameraSpec& camera, bool want_image, bool want_depth, size_t slot,
                           RenderedFrame* out) {
  const int W = camera.intrinsics.width_px, H = camera.intrinsics.height_px;
  const PixelFormat format = camera.format;
  glBindFramebuffer(GL_FRAMEBUFFER, impl_->TargetFor(W, H, format, want_depth, slot).fbo);  // DrawPinhole's
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
