#include "tests/agent/fake_master.h"

#include <deque>
#include <future>
#include <stdexcept>

#include "loop/async.h"
#include "loop/event_loop.h"
#include "loop/framed_connection.h"
#include "loop/tcp_listener.h"
#include "loop/timer.h"
#include "protocol/frame_codec.h"
#include "protocol/protocol_session.h"
#include "protocol/scene_transfer.h"

namespace radfarm::agent::testing {
namespace {

// Flips one bit of the master's tag in an encoded Welcome frame.
void ForgeTag(std::vector<uint8_t>* frame) {
  protocol::DecodedFrame decoded = protocol::DecodeFrame(*frame).value();
  auto& welcome = std::get<protocol::WelcomeMsg>(decoded.message);
  welcome.tag[0] ^= 1;
  *frame = protocol::EncodeFrame(welcome, decoded.version);
}

}  // namespace

// Everything that lives on the master's loop thread.
struct FakeMaster::Loop {
  struct Connection {
    uint64_t agent_id = 0;
    std::unique_ptr<loop::FramedConnection> stream;
    protocol::ProtocolSession session;
    bool counted_open = false;
  };

  Loop(FakeMaster* master, protocol::FarmSecret secret)
      : master(master), secret(std::move(secret)) {}

  void Run(std::promise<uint16_t>* ready);
  void OnAccept(std::unique_ptr<loop::FramedConnection> stream);
  void OnFrame(Connection* c, std::span<const uint8_t> payload);
  void OnClosed(Connection* c);
  void Deliver(Connection* c, const protocol::Message& message);
  void Refuse(Connection* c, const std::string& reason);
  void Write(Connection* c, const protocol::Message& message);
  // A single batch goes out as a LeaseAssignment of that batch alone.
  void WriteOutgoing(Connection* c, const Outgoing& outgoing);
  Connection* Newest();
  void DrainCommands();

  FakeMaster* master;
  protocol::FarmSecret secret;
  loop::EventLoop* event_loop = nullptr;
  std::unique_ptr<loop::Async> wake;
  std::unique_ptr<loop::TcpListener> listener;
  std::unique_ptr<loop::Timer> heartbeat;
  std::vector<std::unique_ptr<Connection>> connections;
  uint64_t next_agent_id = 1;
  int closed_after_welcome = 0;
  std::mutex command_mutex;
  std::deque<std::function<void()>> commands;  // guarded by command_mutex
};

void FakeMaster::Loop::Run(std::promise<uint16_t>* ready) {
  loop::EventLoop loop;
  event_loop = &loop;
  Result<std::unique_ptr<loop::Async>> async =
      loop::Async::Create(loop, [this] { DrainCommands(); });
  Result<std::unique_ptr<loop::TcpListener>> listening = loop::TcpListener::Listen(
      loop, loop::HostPort{"127.0.0.1", 0},
      [this](std::unique_ptr<loop::FramedConnection> stream) { OnAccept(std::move(stream)); });
  if (!async || !listening) {
    ready->set_exception(std::make_exception_ptr(std::runtime_error("fake master cannot start")));
    return;
  }
  wake = std::move(async).value();
  listener = std::move(listening).value();
  heartbeat = std::make_unique<loop::Timer>(loop);
  if (master->options_.send_heartbeats) {
    const std::chrono::milliseconds interval(master->options_.heartbeat_interval_ms);
    heartbeat->Start(interval, interval, [this] {
      for (auto& c : connections) {
        if (c->session.authenticated()) Write(c.get(), protocol::HeartbeatMsg{});
      }
    });
  }
  ready->set_value(listener->port());
  loop.Run();
  connections.clear();
  heartbeat.reset();
  listener.reset();
  wake.reset();
  if (Status closed = loop.Close(); !closed) std::fprintf(stderr, "%s\n", closed.error().c_str());
}

void FakeMaster::Loop::DrainCommands() {
  std::deque<std::function<void()>> batch;
  {
    std::lock_guard lock(command_mutex);
    batch.swap(commands);
  }
  for (auto& command : batch) command();
}

void FakeMaster::Loop::OnAccept(std::unique_ptr<loop::FramedConnection> stream) {
  protocol::MasterConfig config;
  config.agent_id = next_agent_id++;
  config.heartbeat_interval_ms = master->options_.heartbeat_interval_ms;
  auto c = std::make_unique<Connection>(Connection{
      config.agent_id, std::move(stream), protocol::ProtocolSession::ForMaster(secret, config)});
  Connection* raw = c.get();
  raw->stream->Start(
      {}, [this, raw](std::span<const uint8_t> payload) { OnFrame(raw, payload); },
      [this, raw](const std::string&) { OnClosed(raw); });
  connections.push_back(std::move(c));
  std::lock_guard lock(master->mutex_);
  ++master->record_.accepted;
}

void FakeMaster::Loop::OnFrame(Connection* c, std::span<const uint8_t> payload) {
  Result<protocol::DecodedFrame> frame = c->session.Decode(payload);
  if (!frame) {
    Refuse(c, frame.error());
    return;
  }
  const bool was_authenticated = c->session.authenticated();
  Result<protocol::ProtocolSession::Accepted> accepted = c->session.Accept(*frame);
  if (!accepted) {
    Refuse(c, accepted.error());
    return;
  }
  if (!accepted->reply.empty()) {
    if (master->options_.forge_welcome_tag && c->session.authenticated()) {
      ForgeTag(&accepted->reply);
    }
    (void)c->stream->SendPrefixed(std::move(accepted->reply));
  }
  if (!was_authenticated && c->session.authenticated()) {
    {
      std::lock_guard lock(master->mutex_);
      ++master->record_.authenticated;
      ++master->record_.open;
      master->record_.agent_names.push_back(c->session.hello().agent_name);
    }
    c->counted_open = true;
    if (closed_after_welcome < master->options_.close_first_connections) {
      ++closed_after_welcome;
      c->stream->CloseAfterFlush("the fake master closes the first connections");
      return;
    }
    for (const Outgoing& m : master->options_.after_welcome) WriteOutgoing(c, m);
    return;
  }
  if (accepted->deliver) Deliver(c, frame->message);
}

void FakeMaster::Loop::Deliver(Connection* c, const protocol::Message& message) {
  {
    std::lock_guard lock(master->mutex_);
    master->record_.received.push_back(message);
    // Tests look results up by lease whichever frame carried them.
    if (const auto* results = std::get_if<protocol::LeaseResultMsg>(&message)) {
      master->record_.results.insert(master->record_.results.end(), results->results.begin(),
                                     results->results.end());
    }
  }
  if (std::holds_alternative<protocol::CloseMsg>(message)) {
    c->stream->Close("the agent sent Close");
    return;
  }
  const auto* request = std::get_if<protocol::SceneRequestMsg>(&message);
  if (request == nullptr) return;
  std::shared_ptr<const protocol::PackedScene> scene;
  {
    std::lock_guard lock(master->mutex_);
    ++master->record_.scene_requests;
    if (request->offset == 0) ++master->record_.fetches[request->scene_hash];
    if (auto found = master->scenes_.find(request->scene_hash); found != master->scenes_.end()) {
      scene = found->second;
    }
  }
  if (!scene) {
    Write(c, protocol::SceneUnavailableMsg{request->scene_hash});
    return;
  }
  Result<protocol::SceneChunkMsg> chunk = protocol::MakeSceneChunk(*scene, *request);
  if (!chunk) {
    Refuse(c, chunk.error());
    return;
  }
  Write(c, *chunk);
}

void FakeMaster::Loop::Refuse(Connection* c, const std::string& reason) {
  {
    std::lock_guard lock(master->mutex_);
    master->record_.session_errors.push_back(reason);
    if (reason.find("proof does not match") != std::string::npos) ++master->record_.auth_failures;
  }
  (void)c->stream->SendPrefixed(c->session.CloseFrame());
  c->stream->CloseAfterFlush(reason);
}

void FakeMaster::Loop::WriteOutgoing(Connection* c, const Outgoing& outgoing) {
  if (const auto* one = std::get_if<protocol::AssignedBatch>(&outgoing)) {
    Write(c, LeaseOf({*one}));
    return;
  }
  Write(c, std::get<protocol::Message>(outgoing));
}

void FakeMaster::Loop::Write(Connection* c, const protocol::Message& message) {
  Result<std::vector<uint8_t>> frame = c->session.Encode(message);
  if (!frame) {
    std::lock_guard lock(master->mutex_);
    master->record_.session_errors.push_back("cannot send: " + frame.error());
    return;
  }
  (void)c->stream->SendPrefixed(std::move(frame).value());
}

void FakeMaster::Loop::OnClosed(Connection* c) {
  if (c->counted_open) {
    std::lock_guard lock(master->mutex_);
    --master->record_.open;
  }
  std::erase_if(connections, [c](const auto& owned) { return owned.get() == c; });
}

FakeMaster::Loop::Connection* FakeMaster::Loop::Newest() {
  for (auto it = connections.rbegin(); it != connections.rend(); ++it) {
    if ((*it)->session.authenticated() && (*it)->stream->state() == loop::HandleState::kOpen) {
      return it->get();
    }
  }
  return nullptr;
}

FakeMaster::FakeMaster(protocol::FarmSecret secret, FakeMasterOptions options)
    : options_(options), loop_(std::make_unique<Loop>(this, std::move(secret))) {
  std::promise<uint16_t> ready;
  std::future<uint16_t> port = ready.get_future();
  thread_ = std::thread([this, &ready] { loop_->Run(&ready); });
  try {
    port_ = port.get();
  } catch (...) {
    thread_.join();
    throw;
  }
}

FakeMaster::~FakeMaster() {
  Post([this] { loop_->event_loop->Stop(); });
  thread_.join();
}

void FakeMaster::Post(std::function<void()> command) {
  {
    std::lock_guard lock(loop_->command_mutex);
    loop_->commands.push_back(std::move(command));
  }
  loop_->wake->Send();
}

void FakeMaster::AddScene(std::vector<uint8_t> blob) {
  std::lock_guard lock(mutex_);
  auto packed = std::make_shared<const protocol::PackedScene>(protocol::PackScene(blob));
  scenes_[packed->hash] = std::move(packed);
}

void FakeMaster::Send(std::vector<Outgoing> messages) {
  Post([this, messages = std::move(messages)] {
    Loop::Connection* c = loop_->Newest();
    if (c == nullptr) {
      std::lock_guard lock(mutex_);
      record_.session_errors.push_back("Send: no authenticated agent");
      return;
    }
    for (const Outgoing& m : messages) loop_->WriteOutgoing(c, m);
  });
}

void FakeMaster::Drop() {
  Post([this] {
    if (Loop::Connection* c = loop_->Newest()) c->stream->Close("dropped by the test");
  });
}

Record FakeMaster::Snapshot() const {
  std::lock_guard lock(mutex_);
  return record_;
}

bool FakeMaster::WaitFor(const std::function<bool(const Record&)>& done,
                         std::chrono::milliseconds timeout) const {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!done(Snapshot())) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return true;
}

protocol::LeaseAssignmentMsg LeaseOf(const std::vector<protocol::AssignedBatch>& batches) {
  const protocol::AssignedBatch& first = batches.front();
  protocol::LeaseAssignmentMsg lease;
  lease.job_id = first.lease.job_id;
  lease.round = first.round;
  lease.seed = first.seed;
  lease.sampler = first.sampler;
  lease.grid_step_degrees = first.grid_step_degrees;
  lease.scene_hash = first.scene_hash;
  lease.patch_count = first.patch_count;
  lease.lease_ms = first.lease_ms;
  for (const protocol::AssignedBatch& b : batches) {
    lease.batches.push_back(
        {b.lease.batch_id, b.lease.attempt_id, b.shooter, b.first_ray, b.ray_count});
  }
  return lease;
}

}  // namespace radfarm::agent::testing
