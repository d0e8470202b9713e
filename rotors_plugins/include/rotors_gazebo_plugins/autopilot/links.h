// Byte links to an autopilot (POSIX sockets and serial ports, no ROS, no engine): a UDP socket, a
// TCP server that takes one client at a time, a serial device. Constructors throw
// rotors_sim::SimError naming the address and the system's reason (a port in use, a missing device).
#pragma once

#include <netinet/in.h>

#include <cstddef>
#include <cstdint>
#include <string>

namespace rotors_gazebo_plugins {

/// The result of one read: bytes (> 0), nothing within the timeout (0), or the peer gone (-1).
constexpr int kLinkClosed = -1;

/// One link to an autopilot, whatever carries it (UDP, TCP, a serial device), in one vocabulary:
/// Connect (is there a peer? TCP takes a waiting client here), Send (to the peer), Receive,
/// Disconnect (forget the peer), Describe (for messages).
class Transport {
 public:
  virtual ~Transport() = default;
  /// Whether there is a peer to talk to now, waiting up to timeout_s for one (TCP: a client).
  virtual bool Connect(double timeout_s) = 0;
  /// Sends to the peer; false when it could not (no peer yet, the link closed).
  virtual bool Send(const void* data, size_t n) = 0;
  /// Bytes into `buf` (truncated to `size`), waiting up to `timeout_s` (0: only what is there); 0 for
  /// nothing, kLinkClosed when the peer is gone.
  virtual int Receive(void* buf, size_t size, double timeout_s) = 0;
  /// Forgets the peer (TCP: closes the client's connection; the next Connect takes a new one).
  virtual void Disconnect() {}
  /// "UDP 0.0.0.0:9002", "TCP port 4560", "serial /dev/ttyACM0"
  virtual std::string Describe() const = 0;
};

/// One datagram socket bound to `bind_port` on `bind_addr` (port 0: any free port). Its peer is
/// `peer_addr`:`peer_port` when given, else whoever sent the last datagram.
class UdpSocket : public Transport {
 public:
  UdpSocket(const std::string& bind_addr, int bind_port, const std::string& peer_addr = "", int peer_port = 0);
  ~UdpSocket() override;
  UdpSocket(const UdpSocket&) = delete;
  UdpSocket& operator=(const UdpSocket&) = delete;
  bool Connect(double /*timeout_s*/) override { return has_peer_; }
  /// Sends to the peer; false before there is one, or when the system refused.
  bool Send(const void* data, size_t n) override;
  int Receive(void* buf, size_t size, double timeout_s) override;
  std::string Describe() const override;
  /// The port it is bound to.
  int Port() const;
  std::string Peer() const;

 private:
  int fd_ = -1;
  sockaddr_in peer_{};
  bool has_peer_ = false, fixed_peer_ = false;
};

/// A TCP server on `port` that holds at most one client (PX4 connects as a client); a new client
/// replaces a lost one.
class TcpServer : public Transport {
 public:
  TcpServer(const std::string& bind_addr, int port);
  ~TcpServer() override;
  TcpServer(const TcpServer&) = delete;
  TcpServer& operator=(const TcpServer&) = delete;
  /// Takes a waiting client, waiting up to `timeout_s`; true when one is connected (new or held).
  bool Connect(double timeout_s) override;
  bool Connected() const { return client_ >= 0; }
  bool Send(const void* data, size_t n) override;
  /// Bytes from the client; kLinkClosed when it went away (the client is dropped).
  int Receive(void* buf, size_t size, double timeout_s) override;
  void Disconnect() override;
  std::string Describe() const override { return "TCP port " + std::to_string(port_); }
  int Port() const { return port_; }

 private:
  int listen_fd_ = -1, client_ = -1, port_ = 0;
};

/// A serial device (HITL): raw 8N1 at `baud_rate`.
class SerialPort : public Transport {
 public:
  SerialPort(const std::string& device, int baud_rate);
  ~SerialPort() override;
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;
  bool Connect(double /*timeout_s*/) override { return fd_ >= 0; }
  bool Send(const void* data, size_t n) override;
  /// kLinkClosed when the device went away (unplugged; the other end of a pty closed).
  int Receive(void* buf, size_t size, double timeout_s) override;
  std::string Describe() const override { return "serial " + device_; }

 private:
  int fd_ = -1;
  std::string device_;
};

}  // namespace rotors_gazebo_plugins
