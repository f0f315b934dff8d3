// ConnectionDeadlines: which of the web console's connections to close, so slow clients cannot
// hold them. A connection is *waiting* from its start until a request has fully arrived (headers
// and body), and again after each response until the next request; it is *serving* in between
// (an event stream serves until it ends). A waiting connection gets one total deadline, which a
// client trickling a byte at a time cannot extend (libmicrohttpd's own timeout restarts on every
// byte). Waiting connections are also capped, in all and per client address; over a cap the
// oldest waiting one goes, so a burst from one address cannot keep a new browser out.
//
// Pure logic with the clock passed in; HttpServer shuts the sockets it returns. Not thread-safe:
// HttpServer holds a mutex around it.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <list>
#include <string>
#include <unordered_map>
#include <vector>

namespace radfarm::web {

class ConnectionDeadlines {
 public:
  using TimePoint = std::chrono::steady_clock::time_point;
  using Key = const void*;  // the connection (libmicrohttpd's handle)

  ConnectionDeadlines(std::chrono::milliseconds deadline, size_t max_waiting,
                      size_t max_waiting_per_address);

  // A new connection on socket `fd`, waiting; returns the sockets of connections to close.
  std::vector<int> Opened(Key key, std::string address, int fd, TimePoint now);
  // Its request has arrived: no deadline until Waiting.
  void Serving(Key key);
  // Its response is done: waiting for the next request, with a new deadline.
  void Waiting(Key key, TimePoint now);
  void Closed(Key key);
  // The sockets of waiting connections past their deadline (each returned once).
  std::vector<int> Expired(TimePoint now);

  size_t waiting() const { return waiting_.size(); }

 private:
  struct Connection {
    std::string address;
    int fd = -1;
    TimePoint deadline;
  };
  using Queue = std::list<Key>;  // waiting connections, oldest first

  void Unqueue(Key key);
  // Closes the oldest waiting connection of `address` ("" for any): its socket, or -1 if none.
  int TakeOldest(const std::string& address);

  const std::chrono::milliseconds deadline_;
  const size_t max_waiting_, max_waiting_per_address_;
  std::unordered_map<Key, Connection> connections_;
  Queue waiting_;
  std::unordered_map<Key, Queue::iterator> queued_;
  std::unordered_map<std::string, size_t> waiting_per_address_;
};

}  // namespace radfarm::web
