// The renderer's shader programs and their uniforms: the mesh program (Lambert shading under the
// sun, textures, shadow lookups, pixel noise, the optical-axis depth), the sky behind everything,
// a depth-only pre-pass, and the sun's shadow map. Built once per context; released with it.
#pragma once

#include "rendering/gl.h"

namespace rotors_sim {
namespace rendering {

/// A uniform's location; throws when the program has none of that name (misspelt, or unused and
/// optimised away), which glUniform* calls would otherwise ignore silently.
GLint RequireUniform(GLuint program, const char* name);

/// The fragment shader's uniforms in one program, resolved once. The background program draws
/// one flat, unlit colour, so the compiler drops the lighting and mesh colouring there: those are
/// looked up without the check (-1: setting them does nothing, as intended).
struct FragmentUniforms {
  GLint albedo = -1, use_vertex_colour = -1, use_texture = -1, texture_image = -1, uv_scale = -1, to_sun_O = -1,
        ambient = -1, sun_diffuse = -1, use_shadows = -1, shadow_map = -1, use_moving_shadows = -1,
        moving_shadow_map = -1, background = -1, grey = -1, noise = -1, seed = -1, terrain_layers = -1,
        terrain_layer = -1;
  GLint terrain_texture[4] = {-1, -1, -1, -1};
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
    terrain_layers = mesh_only("terrain_layers");
    terrain_layer = mesh_only("terrain_layer");
    const char* textures[4] = {"terrain_texture0", "terrain_texture1", "terrain_texture2", "terrain_texture3"};
    for (int i = 0; i < 4; ++i) terrain_texture[i] = mesh_only(textures[i]);
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

/// The four programs (their context current while they are made and used).
struct ShaderPrograms {
  /// Compiles and links them all; throws SimError with the compiler's log.
  ShaderPrograms();
  ~ShaderPrograms();
  ShaderPrograms(const ShaderPrograms&) = delete;
  ShaderPrograms& operator=(const ShaderPrograms&) = delete;

  GLuint mesh = 0, background = 0, depth = 0, shadow = 0;
  GLuint empty_vao = 0;  // the sky's one triangle has no vertex buffer
  FragmentUniforms mesh_fragment, background_fragment;
  MeshUniforms mesh_vertex;
  DepthUniforms depth_vertex;
  GLint shadow_T_clip_V = -1;
};

}  // namespace rendering
}  // namespace rotors_sim
