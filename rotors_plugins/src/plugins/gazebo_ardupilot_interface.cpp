// librotors_gazebo_ardupilot_interface.so (ours): ArduPilot's SITL flies the vehicle through its JSON
// interface (sim_vehicle.py -f JSON, libraries/SITL/SIM_JSON.cpp). ArduPilot sends a servo packet
// each of its frames to servo_port (9002); the interface answers to the sender with the JSON state
// line (ardupilot_json.h). One servo frame per physics step: the frame received at the start of a
// step drives that step (PWM 1000..2000 us -> 0..1, through <control_channels>), and the state at the
// end of the step answers it. With lockstep (the default), once the first frame has come, the world
// does not start a step before the next frame is in; ArduPilot advances its clock by the
// differences of our timestamps, so the pair runs as fast as both can. A link silent for
// link_timeout [s] of wall time is lost (motors disarmed; ArduPilot resends after 1 s and the exchange
// starts again). A timestamp that goes back (reset) is, for ArduPilot, a physics reset.
#include <cmath>
#include <memory>

#include "rotors_core/error.h"
#include "rotors_gazebo_plugins/autopilot/ardupilot_json.h"
#include "rotors_gazebo_plugins/autopilot/links.h"
#include "rotors_gazebo_plugins/autopilot_interface.h"
#include "rotors_gazebo_plugins/plugin_params.h"

namespace rotors_gazebo_plugins {

class GazeboArdupilotInterface : public AutopilotInterface {
 protected:
  const char* Tag() const override { return "[ardupilot_interface]"; }
  int OutputCount() const override { return 32; }  // a 16- or 32-channel servo packet

  void LoadProtocol() override {
    std::string addr = "127.0.0.1";
    int port = 9002;
    ReadParam(Params(), "ardupilot_addr", &addr);
    ReadParam(Params(), "servo_port", &port);
    ReadParam(Params(), "enable_lockstep", &lockstep_);
    ReadParam(Params(), "link_timeout", &link_timeout_s_);
    if (!(link_timeout_s_ > 0.0)) throw rotors_sim::SimError("link_timeout must be > 0 s of wall time");
    socket_ = std::make_unique<UdpSocket>(addr, port);
    Info("waiting for ArduPilot's servo packets on UDP " + addr + ":" + std::to_string(port) +
         (lockstep_ ? " (lockstep)" : ""));
  }

  void OnReset() override { linked_ = false; }

  void Exchange(const VehicleSnapshot& s) override {
    if (answer_due_) {  // the state after the last frame's step answers it
      int non_finite = 0;
      const std::string json = ardupilot::StateJson(s, s.v_W.norm(), s.has_diff_pressure, &non_finite);
      if (non_finite > 0) Error("nan", std::to_string(non_finite) + " state values not finite: sent as 0");
      socket_->Reply(json.data(), json.size());
      answer_due_ = false;
    }
    if (!lockstep_ || !linked_) {
      ReadFrames(0.0);
      return;
    }
    const auto start = std::chrono::steady_clock::now();
    while (!answer_due_) {
      const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (waited > link_timeout_s_) {
        linked_ = false;
        Error("lost", "no servo packet for " + std::to_string(link_timeout_s_) +
                          " s (link_timeout): motors "
                          "disarmed, the world runs on until ArduPilot sends again");
        ApplyDisarmed();
        return;
      }
      ReadFrames(std::min(0.05, link_timeout_s_ - waited));
    }
  }

 private:
  /// Takes the servo frames there are (waiting up to timeout_s for one); the last one drives the step.
  void ReadFrames(double timeout_s) {
    uint8_t buffer[512];
    int n;
    double wait = timeout_s;
    while ((n = socket_->Receive(buffer, sizeof(buffer), wait)) > 0) {
      wait = 0.0;
      ardupilot::ServoFrame frame;
      const std::string why = ardupilot::ReadServoPacket(buffer, n, &frame);
      if (!why.empty()) {
        Error("packet", why + " (from " + socket_->Peer() + "): ignored");
        continue;
      }
      if (!linked_) {
        linked_ = true;
        Info("servo packets from ArduPilot at " + socket_->Peer() + " (" + std::to_string(frame.frame_rate) + " Hz)" +
             (lockstep_ ? ": lockstep from now on" : ""));
      }
      std::vector<double> u(frame.pwm_us.size());
      for (size_t i = 0; i < u.size(); ++i) u[i] = (frame.pwm_us[i] - 1000.0) / 1000.0;  // 1000..2000 us -> 0..1
      Apply(u, true);
      answer_due_ = true;
    }
  }

  bool lockstep_ = true, linked_ = false, answer_due_ = false;
  double link_timeout_s_ = 2.0;
  std::unique_ptr<UdpSocket> socket_;
};

}  // namespace rotors_gazebo_plugins

GZ_REGISTER_MODEL_PLUGIN(rotors_gazebo_plugins::GazeboArdupilotInterface)
