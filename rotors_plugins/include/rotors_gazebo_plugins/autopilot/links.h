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

/// One datagram socket bound to `bind_port` on `bind_addr` (port 0: any free port).
class UdpSocket {
 public:
  UdpSocket(const std::string& bind_addr, int bind_port);
  ~UdpSocket();
  UdpSocket(const UdpSocket&) = delete;
  UdpSocket& operator=(const UdpSocket&) = delete;
  /// Sends to `addr`:`port`; false when the system refused (no listener is not an error for UDP).
  bool SendTo(const std::string& addr, int port, const void* data, size_t n);
  /// Sends to the sender of the last datagram received; false before the first one.
  bool Reply(const void* data, size_t n);
  /// One datagram into `buf` (truncated to `size`), waiting up to `timeout_s` (0: only what is there).
  int Receive(void* buf, size_t size, double timeout_s);
  int LocalPort() const;
  bool HasPeer() const { return has_peer_; }
  std::string Peer() const;

 private:
  int fd_ = -1;
  sockaddr_in peer_{};
  bool has_peer_ = false;
};

/// A TCP server on `port` that holds at most one client (PX4 connects as a client); a new client
/// replaces a lost one.
class TcpServer {
 public:
  TcpServer(const std::string& bind_addr, int port);
  ~TcpServer();
  TcpServer(const TcpServer&) = delete;
  TcpServer& operator=(const TcpServer&) = delete;
  /// Takes a waiting client, waiting up to `timeout_s`; true when one is connected (new or held).
  bool Accept(double timeout_s);
  bool Connected() const { return client_ >= 0; }
  bool Send(const void* data, size_t n);
  /// Bytes from the client; kLinkClosed when it went away (the client is dropped).
  int Receive(void* buf, size_t size, double timeout_s);
  void Drop();
  int Port() const { return port_; }

 private:
  int listen_fd_ = -1, client_ = -1, port_ = 0;
};

/// A serial device (HITL): raw 8N1 at `baud_rate`.
class SerialPort {
 public:
  SerialPort(const std::string& device, int baud_rate);
  ~SerialPort();
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;
  bool Send(const void* data, size_t n);
  int Receive(void* buf, size_t size, double timeout_s);

 private:
  int fd_ = -1;
  std::string device_;
};

}  // namespace rotors_gazebo_plugins
