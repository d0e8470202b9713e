// A plugin's seeded noise model together with what built it, so that reset_world and
// reset_simulation (and Python's World.reset()) make the model again: a reset world draws the same
// numbers as it did after loading, and a flight after a reset repeats the first one bit for bit.
#pragma once

#include <functional>
#include <memory>
#include <utility>

namespace rotors_gazebo_plugins {

template <class Model>
class SeededModel {
 public:
  /// Builds the model from `args` (parameters and seed, copied) and keeps them for Reset().
  template <class... Args>
  void Emplace(Args... args) {
    make_ = [args...] { return std::make_unique<Model>(args...); };
    model_ = make_();
  }
  /// The model as it was right after Emplace: its generator at its seed, its initial draws again.
  void Reset() {
    if (make_) model_ = make_();
  }
  Model* operator->() const { return model_.get(); }
  Model& operator*() const { return *model_; }
  explicit operator bool() const { return model_ != nullptr; }

 private:
  std::function<std::unique_ptr<Model>()> make_;
  std::unique_ptr<Model> model_;
};

}  // namespace rotors_gazebo_plugins
