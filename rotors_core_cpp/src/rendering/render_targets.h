// The renderer's offscreen framebuffers, one per image size, pixel format, depth output and slot
// (each camera of a RenderAll draws into its own), bounded (lru_cache.h); each releases its GL
// objects when dropped.
#pragma once

#include <tuple>
#include <utility>

#include "rendering/gl.h"
#include "rendering/lru_cache.h"
#include "rotors_core/rendering/camera_model.h"

namespace rotors_sim {
namespace rendering {

/// A framebuffer with a colour buffer, the float depth output (depth cameras) and a depth buffer.
struct Target {
  GLuint fbo = 0, colour = 0, depth_out = 0, depth_buffer = 0;
  Target() = default;
  Target(Target&& other) noexcept { *this = std::move(other); }
  Target& operator=(Target&& other) noexcept {
    std::swap(fbo, other.fbo);
    std::swap(colour, other.colour);
    std::swap(depth_out, other.depth_out);
    std::swap(depth_buffer, other.depth_buffer);
    return *this;
  }
  Target(const Target&) = delete;
  Target& operator=(const Target&) = delete;
  ~Target();
};

class RenderTargets {
 public:
  static constexpr size_t kCapacity = 32;
  RenderTargets() : targets_(kCapacity) {}
  /// The target of that size, format, depth output and slot, made on first use; throws SimError
  /// when the driver cannot make it.
  const Target& For(int width, int height, PixelFormat format, bool depth, size_t slot);
  void NextFrame() { targets_.NextFrame(); }
  size_t Size() const { return targets_.Size(); }

 private:
  LruCache<std::tuple<int, int, int, bool, size_t>, Target> targets_;
};

}  // namespace rendering
}  // namespace rotors_sim
