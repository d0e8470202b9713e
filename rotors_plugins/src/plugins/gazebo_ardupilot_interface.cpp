// librotors_gazebo_ardupilot_interface.so (ours): ArduPilot's SITL flies the vehicle through its JSON
// interface (libraries/SITL/SIM_JSON.cpp). ArduPilot sends a servo packet each of its frames to
// servo_port (9002 + 10 instance); the interface answers to the sender with the JSON state line
// (ardupilot_json.h). One servo frame per physics step: the frame received at the start of a step
// drives that step (PWM through <control_channels>: motors 1000..2000 us -> 0..1, the outputs listed
// in centred_outputs, a plane's surfaces, 1500 +- 500 us -> -1..1; 0 us: no output), and the state at
// the end of the step answers it. As ArduPilot's Gazebo plugin (ArduPilot/ardupilot_gazebo
// src/ArduPilotPlugin.cc): a frame whose frame_count repeats the last one is SIM_JSON resending it
// for want of an answer, and is answered again with the last state, without a step; a count that
// goes back is a restarted ArduPilot (said in one line; the exchange starts again). With lockstep (the
// default), once the first frame has come, the world does not start a step before the next frame is
// in, waiting as long as ArduPilot takes (link_timeout > 0 [s of wall time]: at most that long, then
// the motors are disarmed and the world runs on).
#include <cmath>
#include <memory>
#include <set>
#include <sstream>

#include "rotors_core/error.h"
#include "rotors_gazebo_plugins/autopilot/ardupilot_json.h"
#include "rotors_gazebo_plugins/autopilot/link_session.h"
#include "rotors_gazebo_plugins/autopilot/links.h"
#include "rotors_gazebo_plugins/autopilot_interface.h"
#include "rotors_gazebo_plugins/plugin_params.h"

namespace rotors_gazebo_plugins {

class GazeboArdupilotInterface : public AutopilotInterface {
 protected:
  const char* Tag() const override { return "[ardupilot_interface]"; }
  int OutputCount() const override { return 32; }  // a 16- or 32-channel servo packet

  void LoadProtocol() override {
    std::string addr = "127.0.0.1", centred;
    int port = 9002;
    ReadParam(Params(), "ardupilot_addr", &addr);
    ReadParam(Params(), "servo_port", &port);
    ReadParam(Params(), "enable_lockstep", &lockstep_);
    ReadParam(Params(), "link_timeout", &link_timeout_s_);
    ReadParam(Params(), "centred_outputs", &centred);
    if (!(link_timeout_s_ >= 0.0))
      throw rotors_sim::SimError("link_timeout = " + std::to_string(link_timeout_s_) +
                                 " must be >= 0 s of wall time (0: wait as long as ArduPilot takes)");
    std::istringstream list(centred);
    int output;
    while (list >> output) {
      if (output < 0 || output >= OutputCount())
        throw rotors_sim::SimError("centred_outputs: output " + std::to_string(output) + " is not in 0.." +
                                   std::to_string(OutputCount() - 1));
      centred_.insert(output);
    }
    if (!list.eof())
      throw rotors_sim::SimError("centred_outputs '" + centred + "' must be servo output indices, e.g. \"0 1 3\"");
    session_ = LinkSession({lockstep_, link_timeout_s_, /*only_while_armed=*/false, 1});
    link_ = std::make_unique<UdpSocket>(addr, port);  // answers go to whoever sent the last frame
    Info("waiting for ArduPilot's servo packets on UDP " + addr + ":" + std::to_string(port) +
         (lockstep_ ? " (lockstep)" : ""));
  }

  void OnReset() override {
    session_.On(LinkEvent::kReset);
    have_frame_ = false;
    last_json_.clear();
  }

  void Exchange(const VehicleSnapshot& s) override {
    if (answer_due_) {  // the state after the last frame's step answers it
      int non_finite = 0;
      last_json_ = ardupilot::StateJson(WithTruthForMissingImu(s), &non_finite);
      if (non_finite > 0) Error("nan", std::to_string(non_finite) + " state values not finite: sent as 0");
      link_->Send(last_json_.data(), last_json_.size());
      answer_due_ = false;
    }
    if (!session_.Waits(true)) {
      ReadFrames(0.0);
      return;
    }
    // lockstep: the step waits for ArduPilot's next frame (link_timeout > 0: at most that long)
    const AwaitResult result = session_.AwaitAnswer(
        [this](double timeout_s) {
          ReadFrames(timeout_s);
          return true;  // a UDP link does not close
        },
        [this] { return answer_due_; });
    if (result == AwaitResult::kTimedOut) LoseLink();
  }

 private:
  /// The link is lost (the plugins' one name for it): motors disarmed, the world runs on.
  void LoseLink() {
    session_.On(LinkEvent::kSilent);
    Error("lost", "no servo packet for " + std::to_string(link_timeout_s_) +
                      " s (link_timeout): motors disarmed, the world runs on until ArduPilot sends again");
    ApplyDisarmed();
  }

  /// Takes the servo frames there are (waiting up to timeout_s for one); a new frame drives the step.
  void ReadFrames(double timeout_s) {
    uint8_t buffer[512];
    int n;
    double wait = timeout_s;
    while ((n = link_->Receive(buffer, sizeof(buffer), wait)) > 0) {
      wait = 0.0;
      ardupilot::ServoFrame frame;
      const std::string why = ardupilot::ReadServoPacket(buffer, n, &frame);
      if (!why.empty()) {
        Error("packet", why + " (on " + link_->Describe() + "): ignored");
        continue;
      }
      switch (ardupilot::OrderOf(frame.frame_count, have_frame_, last_frame_count_)) {
        case ardupilot::FrameOrder::kRepeated:
          // SIM_JSON resends a frame it got no answer to: the same answer again, no step
          if (!last_json_.empty()) link_->Send(last_json_.data(), last_json_.size());
          continue;
        case ardupilot::FrameOrder::kBackwards:
          Info("servo frame_count went back from " + std::to_string(last_frame_count_) + " to " +
               std::to_string(frame.frame_count) + ": ArduPilot restarted; the exchange starts again");
          last_json_.clear();
          break;
        case ardupilot::FrameOrder::kFirst:
        case ardupilot::FrameOrder::kNext: break;
      }
      have_frame_ = true;
      last_frame_count_ = frame.frame_count;
      if (session_.On(LinkEvent::kAnswered)) {
        Info("servo packets from ArduPilot on " + link_->Describe() + " (" + std::to_string(frame.frame_rate) + " Hz)" +
             (lockstep_ ? ": lockstep from now on" : ""));
      }
      std::vector<double> u(frame.pwm_us.size(), 0.0);
      for (size_t i = 0; i < u.size(); ++i)
        ardupilot::PwmToInput(frame.pwm_us[i], centred_.count(static_cast<int>(i)) > 0, &u[i]);  // 0 us: u = 0
      Apply(u, true);
      answer_due_ = true;
    }
  }

  LinkSession session_{WaitPolicy{}};
  bool lockstep_ = true, answer_due_ = false, have_frame_ = false;
  uint32_t last_frame_count_ = 0;
  double link_timeout_s_ = 0.0;
  std::set<int> centred_;
  std::string last_json_;
  std::unique_ptr<Transport> link_;
};

}  // namespace rotors_gazebo_plugins

GZ_REGISTER_MODEL_PLUGIN(rotors_gazebo_plugins::GazeboArdupilotInterface)
