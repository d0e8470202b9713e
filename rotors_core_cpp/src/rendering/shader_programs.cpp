#include "rendering/shader_programs.h"

#include <string>

#include "rotors_core/error.h"

namespace rotors_sim {
namespace rendering {
namespace {

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
out float z_V;            // height in the visual frame (a terrain's blend)
invariant gl_Position;  // the depth pre-pass and the shading pass give the same depth, bit for bit
void main() {
  vec4 p = T_OV * vec4(p_V, 1.0);
  p_O = p.xyz;
  p_S = (T_SV * vec4(p_V, 1.0)).xyz;
  n_O = N_OV * n_V;
  vertex_colour = colour_V;
  uv = uv_V;
  z_V = p_V.z;
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
out float z_V;
void main() {
  // one triangle covering the viewport, on the far plane
  vec2 corner = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
  p_O = vec3(0.0);
  n_O = vec3(0.0);
  vertex_colour = vec3(1.0);
  uv = vec2(0.0);
  p_S = vec3(0.0);
  z_V = 0.0;
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
in float z_V;
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
uniform int terrain_layers;     // a heightmap's textures (0: none), blended by height
uniform vec4 terrain_layer[4];  // each: repeats per metre (1 / size), min height, fade distance, 1 if textured
uniform sampler2D terrain_texture0;
uniform sampler2D terrain_texture1;
uniform sampler2D terrain_texture2;
uniform sampler2D terrain_texture3;
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

// a terrain layer's colour: its texture repeated every size metres, or the visual's colour
vec3 Layer(sampler2D image, vec4 layer) { return layer.w > 0.5 ? texture(image, uv * layer.x).rgb : albedo; }
// how much of layer i lies over those below it: 0 below its min height, 1 from min height + fade up
// (Gazebo's terrain blend)
float Blend(vec4 layer) { return layer.z > 0.0 ? clamp((z_V - layer.y) / layer.z, 0.0, 1.0) : step(layer.y, z_V); }

vec3 Terrain() {
  vec3 c = Layer(terrain_texture0, terrain_layer[0]);
  if (terrain_layers > 1) c = mix(c, Layer(terrain_texture1, terrain_layer[1]), Blend(terrain_layer[1]));
  if (terrain_layers > 2) c = mix(c, Layer(terrain_texture2, terrain_layer[2]), Blend(terrain_layer[2]));
  if (terrain_layers > 3) c = mix(c, Layer(terrain_texture3, terrain_layer[3]), Blend(terrain_layer[3]));
  return c;
}

void main() {
  vec3 c = terrain_layers > 0 ? Terrain() : albedo;
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

/// A compiled shader; throws with the compiler's log (the shader released) when it does not compile.
GLuint Compile(GLenum type, const char* source) {
  GLuint shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetShaderInfoLog(shader, sizeof(log), nullptr, log);
    glDeleteShader(shader);
    throw SimError(std::string("camera renderer: shader does not compile: ") + log);
  }
  return shader;
}

/// A linked program of the two shaders; the shaders are released once linked (the program keeps
/// what it needs), the program too when it does not link.
GLuint Link(const char* vertex, const char* fragment) {
  const GLuint vertex_shader = Compile(GL_VERTEX_SHADER, vertex);
  GLuint fragment_shader = 0;
  try {
    fragment_shader = Compile(GL_FRAGMENT_SHADER, fragment);
  } catch (...) {
    glDeleteShader(vertex_shader);
    throw;
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, vertex_shader);
  glAttachShader(program, fragment_shader);
  glBindFragDataLocation(program, 0, "colour");
  glBindFragDataLocation(program, 1, "depth_m");
  glLinkProgram(program);
  glDetachShader(program, vertex_shader);
  glDetachShader(program, fragment_shader);
  glDeleteShader(vertex_shader);
  glDeleteShader(fragment_shader);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    glDeleteProgram(program);
    throw SimError("camera renderer: shader program does not link");
  }
  return program;
}

}  // namespace

GLint RequireUniform(GLuint program, const char* name) {
  const GLint location = glGetUniformLocation(program, name);
  if (location < 0)
    throw SimError(std::string("camera renderer: the shader program has no uniform '") + name +
                   "' (misspelt, or unused and optimised away)");
  return location;
}

ShaderPrograms::ShaderPrograms() {
  mesh = Link(kMeshVertexShader, kFragmentShader);
  background = Link(kBackgroundVertexShader, kFragmentShader);
  depth = Link(kMeshVertexShader, kDepthOnlyFragmentShader);
  shadow = Link(kShadowVertexShader, kShadowFragmentShader);
  mesh_fragment = FragmentUniforms(mesh, true);
  background_fragment = FragmentUniforms(background, false);
  mesh_vertex = MeshUniforms(mesh);
  depth_vertex = DepthUniforms(depth);
  shadow_T_clip_V = RequireUniform(shadow, "T_clip_V");
  glGenVertexArrays(1, &empty_vao);
}

ShaderPrograms::~ShaderPrograms() {
  glDeleteVertexArrays(1, &empty_vao);
  for (GLuint program : {mesh, background, depth, shadow}) glDeleteProgram(program);
}

}  // namespace rendering
}  // namespace rotors_sim
