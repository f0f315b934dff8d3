#include "daemon/control/control_requests.h"

#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <map>
#include <set>

#include "base/cpu_clock.h"
#include "base/result.h"
#include "codec/job_bundle.h"
#include "codec/job_solution.h"
#include "core/solve_control.h"
#include "loop/log.h"
#include "mesh/back_face_warnings.h"
#include "mesh/near_emitter_warnings.h"
#include "mesh/patch_mesh.h"
#include "mesh/refine.h"
#include "protocol/message_checks.h"
#include "protocol/scene_transfer.h"
#include "store/job_transactions.h"

namespace radfarm::daemon {
namespace {

using loop::LogLevel;
using loop::LogLine;
using nlohmann::json;

json Nullable(const std::optional<int64_t>& v) { return v ? json(*v) : json(nullptr); }

// A store result that may be "no such job".
struct Lookup {
  std::optional<JobSummary> summary;
  std::string invalid;  // set: the request is not allowed in the job's state
};

ControlResponse NotFound(uint64_t id) {
  return ControlError("not_found", "no job " + std::to_string(id));
}

// The solution `fetch` sends: the checkpoint's values and the job's statistics up to it.
codec::JobSolution SolutionOf(store::StoredSolution stored, const JobSummary& summary) {
  const store::Checkpoint& c = stored.checkpoint;
  codec::JobSolution solution;
  solution.bundle = std::move(stored.bundle);
  if (stored.refined_scene) solution.scene = std::move(*stored.refined_scene);
  solution.display = std::move(stored.display);
  solution.radiosity = c.radiosity;
  solution.unshot = c.unshot;
  SolveStats& st = solution.stats;
  st = StatsOf(stored.totals.solve_totals(), c.energy);
  if (stored.totals.unshot_fraction) st.unshot_fraction = *stored.totals.unshot_fraction;
  st.rounds = c.rounds_done;
  st.patches = c.radiosity.size();
  st.seed = stored.job.spec.seed;
  st.sampler = summary.settings.sampler;
  JobSummary at_checkpoint = summary;
  at_checkpoint.rays = st.rays;
  at_checkpoint.unshot_fraction = st.unshot_fraction;
  st.stop_reason = c.stop_reason                                ? *c.stop_reason
                   : stored.job.state == store::JobState::kDone ? StopReasonOf(at_checkpoint)
                                                                : "checkpoint";
  return solution;
}

// What the compute thread found in a submitted bundle: the job's settings as listed, its seed,
// and its scene meshed.
struct CheckedSubmission {
  SubmittedSettings settings;
  uint64_t seed = 0;
  std::string bundle_hash;  // hashed here, off the loop thread: half a second for 100 MB
  SubmittedMesh meshed;
  std::vector<std::string> warnings;  // about the patches: `radfarm submit` prints them
};

}  // namespace

ControlRequests::ControlRequests(const Clock& clock, StoreThread& store, loop::WorkQueue& compute,
                                 JobRounds& jobs, AgentConnections& agents)
    : clock_(clock), store_(store), compute_(compute), jobs_(jobs), agents_(agents) {}

void ControlRequests::Handle(ControlRequest request, ControlRespond respond) {
  if (stopping_) {
    respond(ControlError("internal", "the master is shutting down"));
    return;
  }
  // Ids are positive int64 in the store; a larger one names no job (and is said as given).
  if (request.id && *request.id > uint64_t(std::numeric_limits<store::JobId>::max())) {
    respond(NotFound(*request.id));
    return;
  }
  switch (request.command) {
    case ControlCommand::kSubmit:
      return Submit(std::move(request), std::move(respond));
    case ControlCommand::kList:
      return RespondWithJobs(std::nullopt, std::move(respond));
    case ControlCommand::kStatus:
      return RespondWithJobs(store::JobId(*request.id), std::move(respond));
    case ControlCommand::kCancel:
    case ControlCommand::kPause:
    case ControlCommand::kResume:
      return ChangeState(std::move(request), std::move(respond));
    case ControlCommand::kFetch:
      return Fetch(std::move(request), std::move(respond));
    case ControlCommand::kLog:
      return Log(std::move(request), std::move(respond));
    case ControlCommand::kAgents: {
      json list = json::array();
      for (const AgentLink* link : agents_.Authenticated()) list.push_back(AgentJson(*link));
      respond({json{{"ok", true}, {"agents", list}, {"connections", DoorsJson()}}, {}});
      return;
    }
    case ControlCommand::kEnrolledAgents:
      respond({json{{"ok", true}, {"enrolled", EnrolledJson()}}, {}});
      return;
    case ControlCommand::kEnrollAgent:
    case ControlCommand::kRevokeAgent:
      if (!protocol::IsValidAgentName(request.name)) {
        respond(ControlError("bad_request",
                             "'name' must be an agent name: 1 to 64 of A-Z a-z 0-9 . _ : @ -"));
        return;
      }
      if (request.command == ControlCommand::kRevokeAgent) {
        return RevokeAgent(request.name, std::move(respond));
      }
      return EnrollAgent(request.name, std::move(respond));
  }
}

void ControlRequests::EnrollAgent(const std::string& name, ControlRespond respond) {
  store_.Run(
      [name](store::JobStore& s) -> Result<store::AgentCredential> {
        Result<store::AgentCredential> enrolled = s.EnrollAgent(name);
        RADFARM_RETURN_IF_ERROR(enrolled);
        (void)s.AppendEvent(std::nullopt, store::EventLevel::kInfo,
                            "agent " + name + " enrolled (generation " +
                                std::to_string(enrolled->generation) + ")");
        return enrolled;
      },
      [this, respond](Result<store::AgentCredential> enrolled) {
        if (!enrolled) return respond(ControlError("internal", enrolled.error()));
        const protocol::FarmSecret key = agents_.Enrolled(*enrolled);
        respond({json{{"ok", true},
                      {"name", enrolled->name},
                      {"generation", enrolled->generation},
                      {"key", key.ToHex()}},
                 {}});
      });
}

void ControlRequests::RevokeAgent(const std::string& name, ControlRespond respond) {
  store_.Run(
      [name](store::JobStore& s) -> Result<std::optional<store::AgentCredential>> {
        Result<std::optional<store::AgentCredential>> revoked = s.RevokeAgent(name);
        RADFARM_RETURN_IF_ERROR(revoked);
        if (*revoked) {
          (void)s.AppendEvent(std::nullopt, store::EventLevel::kWarning,
                              "agent " + name + " revoked (generation " +
                                  std::to_string((*revoked)->generation) + ")");
        }
        return revoked;
      },
      [this, name, respond](Result<std::optional<store::AgentCredential>> revoked) {
        if (!revoked) return respond(ControlError("internal", revoked.error()));
        if (!*revoked) {
          return respond(ControlError("not_found", "agent " + name +
                                                       " is not enrolled (an agent using the "
                                                       "farm secret is cut off by changing it)"));
        }
        const size_t closed = agents_.Revoked(**revoked);
        respond({json{{"ok", true},
                      {"name", name},
                      {"generation", (*revoked)->generation},
                      {"closed", closed}},
                 {}});
      });
}

void ControlRequests::Log(ControlRequest request, ControlRespond respond) {
  const std::optional<store::JobId> id =
      request.id ? std::optional<store::JobId>(store::JobId(*request.id)) : std::nullopt;
  const int limit = static_cast<int>(request.limit);
  store_.Run(
      [id, limit](store::JobStore& s) -> Result<std::optional<std::vector<store::Event>>> {
        if (id) {
          Result<std::optional<store::JobRecord>> job = s.GetJob(*id);
          RADFARM_RETURN_IF_ERROR(job);
          if (!*job) return std::optional<std::vector<store::Event>>();
        }
        // Without an id: the whole farm's, every job's events with its own (a farm-wide log of
        // only the events tied to no job printed nothing after jobs had run).
        Result<std::vector<store::Event>> events =
            id ? s.ListEvents(id, limit) : s.ListRecentEvents(limit);
        RADFARM_RETURN_IF_ERROR(events);
        return std::optional(std::move(*events));
      },
      [id, respond](Result<std::optional<std::vector<store::Event>>> events) {
        if (!events) return respond(ControlError("internal", events.error()));
        if (!*events) return respond(NotFound(*id));
        json list = json::array();
        for (const store::Event& e : **events) {
          list.push_back({{"time_ms", e.time_ms},
                          {"level", std::string(store::EventLevelName(e.level))},
                          {"job", e.job ? json(*e.job) : json(nullptr)},
                          {"text", e.text}});
        }
        respond({json{{"ok", true}, {"events", list}}, {}});
      });
}

json ControlRequests::JobJson(const JobSummary& s) {
  const store::JobRecord& r = s.record;
  json job{{"id", r.id},
           {"name", r.spec.name},
           {"state", std::string(store::JobStateName(r.state))},
           {"priority", r.spec.priority},
           {"seed", r.spec.seed},
           {"scene_hash", r.spec.scene_hash},
           {"patches", s.settings.patches},
           {"submitted_at_ms", r.submitted_at_ms},
           {"started_at_ms", Nullable(r.started_at_ms)},
           {"finished_at_ms", Nullable(r.finished_at_ms)},
           {"error", r.error ? json(*r.error) : json(nullptr)},
           {"round", s.rounds},
           {"rays", s.rays},
           {"unshot_fraction", s.unshot_fraction},
           {"tolerance", s.settings.tolerance},
           {"rays_per_second", 0.0},
           {"agents", 0},
           {"eta_seconds", nullptr},
           {"stop_reason", nullptr},
           {"waiting_for_agents", false},
           {"phase", nullptr},
           {"last_checkpoint", nullptr},
           {"direct_start", nullptr},
           {"display", nullptr}};
  if (const JobRules* rules = jobs_.RulesOf(r.id)) {
    job["direct_start"] = rules->direct_start;
    job["display"] = rules->display;
  }
  const std::string_view phase = jobs_.PhaseOf(r.id);
  if (!phase.empty()) job["phase"] = std::string(phase);
  if (const JobTimeline* timeline = jobs_.TimelineOf(r.id); timeline && !timeline->empty()) {
    json entries = json::array();
    for (const TimelineEntry& e : *timeline) {
      entries.push_back({{"phase", std::string(JobPhaseName(e.phase))},
                         {"where", e.where},
                         {"wall_seconds", e.wall_seconds},
                         {"cpu_seconds", e.cpu_seconds}});
    }
    job["timeline"] = std::move(entries);
  }
  if (const CheckpointReport* c = jobs_.LastCheckpoint(r.id)) {
    job["last_checkpoint"] =
        json{{"round", c->round},         {"bytes", c->bytes},         {"copy_ms", c->copy_ms},
             {"encode_ms", c->encode_ms}, {"commit_ms", c->commit_ms}, {"queued_ms", c->queued_ms},
             {"committed", c->committed}};
  }
  // A job not running: how far its convergence came, in log space (no rays to count it by).
  double progress = ConvergenceFraction(s.unshot_fraction, s.settings.tolerance);
  if (RunningJob* runner = jobs_.FindRunner(static_cast<uint64_t>(r.id))) {
    // The live view is ahead of the store by the rounds not yet committed.
    const JobTotals& t = runner->totals();
    job["round"] = t.round;
    const auto now = clock_.Now();
    job["rays"] = runner->RaysShown(now);
    job["unshot_fraction"] = t.unshot_fraction;
    job["rays_per_second"] = runner->RaysPerSecond(now);
    // Agents holding its leases: the round's, or its final gather's leased ahead (gather_ahead.h).
    std::set<scheduler::AgentId> working;
    runner->ForEachScheduler([&](const scheduler::RoundScheduler& s) {
      for (const auto& a : s.counters(clock_.Now()).agents) {
        if (a.leases_held > 0) working.insert(a.agent);
      }
    });
    job["agents"] = working.size();
    const ProgressEstimate estimate = runner->Progress(clock_.Now());
    if (estimate.seconds_left) job["eta_seconds"] = *estimate.seconds_left;
    progress = estimate.fraction;
    // Its round is leased out (a round computed here, a reduction or the end run on the compute
    // thread in the other phases) and nobody is there to take the leases.
    job["waiting_for_agents"] =
        runner->phase() == RunningJob::Phase::kRound && agents_.active() == 0;
  } else if (std::optional<SolveShown> solve = jobs_.DisplayedSolve(r.id)) {
    // Drawing its display: the record read from the store may predate the rounds' end.
    job["round"] = std::max(s.rounds, solve->round);
    job["rays"] = std::max(s.rays, solve->rays);
    if (std::optional<double> display = jobs_.DisplaySecondsLeft(r.id)) {
      job["eta_seconds"] = *display;
    }
  }
  if (r.state == store::JobState::kDone) {
    job["stop_reason"] = StopReasonOf(s);
    job["eta_seconds"] = 0.0;
  }
  job["progress"] = ShownProgress(r, progress);
  return job;
}

double ControlRequests::ShownProgress(const store::JobRecord& record, double estimate) {
  if (record.state == store::JobState::kDone) {
    shown_progress_.erase(record.id);
    return 1.0;
  }
  if (store::IsTerminal(record.state)) {
    shown_progress_.erase(record.id);
    return estimate;
  }
  // 1 only once done: a job whose rounds are over still has its display to draw and store.
  return shown_progress_[record.id].Show(std::min(estimate, kProgressBeforeDone));
}

json ControlRequests::DoorsJson() const {
  const DoorCounters& d = agents_.doors();
  return json{{"unauthenticated", d.unauthenticated},
              {"unauthenticated_peak", d.unauthenticated_peak},
              {"max_unauthenticated", agents_.max_unauthenticated()},
              {"accepted", d.accepted},
              {"authenticated", d.authenticated},
              {"evicted", d.evicted},
              {"closed_before_auth", d.closed_before_auth},
              {"refused_full", d.refused_full},
              {"refused_per_agent", d.refused_per_agent},
              {"frame_bytes_held", agents_.frame_budget().held()},
              {"frame_bytes_held_peak", agents_.frame_budget().peak()},
              {"max_frame_bytes_held", agents_.frame_budget().limit()},
              {"frames_refused_over_budget", agents_.frame_budget().refused()},
              {"frames_evicted_over_budget", agents_.frame_budget().evicted()}};
}

json ControlRequests::EnrolledJson() const {
  std::map<std::string, uint64_t> connected;
  for (const AgentLink* link : agents_.Authenticated()) ++connected[link->name()];
  json list = json::array();
  for (const store::AgentCredential& c : agents_.Enrollments()) {
    const auto it = connected.find(c.name);
    list.push_back(json{{"name", c.name},
                        {"generation", c.generation},
                        {"revoked", c.revoked},
                        {"enrolled_at_ms", c.enrolled_at_ms},
                        {"revoked_at_ms", Nullable(c.revoked_at_ms)},
                        {"connected", it == connected.end() ? 0 : it->second}});
  }
  return list;
}

json ControlRequests::AgentJson(const AgentLink& link) const {
  uint32_t leases = 0;
  double rays_per_second = 0;
  const auto now = clock_.Now();
  for (const auto& [job, runner] : jobs_.runners()) {
    runner->ForEachScheduler([&](const scheduler::RoundScheduler& s) {
      if (const auto a = s.agent_counters(link.id(), now)) {
        leases += a->leases_held;
        rays_per_second = std::max(rays_per_second, a->rays_per_second);
      }
    });
  }
  return json{{"id", link.id()},
              {"name", link.name()},
              {"address", link.address()},
              {"threads", link.threads()},
              {"rays_per_second", rays_per_second},
              {"load", link.last_heartbeat().load},
              {"leases", leases},
              {"connected_ms", link.connected_unix_ms()},
              {"last_heartbeat_ms_ago", clock_.NowMs() - link.last_heard_ms()},
              {"results", link.results_accepted()},
              {"stale", link.stale()}};
}

void ControlRequests::RespondWithJobs(std::optional<store::JobId> id, ControlRespond respond) {
  store_.Run(
      [id](store::JobStore& s) -> Result<std::vector<JobSummary>> {
        std::vector<store::JobRecord> records;
        if (id) {
          Result<std::optional<store::JobRecord>> job = s.GetJob(*id);
          RADFARM_RETURN_IF_ERROR(job);
          if (*job) records.push_back(std::move(**job));
        } else {
          Result<std::vector<store::JobRecord>> all = s.ListJobs();
          RADFARM_RETURN_IF_ERROR(all);
          records = std::move(*all);
        }
        std::vector<JobSummary> summaries;
        for (const store::JobRecord& record : records) {
          Result<JobSummary> summary = ReadJobSummary(s, record);
          RADFARM_RETURN_IF_ERROR(summary);
          summaries.push_back(std::move(*summary));
        }
        return summaries;
      },
      [this, id, respond](Result<std::vector<JobSummary>> summaries) {
        if (!summaries) return respond(ControlError("internal", summaries.error()));
        if (id) {
          if (summaries->empty()) return respond(NotFound(*id));
          return respond({json{{"ok", true}, {"job", JobJson(summaries->front())}}, {}});
        }
        json jobs = json::array();
        for (const JobSummary& s : *summaries) jobs.push_back(JobJson(s));
        respond({json{{"ok", true}, {"jobs", jobs}}, {}});
      });
}

void ControlRequests::Submit(ControlRequest request, ControlRespond respond) {
  // Decode and mesh on the compute thread: a bundle the agents could not use is refused now. The
  // mesh goes on to the job's preparation if the job starts at once
  // (JobRounds::OfferSubmittedMesh).
  auto blob = std::make_shared<std::vector<uint8_t>>(std::move(request.attachment));
  Status s = compute_.Submit(
      [blob]() -> Result<CheckedSubmission> {
        LapClock lap;
        Result<codec::JobBundle> bundle = codec::DecodeJobBundle(*blob);
        RADFARM_RETURN_IF_ERROR(bundle);
        Result<PatchMesh> mesh = PatchMesh::Build(bundle->scene, bundle->job.mesh, nullptr);
        RADFARM_RETURN_IF_ERROR(mesh);
        if (bundle->job.refine.enabled) {
          // The checks that need the mesh, as LoadJobForSolve makes them before a local render.
          Result<ResolvedRefineSettings> refine = ResolveRefineSettings(
              bundle->job.refine, mesh->patch_size(), mesh->patch_scene().patches.size(),
              mesh->weld_tolerance(), mesh->memory_limit());
          if (!refine) return Error{bundle->job.scene_path + ": " + refine.error()};
        }
        const SolverSettings& solver = bundle->job.solver;
        SubmittedSettings settings{solver.tolerance,
                                   solver.max_rays,
                                   solver.max_seconds,
                                   std::string(SamplerName(solver.sampler)),
                                   mesh->patch_scene().patches.size(),
                                   bundle->job.scene_path};
        // A job that does not refine needs only the patches (RunningJob::Prepare): the rest of
        // the mesh goes before the survey below builds its ray caster.
        SubmittedMesh meshed;
        meshed.meshing = lap.Lap();
        if (bundle->job.refine.enabled) {
          meshed.mesh = std::make_shared<PatchMesh>(std::move(*mesh));
        } else {
          meshed.patches = std::make_shared<PatchScene>(std::move(*mesh).TakePatchScene());
          malloc_trim(0);  // the freed pages back to the system, which freeing leaves in the heap
        }
        // The warnings `radfarm render` gives once it has the patches; submit checks the scene
        // without meshing it and prints these from the reply.
        const PatchScene& patches = meshed.mesh ? meshed.mesh->patch_scene() : *meshed.patches;
        std::vector<std::string> warnings = BackFaceWarnings(bundle->scene.path, patches);
        for (std::string& w : NearEmitterWarnings(bundle->scene.path, patches)) {
          warnings.push_back(std::move(w));
        }
        return CheckedSubmission{settings, solver.seed,
                                 protocol::HashToHex(protocol::HashScene(*blob)), std::move(meshed),
                                 std::move(warnings)};
      },
      [this, blob, request = std::move(request), respond](Result<CheckedSubmission> checked) {
        if (!checked) return respond(ControlError("bad_request", checked.error()));
        store::JobSpec spec;
        spec.name = request.name;
        if (spec.name.empty()) {
          const std::string& scene = checked->settings.scene;
          const size_t slash = scene.find_last_of('/');
          spec.name = scene.substr(slash == std::string::npos ? 0 : slash + 1);
        }
        spec.scene_hash = checked->bundle_hash;
        spec.settings = checked->settings.ToJson();
        spec.seed = checked->seed;
        spec.priority = request.priority;
        store_.Run(
            [blob, spec](store::JobStore& s) -> Result<JobSummary> {
              if (Status st = s.PutScene(spec.scene_hash, *blob); !st) return Error{st.error()};
              Result<store::JobId> id = s.SubmitJob(spec);
              RADFARM_RETURN_IF_ERROR(id);
              (void)s.AppendEvent(*id, store::EventLevel::kInfo, "submitted");
              Result<std::optional<store::JobRecord>> job = s.GetJob(*id);
              if (!job || !*job) return Error{"the new job cannot be read back"};
              return ReadJobSummary(s, **job);
            },
            [this, respond, meshed = std::move(checked->meshed),
             warnings = std::move(checked->warnings)](Result<JobSummary> summary) {
              if (!summary) return respond(ControlError("internal", summary.error()));
              jobs_.OfferSubmittedMesh(summary->record.id, meshed);
              LogLine(LogLevel::kInfo, "job " + std::to_string(summary->record.id))
                  << "submitted: " << summary->record.spec.name << ", " << summary->settings.patches
                  << " patches, priority " << summary->record.spec.priority;
              respond({json{{"ok", true}, {"job", JobJson(*summary)}, {"warnings", warnings}}, {}});
              jobs_.StartQueuedJobs();
            });
      });
  if (!s) respond(ControlError("internal", s.error()));
}

void ControlRequests::ChangeState(ControlRequest request, ControlRespond respond) {
  const store::JobId id = store::JobId(*request.id);
  const ControlCommand command = request.command;
  const store::JobCommand job_command =
      command == ControlCommand::kCancel  ? store::JobCommand::kCancel
      : command == ControlCommand::kPause ? store::JobCommand::kPause
                                          : store::JobCommand::kResume;
  store_.Run(
      [id, job_command](store::JobStore& s) -> Result<Lookup> {
        Result<store::StateChange> change = store::ChangeJobState(s, id, job_command);
        RADFARM_RETURN_IF_ERROR(change);
        Lookup lookup;
        lookup.invalid = std::move(change->refused);
        if (!change->job || !lookup.invalid.empty()) return lookup;
        Result<JobSummary> summary = ReadJobSummary(s, *change->job);
        RADFARM_RETURN_IF_ERROR(summary);
        lookup.summary = std::move(*summary);
        return lookup;
      },
      [this, id, command, respond](Result<Lookup> lookup) {
        if (!lookup) return respond(ControlError("internal", lookup.error()));
        if (!lookup->invalid.empty())
          return respond(ControlError("invalid_state", lookup->invalid));
        if (!lookup->summary) return respond(NotFound(id));
        if (command == ControlCommand::kResume) {
          jobs_.StartQueuedJobs();
        } else {
          jobs_.DropJob(id);
          LogLine(LogLevel::kInfo, "job " + std::to_string(id))
              << (command == ControlCommand::kCancel ? "cancelled" : "paused");
          jobs_.StartQueuedJobs();
          // A paused job resumes with its kept results; a cancelled one never does.
          if (command == ControlCommand::kCancel) jobs_.PruneKeptResults(id, UINT32_MAX);
        }
        respond({json{{"ok", true}, {"job", JobJson(*lookup->summary)}}, {}});
      });
}

void ControlRequests::Fetch(ControlRequest request, ControlRespond respond) {
  const store::JobId id = store::JobId(*request.id);
  using Answer = std::pair<std::optional<JobSummary>, std::vector<uint8_t>>;
  store_.Run(
      [id](store::JobStore& s) -> Result<Answer> {
        Result<std::optional<store::JobRecord>> job = s.GetJob(id);
        RADFARM_RETURN_IF_ERROR(job);
        if (!*job) return Answer{};
        Result<JobSummary> summary = ReadJobSummary(s, **job);
        RADFARM_RETURN_IF_ERROR(summary);
        Result<std::optional<store::StoredSolution>> stored = store::LoadSolution(s, id);
        RADFARM_RETURN_IF_ERROR(stored);
        if (!*stored) return Answer{std::move(*summary), {}};
        std::vector<uint8_t> blob =
            codec::EncodeJobSolution(SolutionOf(std::move(**stored), *summary));
        return Answer{std::move(*summary), std::move(blob)};
      },
      [this, id, respond](Result<Answer> answer) {
        if (!answer) return respond(ControlError("internal", answer.error()));
        if (!answer->first) return respond(NotFound(id));
        if (answer->second.empty()) {
          return respond(ControlError("invalid_state",
                                      "job " + std::to_string(id) + " has no checkpoint yet"));
        }
        respond({json{{"ok", true}, {"job", JobJson(*answer->first)}}, std::move(answer->second)});
      });
}

}  // namespace radfarm::daemon
