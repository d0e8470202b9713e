#include "rendering/gl_context.h"

#include <EGL/eglext.h>

#include <cstdio>
#include <string>

#include "rotors_core/error.h"

namespace rotors_sim {
namespace rendering {
namespace {
std::string Hex(EGLint code) {
  char text[16];
  std::snprintf(text, sizeof(text), "%04x", static_cast<unsigned>(code));
  return text;
}
}  // namespace

GlContext::GlContext() {
  auto get_platform_display =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  const std::string fix = " (headless rendering needs Mesa's EGL: apt install libegl-mesa0 libgl1-mesa-dri)";
  if (!get_platform_display) throw SimError("camera renderer: EGL has no eglGetPlatformDisplayEXT" + fix);
  display_ = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  EGLint major = 0, minor = 0;
  if (display_ == EGL_NO_DISPLAY || !eglInitialize(display_, &major, &minor))
    throw SimError("camera renderer: no surfaceless EGL display" + fix);
  if (!eglBindAPI(EGL_OPENGL_API)) throw SimError("camera renderer: EGL cannot bind OpenGL" + fix);
  const EGLint attributes[] = {
      EGL_CONTEXT_MAJOR_VERSION,           3,       EGL_CONTEXT_MINOR_VERSION, 3, EGL_CONTEXT_OPENGL_PROFILE_MASK,
      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  context_ = eglCreateContext(display_, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
  if (context_ == EGL_NO_CONTEXT) throw SimError("camera renderer: no OpenGL 3.3 core context" + fix);
  if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
    eglDestroyContext(display_, context_);  // the destructor does not run for a constructor that throws
    throw SimError("camera renderer: cannot make its OpenGL 3.3 context current (EGL error 0x" + Hex(eglGetError()) +
                   ")" + fix);
  }
}

GlContext::~GlContext() {
  if (display_ == EGL_NO_DISPLAY) return;
  if (eglGetCurrentContext() == context_) eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  // destroying the context frees every object made in it (programs, buffers, textures); no
  // eglTerminate: the surfaceless display is one per process, shared with other worlds' renderers
  if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
}

ContextBinding::ContextBinding(const GlContext& gl)
    : display_(gl.Display()), bound_here_(eglGetCurrentContext() != gl.Context()) {
  if (bound_here_ && !eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, gl.Context()))
    throw SimError("camera renderer: cannot make its OpenGL context current (EGL error 0x" + Hex(eglGetError()) + ")");
}

ContextBinding::~ContextBinding() {
  if (bound_here_) eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

}  // namespace rendering
}  // namespace rotors_sim
