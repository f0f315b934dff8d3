#include "tests/daemon/master_parts.h"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <utility>

#include "codec/job_bundle.h"
#include "input/input_scene.h"
#include "job/job.h"
#include "loop/host_port.h"
#include "store/job_store.h"
#include "tests/loop/loop_test_util.h"

namespace radfarm::daemon::fakes {
namespace {

template <typename T>
T Must(Result<T> result, const char* what) {
  if (!result) throw std::runtime_error(std::string(what) + ": " + result.error());
  return std::move(result).value();
}

}  // namespace

MasterConfig TestMasterConfig() {
  MasterConfig config;
  config.local_round_rays = 0;
  config.gather_ahead_rays = 0;
  config.verify_fraction = 0;
  config.keep_round_results = false;
  return config;
}

std::vector<uint8_t> CornellBundle(uint64_t max_rays, uint32_t gather_rays) {
  Job job = Must(LoadJob(RADFARM_SOURCE_DIR "/scenes/cornell-box.toml"), "job file");
  InputScene scene = Must(LoadObjScene(job.scene_path), "scene");
  job.mesh.patch_size = 150;  // a few hundred patches: rounds of a few leases
  job.solver.max_rays = max_rays;
  job.solver.gather_rays = gather_rays;
  return codec::EncodeJobBundle({job, scene});
}

MasterParts::MasterParts(const MasterConfig& config)
    : state_("radfarm-master-parts"),
      config_(config),
      secret_(Must(protocol::FarmSecret::Generate(), "farm secret")) {
  config_.state_dir = state_.path();
  options_.target_lease_seconds = config_.lease_seconds;
  options_.deadline_floor = std::chrono::milliseconds(config_.agent_timeout_ms);
  options_.blocklist_duration = std::chrono::seconds(config_.blocklist_seconds);
  options_.gather_ahead_rays = config_.gather_ahead_rays;

  store_ = Must(
      StoreThread::Start(loop_, Must(store::JobStore::Open(config_.DatabasePath()), "job store")),
      "store thread");
  compute_ = Must(loop::WorkQueue::Create(loop_, 1, "compute"), "compute thread");
  AgentHooks hooks{[this] { agents_->DispatchAll(); },
                   [this](store::JobId id) { agents_->CancelJob(id); },
                   [this] { return agents_->Available(); },
                   [this] { return agents_->ReportedRaysPerSecond(); },
                   [this](store::JobId id, const std::string& agent, const std::string& why) {
                     agents_->Convict(id, agent, why);
                   },
                   [this] { return agents_->PointAgents(protocol::kPointLeaseVersion); },
                   [this] { return agents_->PointAgents(protocol::kStartLeaseVersion); },
                   [this] { return agents_->PointAgents(protocol::kSkyVersion); }};
  jobs_ = std::make_unique<JobRounds>(loop_, clock_, config_, options_, *store_, *compute_,
                                      std::move(hooks));
  agents_ = std::make_unique<AgentConnections>(loop_, clock_, config_, secret_, options_, *store_,
                                               *jobs_, std::vector<store::AgentCredential>{});
  control_ = std::make_unique<ControlRequests>(clock_, *store_, *compute_, *jobs_, *agents_);
  AgentConnections* agents = agents_.get();
  listener_ = Must(loop::TcpListener::Listen(
                       loop_, Must(loop::ParseHostPort("127.0.0.1:0", "listen"), "address"),
                       [agents](std::unique_ptr<loop::FramedConnection> c) {
                         agents->OnConnection(std::move(c));
                       }),
                   "listener");
  agent_address_ = Must(loop::SocketAddress::FromIpLiteral(
                            Must(loop::ParseHostPort(listener_->address(), "bound"), "bound")),
                        "bound address");
}

MasterParts::~MasterParts() {
  // Master::Shutdown's order: the parts stop, the compute thread is cancelled, the store thread
  // drains, then the parts let go of their links and runners.
  agents_->Stop();
  jobs_->Stop();
  control_->Stop();
  listener_->Close();
  compute_->Shutdown(loop::WorkQueue::ShutdownMode::kCancel, [] {});
  bool drained = false;
  store_->Drain([this, &drained] {
    agents_->Clear();
    jobs_->Clear();
    drained = true;
  });
  EXPECT_TRUE(RunUntil([&] { return drained; }));
  control_.reset();
  agents_.reset();
  jobs_.reset();
  listener_.reset();
  compute_.reset();
  store_.reset();
  loop::testing::ExpectClosesClean(loop_);
}

bool MasterParts::RunUntil(const std::function<bool()>& done) {
  return loop::testing::RunUntil(loop_, done);
}

ControlResponse MasterParts::Request(ControlRequest request) {
  std::optional<ControlResponse> answer;
  control_->Handle(std::move(request), [&answer](ControlResponse r) { answer = std::move(r); });
  EXPECT_TRUE(RunUntil([&] { return answer.has_value(); })) << "no answer";
  return answer ? std::move(*answer) : ControlError("internal", "no answer");
}

ControlResponse MasterParts::Request(ControlCommand command, uint64_t id) {
  ControlRequest request;
  request.command = command;
  request.id = id;
  return Request(std::move(request));
}

uint64_t MasterParts::Submit(uint64_t max_rays, int64_t priority, uint32_t gather_rays) {
  ControlRequest request;
  request.command = ControlCommand::kSubmit;
  request.name = "cornell";
  request.priority = priority;
  request.attachment = CornellBundle(max_rays, gather_rays);
  const ControlResponse answer = Request(std::move(request));
  EXPECT_TRUE(answer.body.value("ok", false)) << answer.body.dump();
  return answer.body.value("ok", false) ? answer.body["job"]["id"].get<uint64_t>() : 0;
}

std::string MasterParts::StateOf(uint64_t id) {
  const ControlResponse answer = Request(ControlCommand::kStatus, id);
  return answer.body.value("ok", false) ? answer.body["job"]["state"].get<std::string>()
                                        : "error: " + answer.body.dump();
}

}  // namespace radfarm::daemon::fakes
