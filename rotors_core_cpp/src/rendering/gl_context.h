// The renderer's headless OpenGL 3.3 core context: EGL on Mesa's surfaceless platform (llvmpipe),
// no X server. The context is released when this object goes, also when a start failed halfway.
#pragma once

#include <EGL/egl.h>

namespace rotors_sim {
namespace rendering {

class GlContext {
 public:
  /// Creates the context and makes it current on this thread; throws SimError naming the missing
  /// package when there is no headless OpenGL 3.3 core context.
  GlContext();
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  EGLDisplay Display() const { return display_; }
  EGLContext Context() const { return context_; }

 private:
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
};

/// Makes a context current on this thread for one render call and releases it after. A context
/// left current on a thread that has ended cannot be made current on another one (Mesa answers
/// EGL_BAD_ACCESS unless the new thread happens to get the old one's bookkeeping address), and a
/// world may step from any thread. Nested bindings (a distorted camera in a batch) reuse it.
class ContextBinding {
 public:
  explicit ContextBinding(const GlContext& gl);
  ~ContextBinding();
  ContextBinding(const ContextBinding&) = delete;
  ContextBinding& operator=(const ContextBinding&) = delete;

 private:
  EGLDisplay display_;
  bool bound_here_;
};

}  // namespace rendering
}  // namespace rotors_sim
