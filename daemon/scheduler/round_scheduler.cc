#include "daemon/scheduler/round_scheduler.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace radfarm::scheduler {

RoundScheduler::RoundScheduler(const SchedulerOptions& options)
    : options_(options), next_attempt_(std::max<AttemptId>(1, options.first_attempt_id)) {}

template <typename Visit>
void RoundScheduler::ForEachAttempt(const BatchSlot& slot, const Visit& visit) const {
  for (AttemptId id = slot.newest_attempt; id != 0;) {
    const AttemptRecord& attempt = *FindAttempt(id);
    visit(id, attempt);
    id = attempt.earlier;
  }
}

// --- Agents ---

void RoundScheduler::AddAgent(AgentId agent) { agents_.try_emplace(agent); }

void RoundScheduler::ReportSpeed(AgentId agent, double rays_per_second) {
  if (const auto it = agents_.find(agent); it != agents_.end()) {
    it->second.throughput.SetReportedSpeed(rays_per_second);
  }
}

void RoundScheduler::OnAgentLost(AgentId agent) {
  const auto it = agents_.find(agent);
  if (it == agents_.end()) return;
  std::vector<AttemptId> live;
  for (const auto& [id, index] : it->second.live) live.push_back(id);
  for (AttemptId id : live) EndAttempt(id, AttemptState::kLost);
  measured_rays_per_second_ =
      std::max(0.0, measured_rays_per_second_ - it->second.throughput.rays_per_second());
  agents_.erase(it);
}

size_t RoundScheduler::ReturnLeases(AgentId agent, std::span<const BatchId> batches) {
  const auto it = agents_.find(agent);
  if (it == agents_.end() || !round_) return 0;
  size_t returned = 0;
  for (BatchId batch_id : batches) {
    if (BatchRound(batch_id) != round_->plan.round) continue;
    const auto& live = it->second.live;
    const auto held = std::find_if(live.begin(), live.end(), [&](const auto& entry) {
      return entry.second == BatchIndex(batch_id);
    });
    if (held == live.end()) continue;
    EndAttempt(held->first, AttemptState::kReturned);
    ++returned;
  }
  return returned;
}

std::vector<Takeover> RoundScheduler::Preempt(AgentId agent) {
  std::vector<Takeover> taken;
  const auto it = agents_.find(agent);
  if (it == agents_.end() || !round_) return taken;
  std::vector<AttemptId> live;
  for (const auto& [id, index] : it->second.live) live.push_back(id);
  // Newest first: EndAttempt puts each batch at the queue's front, so they end up in lease order.
  for (auto id = live.rbegin(); id != live.rend(); ++id) {
    const uint32_t index = AttemptAt(*id).batch_index;
    taken.push_back({agent, MakeBatchId(round_->plan.round, index), *id});
    EndAttempt(*id, AttemptState::kPreempted);
  }
  totals_.leases_preempted += taken.size();
  return taken;
}

void RoundScheduler::Blocklist(AgentId agent, TimePoint until) {
  TimePoint& blocked = blocked_until_[agent];
  blocked = std::max(blocked, until);
}

bool RoundScheduler::IsBlocklisted(AgentId agent, TimePoint now) const {
  const auto it = blocked_until_.find(agent);
  return it != blocked_until_.end() && now < it->second;
}

// --- Rounds ---

Status RoundScheduler::StartRound(RoundPlan plan, TimePoint /*now*/,
                                  std::span<const uint32_t> restored,
                                  std::vector<std::pair<uint32_t, BatchResult>> computed,
                                  std::span<const uint32_t> later) {
  if (round_) {
    return Error{"round " + std::to_string(round_->plan.round) + " is still active"};
  }
  if (plan.batches.empty()) return Error{"round " + std::to_string(plan.round) + " has no batches"};
  if (plan.batches.size() > std::numeric_limits<uint32_t>::max()) {
    return Error{"round " + std::to_string(plan.round) + " has too many batches"};
  }
  Round& round = round_.emplace();
  round.batches.resize(plan.batches.size());
  round.first_attempt = next_attempt_;
  uint64_t rays = 0;
  for (uint32_t k : restored) {
    if (k >= plan.batches.size() || round.batches[k].state == BatchState::kDone) continue;
    round.batches[k].state = BatchState::kDone;  // its result is the store's: none here
    ++round.done;
  }
  for (auto& [k, result] : computed) {
    if (k >= plan.batches.size() || round.batches[k].state == BatchState::kDone) continue;
    round.batches[k].state = BatchState::kDone;
    round.results[k] = std::move(result);
    ++round.done;
  }
  std::vector<bool> last(later.empty() ? 0 : plan.batches.size());
  for (uint32_t k : later) {
    if (k < last.size()) last[k] = true;
  }
  auto enqueue = [&](uint32_t k) {
    round.fresh.push_back(k);
    round.batches[k].in_fresh_queue = true;
    ++round.queued;
    round.rays_left += plan.batches[k].ray_count;
  };
  for (uint32_t k = 0; k < plan.batches.size(); ++k) {
    rays += plan.batches[k].ray_count;
    if (round.batches[k].state == BatchState::kDone || (!last.empty() && last[k])) continue;
    enqueue(k);
  }
  for (uint32_t k = 0; k < last.size(); ++k) {
    if (last[k] && round.batches[k].state != BatchState::kDone) enqueue(k);
  }
  measured_rays_per_second_ = 0;
  for (const auto& [id, agent] : agents_) {
    measured_rays_per_second_ += agent.throughput.rays_per_second();
  }
  round.mean_batch_rays = double(rays) / double(plan.batches.size());
  round.plan = std::move(plan);
  return Ok{};
}

bool RoundScheduler::RoundComplete() const {
  return round_ && round_->done == round_->batches.size();
}

bool RoundScheduler::InEndGame() const { return round_ && !RoundComplete() && round_->queued == 0; }

bool RoundScheduler::WantsAgent(AgentId agent, TimePoint now) const {
  return round_ && round_->queued > 0 && agents_.count(agent) > 0 && !IsBlocklisted(agent, now);
}

Result<CompletedRound> RoundScheduler::TakeCompletedRound() {
  if (!round_) return Error{"no round is active"};
  if (!RoundComplete()) {
    return Error{"round " + std::to_string(round_->plan.round) + " has " +
                 std::to_string(round_->batches.size() - round_->done) + " batches left"};
  }
  CompletedRound done;
  done.results.resize(round_->batches.size());
  for (auto& [k, result] : round_->results) done.results[k] = std::move(result);
  done.plan = std::move(round_->plan);
  round_.reset();
  return done;
}

std::optional<BatchResult> RoundScheduler::TakeResult(BatchId batch_id) {
  if (PeekResult(batch_id) == nullptr) return std::nullopt;
  return std::move(round_->results.extract(BatchIndex(batch_id)).mapped());
}

const BatchResult* RoundScheduler::PeekResult(BatchId batch_id) const {
  if (!round_ || BatchRound(batch_id) != round_->plan.round) return nullptr;
  // Only a done batch whose result is not taken yet has one there.
  const auto found = round_->results.find(BatchIndex(batch_id));
  return found == round_->results.end() ? nullptr : &found->second;
}

bool RoundScheduler::HasLiveLease(BatchId batch_id) const {
  if (!round_ || BatchRound(batch_id) != round_->plan.round) return false;
  const uint32_t index = BatchIndex(batch_id);
  return index < round_->batches.size() && LiveAttempts(round_->batches[index]) > 0;
}

const Batch* RoundScheduler::FindBatch(BatchId batch_id) const {
  if (!round_ || BatchRound(batch_id) != round_->plan.round) return nullptr;
  const uint32_t index = BatchIndex(batch_id);
  return index < round_->plan.batches.size() ? &round_->plan.batches[index] : nullptr;
}

// --- Work ---

uint32_t RoundScheduler::LeasesHeld(AgentId agent) const {
  const auto it = agents_.find(agent);
  return it == agents_.end() ? 0 : static_cast<uint32_t>(it->second.live.size());
}

uint32_t RoundScheduler::LeaseSizeOf(AgentId agent) const {
  const auto it = agents_.find(agent);
  if (it == agents_.end()) return 0;
  const double batch_rays = round_ ? round_->mean_batch_rays : options_.default_batch_rays;
  uint32_t size = it->second.throughput.LeaseBatches(batch_rays, options_);
  if (round_ && !round_->fresh.empty()) {
    const size_t share = EqualShare(round_->fresh.size());
    size = static_cast<uint32_t>(std::min<size_t>(size, std::max<size_t>(1, share)));
  }
  return size;
}

uint32_t RoundScheduler::LeaseCapacityOf(AgentId agent) const {
  const auto it = agents_.find(agent);
  return it == agents_.end() ? 0 : LeaseCapacity(it->second);
}

std::optional<Assignment> RoundScheduler::NextAssignment(AgentId agent_id, TimePoint now,
                                                         uint32_t leases_elsewhere,
                                                         std::optional<uint32_t> capacity) {
  const auto it = agents_.find(agent_id);
  if (!round_ || it == agents_.end() || IsBlocklisted(agent_id, now)) return std::nullopt;
  AgentState& agent = it->second;
  const bool full = agent.live.size() + leases_elsewhere >= capacity.value_or(LeaseCapacity(agent));
  // A full agent below min_held_seconds of work may still take fresh batches, nothing else; one
  // holding other jobs' leases is left to them (their work may be what keeps it busy, and a
  // lower-priority job must not queue work beyond the capacity behind a higher one's).
  if (full && !(leases_elsewhere == 0 && HoldsTooLittle(agent) && PeekFresh())) {
    return std::nullopt;
  }
  if (const auto next = PeekFresh()) {
    if (!RoundEndAllows(agent, round_->plan.batches[*next].ray_count, now)) return std::nullopt;
    return Issue(*PopFresh(), agent_id, agent, now, false);
  }
  if (const auto index = PopOverdueFor(agent_id)) return Issue(*index, agent_id, agent, now, true);
  if (const auto taken = TakeOverFor(agent_id, agent, now)) {
    const AttemptRecord& old = AttemptAt(taken->second);
    const Takeover from{old.agent, MakeBatchId(round_->plan.round, taken->first), taken->second};
    Assignment a = Issue(taken->first, agent_id, agent, now, false);
    EndAttempt(taken->second, AttemptState::kTakenOver);
    round_->batches[taken->first].taken_over = true;
    ++totals_.takeovers;
    a.taken_from = from;
    return a;
  }
  if (const auto index = EndGameCopyFor(agent_id, agent, now)) {
    return Issue(*index, agent_id, agent, now, true);
  }
  return std::nullopt;
}

ResultVerdict RoundScheduler::OnResult(AgentId agent_id, BatchId batch_id, AttemptId attempt_id,
                                       BatchResult result, TimePoint now) {
  uint64_t rays = 0;
  TimePoint issued = now;
  const ResultVerdict verdict =
      Record(agent_id, batch_id, attempt_id, std::move(result), now, &rays, &issued);
  if (rays > 0) {
    if (const auto agent = agents_.find(agent_id); agent != agents_.end()) {
      Measure(agent->second, rays, issued, now);
    }
  }
  return verdict;
}

std::vector<ResultVerdict> RoundScheduler::OnResults(AgentId agent_id,
                                                     std::vector<SubmittedResult> results,
                                                     TimePoint now) {
  std::vector<ResultVerdict> verdicts;
  verdicts.reserve(results.size());
  uint64_t total_rays = 0;
  TimePoint first_issued = now;
  for (SubmittedResult& r : results) {
    uint64_t rays = 0;
    TimePoint issued = now;
    verdicts.push_back(
        Record(agent_id, r.batch_id, r.attempt_id, std::move(r.result), now, &rays, &issued));
    total_rays += rays;
    if (rays > 0) first_issued = std::min(first_issued, issued);
  }
  if (total_rays > 0) {
    if (const auto agent = agents_.find(agent_id); agent != agents_.end()) {
      Measure(agent->second, total_rays, first_issued, now);
    }
  }
  // The round may have completed on an earlier result of the frame: say so on every verdict.
  const bool complete = RoundComplete();
  for (ResultVerdict& v : verdicts) v.round_complete = complete;
  return verdicts;
}

ResultVerdict RoundScheduler::Record(AgentId agent_id, BatchId batch_id, AttemptId attempt_id,
                                     BatchResult result, TimePoint now, uint64_t* rays,
                                     TimePoint* issued) {
  if (!round_ || BatchRound(batch_id) != round_->plan.round) {
    return Verdict(Disposition::kDropped, DropReason::kStaleRound);
  }
  AttemptRecord* const found = FindAttempt(attempt_id);
  if (found == nullptr) return Verdict(Disposition::kDropped, DropReason::kUnknownAttempt);
  AttemptRecord& attempt = *found;
  if (attempt.batch_index != BatchIndex(batch_id)) {
    return Verdict(Disposition::kRejected, DropReason::kWrongBatch);
  }
  if (attempt.agent != agent_id) return Verdict(Disposition::kRejected, DropReason::kNotHolder);
  if (IsBlocklisted(agent_id, now)) {
    return Verdict(Disposition::kRejected, DropReason::kBlocklisted);
  }

  // The agent did the work whatever becomes of the result: measure it, free its lease.
  const bool already_answered = attempt.state == AttemptState::kAnswered;
  if (!already_answered) {
    const uint32_t batch_rays = round_->plan.batches[attempt.batch_index].ray_count;
    *rays = batch_rays;
    *issued = attempt.issued;
    const auto agent = agents_.find(agent_id);
    if (agent != agents_.end() && agent->second.live.erase(attempt_id) > 0) {
      agent->second.live_rays -= batch_rays;
      Reindex(agent_id, agent->second);
    }
    attempt.state = AttemptState::kAnswered;
  }

  BatchSlot& slot = round_->batches[attempt.batch_index];
  if (slot.state == BatchState::kDone) {
    return Verdict(Disposition::kDropped,
                   already_answered ? DropReason::kDuplicate : DropReason::kLate);
  }
  SetState(slot, BatchState::kDone);
  round_->rays_left -= round_->plan.batches[attempt.batch_index].ray_count;
  round_->results[attempt.batch_index] = std::move(result);
  ++round_->done;
  ForEachAttempt(slot, [&](AttemptId other, const AttemptRecord&) {
    if (other != attempt_id) EndAttempt(other, AttemptState::kSuperseded);
  });
  if (const auto agent = agents_.find(agent_id); agent != agents_.end()) {
    ++agent->second.results_accepted;
  }
  return Verdict(Disposition::kAccepted, DropReason::kNone);
}

ResultVerdict RoundScheduler::OnComputedResult(uint32_t index, BatchResult result) {
  if (!round_ || index >= round_->batches.size()) {
    return Verdict(Disposition::kDropped, DropReason::kStaleRound);
  }
  BatchSlot& slot = round_->batches[index];
  if (slot.state == BatchState::kDone) return Verdict(Disposition::kDropped, DropReason::kLate);
  SetState(slot, BatchState::kDone);
  round_->rays_left -= round_->plan.batches[index].ray_count;
  round_->results[index] = std::move(result);
  ++round_->done;
  ForEachAttempt(slot, [&](AttemptId other, const AttemptRecord&) {
    EndAttempt(other, AttemptState::kSuperseded);
  });
  return Verdict(Disposition::kAccepted, DropReason::kNone);
}

void RoundScheduler::LeaseFirst(uint32_t index) {
  if (!round_ || index >= round_->batches.size()) return;
  BatchSlot& slot = round_->batches[index];
  if (slot.state != BatchState::kQueued) return;
  // Its place further back, if any, is dropped by PeekFresh once it is leased from here.
  slot.in_fresh_queue = true;
  round_->fresh.push_front(index);
}

std::vector<uint32_t> RoundScheduler::TakeQueued() {
  std::vector<uint32_t> queued;
  if (!round_) return queued;
  while (const std::optional<uint32_t> index = PopFresh()) queued.push_back(*index);
  return queued;
}

ResultVerdict RoundScheduler::OnInvalidResult(AgentId agent_id, BatchId /*batch_id*/,
                                              AttemptId /*attempt_id*/, TimePoint /*now*/) {
  if (const auto it = agents_.find(agent_id); it != agents_.end()) {
    std::vector<AttemptId> live;
    for (const auto& [id, index] : it->second.live) live.push_back(id);
    for (AttemptId id : live) EndAttempt(id, AttemptState::kRevoked);
  }
  return Verdict(Disposition::kRejected, DropReason::kInvalid);
}

size_t RoundScheduler::Tick(TimePoint now) {
  if (!round_) return 0;
  // Only a batch with a live lease past its deadline can be overdue: the agents' live leases are
  // walked, not the round's batches (a million of them at 10^6 patches, every tick), and the
  // candidates taken in batch order.
  std::vector<uint32_t> candidates;
  for (const auto& [agent_id, agent] : agents_) {
    for (const auto& [attempt_id, index] : agent.live) {
      if (now >= AttemptAt(attempt_id).deadline) candidates.push_back(index);
    }
  }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  size_t offered = 0;
  for (uint32_t k : candidates) {
    BatchSlot& slot = round_->batches[k];
    if (slot.state != BatchState::kLeased || slot.in_overdue_queue) continue;
    size_t live = 0;
    bool all_overdue = true;
    ForEachAttempt(slot, [&](AttemptId, const AttemptRecord& attempt) {
      if (attempt.state != AttemptState::kLive) return;
      ++live;
      all_overdue = all_overdue && now >= attempt.deadline;
    });
    if (live == 0 || !all_overdue || live >= options_.max_live_attempts) continue;
    slot.in_overdue_queue = true;
    round_->overdue.push_back(k);
    ++offered;
  }
  return offered;
}

// --- Status ---

uint32_t RoundScheduler::SuggestedBatchRays() const {
  double slowest = 0;
  for (const auto& [id, agent] : agents_) {
    if (!agent.throughput.measured()) continue;
    const double rate = agent.throughput.rays_per_second();
    if (slowest == 0 || rate < slowest) slowest = rate;
  }
  if (slowest == 0) return options_.default_batch_rays;
  const double rays = slowest * options_.target_lease_seconds;
  return static_cast<uint32_t>(
      std::clamp(rays, double(options_.min_batch_rays), double(options_.max_batch_rays)));
}

BatchSizing RoundScheduler::SuggestedSizing() const {
  return {SuggestedBatchRays(), TaperWays(options_, agents_.size())};
}

SchedulerCounters RoundScheduler::counters(TimePoint now) const {
  SchedulerCounters c = totals_;
  if (round_) {
    c.round_active = true;
    c.round = round_->plan.round;
    c.batches = round_->batches.size();
    c.batches_queued = round_->queued;
    c.batches_done = round_->done;
    c.batches_leased = c.batches - c.batches_queued - c.batches_done;
  }
  for (const auto& [id, agent] : agents_) c.agents.push_back(CountersOf(id, agent, now));
  return c;
}

std::optional<AgentCounters> RoundScheduler::agent_counters(AgentId agent, TimePoint now) const {
  const auto it = agents_.find(agent);
  if (it == agents_.end()) return std::nullopt;
  return CountersOf(agent, it->second, now);
}

// --- Private ---

uint32_t RoundScheduler::LeaseCapacity(const AgentState& agent) const {
  const double batch_rays = round_ ? round_->mean_batch_rays : options_.default_batch_rays;
  return agent.throughput.LeaseCapacity(batch_rays, options_);
}

AgentCounters RoundScheduler::CountersOf(AgentId id, const AgentState& agent, TimePoint now) const {
  return {id,
          static_cast<uint32_t>(agent.live.size()),
          LeaseCapacity(agent),
          agent.throughput.rays_per_second(),
          IsBlocklisted(id, now),
          agent.results_accepted};
}

std::optional<uint32_t> RoundScheduler::PopFresh() {
  const std::optional<uint32_t> index = PeekFresh();
  if (index) {
    round_->fresh.pop_front();
    round_->batches[*index].in_fresh_queue = false;
  }
  return index;
}

std::optional<uint32_t> RoundScheduler::PeekFresh() {
  while (!round_->fresh.empty()) {
    const uint32_t index = round_->fresh.front();
    BatchSlot& slot = round_->batches[index];
    // A requeued batch may have been answered since by a lease that was given up.
    if (slot.state == BatchState::kQueued) return index;
    round_->fresh.pop_front();
    slot.in_fresh_queue = false;
  }
  return std::nullopt;
}

std::optional<double> RoundScheduler::RoundSecondsLeft() const {
  if (measured_rays_per_second_ <= 0) return std::nullopt;
  return double(round_->rays_left) / measured_rays_per_second_;
}

size_t RoundScheduler::EqualShare(size_t batches) const {
  const size_t agents = std::max<size_t>(1, agents_.size());
  return (batches + agents - 1) / agents;
}

bool RoundScheduler::HoldsTooLittle(const AgentState& agent) const {
  if (options_.min_held_seconds <= 0 || !agent.throughput.measured()) return false;
  return double(agent.live_rays) < options_.min_held_seconds * agent.throughput.rays_per_second();
}

bool RoundScheduler::RoundEndAllows(const AgentState& agent, uint32_t rays, TimePoint now) const {
  // An agent holding nothing always gets work.
  if (options_.round_end_share <= 0 || agent.live.empty()) return true;
  if (!agent.throughput.measured()) {
    // Not measured here (at most its reported speed sizes its leases): its equal share of the
    // round's batches not done. Otherwise the first agents asked fill a capacity sized for a lease
    // horizon and a short round waits on them, or is taken back from them, while others idle.
    return agent.live.size() < EqualShare(round_->batches.size() - round_->done);
  }
  const std::optional<double> left = RoundSecondsLeft();
  if (!left) return true;
  const double done_after =
      FinishEstimate(agent, now) + agent.throughput.ExpectedSeconds(rays, options_);
  return done_after <= options_.round_end_share * *left;
}

void RoundScheduler::Measure(AgentState& agent, uint64_t rays, TimePoint issued, TimePoint now) {
  const double before = agent.throughput.rays_per_second();
  agent.throughput.AddResult(rays, issued, now, options_.throughput_smoothing,
                             options_.min_batch_rays);
  measured_rays_per_second_ =
      std::max(0.0, measured_rays_per_second_ + agent.throughput.rays_per_second() - before);
}

std::optional<uint32_t> RoundScheduler::PopOverdueFor(AgentId agent) {
  auto& queue = round_->overdue;
  for (auto it = queue.begin(); it != queue.end();) {
    BatchSlot& slot = round_->batches[*it];
    // Answered, back in the fresh queue, or no room for another attempt: not an offer any more.
    if (slot.state != BatchState::kLeased || LiveAttempts(slot) >= options_.max_live_attempts) {
      slot.in_overdue_queue = false;
      it = queue.erase(it);
      continue;
    }
    bool holds = false;
    ForEachAttempt(slot, [&](AttemptId, const AttemptRecord& a) {
      holds = holds || (a.state == AttemptState::kLive && a.agent == agent);
    });
    if (holds) {
      ++it;
      continue;
    }
    const uint32_t index = *it;
    slot.in_overdue_queue = false;
    queue.erase(it);
    return index;
  }
  return std::nullopt;
}

namespace {

// Moves `id`'s entry in `index` from `*key` to `next` (either may be absent). An unchanged key
// is left alone: a lease issued behind others keeps the agent's oldest, a result for any but the
// newest its newest, and two tree updates a batch are a noticeable share of dispatch.
void MoveKey(std::set<std::pair<TimePoint, AgentId>>& index, AgentId id,
             std::optional<TimePoint>& key, std::optional<TimePoint> next) {
  if (key == next) return;
  if (key) index.erase({*key, id});
  if (next) index.emplace(*next, id);
  key = next;
}

}  // namespace

void RoundScheduler::Reindex(AgentId id, AgentState& agent) {
  std::optional<TimePoint> finish, copy;
  if (!agent.live.empty() && round_) {
    finish = AttemptAt(agent.live.rbegin()->first).expected_done;
    if (options_.end_game_copy_factor > 0) {
      const AttemptRecord& oldest = AttemptAt(agent.live.begin()->first);
      // At least 1 ms of expected time, as EndGameCopyFor counts it.
      const auto expected =
          std::max<Duration>(std::chrono::milliseconds(1), oldest.expected_done - oldest.issued);
      copy = oldest.issued +
             std::chrono::duration_cast<Duration>(expected * options_.end_game_copy_factor);
    }
  }
  MoveKey(finish_index_, id, agent.finish_key, finish);
  MoveKey(copy_index_, id, agent.copy_key, copy);
}

double RoundScheduler::FinishEstimate(const AgentState& agent, TimePoint now) const {
  if (agent.live.empty()) return 0;
  // Its newest lease was expected done after all it held then; time since has run down that
  // work, but an agent running late still needs at least that batch's time.
  const auto& [attempt_id, index] = *agent.live.rbegin();
  const double left =
      std::chrono::duration<double>(AttemptAt(attempt_id).expected_done - now).count();
  return std::max(
      left, agent.throughput.ExpectedSeconds(round_->plan.batches[index].ray_count, options_));
}

std::optional<std::pair<uint32_t, AttemptId>> RoundScheduler::TakeOverFor(AgentId agent_id,
                                                                          const AgentState& agent,
                                                                          TimePoint now) {
  // The agent expected to finish last: among the few latest in finish_index_ (an agent running
  // late still needs its newest batch's time, which the index does not order by).
  constexpr int kCandidates = 4;
  const AgentState* victim = nullptr;
  double victim_finish = 0;
  int seen = 0;
  for (auto it = finish_index_.rbegin(); it != finish_index_.rend() && seen < kCandidates; ++it) {
    if (it->second == agent_id) continue;
    ++seen;
    const AgentState& other = agents_.at(it->second);
    const double finish = FinishEstimate(other, now);
    if (victim == nullptr || finish > victim_finish) {
      victim = &other;
      victim_finish = finish;
    }
  }
  if (victim == nullptr) return std::nullopt;
  // Its newest lease is the last it would start. Moving it pays when this agent would finish it
  // clearly before the victim would start it: by a quarter of the victim's time for it, which
  // covers the round trip and keeps two equal agents from trading a batch about to start.
  const auto& [attempt_id, index] = *victim->live.rbegin();
  const uint32_t rays = round_->plan.batches[index].ray_count;
  const double mine = FinishEstimate(agent, now) + agent.throughput.ExpectedSeconds(rays, options_);
  const double start_there =
      victim_finish - 0.25 * victim->throughput.ExpectedSeconds(rays, options_);
  if (mine >= start_there) return std::nullopt;
  const BatchSlot& slot = round_->batches[index];
  if (slot.taken_over || LiveAttempts(slot) != 1) return std::nullopt;
  return std::make_pair(index, attempt_id);
}

std::optional<uint32_t> RoundScheduler::EndGameCopyFor(AgentId agent_id, const AgentState& agent,
                                                       TimePoint now) {
  if (!agent.live.empty() || options_.end_game_copy_factor <= 0) return std::nullopt;
  // The running lease (some agent's oldest) that has taken longest past its expected time,
  // counted in expected times; only one past end_game_copy_factor of them is worth a copy. Only
  // the first few agents of copy_index_ past that point are looked at (in the order they got
  // there), not every agent.
  constexpr int kLooked = 16;
  std::optional<uint32_t> pick;
  double worst = options_.end_game_copy_factor;
  int looked = 0;
  for (auto it = copy_index_.begin();
       it != copy_index_.end() && it->first <= now && looked < kLooked; ++it, ++looked) {
    if (it->second == agent_id) continue;
    const AgentState& other = agents_.at(it->second);
    const auto& [attempt_id, index] = *other.live.begin();
    const AttemptRecord& attempt = AttemptAt(attempt_id);
    const double expected = std::max(
        1e-3, std::chrono::duration<double>(attempt.expected_done - attempt.issued).count());
    const double taken = std::chrono::duration<double>(now - attempt.issued).count();
    if (taken / expected < worst) continue;
    if (LiveAttempts(round_->batches[index]) >= options_.max_live_attempts) continue;
    worst = taken / expected;
    pick = index;
  }
  return pick;
}

Assignment RoundScheduler::Issue(uint32_t index, AgentId agent_id, AgentState& agent, TimePoint now,
                                 bool speculative) {
  const AttemptId id = next_attempt_++;
  if (next_attempt_ == 0) next_attempt_ = 1;  // 0 is never an attempt id
  const Batch& batch = round_->plan.batches[index];
  agent.live.emplace(id, index);
  agent.live_rays += batch.ray_count;
  const TimePoint deadline = agent.throughput.Deadline(agent.live_rays, now, options_);
  const TimePoint expected_done =
      now + std::chrono::duration_cast<Duration>(std::chrono::duration<double>(
                agent.throughput.ExpectedSeconds(agent.live_rays, options_)));
  BatchSlot& slot = round_->batches[index];
  // Ids skip 0 where they wrap: a record that no id finds keeps attempts[id - first_attempt].
  while (AttemptId(round_->first_attempt + round_->attempts.size()) != id) {
    AttemptRecord unused;
    unused.state = AttemptState::kLost;
    round_->attempts.push_back(unused);
  }
  round_->attempts.push_back(
      {agent_id, index, slot.newest_attempt, now, deadline, expected_done, AttemptState::kLive});
  slot.newest_attempt = id;
  Reindex(agent_id, agent);
  SetState(slot, BatchState::kLeased);
  ++totals_.attempts_issued;
  if (speculative) ++totals_.speculative_attempts;
  return {MakeBatchId(round_->plan.round, index), id, batch, deadline, speculative, std::nullopt};
}

size_t RoundScheduler::LiveAttempts(const BatchSlot& slot) const {
  size_t live = 0;
  ForEachAttempt(slot, [&](AttemptId, const AttemptRecord& attempt) {
    live += attempt.state == AttemptState::kLive;
  });
  return live;
}

const RoundScheduler::AttemptRecord* RoundScheduler::FindAttempt(AttemptId id) const {
  if (!round_ || id == 0) return nullptr;
  const AttemptId k = id - round_->first_attempt;  // modulo 2^32, as ids wrap
  return k < round_->attempts.size() ? &round_->attempts[k] : nullptr;
}

RoundScheduler::AttemptRecord* RoundScheduler::FindAttempt(AttemptId id) {
  return const_cast<AttemptRecord*>(std::as_const(*this).FindAttempt(id));
}

const RoundScheduler::AttemptRecord& RoundScheduler::AttemptAt(AttemptId id) const {
  const AttemptRecord* attempt = FindAttempt(id);
  if (attempt == nullptr) throw std::out_of_range("no attempt " + std::to_string(id));
  return *attempt;
}

RoundScheduler::AttemptRecord& RoundScheduler::AttemptAt(AttemptId id) {
  return const_cast<AttemptRecord&>(std::as_const(*this).AttemptAt(id));
}

void RoundScheduler::SetState(BatchSlot& slot, BatchState state) {
  if (slot.state == BatchState::kQueued) --round_->queued;
  if (state == BatchState::kQueued) ++round_->queued;
  slot.state = state;
}

void RoundScheduler::EndAttempt(AttemptId id, AttemptState how) {
  AttemptRecord& attempt = AttemptAt(id);
  if (attempt.state != AttemptState::kLive) return;
  attempt.state = how;
  const uint32_t rays = round_->plan.batches[attempt.batch_index].ray_count;
  if (const auto agent = agents_.find(attempt.agent); agent != agents_.end()) {
    if (agent->second.live.erase(id) > 0) {
      agent->second.live_rays -= rays;
      Reindex(attempt.agent, agent->second);
    }
  }
  BatchSlot& slot = round_->batches[attempt.batch_index];
  if (slot.state == BatchState::kDone || LiveAttempts(slot) > 0) return;
  SetState(slot, BatchState::kQueued);
  ++totals_.leases_requeued;
  if (!slot.in_fresh_queue) {
    slot.in_fresh_queue = true;
    round_->fresh.push_front(attempt.batch_index);  // waited longest: first again
  }
}

ResultVerdict RoundScheduler::Verdict(Disposition disposition, DropReason reason) {
  if (disposition == Disposition::kAccepted) {
    ++totals_.results_accepted;
  } else {
    ++totals_.results_dropped[size_t(reason)];
  }
  return {disposition, reason, RoundComplete()};
}

}  // namespace radfarm::scheduler
