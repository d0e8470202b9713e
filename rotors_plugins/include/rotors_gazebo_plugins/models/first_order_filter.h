// First-order lag with separate rise and fall time constants (rotor speed dynamics).
#pragma once

#include <cmath>

namespace rotors_gazebo_plugins {

class FirstOrderFilter {
 public:
  /// tau_up_s / tau_down_s [s]: time constants while the input is above / below the output.
  FirstOrderFilter(double tau_up_s, double tau_down_s, double initial = 0.0)
      : tau_up_s_(tau_up_s), tau_down_s_(tau_down_s), y_(initial) {}

  /// Exact discretisation of  tau dy/dt = u - y  over dt with u held:
  /// y_k = a y_{k-1} + (1 - a) u,  a = exp(-dt / tau).
  double Update(double u, double dt_s) {
    const double tau_s = u > y_ ? tau_up_s_ : tau_down_s_;
    y_ = Blend(y_, u, std::exp(-dt_s / tau_s));
    return y_;
  }
  /// The same step with the factors exp(-dt / tau_up) and exp(-dt / tau_down) computed once
  /// (the batched flight engine's form, equal to Update bit for bit).
  static double Step(double y, double u, double a_up, double a_down) { return Blend(y, u, u > y ? a_up : a_down); }
  double Output() const { return y_; }
  void Reset(double y = 0.0) { y_ = y; }

 private:
  static double Blend(double y, double u, double a) { return a * y + (1.0 - a) * u; }
  double tau_up_s_, tau_down_s_, y_;
};

}  // namespace rotors_gazebo_plugins
