// librotors_gazebo_betaflight_interface.so (ours): a real Betaflight firmware (its SITL build) flies
// the vehicle. Each step the interface sends the state packet to Betaflight's UDP port (9003) and the
// RC channels (VehicleBus: the rcSubTopic or World.set_rc) to its RC port (9004), and takes the motor
// outputs Betaflight sends to motor_port (9002) through <control_channels> to the motors (output i
// drives motor i by default: Betaflight's packet is in the ArduCopter plugin's order, front right,
// rear left, front left, rear right, which is the iris'). Betaflight answers each state packet with
// one motor packet.
//   firmware_lockstep true (our lockstep build, resource/betaflight_lockstep.patch): the firmware's
//     clock is the state packets' timestamps and it runs one gyro/PID loop per state; the RC packet
//     goes before its state, every step waits for its answer from the first one on (at most
//     link_timeout), and the physics step must be the firmware's loop period (lockstep_rate, 500 Hz).
//     Two flights with the same inputs are the same, bit for bit.
//   firmware_lockstep false (Betaflight's own build): its clock is scaled to the simulator's rate from
//     the state timestamps (its sitl.c), so its loops are not repeatable from run to run; the exchange
//     is: once it answers steadily, each state waits for its answer at most answer_timeout.
// A firmware silent for link_timeout [s] of wall time is lost: motors to their disarmed values, the
// world runs on until it answers again.
#include <sensor_msgs/Joy.h>

#include <array>
#include <cmath>
#include <memory>

#include "rotors_core/error.h"
#include "rotors_gazebo_plugins/autopilot/betaflight_packets.h"
#include "rotors_gazebo_plugins/autopilot/link_session.h"
#include "rotors_gazebo_plugins/autopilot/links.h"
#include "rotors_gazebo_plugins/autopilot_interface.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"

namespace rotors_gazebo_plugins {

class GazeboBetaflightInterface : public AutopilotInterface {
 protected:
  const char* Tag() const override { return "[betaflight_interface]"; }
  int OutputCount() const override { return betaflight::kMotors; }

  void LoadProtocol() override {
    std::string rc_topic = "rc";
    int motor_port = 9002;
    ReadParam(Params(), "betaflight_addr", &addr_);
    ReadParam(Params(), "state_port", &state_port_);
    ReadParam(Params(), "rc_port", &rc_port_);
    ReadParam(Params(), "motor_port", &motor_port);
    ReadParam(Params(), "enable_lockstep", &lockstep_);
    ReadParam(Params(), "link_timeout", &link_timeout_s_);
    ReadParam(Params(), "answer_timeout", &answer_timeout_s_);
    if (!(answer_timeout_s_ > 0.0)) throw rotors_sim::SimError("answer_timeout must be > 0 s of wall time");
    ReadParam(Params(), "rcSubTopic", &rc_topic);
    ReadParam(Params(), "firmware_lockstep", &firmware_lockstep_);
    ReadParam(Params(), "rc_rate", &rc_rate_hz_);
    if (!(rc_rate_hz_ >= 0.0)) throw rotors_sim::SimError("rc_rate must be >= 0 Hz (0: an RC packet with every state)");
    double lockstep_rate_hz = 500.0;
    ReadParam(Params(), "lockstep_rate", &lockstep_rate_hz);
    if (!(link_timeout_s_ > 0.0)) throw rotors_sim::SimError("link_timeout must be > 0 s of wall time");
    // the lockstep firmware's state rate is compiled in (SIMULATOR_LOCKSTEP_HZ in
    // betaflight_lockstep.patch): another rate would run its loops at the wrong period
    constexpr double kFirmwareLockstepHz = 500.0;
    if (firmware_lockstep_ && lockstep_rate_hz != kFirmwareLockstepHz)
      throw rotors_sim::SimError("lockstep_rate " + std::to_string(lockstep_rate_hz) +
                                 " Hz: the lockstep firmware is built for 500 Hz (SIMULATOR_LOCKSTEP_HZ in "
                                 "betaflight_lockstep.patch); use 500, or rebuild it with another rate");
    if (firmware_lockstep_ && std::abs(PhysicsStep_s() * lockstep_rate_hz - 1.0) > 1e-6)
      throw rotors_sim::SimError("physics step " + std::to_string(PhysicsStep_s()) +
                                 " s: Betaflight's lockstep firmware runs one gyro/PID loop per state at " +
                                 std::to_string(lockstep_rate_hz) + " Hz (lockstep_rate): use a step of " +
                                 std::to_string(1.0 / lockstep_rate_hz) + " s");
    if (firmware_lockstep_) lockstep_ = true;  // the firmware waits for each state: so must the world
    session_ = firmware_lockstep_ ? LinkSession({true, link_timeout_s_, false, /*from the first state*/ 0})
                                  : LinkSession({lockstep_, answer_timeout_s_, false, kAnswersBeforeLockstep});
    motors_ = std::make_unique<UdpSocket>("127.0.0.1", motor_port);
    states_ = std::make_unique<UdpSocket>("0.0.0.0", 0, addr_, state_port_);
    rc_ = std::make_unique<UdpSocket>("0.0.0.0", 0, addr_, rc_port_);
    node_ = MakeNode(Namespace());
    if (node_ && !rc_topic.empty())
      rc_sub_ =
          node_->subscribe(rc_topic, 1, &GazeboBetaflightInterface::OnRc, this, ros::TransportHints().tcpNoDelay());
    Info("state to " + addr_ + ":" + std::to_string(state_port_) + ", RC to :" + std::to_string(rc_port_) +
         ", motor outputs on :" + std::to_string(motor_port) +
         (firmware_lockstep_ ? " (the firmware in lockstep)"
          : lockstep_        ? " (lockstep)"
                             : ""));
  }

  void OnReset() override {
    session_.On(LinkEvent::kReset);
    last_rc_s_ = -1e9;
  }

  void Exchange(const VehicleSnapshot& s) override {
    ReadMotors(0.0);
    if (firmware_lockstep_) {
      ExchangeInLockstep(s);
      return;
    }
    SendState(s);
    // RC only once the firmware answers steadily: its sitl.c hooks the UDP receiver up with the first
    // RC packet, and a packet that comes before the firmware's receiver is set up is lost for good
    // (RXLOSS until a restart)
    if (!Bus().rc_channels_us.empty() && session_.State() == LinkState::kLockstep) SendRc(s);
    if (!session_.Waits(true)) return;
    // wait for the answer to this state, at most answer_timeout: Betaflight's clock follows the
    // state timestamps (its simRate), and a world that stalled on it would slow its clock to a crawl
    if (AwaitAnswer()) return;
    session_.On(LinkEvent::kLate);
    if (SilentFor_s() > link_timeout_s_) LoseLink(s.time_s);
  }

 private:
  /// The lockstep firmware: RC, then the state, then its answer (it reads the RC that came before it).
  void ExchangeInLockstep(const VehicleSnapshot& s) {
    // RC frames at the radio link's rate (rc_rate), as a receiver delivers them
    const bool rc_due = rc_rate_hz_ <= 0.0 || s.time_s - last_rc_s_ >= 1.0 / rc_rate_hz_ - 1e-9;
    if (!Bus().rc_channels_us.empty() && rc_due) {
      last_rc_s_ = s.time_s;
      SendRc(s);
    }
    SendState(s);
    if (session_.Waits(true) && !AwaitAnswer()) LoseLink(s.time_s);
  }

  void SendState(const VehicleSnapshot& s) {
    const betaflight::FdmPacket state = betaflight::StatePacket(WithTruthForMissingImu(s));
    states_->Send(&state, sizeof(state));
  }

  void SendRc(const VehicleSnapshot& s) {
    const betaflight::RcPacket rc = betaflight::MakeRcPacket(s.time_s, Bus().rc_channels_us);
    rc_->Send(&rc, sizeof(rc));
  }

  /// Reads motor packets until the answer to the state just sent is in, at most the session's
  /// answer_timeout (answer_timeout, or link_timeout for the lockstep firmware).
  bool AwaitAnswer() {
    answered_ = false;
    const AwaitResult result = session_.AwaitAnswer(
        [this](double timeout_s) {
          ReadMotors(timeout_s);
          return true;  // a UDP link does not close
        },
        [this] { return answered_; });
    if (result != AwaitResult::kAnswered) return false;
    last_answer_ = std::chrono::steady_clock::now();  // an answer, used or not
    return true;
  }

  double SilentFor_s() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - last_answer_).count();
  }

  /// The link is lost (the plugins' one name for it): motors disarmed, the world runs on.
  void LoseLink(double t_s) {
    session_.On(LinkEvent::kSilent);
    Error("lost", "no motor packet for " + std::to_string(link_timeout_s_) + " s of wall time (link_timeout) at t = " +
                      std::to_string(t_s) + " s: motors disarmed, the world runs on until Betaflight answers again");
    ApplyDisarmed();
  }

  /// Takes every motor packet there is (waiting up to timeout_s for the first).
  void ReadMotors(double timeout_s) {
    uint8_t buffer[256];
    int n;
    double wait = timeout_s;
    while ((n = motors_->Receive(buffer, sizeof(buffer), wait)) > 0) {
      wait = 0.0;
      std::array<double, betaflight::kMotors> u;
      const std::string why = betaflight::ReadServoPacket(buffer, n, &u);
      answered_ = true;  // an answer, used or not: lockstep goes on
      if (!why.empty()) {
        Error("packet", why + ": ignored, the last valid outputs stay in force");
        continue;
      }
      const bool now_steady = session_.On(LinkEvent::kAnswered) && session_.State() == LinkState::kLockstep;
      if (now_steady || (firmware_lockstep_ && session_.AnswersSinceStart() == 1))
        Info(std::string("Betaflight answers") + (firmware_lockstep_
                                                      ? ": the firmware in lockstep, each state waits for its answer"
                                                  : lockstep_ ? ": each state waits for its answer from now on"
                                                              : ""));
      last_answer_ = std::chrono::steady_clock::now();
      // Betaflight sends 0 for a stopped motor whether armed or not: its outputs are the command
      Apply({u.begin(), u.end()}, true);
    }
  }

  /// sensor_msgs/Joy: axes[i] in [-1, 1] is RC channel i + 1 (AETR, AUX1..) at 1500 + 500 axes[i] us.
  void OnRc(const sensor_msgs::JoyConstPtr& msg) {
    std::vector<int> channels;
    for (size_t i = 0; i < msg->axes.size(); ++i) {
      if (!std::isfinite(msg->axes[i]) || std::abs(msg->axes[i]) > 1.0f) {
        Error("rc", "rc axes[" + std::to_string(i) + "] = " + std::to_string(msg->axes[i]) +
                        " is not in [-1, 1]: the RC message is ignored");
        return;
      }
      channels.push_back(static_cast<int>(std::lround(1500.0 + 500.0 * msg->axes[i])));
    }
    const std::string why = Bus().SetRcChannels(channels);
    if (!why.empty()) Error("rc", "RC message refused: " + why);
  }

  std::string addr_ = "127.0.0.1";
  int state_port_ = 9003, rc_port_ = 9004;
  /// Betaflight answers its first state packets while it boots, then falls silent for a while: the
  /// waiting starts once it has answered this many.
  static constexpr uint64_t kAnswersBeforeLockstep = 100;
  LinkSession session_{WaitPolicy{}};
  bool lockstep_ = true, answered_ = false, firmware_lockstep_ = false;
  double rc_rate_hz_ = 0.0, last_rc_s_ = -1e9;
  double link_timeout_s_ = 2.0, answer_timeout_s_ = 0.02;
  std::chrono::steady_clock::time_point last_answer_;
  std::unique_ptr<Transport> motors_, states_, rc_;  ///< motor outputs in; the state and RC packets out
  std::shared_ptr<ros::NodeHandle> node_;
  ros::Subscriber rc_sub_;
};

}  // namespace rotors_gazebo_plugins

GZ_REGISTER_MODEL_PLUGIN(rotors_gazebo_plugins::GazeboBetaflightInterface)
