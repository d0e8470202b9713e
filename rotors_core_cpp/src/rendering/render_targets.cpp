#include "rendering/render_targets.h"

#include <string>

#include "rotors_core/error.h"

namespace rotors_sim {
namespace rendering {

Target::~Target() {
  for (GLuint rb : {colour, depth_out, depth_buffer})
    if (rb) glDeleteRenderbuffers(1, &rb);
  if (fbo) glDeleteFramebuffers(1, &fbo);
}

const Target& RenderTargets::For(int width, int height, PixelFormat format, bool depth, size_t slot) {
  const auto key = std::make_tuple(width, height, static_cast<int>(format), depth, slot);
  if (const Target* found = targets_.Find(key)) return *found;
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
                   " render target");  // t releases what was made
  return targets_.Insert(key, std::move(t));
}

}  // namespace rendering
}  // namespace rotors_sim
