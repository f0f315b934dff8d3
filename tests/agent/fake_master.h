// FakeMaster: an in-process stand-in for radfarmd, for tests that run the real radfarm-agent. A
// thread runs its own loop::EventLoop with a TcpListener on 127.0.0.1 (port 0) and one
// ProtocolSession::ForMaster per accepted connection. It records every message agents send,
// answers SceneRequests from the scenes it was given, and sends what the test tells it to.
// Tests may speak in single batches: an AssignedBatch is sent as a LeaseAssignment of that
// one batch (LeaseOf), and every batch of a LeaseResult is recorded in Record::results.
//
// Threads: the test thread calls every method; the loop runs on the master's thread. Commands
// cross over through an Async; what the master saw comes back as a Record snapshot under a mutex.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include "protocol/farm_secret.h"
#include "protocol/messages.h"
#include "protocol/scene_packing.h"

namespace radfarm::agent::testing {

inline constexpr std::chrono::milliseconds kWaitTimeout{60000};  // generous: ASan on 2 shared cores

// What a test sends an agent: a message, or one batch, which goes out as a LeaseAssignment of
// that batch alone (LeaseOf).
using Outgoing = std::variant<protocol::Message, protocol::AssignedBatch>;

struct FakeMasterOptions {
  uint32_t heartbeat_interval_ms = 60000;
  bool send_heartbeats = false;         // every interval, to each authenticated agent
  int close_first_connections = 0;      // close this many connections right after their Welcome
  std::vector<Outgoing> after_welcome;  // sent to every agent right after its Welcome
  bool forge_welcome_tag = false;  // send Welcomes whose master tag is wrong (an impostor master)
};

// A master whose heartbeat interval is `interval_ms`, and that sends heartbeats itself or not.
inline FakeMasterOptions Heartbeats(uint32_t interval_ms, bool send_heartbeats) {
  FakeMasterOptions options;
  options.heartbeat_interval_ms = interval_ms;
  options.send_heartbeats = send_heartbeats;
  return options;
}

// The lease frame carrying these batches (all of one job, round and scene).
protocol::LeaseAssignmentMsg LeaseOf(const std::vector<protocol::AssignedBatch>& batches);

// What the master has seen so far.
struct Record {
  int accepted = 0;       // TCP connections
  int authenticated = 0;  // handshakes completed
  int auth_failures = 0;  // agent proofs that did not match the secret
  int open = 0;           // authenticated connections still open
  std::vector<std::string> session_errors;
  std::vector<protocol::Message> received;      // application messages, in order, all connections
  std::vector<protocol::BatchOutcome> results;  // every batch of every LeaseResult, in order
  std::vector<std::string> agent_names;         // from each Hello
  std::map<protocol::SceneHash, int> fetches;   // SceneRequests at offset 0, per scene
  int scene_requests = 0;

  template <typename T>
  std::vector<T> All() const {
    std::vector<T> out;
    for (const protocol::Message& m : received) {
      if (const T* t = std::get_if<T>(&m)) out.push_back(*t);
    }
    return out;
  }
};

class FakeMaster {
 public:
  FakeMaster(protocol::FarmSecret secret, FakeMasterOptions options = {});
  ~FakeMaster();
  FakeMaster(const FakeMaster&) = delete;
  FakeMaster& operator=(const FakeMaster&) = delete;

  uint16_t port() const { return port_; }
  std::string address() const { return "127.0.0.1:" + std::to_string(port_); }

  // Scene blobs served to SceneRequests by hash; others get SceneUnavailable.
  void AddScene(std::vector<uint8_t> blob);
  // Sends the messages, in order and in one loop iteration, to the newest authenticated agent.
  void Send(std::vector<Outgoing> messages);
  void Send(Outgoing message) { Send(std::vector<Outgoing>{std::move(message)}); }
  // Closes the newest authenticated connection (TCP close, no Close message).
  void Drop();

  Record Snapshot() const;
  // Polls the record until `done` holds; false after `timeout`.
  bool WaitFor(const std::function<bool(const Record&)>& done,
               std::chrono::milliseconds timeout = kWaitTimeout) const;

 private:
  struct Loop;
  void Post(std::function<void()> command);

  FakeMasterOptions options_;
  uint16_t port_ = 0;
  mutable std::mutex mutex_;
  Record record_;  // guarded by mutex_
  // Packed as the master packs them; guarded by mutex_.
  std::map<protocol::SceneHash, std::shared_ptr<const protocol::PackedScene>> scenes_;
  std::unique_ptr<Loop> loop_;
  std::thread thread_;
};

}  // namespace radfarm::agent::testing
