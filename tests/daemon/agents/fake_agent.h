// FakeAgent: an agent the test steers, on a real loopback connection to MasterParts' listener. It
// runs the real handshake (ProtocolSession::ForAgent) and reports its speed in a heartbeat, as
// radfarm-agent does on its welcome; then it keeps every lease it is given and, when answering,
// returns each lease at once with the simulated results farmsim/ makes (valid for their batches,
// not physics), and each display piece with zero values of the right counts. Silent (answering
// off), it holds its leases until the test closes it or the master cancels their job.
//
// Loop thread only; its connection closes with it.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "base/result.h"
#include "loop/event_loop.h"
#include "loop/framed_connection.h"
#include "loop/socket_address.h"
#include "protocol/farm_secret.h"
#include "protocol/messages.h"
#include "protocol/protocol_session.h"

namespace radfarm::daemon::fakes {

// (job, round, batch index within the round): a batch whatever attempt carries it.
using BatchKey = std::tuple<uint64_t, uint32_t, uint64_t>;

class FakeAgent {
 public:
  FakeAgent(loop::EventLoop& loop, const loop::SocketAddress& master,
            const protocol::FarmSecret& secret, std::string name, bool answering);
  ~FakeAgent();
  FakeAgent(const FakeAgent&) = delete;
  FakeAgent& operator=(const FakeAgent&) = delete;

  Status Connect();
  // Drops the connection without a word, as a crashed agent or a cut cable does.
  void Drop();
  // Speaks: a heartbeat reporting its speed and the leases it holds.
  void SendHeartbeat();

  bool authenticated() const { return session_.authenticated(); }
  bool closed() const { return closed_reason_.has_value(); }
  // Why the connection closed: the master's Close detail, or the socket's reason.
  const std::optional<std::string>& closed_reason() const { return closed_reason_; }
  // Every batch it was leased, and those it holds unanswered.
  const std::set<BatchKey>& leased() const { return leased_; }
  const std::set<BatchKey>& held() const { return held_; }
  // Batches received in leases, counting every time one comes again.
  uint64_t batches_received() const { return batches_received_; }
  uint64_t results_sent() const { return results_sent_; }
  // Whether it answers display pieces (by default as it answers batches).
  void set_answering_pieces(bool answering) { answering_pieces_ = answering; }
  // Display pieces (PointLease) received, and those it holds unanswered.
  uint64_t pieces_received() const { return pieces_received_; }
  size_t pieces_held() const { return pieces_held_.size(); }
  const std::vector<uint64_t>& cancelled_jobs() const { return cancelled_jobs_; }
  // Whether it answers the pieces of a direct-light start (by default it does, whatever it does
  // with batches); the start pieces received, and those held unanswered.
  void set_answering_starts(bool answering) { answering_starts_ = answering; }
  uint64_t start_pieces_received() const { return start_pieces_received_; }
  size_t start_pieces_held() const { return start_pieces_held_.size(); }

 private:
  void OnFrame(std::span<const uint8_t> payload);
  void OnLease(const protocol::LeaseAssignmentMsg& lease);
  void OnPointLease(const protocol::PointLeaseMsg& lease);
  void Send(const protocol::Message& message);
  void Fail(const std::string& reason);

  loop::EventLoop& loop_;
  loop::SocketAddress master_;
  std::string name_;
  bool answering_;
  protocol::ProtocolSession session_;
  std::unique_ptr<loop::FramedConnection> connection_;
  std::optional<std::string> closed_reason_;
  std::set<BatchKey> leased_;
  std::set<BatchKey> held_;
  uint64_t batches_received_ = 0;
  uint64_t results_sent_ = 0;
  std::vector<uint64_t> cancelled_jobs_;
  std::optional<bool> answering_pieces_;
  uint64_t pieces_received_ = 0;
  std::set<std::pair<uint64_t, uint64_t>> pieces_held_;  // (job, piece)
  bool answering_starts_ = true;
  uint64_t start_pieces_received_ = 0;
  std::set<std::pair<uint64_t, uint64_t>> start_pieces_held_;  // (job, piece)
};

}  // namespace radfarm::daemon::fakes
