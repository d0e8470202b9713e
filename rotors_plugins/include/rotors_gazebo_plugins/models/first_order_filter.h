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
  /// y_k = a y_{k-1} + (1 - a) u for a = exp(-dt / tau) computed by the caller; T is double or a
  /// vector of lanes (the batched flight engine steps many filters at once, each equal to Update).
  template <class T>
  static T Blend(const T& y, const T& u, const T& a) {
    return a * y + (1.0 - a) * u;
  }
  double Output() const { return y_; }
  void Reset(double y = 0.0) { y_ = y; }

 private:
  double tau_up_s_, tau_down_s_, y_;
};

}  // namespace rotors_gazebo_plugins
