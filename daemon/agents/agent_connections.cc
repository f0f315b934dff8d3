#include "daemon/agents/agent_connections.h"

#include <algorithm>

#include "daemon/scheduler/result_intake.h"
#include "loop/frame_budget.h"
#include "loop/log.h"
#include "protocol/batch_convert.h"
#include "protocol/limits.h"
#include "protocol/scene_transfer.h"

namespace radfarm::daemon {
namespace {

// The compute seconds the agent reported for those of `results` that were accepted, for the job's
// timeline.
double AcceptedSeconds(const std::vector<const protocol::BatchOutcome*>& results,
                       std::vector<scheduler::BatchId> accepted) {
  // Sorted once: a frame may answer thousands of short batches.
  std::sort(accepted.begin(), accepted.end());
  double seconds = 0;
  for (const protocol::BatchOutcome* r : results) {
    if (std::binary_search(accepted.begin(), accepted.end(), r->lease.batch_id)) {
      seconds += r->compute_seconds;
    }
  }
  return seconds;
}

static_assert(kMinFrameBytesHeld >= protocol::kDefaultMaxFrameBytes,
              "--max-frame-bytes-held must hold one whole frame of the agents' limit");

using loop::LogLevel;
using loop::LogLine;

// Door log lines: enough to see who knocks, too few to flood the journal.
constexpr uint32_t kDoorLogLines = 20;
constexpr auto kDoorLogWindow = std::chrono::seconds(10);

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};

// Takes back the leases `agent` holds for jobs of lower priority than order[k] (a job with
// batches queued for it), into `refs` for one LeaseRevoke; returns how many. The agent runs its
// queue in order, so a higher-priority lease sent behind them would wait until they are done: with
// leases filling lease_seconds, the whole of every reduction of the higher job (CI: the low job of
// FarmTest.AHigherPriorityJobGetsTheAgentsFirst finished first on one agent).
uint32_t PreemptLowerPriority(const std::vector<RunningJob*>& order, size_t k, uint64_t agent,
                              std::vector<protocol::LeaseRef>& refs) {
  uint32_t taken = 0;
  auto take = [&](const RunningJob& job, scheduler::RoundScheduler& s) {
    for (const scheduler::Takeover& t : s.Preempt(agent)) {
      refs.push_back({static_cast<uint64_t>(job.id()), t.batch_id, t.attempt_id});
      ++taken;
    }
  };
  for (size_t j = k + 1; j < order.size(); ++j) {
    if (order[j]->priority() >= order[k]->priority()) continue;
    take(*order[j], order[j]->scheduler());
    // Once its round adopted it, a gather ahead's leases are that round's work (gather_ahead.h).
    GatherAhead* ahead = order[j]->gather_ahead();
    if (ahead != nullptr && ahead->adopted()) take(*order[j], ahead->scheduler());
  }
  // Until then, any job's gather ahead is below every round's work.
  for (RunningJob* job : order) {
    GatherAhead* ahead = job->gather_ahead();
    if (ahead != nullptr && !ahead->adopted()) take(*job, ahead->scheduler());
  }
  return taken;
}

}  // namespace

AgentConnections::AgentConnections(loop::EventLoop& loop, const Clock& clock,
                                   const MasterConfig& config, const protocol::FarmSecret& secret,
                                   const scheduler::SchedulerOptions& options, StoreThread& store,
                                   JobRounds& jobs,
                                   const std::vector<store::AgentCredential>& credentials)
    : loop_(loop),
      clock_(clock),
      config_(config),
      secret_(secret),
      options_(options),
      store_(store),
      jobs_(jobs),
      blocklist_(options.blocklist_duration),
      credentials_(secret, credentials, config.allow_shared_secret),
      doors_(config.max_unauthenticated),
      frame_budget_(std::make_shared<loop::FrameBudget>(config.max_frame_bytes_held,
                                                        "--max-frame-bytes-held")),
      door_log_(kDoorLogLines, kDoorLogWindow) {}

void AgentConnections::LogAtDoor(const std::string& line) {
  if (door_log_.Allow(clock_.Now())) LogLine(LogLevel::kWarning, "agents") << line;
}

void AgentConnections::OnConnection(std::unique_ptr<loop::FramedConnection> connection) {
  if (stopping_) return;  // dropped: closes silently
  const uint64_t id = next_agent_id_++;
  protocol::MasterConfig session;
  session.agent_id = id;
  session.heartbeat_interval_ms = config_.heartbeat_ms;
  session.key_for_agent = [this](const std::string& name) { return credentials_.KeyFor(name); };
  AgentLinkOptions options;
  options.handshake_timeout = std::chrono::milliseconds(config_.handshake_timeout_ms);
  options.idle_close_timeout = std::chrono::milliseconds(6 * uint64_t{config_.agent_timeout_ms});
  options.frame_budget = frame_budget_;
  AgentLink::Callbacks callbacks{
      [this](AgentLink& link) { OnAuthenticated(link); },
      [this](AgentLink& link, protocol::Message& m) { OnAgentMessage(link, m); },
      [this](AgentLink& link, const std::string& reason) { OnAgentClosed(link, reason); }};
  auto link = std::make_unique<AgentLink>(loop_, clock_, std::move(connection), secret_, session,
                                          options, std::move(callbacks));
  AgentLink& ref = *link;
  links_[id] = std::move(link);
  ref.Start();
  // Over the quota of strangers: the oldest goes (door_keeper.h says why not the newcomer).
  if (const std::optional<uint64_t> oldest = doors_.Admit(id)) {
    const auto it = links_.find(*oldest);
    if (it != links_.end()) {
      const std::string why = "over the quota of " + std::to_string(doors_.max_unauthenticated()) +
                              " unauthenticated connections (--max-unauthenticated); the oldest "
                              "goes";
      LogAtDoor(it->second->address() + ": closed before authentication: " + why);
      it->second->Drop(why);
    }
  }
}

protocol::FarmSecret AgentConnections::Enrolled(const store::AgentCredential& credential) {
  credentials_.Update(credential);
  LogLine(LogLevel::kInfo, "agents")
      << "agent " << credential.name << " enrolled (generation " << credential.generation << ")";
  return credentials_.KeyOf(credential);
}

size_t AgentConnections::Revoked(const store::AgentCredential& credential) {
  credentials_.Update(credential);
  const std::string why =
      "the credential of agent " + credential.name + " was revoked (`radfarm agents revoke`)";
  std::vector<AgentLink*> closing;
  // A link has a name once its Hello passed: authenticated, or awaiting a Proof made with the key
  // just revoked.
  for (auto& [id, link] : links_) {
    if (!link->closing() && link->name() == credential.name) closing.push_back(link.get());
  }
  LogLine(LogLevel::kWarning, "agents")
      << "agent " << credential.name << " revoked (generation " << credential.generation
      << "): closing " << closing.size() << " connections";
  for (AgentLink* link : closing) link->Close(protocol::CloseCode::kAuthFailed, why);
  return closing.size();
}

std::optional<std::string> AgentConnections::RefusalOf(const AgentLink& link) {
  size_t agents = 0, same_name = 0;
  for (const auto& [id, other] : links_) {
    if (other.get() == &link || !other->authenticated() || other->closing()) continue;
    ++agents;
    same_name += other->name() == link.name();
  }
  // The name first: one credential must not take every place, and its owner learns which limit.
  if (same_name >= config_.max_connections_per_agent) {
    doors_.RefusedPerAgent();
    return "agent " + link.name() + " already has " + std::to_string(same_name) +
           " connections (--max-connections-per-agent)";
  }
  if (agents >= config_.max_agents) {
    doors_.RefusedFull();
    return "the master has its " + std::to_string(config_.max_agents) + " agents (--max-agents)";
  }
  return std::nullopt;
}

void AgentConnections::OnAuthenticated(AgentLink& link) {
  doors_.Authenticated(link.id());
  if (const std::optional<std::string> refusal = RefusalOf(link)) {
    // Right after the Welcome: the agent backs off further at each refusal (agent/README.md).
    LogAtDoor(link.Describe() + ": refused: " + *refusal);
    link.Close(protocol::CloseCode::kShutdown, *refusal);
    return;
  }
  LogLine(LogLevel::kInfo, "agents")
      << link.Describe() << " connected (" << link.threads() << " threads)";
  const std::string name = link.name(), address = link.address();
  const uint32_t threads = link.threads();
  store_.Run([name, address,
              threads](store::JobStore& s) { return s.RecordAgentSeen(name, address, threads); },
             [](Status s) {
               if (!s) LogLine(LogLevel::kError, "store") << s.error();
             });
  for (auto& [job, runner] : jobs_.runners()) {
    runner->ForEachScheduler([&](scheduler::RoundScheduler& s) { s.AddAgent(link.id()); });
  }
  Dispatch(link);
}

void AgentConnections::OnAgentClosed(AgentLink& link, const std::string& reason) {
  const uint64_t id = link.id();
  if (link.was_authenticated()) {
    LogLine(LogLevel::kInfo, "agents") << link.Describe() << " disconnected: " << reason;
    for (auto& [job, runner] : jobs_.runners()) {
      runner->ForEachScheduler([&](scheduler::RoundScheduler& s) { s.OnAgentLost(id); });
    }
    jobs_.OnPointAgentLost(id);
  } else if (doors_.ClosedBeforeAuth(id)) {
    LogAtDoor(link.address() + ": closed before authentication: " + reason);
  }
  links_.erase(id);  // destroys the link; it is not used after this
  DispatchAll();
}

void AgentConnections::TakeLeasesAway(AgentLink& link, const char* why) {
  size_t held = 0;
  for (auto& [job, runner] : jobs_.runners()) {
    runner->ForEachScheduler([&](scheduler::RoundScheduler& s) {
      held += s.LeasesHeld(link.id());
      s.OnAgentLost(link.id());
    });
  }
  jobs_.OnPointAgentLost(link.id());
  LogLine(LogLevel::kWarning, "agents")
      << link.Describe() << " " << why << ": its " << held << " leases go back to the queue";
}

void AgentConnections::OnAgentMessage(AgentLink& link, protocol::Message& message) {
  if (link.Revive()) {
    // Heard from again after missing its heartbeats: back in the pool.
    LogLine(LogLevel::kInfo, "agents") << link.Describe() << " is back";
    for (auto& [job, runner] : jobs_.runners()) {
      runner->ForEachScheduler([&](scheduler::RoundScheduler& s) { s.AddAgent(link.id()); });
    }
  }
  std::visit(Overloaded{
                 [&](const protocol::HeartbeatMsg& h) { link.set_last_heartbeat(h); },
                 [&](const protocol::LeaseResultMsg& r) { OnLeaseResult(link, r); },
                 [&](const protocol::LeaseReturnMsg& r) { OnLeaseReturn(link, r); },
                 [&](const protocol::SceneRequestMsg& r) { OnSceneRequest(link, r); },
                 [&](const protocol::PointResultMsg& r) { OnPointResult(link, r); },
                 [&](const auto& other) {
                   // The session lets through only what an agent may send; anything else is a bug.
                   LogLine(LogLevel::kError, "agents")
                       << link.Describe() << ": unexpected " << protocol::MessageName(other);
                 },
             },
             message);
  if (!link.closing()) Dispatch(link);
}

void AgentConnections::OnLeaseResult(AgentLink& link, const protocol::LeaseResultMsg& message) {
  // One frame may answer leases of several jobs: each job's results go to its scheduler together.
  std::map<uint64_t, std::vector<const protocol::BatchOutcome*>> by_job;
  for (const protocol::BatchOutcome& r : message.results) by_job[r.lease.job_id].push_back(&r);
  for (auto& [job_id, results] : by_job) {
    RunningJob* runner = jobs_.FindRunner(job_id);
    if (runner != nullptr && runner->gather_ahead() != nullptr) {
      // The gather's batches leased ahead of its round, in any phase of the job.
      std::vector<const protocol::BatchOutcome*> ahead;
      std::erase_if(results, [&](const protocol::BatchOutcome* r) {
        if (!GatherAhead::Names(r->lease.batch_id)) return false;
        ahead.push_back(r);
        return true;
      });
      if (!ahead.empty() && !OnGatherAheadResults(link, *runner, ahead)) return;
      if (results.empty()) continue;
    }
    if (runner == nullptr || runner->phase() != RunningJob::Phase::kRound) {
      LogLine(LogLevel::kDebug, "agents")
          << link.Describe() << ": " << results.size() << " results for job " << job_id
          << " dropped (job not in a round)";
      continue;
    }
    const scheduler::LeaseIntake intake =
        scheduler::SubmitLeaseResults(runner->scheduler(), link.id(), results, runner->sampler(),
                                      runner->patch_count(), clock_.Now());
    link.CountAccepted(intake.accepted_batches.size());
    runner->AddAgentSeconds(runner->running_gather(),
                            AcceptedSeconds(results, intake.accepted_batches));
    const scheduler::ResultVerdict& v = intake.last.verdict;
    if (v.reason == scheduler::DropReason::kInvalid) {
      for (scheduler::BatchId batch : intake.accepted_batches) {
        jobs_.OnResultAccepted(runner->id(), batch, link.name());
      }
      OnInvalidResult(link, *runner, intake.last.detail);
      if (link.closing()) return;
      continue;
    }
    for (scheduler::BatchId batch : intake.accepted_batches) {
      jobs_.OnResultAccepted(runner->id(), batch, link.name());
    }
    if (intake.dropped > 0 || intake.rejected > 0) {
      LogLine(intake.rejected > 0 ? LogLevel::kWarning : LogLevel::kDebug, "agents")
          << "job " << job_id << " from " << link.Describe() << ": "
          << intake.accepted_batches.size() << " results accepted, " << intake.dropped
          << " dropped (late, duplicate or old), " << intake.rejected
          << " rejected (not its lease)";
    }
    // A verification may have failed meanwhile: the job was rewound, its runner dropped.
    if (v.round_complete && jobs_.FindRunner(job_id) == runner) jobs_.OnRoundComplete(runner->id());
    if (link.closing()) return;
  }
}

bool AgentConnections::OnGatherAheadResults(
    AgentLink& link, RunningJob& runner,
    const std::vector<const protocol::BatchOutcome*>& results) {
  GatherAhead& ahead = *runner.gather_ahead();
  const scheduler::LeaseIntake intake = scheduler::SubmitLeaseResults(
      ahead.scheduler(), link.id(), results, runner.sampler(), runner.patch_count(), clock_.Now());
  link.CountAccepted(intake.accepted_batches.size());
  runner.AddAgentSeconds(true, AcceptedSeconds(results, intake.accepted_batches));
  bool round_complete = false;
  for (scheduler::BatchId batch : intake.accepted_batches) {
    if (!ahead.adopted()) {
      ahead.NoteAccepted(batch, link.name());
      continue;
    }
    // A lease still out when the gather round started: its result is the round's now.
    std::optional<BatchResult> result = ahead.scheduler().TakeResult(batch);
    if (!result || runner.phase() != RunningJob::Phase::kRound) continue;
    const uint32_t index = scheduler::BatchIndex(batch);
    const scheduler::ResultVerdict v =
        runner.scheduler().OnComputedResult(index, std::move(*result));
    if (v.disposition != scheduler::Disposition::kAccepted) continue;
    jobs_.OnResultAccepted(runner.id(), scheduler::MakeBatchId(runner.running_round(), index),
                           link.name());
    round_complete = runner.scheduler().RoundComplete();
  }
  if (intake.last.verdict.reason == scheduler::DropReason::kInvalid) {
    OnInvalidResult(link, runner, intake.last.detail);
  }
  // A verification may have failed meanwhile: the job was rewound, its runner dropped.
  if (round_complete && jobs_.FindRunner(runner.id()) == &runner)
    jobs_.OnRoundComplete(runner.id());
  return !link.closing();
}

void AgentConnections::OnInvalidResult(AgentLink& link, RunningJob& runner,
                                       const std::string& why) {
  // The frame authenticated, so the agent computed (or made up) this result itself: its fault.
  const auto now = clock_.Now();
  const std::optional<scheduler::TimePoint> until =
      blocklist_.Strike(runner.id(), link.name(), now);
  const uint32_t strikes =
      until ? JobBlocklist::kStrikes : blocklist_.Strikes(runner.id(), link.name(), now);
  LogLine(LogLevel::kWarning, "agents")
      << "job " << runner.id() << " from " << link.Describe() << ": result rejected (invalid, "
      << strikes << " of " << JobBlocklist::kStrikes << "): " << why;
  if (!until) return;  // its leases of this job were revoked and requeued by the scheduler
  const auto seconds = std::chrono::duration_cast<std::chrono::seconds>(*until - now).count();
  const std::string reason = "job " + std::to_string(runner.id()) + ": " +
                             std::to_string(JobBlocklist::kStrikes) +
                             " results failed validation (last: " + why +
                             "); no work of this job for " + std::to_string(seconds) + " s";
  LogLine(LogLevel::kWarning, "agents")
      << "agent " << link.name() << " blocklisted for job " << runner.id() << " for " << seconds
      << " s after " << JobBlocklist::kStrikes << " invalid results";
  store_.LogEvent(runner.id(), store::EventLevel::kWarning,
                  "agent " + link.name() + " is blocklisted for this job for " +
                      std::to_string(seconds) + " s: " + std::to_string(JobBlocklist::kStrikes) +
                      " of its results failed validation (last: " + why + ")");
  for (auto& [id, other] : links_) {
    if (other->was_authenticated() && other->name() == link.name()) {
      runner.ForEachScheduler([&](scheduler::RoundScheduler& s) { s.Blocklist(id, *until); });
    }
  }
  link.Close(protocol::CloseCode::kBlocklisted, reason);
}

void AgentConnections::Convict(store::JobId job, const std::string& name, const std::string& why) {
  const auto now = clock_.Now();
  const scheduler::TimePoint until = blocklist_.Block(job, name, now);
  const auto seconds = std::chrono::duration_cast<std::chrono::seconds>(until - now).count();
  LogLine(LogLevel::kWarning, "agents")
      << "agent " << name << " blocklisted for job " << job << " for " << seconds
      << " s: a result failed verification: " << why;
  store_.LogEvent(job, store::EventLevel::kWarning,
                  "agent " + name + " is blocklisted for this job for " + std::to_string(seconds) +
                      " s: a result failed verification (" + why + ")");
  const std::string reason = "job " + std::to_string(job) +
                             ": a result failed verification against the master's (" + why +
                             "); no work of this job for " + std::to_string(seconds) + " s";
  RunningJob* runner = jobs_.FindRunner(job);
  for (auto& [id, link] : links_) {
    if (!link->was_authenticated() || link->name() != name) continue;
    if (runner != nullptr) {
      runner->ForEachScheduler([&](scheduler::RoundScheduler& s) { s.Blocklist(id, until); });
    }
    if (!link->closing()) link->Close(protocol::CloseCode::kBlocklisted, reason);
  }
}

bool AgentConnections::Blocklisted(AgentLink& link, RunningJob& runner, scheduler::TimePoint now) {
  const std::optional<scheduler::TimePoint> until =
      blocklist_.BlockedUntil(runner.id(), link.name(), now);
  if (until) {
    runner.ForEachScheduler([&](scheduler::RoundScheduler& s) { s.Blocklist(link.id(), *until); });
  }
  return until.has_value();
}

void AgentConnections::OnLeaseReturn(AgentLink& link, const protocol::LeaseReturnMsg& message) {
  std::map<uint64_t, std::vector<scheduler::BatchId>> by_job;
  for (const protocol::LeaseRef& lease : message.leases)
    by_job[lease.job_id].push_back(lease.batch_id);
  size_t returned = 0;
  for (const protocol::LeaseRef& lease : message.leases) {
    returned += jobs_.ReturnPointPieces(link.id(), lease);
  }
  for (auto& [job, batches] : by_job) {
    if (RunningJob* runner = jobs_.FindRunner(job)) {
      // Each scheduler takes back the batches of its own round.
      runner->ForEachScheduler(
          [&](scheduler::RoundScheduler& s) { returned += s.ReturnLeases(link.id(), batches); });
    }
  }
  const char* why = message.reason == protocol::LeaseReturnReason::kDraining     ? "draining"
                    : message.reason == protocol::LeaseReturnReason::kOverloaded ? "overloaded"
                    : message.reason == protocol::LeaseReturnReason::kSceneUnavailable
                        ? "scene unavailable"
                        : "failed";
  // A stopping or busy agent must not get the batches straight back.
  if (message.reason == protocol::LeaseReturnReason::kDraining ||
      message.reason == protocol::LeaseReturnReason::kOverloaded) {
    link.Decline();
  }
  LogLine(LogLevel::kInfo, "agents") << link.Describe() << " returned " << returned << " of "
                                     << message.leases.size() << " leases (" << why << ")";
  if (returned > 0) DispatchAll();
}

void AgentConnections::OnSceneRequest(AgentLink& link, const protocol::SceneRequestMsg& request) {
  for (auto& [job, runner] : jobs_.runners()) {
    if (runner->wire_info().scene_hash != request.scene_hash) continue;
    Result<protocol::SceneChunkMsg> chunk =
        protocol::MakeSceneChunk(*runner->packed_scene(), request);
    if (!chunk) {
      LogLine(LogLevel::kWarning, "agents")
          << link.Describe() << ": bad scene request: " << chunk.error() << "; closing";
      link.Close(protocol::CloseCode::kProtocolError, chunk.error());
      return;
    }
    if (request.offset == 0) {
      LogLine(LogLevel::kInfo, "agents")
          << link.Describe() << " fetches the scene of job " << job << " ("
          << runner->packed_scene()->compressed.size() << " bytes compressed)";
    }
    (void)link.Send(std::move(*chunk));
    return;
  }
  if (const auto context = jobs_.PointContextOf(request.scene_hash)) {
    Result<protocol::SceneChunkMsg> chunk = protocol::MakeSceneChunk(*context, request);
    if (!chunk) {
      LogLine(LogLevel::kWarning, "agents")
          << link.Describe() << ": bad point context request: " << chunk.error() << "; closing";
      link.Close(protocol::CloseCode::kProtocolError, chunk.error());
      return;
    }
    (void)link.Send(std::move(*chunk));
    return;
  }
  (void)link.Send(protocol::SceneUnavailableMsg{request.scene_hash});
}

void AgentConnections::OnPointResult(AgentLink& link, const protocol::PointResultMsg& result) {
  const Result<bool> accepted = jobs_.OnPointResult(link.id(), result);
  if (!accepted) {
    // The frame authenticated, so the agent computed (or made up) these values itself.
    Convict(static_cast<store::JobId>(result.lease.job_id), link.name(), accepted.error());
    return;
  }
  if (*accepted) link.CountAccepted(1);
}

size_t AgentConnections::PointAgents(uint16_t version) const {
  size_t agents = 0;
  for (const auto& [id, link] : links_) {
    agents += link->authenticated() && !link->stale() && link->version() >= version;
  }
  return agents;
}

void AgentConnections::Dispatch(AgentLink& link) {
  if (!link.TakesWork() || stopping_) return;
  // Don't queue work behind a slow socket.
  if (link.queued_bytes() > (4u << 20)) return;
  const auto now = clock_.Now();
  const std::vector<RunningJob*> order = jobs_.RunnersByPriority();
  uint32_t held = 0, capacity = 0;
  for (RunningJob* runner : order) {
    // Until a job has measured the agent, its own last reported speed sizes its leases there.
    runner->ForEachScheduler([&](scheduler::RoundScheduler& s) {
      s.ReportSpeed(link.id(), link.last_heartbeat().rays_per_second);
      held += s.LeasesHeld(link.id());
    });
    // The rounds' own measurements size the agent. The gather ahead's, from the agent's reported
    // speed until it has measured it, let agents hold more round work than their measured speed
    // allows, and the rounds' ends waited on them.
    capacity = std::max(capacity, runner->scheduler().LeaseCapacityOf(link.id()));
  }
  // The highest-priority job with work fills the agent first; a lower one gets what is left of
  // its capacity (the tail of a round, a job between rounds), and the jobs' gathers ahead what is
  // left after every round (gather_ahead.h). Each scheduler's new leases go out as
  // LeaseAssignment frames of at most LeaseSizeOf() batches; leases taken over from another agent
  // are revoked there in one LeaseRevoke per agent. A job with batches queued takes the agent's
  // leases of lower-priority jobs and of the gathers ahead back first.
  // Point work first: a running job's start (its job waits for the last piece) and a finished
  // job's display (its steps are the end of a job, and each waits for its last piece). An agent
  // holds a piece per thread and one more, so it has the next when one ends.
  if (link.version() >= protocol::kPointLeaseVersion) {
    const auto refused = [&](store::JobId job) {
      return blocklist_.BlockedUntil(job, link.name(), now).has_value();
    };
    bool sending = true;
    for (protocol::PointLeaseMsg& lease :
         jobs_.PointLeasesFor(link.id(), link.version(), link.threads() + 1, refused)) {
      const protocol::LeaseRef ref = lease.lease;
      if (sending) {
        const Status st = link.Send(std::move(lease));
        if (st) continue;
        LogLine(LogLevel::kWarning, "agents") << link.Describe() << ": " << st.error();
        sending = false;
      }
      // Not sent: back to the queue rather than wait for its deadline.
      jobs_.ReturnPointPieces(link.id(), ref);
    }
  }
  std::map<uint64_t, std::vector<protocol::LeaseRef>> revoked;
  auto lease_from = [&](RunningJob& runner, scheduler::RoundScheduler& s) {
    bool more = true;
    while (more) {
      const uint32_t size = std::min<uint32_t>(s.LeaseSizeOf(link.id()),
                                               static_cast<uint32_t>(protocol::kMaxLeaseBatches));
      std::vector<protocol::LeasedBatch> lease;
      scheduler::TimePoint deadline = now;
      while (lease.size() < size) {
        const uint32_t here = s.LeasesHeld(link.id());
        auto a = s.NextAssignment(link.id(), now, held - here, capacity);
        if (!a) {
          more = false;
          break;
        }
        ++held;
        deadline = std::max(deadline, a->deadline);
        lease.push_back({a->batch_id, a->attempt_id, a->batch});
        if (a->taken_from) {
          revoked[a->taken_from->agent].push_back({static_cast<uint64_t>(runner.id()),
                                                   a->taken_from->batch_id,
                                                   a->taken_from->attempt_id});
        }
      }
      if (lease.empty()) break;
      const auto lease_ms = std::max<int64_t>(
          1, std::chrono::duration_cast<std::chrono::milliseconds>(deadline - now).count());
      if (Status st = link.Send(protocol::MakeLeaseAssignment(runner.wire_info(), lease,
                                                              static_cast<uint32_t>(lease_ms)));
          !st) {
        LogLine(LogLevel::kWarning, "agents") << link.Describe() << ": " << st.error();
        more = false;
      }
    }
  };
  for (size_t k = 0; k < order.size(); ++k) {
    RunningJob* runner = order[k];
    scheduler::RoundScheduler& s = runner->scheduler();
    runner->LeaseReturnedAheadFirst();
    if (Blocklisted(link, *runner, now)) continue;
    if (s.WantsAgent(link.id(), now)) {
      std::vector<protocol::LeaseRef> preempted;
      held -= PreemptLowerPriority(order, k, link.id(), preempted);
      // Before the new leases, so that the agent drops the old ones first.
      for (size_t i = 0; i < preempted.size(); i += protocol::kMaxLeaseBatches) {
        const auto end =
            preempted.begin() + std::min(preempted.size(), i + protocol::kMaxLeaseBatches);
        (void)link.Send(protocol::LeaseRevokeMsg{{preempted.begin() + i, end}});
      }
    }
    lease_from(*runner, s);
  }
  // What the rounds leave: queued behind an agent's last round leases, it has the next batch
  // there when they end (no round trip), and between rounds it works while the master reduces.
  for (RunningJob* runner : order) {
    GatherAhead* ahead = runner->gather_ahead();
    if (ahead != nullptr && !ahead->adopted() && !Blocklisted(link, *runner, now)) {
      lease_from(*runner, ahead->scheduler());
    }
  }
  for (auto& [agent_id, leases] : revoked) {
    const auto it = links_.find(agent_id);
    if (it == links_.end() || !it->second->authenticated() || it->second->closing()) continue;
    (void)it->second->Send(protocol::LeaseRevokeMsg{std::move(leases)});
  }
}

void AgentConnections::DispatchAll() {
  for (auto& [id, link] : links_) Dispatch(*link);
}

void AgentConnections::CancelJob(store::JobId id) {
  for (auto& [agent_id, link] : links_) {
    if (link->authenticated() && !link->closing()) {
      (void)link->Send(protocol::CancelMsg{static_cast<uint64_t>(id)});
    }
  }
}

std::vector<uint64_t> AgentConnections::Available() const {
  std::vector<uint64_t> ids;
  for (const auto& [id, link] : links_) {
    if (link->authenticated() && !link->stale()) ids.push_back(id);
  }
  return ids;
}

double AgentConnections::ReportedRaysPerSecond() const {
  double sum = 0;
  for (const auto& [id, link] : links_) {
    if (link->authenticated() && !link->stale()) sum += link->last_heartbeat().rays_per_second;
  }
  return sum;
}

std::vector<const AgentLink*> AgentConnections::Authenticated() const {
  std::vector<const AgentLink*> links;
  for (const auto& [id, link] : links_) {
    if (link->authenticated()) links.push_back(link.get());
  }
  return links;
}

size_t AgentConnections::active() const {
  size_t agents = 0;
  for (const auto& [id, link] : links_) agents += link->authenticated() && !link->stale();
  return agents;
}

void AgentConnections::Heartbeat() {
  if (const std::optional<uint64_t> held_back = door_log_.TakeSuppressed(clock_.Now())) {
    LogLine(LogLevel::kWarning, "agents")
        << *held_back << " more connections refused or closed before authentication were not "
        << "logged (at most " << kDoorLogLines << " lines per "
        << std::chrono::seconds(kDoorLogWindow).count() << " s)";
  }
  const uint64_t now_ms = clock_.NowMs();
  protocol::HeartbeatMsg beat;
  for (auto& [job, runner] : jobs_.runners()) beat.rays_per_second += runner->RaysPerSecond();
  for (auto& [id, link] : links_) {
    if (!link->authenticated() || link->closing()) continue;
    if (!link->stale() && now_ms - link->last_heard_ms() > config_.agent_timeout_ms) {
      link->MarkStale();
      TakeLeasesAway(*link, "missed its heartbeats");
      continue;
    }
    // One lookup per agent and job: counters() costs O(agents) (it was O(batches + agents)) and,
    // called per agent, took most of the loop thread's time with 1000 agents (farm_bench,
    // docs/BENCHMARKS-farm.md).
    uint32_t leases = 0;
    for (auto& [job, runner] : jobs_.runners()) {
      runner->ForEachScheduler([&](scheduler::RoundScheduler& s) { leases += s.LeasesHeld(id); });
    }
    beat.leases_held = leases;
    (void)link->Send(beat);
  }
  DispatchAll();
}

void AgentConnections::Stop() {
  stopping_ = true;
  // Agents keep their state; they reconnect to the next master by themselves.
  for (auto& [id, link] : links_) {
    if (link->authenticated()) link->Close(protocol::CloseCode::kShutdown, "master shutting down");
  }
}

}  // namespace radfarm::daemon
