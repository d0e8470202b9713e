// Whether the nodes publishing a topic are alive, asked on a worker thread: the master lists
// publishers until they unregister, which a node killed with SIGKILL never does, so each is pinged
// over XML-RPC. The simulation thread only posts requests and reads answers; it never waits on the
// network, so a participant stopped in a debugger cannot freeze /clock or the services.
#pragma once

#include <condition_variable>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include <ros/time.h>

namespace rotors_sim {

class NodePinger {
 public:
  enum class Answer { kNone, kAlive, kDead };
  /// deadline_s: [s wall] a ping not answered within it counts as dead (the worker may still be
  /// waiting on the network; its late answer is taken by a later Take()).
  explicit NodePinger(double deadline_s);
  ~NodePinger();
  NodePinger(const NodePinger&) = delete;
  NodePinger& operator=(const NodePinger&) = delete;
  /// Starts a ping of the nodes publishing `topic`, unless one is under way. Never blocks.
  void Request(const std::string& topic);
  /// The answer to the latest request for `topic` once (then kNone until the next one finishes);
  /// kDead when its ping has run longer than the deadline (a request still queued behind another
  /// topic's ping is not overdue: only pings that ran are judged). Never blocks.
  Answer Take(const std::string& topic);

 private:
  struct Entry {
    bool under_way = false;  // requested, answer not in yet
    bool started = false;    // the worker is pinging it
    bool overdue_reported = false;
    ros::WallTime started_at;
    Answer answer = Answer::kNone;
  };
  struct Shared {  // shared with the worker, which may outlive the pinger while stuck on the network
    std::mutex mutex;
    std::condition_variable wake;
    std::deque<std::string> queue;
    std::map<std::string, Entry> entries;
    bool stop = false;
    bool busy = false;
  };
  static void Work(const std::shared_ptr<Shared>& shared);
  std::shared_ptr<Shared> shared_;
  std::thread worker_;
  double deadline_s_;
};

/// True when at least one node that publishes `topic` (per the master) answers an XML-RPC ping.
/// Blocks on the network: call it from NodePinger's worker, not from the simulation thread.
bool AnyPublisherAlive(const std::string& topic);

}  // namespace rotors_sim
