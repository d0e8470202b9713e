// librotors_gazebo_mavlink_interface.so: RotorS' MAVLink interface, speaking PX4's simulator
// protocol as PX4's simulator_mavlink module expects it today (docs/autopilots.md).
//   SITL:  PX4 connects over TCP to mavlink_tcp_port (4560 + instance; use_tcp, the default), or
//          over UDP (use_tcp false: datagrams to mavlink_addr:mavlink_udp_port, PX4's "-u").
//   HITL:  serialEnabled: a Pixhawk on serialDevice at baudRate; QGroundControl's traffic is
//          relayed to and from qgc_addr:qgc_udp_port, as RotorS' plugin does.
// Each step with a new IMU reading it sends HIL_SENSOR (IMU; magnetometer, barometer and
// differential pressure when theirs are new), HIL_GPS when the GPS plugin has a new fix,
// HIL_STATE_QUATERNION (ground truth) at the interval PX4 asks for, DISTANCE_SENSOR and
// HIL_OPTICAL_FLOW when the vehicle has those sensors. HIL_ACTUATOR_CONTROLS come back through
// <control_channels> to the motors. Lockstep (enable_lockstep, on by default, SITL only), as PX4's
// Gazebo plugin (PX4-SITL_gazebo-classic src/gazebo_mavlink_interface.cpp): PX4 sets its clock from
// each HIL_SENSOR and never runs ahead of it; once the first HIL_ACTUATOR_CONTROLS has arrived and
// while PX4 says it is armed, a step waits for the answer to its HIL_SENSOR at most answer_timeout
// [s of wall time, 0.01] and then goes on with the last outputs. Silence never closes the link: only
// PX4 closing it does (the motors go to their disarmed values, and a restarted PX4 may connect
// again; a running PX4's simulator module connects only once).
#include <cmath>
#include <functional>
#include <memory>
#include <sstream>

#include "rotors_core/error.h"
#include "rotors_gazebo_plugins/autopilot/link_session.h"
#include "rotors_gazebo_plugins/autopilot/links.h"
#include "rotors_gazebo_plugins/autopilot/px4_mavlink.h"
#include "rotors_gazebo_plugins/autopilot_interface.h"
#include "rotors_gazebo_plugins/plugin_params.h"

namespace rotors_gazebo_plugins {

class GazeboMavlinkInterface : public AutopilotInterface {
 protected:
  const char* Tag() const override { return "[mavlink_interface]"; }
  int OutputCount() const override { return 16; }  // HIL_ACTUATOR_CONTROLS.controls

  void LoadProtocol() override {
    std::string addr = "INADDR_ANY", qgc_addr = "INADDR_ANY", device = "/dev/ttyACM0";
    int udp_port = 14560, tcp_port = 4560, qgc_port = 14550, baud = 921600;
    bool use_tcp = true;
    double protocol_version = 2.0;
    ReadParam(Params(), "mavlink_addr", &addr);
    ReadParam(Params(), "mavlink_udp_port", &udp_port);
    ReadParam(Params(), "mavlink_tcp_port", &tcp_port);
    ReadParam(Params(), "use_tcp", &use_tcp);
    ReadParam(Params(), "qgc_addr", &qgc_addr);
    ReadParam(Params(), "qgc_udp_port", &qgc_port);
    ReadParam(Params(), "serialEnabled", &serial_enabled_);
    ReadParam(Params(), "serialDevice", &device);
    ReadParam(Params(), "baudRate", &baud);
    ReadParam(Params(), "hil_mode", &hil_mode_);
    ReadParam(Params(), "hil_state_level", &hil_state_level_);
    ReadParam(Params(), "enable_lockstep", &lockstep_);
    ReadParam(Params(), "answer_timeout", &answer_timeout_s_);
    ReadParam(Params(), "protocol_version", &protocol_version);
    double imu_rate_hz = 0.0;
    ReadParam(Params(), "imu_rate", &imu_rate_hz);
    int system_id = 1;
    ReadParam(Params(), "system_id", &system_id);
    if (protocol_version != 2.0)
      throw rotors_sim::SimError("protocol_version " + std::to_string(protocol_version) +
                                 ": this interface speaks MAVLink 2 (2.0), as PX4 does since v1.9");
    if (!(imu_rate_hz >= 0.0)) throw rotors_sim::SimError("imu_rate must be >= 0 Hz (0: every step)");
    if (!(answer_timeout_s_ >= 0.0))
      throw rotors_sim::SimError("answer_timeout = " + std::to_string(answer_timeout_s_) +
                                 " must be >= 0 s of wall time (PX4's Gazebo plugin waits 0.01 s; 0: no limit)");
    if (system_id < 1 || system_id > 255) throw rotors_sim::SimError("system_id must be 1..255");
    imu_interval_s_ = imu_rate_hz > 0.0 ? 1.0 / imu_rate_hz : 0.0;
    // hardware in the loop: a real autopilot runs on its own clock
    if (hil_mode_ || serial_enabled_) lockstep_ = false;
    session_ = LinkSession({lockstep_, answer_timeout_s_, /*only_while_armed=*/true, 1});
    CheckImuRate(imu_rate_hz);
    // HIL_GPS carries UTC: the wall clock when the sim time was zero (PX4's plugin: the world's start time)
    utc_at_sim_zero_us_ = static_cast<uint64_t>(
        std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
            .count() -
        static_cast<int64_t>(SimTime_s() * 1e6));
    // component 200, as PX4's Gazebo plugins frame their messages
    endpoint_ = std::make_unique<px4::MavlinkEndpoint>(static_cast<uint8_t>(system_id), 200);
    if (serial_enabled_) {
      // a device that is not there (yet) is tried again every second
      open_link_ = [device, baud]() -> std::unique_ptr<Transport> {
        return std::make_unique<SerialPort>(device, baud);
      };
      OpenLink();
      qgc_ = std::make_unique<UdpSocket>("0.0.0.0", 0, qgc_addr == "INADDR_ANY" ? "127.0.0.1" : qgc_addr, qgc_port);
    } else if (use_tcp) {
      link_ = std::make_unique<TcpServer>(addr == "INADDR_ANY" ? "0.0.0.0" : addr, tcp_port);
      Info("waiting for PX4 on " + link_->Describe() + (lockstep_ ? " (lockstep)" : ""));
    } else {  // PX4's -u: it binds and waits for our first datagram
      link_ = std::make_unique<UdpSocket>("0.0.0.0", 0, addr == "INADDR_ANY" ? "127.0.0.1" : addr, udp_port);
    }
  }

  void OnReset() override {
    awaiting_answer_ = false;
    armed_ = false;
    session_.On(LinkEvent::kReset);  // the next answer starts the exchange again
    last_imu_count_ = last_gps_count_ = last_mag_count_ = last_baro_count_ = last_diff_count_ = 0;
    last_range_count_ = last_flow_count_ = 0;
    last_sensor_time_s_ = last_state_time_s_ = -1e9;
  }

  void Exchange(const VehicleSnapshot& s) override {
    Poll(0.0);
    if (!connected_) return;
    const bool imu_due =
        s.has_imu && s.imu_count != last_imu_count_ && s.time_s - last_sensor_time_s_ >= imu_interval_s_ - 1e-9;
    if (!imu_due) return;
    last_imu_count_ = s.imu_count;
    last_sensor_time_s_ = s.time_s;
    Send(s);
    if (hil_mode_ && !heard_heartbeat_) Write(endpoint_->Frame(SimulatorHeartbeat()));
    if (!session_.Waits(armed_)) return;
    // lockstep while armed: this step waits for the answer to the HIL_SENSOR just sent, at most answer_timeout
    awaiting_answer_ = true;
    awaited_time_usec_ = px4::Microseconds(s.time_s);
    const AwaitResult result = session_.AwaitAnswer([this](double timeout_s) { return Poll(timeout_s); },
                                                    [this] { return !awaiting_answer_; });
    awaiting_answer_ = false;
    if (result != AwaitResult::kTimedOut) return;  // answered, or the link closed (LoseLink said so)
    session_.On(LinkEvent::kLate);
    Error("late answer", "no HIL_ACTUATOR_CONTROLS within " + std::to_string(answer_timeout_s_) +
                             " s (answer_timeout) for the HIL_SENSOR of t = " + std::to_string(s.time_s) + " s (" +
                             std::to_string(session_.LateAnswers()) +
                             " so far): the step goes on with the last outputs, the link stays up");
  }

 private:
  void OnConnected() {
    endpoint_->ResetParser();
    autopilot_system_id_ = -1;
    armed_ = false;
    session_.On(LinkEvent::kConnected);
    Info("autopilot connected on " + link_->Describe());
  }

  /// A link that can go away and come back (a serial device): opened again here.
  void OpenLink() {
    try {
      link_ = open_link_();
      Info("HITL on " + link_->Describe());
    } catch (const rotors_sim::SimError& e) {
      Error("serial", std::string(e.what()) + "; retrying every second, the world runs on");
    }
  }

  /// Sends the step's messages (HIL_SENSOR first: PX4 sets its clock from it).
  void Send(const VehicleSnapshot& s) {
    const bool new_mag = s.has_mag && s.mag_count != last_mag_count_;
    const bool new_baro = s.has_baro && s.baro_count != last_baro_count_;
    const bool new_diff = s.has_diff_pressure && s.diff_pressure_count != last_diff_count_;
    last_mag_count_ = s.mag_count;
    last_baro_count_ = s.baro_count;
    last_diff_count_ = s.diff_pressure_count;
    if (!hil_state_level_) Write(endpoint_->Frame(px4::HilSensor(s, new_mag, new_baro, new_diff)));
    if (s.has_gps && s.gps_count != last_gps_count_) {
      last_gps_count_ = s.gps_count;
      if (!hil_state_level_) Write(endpoint_->Frame(px4::HilGps(s, utc_at_sim_zero_us_)));
    }
    // ground truth: in SITL, and in HITL only at state level (sensor-level HITL: PX4's own estimate)
    const bool send_state = !hil_mode_ || hil_state_level_;
    if (send_state && (hil_state_level_ || s.time_s - last_state_time_s_ >= state_interval_s_ - 1e-9)) {
      last_state_time_s_ = s.time_s;
      Write(endpoint_->Frame(px4::HilStateQuaternion(s)));
    }
    if (s.has_range && s.range_count != last_range_count_) {
      last_range_count_ = s.range_count;
      Write(endpoint_->Frame(px4::DistanceSensor(s)));
    }
    if (s.has_flow && s.flow_count != last_flow_count_) {
      last_flow_count_ = s.flow_count;
      Write(endpoint_->Frame(px4::HilOpticalFlow(s)));
    }
  }

  void Write(const std::vector<uint8_t>& bytes) {
    // a TCP client gone is seen by the next Receive; a serial device gone is seen here too
    if (connected_ && !link_->Send(bytes.data(), bytes.size()) && open_link_) LoseLink();
  }

  /// Takes a new connection and reads what is there (waiting up to timeout_s for the first bytes);
  /// false when the link closed.
  bool Poll(double timeout_s) {
    uint8_t buffer[2048];
    if (!link_) {
      const auto now = std::chrono::steady_clock::now();
      if (now - last_open_try_ > std::chrono::seconds(1)) {
        last_open_try_ = now;
        OpenLink();
      }
      if (!link_) return false;
    }
    if (!connected_) {
      if (!link_->Connect(0.0)) return false;
      connected_ = true;
      OnConnected();
    }
    int n;
    double wait = timeout_s;
    do {
      n = link_->Receive(buffer, sizeof(buffer), wait);
      if (n == kLinkClosed) {
        LoseLink();
        return false;
      }
      if (n > 0) Handle(buffer, n);
      wait = 0.0;  // after the first bytes, only what is already there
    } while (n > 0);
    if (qgc_) RelayFromQgc();
    return true;
  }

  void Handle(const uint8_t* bytes, int n) {
    const uint64_t bad_before = endpoint_->BadFrames();
    endpoint_->Feed(bytes, static_cast<size_t>(n), [this](const mavlink_message_t& m) { OnMessage(m); });
    if (endpoint_->BadFrames() != bad_before)
      Error("frames", std::to_string(endpoint_->BadFrames()) +
                          " malformed MAVLink frame(s) dropped so far (bad checksum, truncated, or a message "
                          "this interface does not know); the link stays up");
  }

  void OnMessage(const mavlink_message_t& m) {
    if (qgc_) {  // HITL: the autopilot's traffic goes on to QGroundControl
      std::vector<uint8_t> bytes(MAVLINK_MAX_PACKET_LEN);
      bytes.resize(mavlink_msg_to_send_buffer(bytes.data(), &m));
      qgc_->Send(bytes.data(), bytes.size());
    }
    if (m.msgid == MAVLINK_MSG_ID_HEARTBEAT) {
      heard_heartbeat_ = true;
      if (autopilot_system_id_ != m.sysid) {
        // the first heartbeat, or PX4 took another system id (MAV_SYS_ID): follow it
        Info("autopilot heartbeat from system id " + std::to_string(m.sysid) +
             (autopilot_system_id_ < 0 ? std::string() : " (was " + std::to_string(autopilot_system_id_) + ")"));
        autopilot_system_id_ = m.sysid;
      }
      return;
    }
    if (autopilot_system_id_ >= 0 && m.sysid != autopilot_system_id_) {
      Error("sysid", "message " + std::to_string(m.msgid) + " from system id " + std::to_string(m.sysid) +
                         ", but the autopilot on this link is system id " + std::to_string(autopilot_system_id_) +
                         ": ignored");
      return;
    }
    if (m.msgid == MAVLINK_MSG_ID_COMMAND_LONG) {
      mavlink_command_long_t c;
      mavlink_msg_command_long_decode(&m, &c);
      if (c.command == MAV_CMD_SET_MESSAGE_INTERVAL &&
          static_cast<int>(c.param1) == MAVLINK_MSG_ID_HIL_STATE_QUATERNION)
        state_interval_s_ = c.param2 > 0.0f ? c.param2 * 1e-6 : 0.0;
      return;
    }
    if (m.msgid != MAVLINK_MSG_ID_HIL_ACTUATOR_CONTROLS) return;
    px4::ActuatorControls a;
    std::string clamped;
    const std::string why = px4::DecodeActuatorControls(m, &a, &clamped);
    // PX4 stamps its outputs with its clock, which in lockstep is the time of the last HIL_SENSOR it
    // took: an answer releases the waiting step when it answers that step's HIL_SENSOR (or a later
    // one); an older answer is applied and the step keeps waiting, so the exchange never falls one
    // answer behind. An unstamped answer (time_usec 0: not PX4's clock) releases it, used or not.
    if (a.time_usec == 0 || a.time_usec >= awaited_time_usec_) awaiting_answer_ = false;
    if (session_.On(LinkEvent::kAnswered) && session_.State() == LinkState::kLockstep)
      Info(std::string("first HIL_ACTUATOR_CONTROLS") + (lockstep_ ? ": lockstep from now on (while armed)" : ""));
    if (!why.empty()) {
      Error("nan", why);
      return;
    }
    if (!clamped.empty()) Error("range", clamped);
    armed_ = a.armed;
    Apply(a.controls, armed_);
  }

  /// HITL: the simulator's heartbeat, each step until the autopilot's first one (current PX4 starts
  /// MAVLink on USB only after it hears one), as PX4's Gazebo plugin sends it.
  static mavlink_heartbeat_t SimulatorHeartbeat() {
    mavlink_heartbeat_t h{};
    h.type = MAV_TYPE_GENERIC;
    h.autopilot = MAV_AUTOPILOT_INVALID;
    h.system_status = MAV_STATE_ACTIVE;
    return h;
  }

  /// PX4 integrates its IMU at IMU_INTEG_RATE (250 Hz in its SITL): one line when the HIL_SENSOR rate
  /// (the physics rate, or imu_rate) is not a whole multiple of it.
  void CheckImuRate(double imu_rate_hz) {
    if (hil_mode_ || serial_enabled_) return;
    const double step_s = PhysicsStep_s();
    const double rate_hz = imu_rate_hz > 0.0 ? std::min(imu_rate_hz, 1.0 / step_s) : 1.0 / step_s;
    const double multiple = rate_hz / kPx4ImuIntegrationRate_Hz;
    if (multiple < 1.0 - 1e-6 || std::abs(multiple - std::round(multiple)) > 1e-6)
      Error("imu rate", "HIL_SENSOR at " + std::to_string(rate_hz) + " Hz (physics step " + std::to_string(step_s) +
                            " s): PX4 integrates its IMU at " + std::to_string(kPx4ImuIntegrationRate_Hz) +
                            " Hz and needs a whole multiple of it: use a step of 0.004 s (or 0.002, 0.001)");
  }

  void RelayFromQgc() {
    uint8_t buffer[2048];
    int n;
    while ((n = qgc_->Receive(buffer, sizeof(buffer), 0.0)) > 0)
      if (connected_) link_->Send(buffer, static_cast<size_t>(n));
  }

  /// The link is lost (the plugins' one name for it): motors disarmed, the world runs on. A link
  /// that can come back (a serial device, a TCP client) is dropped, to be opened again.
  void LoseLink() {
    const std::string why = open_link_ ? link_->Describe() + " went away" : "the autopilot closed the connection";
    awaiting_answer_ = false;
    session_.On(LinkEvent::kClosed);
    armed_ = false;
    connected_ = false;
    if (link_) link_->Disconnect();
    Error("lost", why + ": motors disarmed, the world runs on (a restarted PX4 may connect again)");
    ApplyDisarmed();
    if (open_link_) link_.reset();
  }

  // links: the autopilot's (TCP, UDP or serial), and QGroundControl's in HITL
  std::unique_ptr<Transport> link_;
  std::function<std::unique_ptr<Transport>()> open_link_;  ///< set for a link that can come back
  bool connected_ = false;
  std::unique_ptr<UdpSocket> qgc_;
  std::chrono::steady_clock::time_point last_open_try_;
  std::unique_ptr<px4::MavlinkEndpoint> endpoint_;
  /// PX4's IMU_INTEG_RATE in its SITL [Hz]
  static constexpr double kPx4ImuIntegrationRate_Hz = 250.0;
  // parameters
  bool serial_enabled_ = false, hil_mode_ = false, hil_state_level_ = false, lockstep_ = true;
  double answer_timeout_s_ = 0.01, imu_interval_s_ = 0.0, state_interval_s_ = 0.0;
  uint64_t utc_at_sim_zero_us_ = 0;
  // exchange state
  int autopilot_system_id_ = -1;
  LinkSession session_{WaitPolicy{}};
  bool awaiting_answer_ = false, armed_ = false, heard_heartbeat_ = false;
  uint64_t awaited_time_usec_ = 0;  ///< time_usec of the HIL_SENSOR the step waits for
  uint64_t last_imu_count_ = 0, last_gps_count_ = 0, last_mag_count_ = 0, last_baro_count_ = 0, last_diff_count_ = 0,
           last_range_count_ = 0, last_flow_count_ = 0;
  double last_sensor_time_s_ = -1e9, last_state_time_s_ = -1e9;
};

}  // namespace rotors_gazebo_plugins

GZ_REGISTER_MODEL_PLUGIN(rotors_gazebo_plugins::GazeboMavlinkInterface)
