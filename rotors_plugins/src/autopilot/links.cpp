#include "rotors_gazebo_plugins/autopilot/links.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "rotors_core/error.h"

namespace rotors_gazebo_plugins {
namespace {

sockaddr_in Address(const std::string& addr, int port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<uint16_t>(port));
  if (addr.empty() || addr == "INADDR_ANY" || addr == "0.0.0.0") {
    a.sin_addr.s_addr = htonl(INADDR_ANY);
  } else if (inet_pton(AF_INET, addr.c_str(), &a.sin_addr) != 1) {
    throw rotors_sim::SimError("'" + addr + "' is not an IPv4 address (give dotted numbers, e.g. 127.0.0.1)");
  }
  return a;
}

std::string Where(const std::string& addr, int port) {
  return (addr.empty() ? "0.0.0.0" : addr) + ":" + std::to_string(port);
}

/// Waits up to timeout_s for `fd` to be readable.
bool Readable(int fd, double timeout_s) {
  pollfd p{fd, POLLIN, 0};
  const int ms = timeout_s <= 0.0 ? 0 : static_cast<int>(timeout_s * 1000.0 + 0.5);
  int r;
  do {
    r = ::poll(&p, 1, ms);
  } while (r < 0 && errno == EINTR);
  return r > 0;
}

}  // namespace

UdpSocket::UdpSocket(const std::string& bind_addr, int bind_port, const std::string& peer_addr, int peer_port) {
  if (!peer_addr.empty()) {
    peer_ = Address(peer_addr, peer_port);
    has_peer_ = fixed_peer_ = true;
  }
  fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd_ < 0) throw rotors_sim::SimError(std::string("cannot open a UDP socket: ") + std::strerror(errno));
  const sockaddr_in a = Address(bind_addr, bind_port);
  if (::bind(fd_, reinterpret_cast<const sockaddr*>(&a), sizeof(a)) != 0) {
    const std::string why = std::strerror(errno);
    ::close(fd_);
    fd_ = -1;
    throw rotors_sim::SimError("cannot bind UDP " + Where(bind_addr, bind_port) + ": " + why +
                               (why.find("in use") != std::string::npos
                                    ? " (another simulator or bridge holds it: stop it, or give this one another port)"
                                    : ""));
  }
}

UdpSocket::~UdpSocket() {
  if (fd_ >= 0) ::close(fd_);
}

bool UdpSocket::Send(const void* data, size_t n) {
  if (!has_peer_) return false;
  return ::sendto(fd_, data, n, 0, reinterpret_cast<const sockaddr*>(&peer_), sizeof(peer_)) == static_cast<ssize_t>(n);
}

int UdpSocket::Receive(void* buf, size_t size, double timeout_s) {
  if (!Readable(fd_, timeout_s)) return 0;
  sockaddr_in from{};
  socklen_t len = sizeof(from);
  const ssize_t n = ::recvfrom(fd_, buf, size, MSG_DONTWAIT, reinterpret_cast<sockaddr*>(&from), &len);
  if (n <= 0) return 0;  // an ICMP "port unreachable" of an earlier send, or nothing after all
  if (!fixed_peer_) {    // the peer is whoever sent last
    peer_ = from;
    has_peer_ = true;
  }
  return static_cast<int>(n);
}

int UdpSocket::Port() const {
  sockaddr_in a{};
  socklen_t len = sizeof(a);
  ::getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len);
  return ntohs(a.sin_port);
}

std::string UdpSocket::Describe() const { return "UDP port " + std::to_string(Port()) + " (peer " + Peer() + ")"; }

std::string UdpSocket::Peer() const {
  if (!has_peer_) return "none";
  char text[INET_ADDRSTRLEN] = {0};
  inet_ntop(AF_INET, &peer_.sin_addr, text, sizeof(text));
  return std::string(text) + ":" + std::to_string(ntohs(peer_.sin_port));
}

TcpServer::TcpServer(const std::string& bind_addr, int port) : port_(port) {
  listen_fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (listen_fd_ < 0) throw rotors_sim::SimError(std::string("cannot open a TCP socket: ") + std::strerror(errno));
  const int one = 1;
  ::setsockopt(listen_fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof(one));
  const sockaddr_in a = Address(bind_addr, port);
  if (::bind(listen_fd_, reinterpret_cast<const sockaddr*>(&a), sizeof(a)) != 0 || ::listen(listen_fd_, 1) != 0) {
    const std::string why = std::strerror(errno);
    ::close(listen_fd_);
    listen_fd_ = -1;
    throw rotors_sim::SimError(
        "cannot listen on TCP " + Where(bind_addr, port) + ": " + why +
        (why.find("in use") != std::string::npos
             ? " (another simulator holds it: stop it, or give this vehicle another instance port)"
             : ""));
  }
}

TcpServer::~TcpServer() {
  Disconnect();
  if (listen_fd_ >= 0) ::close(listen_fd_);
}

bool TcpServer::Connect(double timeout_s) {
  if (client_ >= 0) return true;
  if (!Readable(listen_fd_, timeout_s)) return false;
  client_ = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
  if (client_ < 0) return false;
  const int one = 1;
  ::setsockopt(client_, IPPROTO_TCP, TCP_NODELAY, &one, sizeof(one));
  return true;
}

bool TcpServer::Send(const void* data, size_t n) {
  if (client_ < 0) return false;
  const char* p = static_cast<const char*>(data);
  while (n > 0) {
    const ssize_t sent = ::send(client_, p, n, MSG_NOSIGNAL);
    if (sent < 0 && errno == EINTR) continue;
    if (sent <= 0) {
      Disconnect();
      return false;
    }
    p += sent;
    n -= static_cast<size_t>(sent);
  }
  return true;
}

int TcpServer::Receive(void* buf, size_t size, double timeout_s) {
  if (client_ < 0) return kLinkClosed;
  if (!Readable(client_, timeout_s)) return 0;
  const ssize_t n = ::recv(client_, buf, size, MSG_DONTWAIT);
  if (n > 0) return static_cast<int>(n);
  if (n < 0 && (errno == EAGAIN || errno == EINTR)) return 0;
  Disconnect();  // 0: an orderly close; < 0: reset
  return kLinkClosed;
}

void TcpServer::Disconnect() {
  if (client_ >= 0) ::close(client_);
  client_ = -1;
}

namespace {
speed_t BaudConstant(int baud) {
  switch (baud) {
    case 9600: return B9600;
    case 19200: return B19200;
    case 38400: return B38400;
    case 57600: return B57600;
    case 115200: return B115200;
    case 230400: return B230400;
    case 460800: return B460800;
    case 500000: return B500000;
    case 921600: return B921600;
    case 1000000: return B1000000;
    case 1500000: return B1500000;
    case 2000000: return B2000000;
    case 3000000: return B3000000;
    default:
      throw rotors_sim::SimError("baudRate " + std::to_string(baud) +
                                 " is not a serial speed this system sets (e.g. 57600, 115200, 921600)");
  }
}
}  // namespace

SerialPort::SerialPort(const std::string& device, int baud_rate) : device_(device) {
  const speed_t speed = BaudConstant(baud_rate);
  fd_ = ::open(device.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0)
    throw rotors_sim::SimError("cannot open serial device " + device + ": " + std::strerror(errno) +
                               " (is the autopilot plugged in? serialDevice names it)");
  termios t{};
  if (::tcgetattr(fd_, &t) == 0) {  // a pty pair (socat) has attributes too; a plain file has none
    ::cfmakeraw(&t);
    ::cfsetispeed(&t, speed);
    ::cfsetospeed(&t, speed);
    t.c_cflag |= CLOCAL | CREAD;
    ::tcsetattr(fd_, TCSANOW, &t);
  }
}

SerialPort::~SerialPort() {
  if (fd_ >= 0) ::close(fd_);
}

bool SerialPort::Send(const void* data, size_t n) {
  const char* p = static_cast<const char*>(data);
  while (n > 0) {
    const ssize_t sent = ::write(fd_, p, n);
    if (sent < 0 && (errno == EINTR || errno == EAGAIN)) {
      pollfd w{fd_, POLLOUT, 0};
      ::poll(&w, 1, 10);
      continue;
    }
    if (sent <= 0) return false;
    p += sent;
    n -= static_cast<size_t>(sent);
  }
  return true;
}

int SerialPort::Receive(void* buf, size_t size, double timeout_s) {
  if (!Readable(fd_, timeout_s)) return 0;
  const ssize_t n = ::read(fd_, buf, size);
  if (n > 0) return static_cast<int>(n);
  if (n < 0 && (errno == EAGAIN || errno == EINTR)) return 0;
  return kLinkClosed;  // the device went away (unplugged; the other end of a pty closed)
}

}  // namespace rotors_gazebo_plugins
