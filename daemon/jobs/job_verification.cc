// JobRounds: exact validation of accepted results (batch_verifier.h says which are
// checked). The master computes the chosen batches again on its compute thread, between the
// folds, and compares the SHA-256 of the bits. A round is reduced only once every verification
// of it agreed (OnRoundComplete waits here), so a caught lie never reaches the solver or a
// checkpoint. A mismatch convicts the agent (the master's own result is the reference: it is
// trusted, the agents are not), blocklists it for the job at once, and sends the job back to
// before that agent's first accepted result: the checkpoints from that round on and the kept
// results after it are deleted, and its own results of that round; the job is queued again and
// resumes as a restarted master would, folding everyone else's kept results first and leasing
// the liar's batches again, so it still ends bit-identical to `radfarm render`.
#include <memory>

#include "daemon/jobs/job_rounds.h"
#include "loop/log.h"
#include "store/job_transactions.h"

namespace radfarm::daemon {

using loop::LogLevel;
using loop::LogLine;

void JobRounds::StartVerifying(const std::shared_ptr<RunningJob>& runner) {
  const store::JobId id = runner->id();
  auto it = verifiers_.find(id);
  if (it == verifiers_.end()) {
    it = verifiers_.try_emplace(id, config_.verify_fraction, verify_seed_, id).first;
  }
  it->second.StartRound(runner->running_round());
  awaiting_verification_.erase(id);
}

void JobRounds::VerifyOnComputeThread(const std::shared_ptr<RunningJob>& runner,
                                      std::vector<uint32_t> indices) {
  const uint32_t round = runner->running_round();
  auto batches = std::make_shared<std::vector<Batch>>();
  for (uint32_t index : indices) {
    batches->push_back(*runner->scheduler().FindBatch(scheduler::MakeBatchId(round, index)));
  }
  // The digests come back through `digests`: a Result<std::vector> through the WorkQueue trips
  // GCC 12's -Wfree-nonheap-object (job_holds.cc).
  auto digests = std::make_shared<std::vector<ResultDigest>>();
  Status s = compute_.Submit(
      [runner, batches, digests]() -> Status {
        *digests = runner->VerifyBatches(*batches);
        return Ok{};
      },
      [this, runner, round, indices = std::move(indices), digests](Status) {
        if (stopping_) return;
        OnBatchesVerified(runner, round, indices, *digests);
      });
  if (!s) FailJob(runner->id(), s.error());
}

void JobRounds::OnBatchesVerified(const std::shared_ptr<RunningJob>& runner, uint32_t round,
                                  const std::vector<uint32_t>& indices,
                                  const std::vector<ResultDigest>& digests) {
  const store::JobId id = runner->id();
  if (FindRunner(id) != runner.get()) return;  // dropped meanwhile
  const auto it = verifiers_.find(id);
  if (it == verifiers_.end() || it->second.round() != round) return;
  BatchVerifier& verifier = it->second;
  for (size_t k = 0; k < indices.size() && k < digests.size(); ++k) {
    ++verify_counters_.verified;
    if (std::optional<Mismatch> lie = verifier.OnVerified(indices[k], digests[k])) {
      ++verify_counters_.mismatched;
      Rewind(runner, *lie);
      return;
    }
  }
  if (verifier.pending() == 0 && awaiting_verification_.erase(id) > 0) OnRoundComplete(id);
}

bool JobRounds::RoundVerified(const std::shared_ptr<RunningJob>& runner) {
  const auto it = verifiers_.find(runner->id());
  if (it == verifiers_.end() || !it->second.enabled()) return true;
  std::vector<uint32_t> picks = it->second.PicksAtRoundEnd();
  if (!picks.empty()) VerifyOnComputeThread(runner, std::move(picks));
  if (it->second.pending() == 0) return true;
  awaiting_verification_.insert(runner->id());
  return false;
}

void JobRounds::Rewind(const std::shared_ptr<RunningJob>& runner, const Mismatch& lie) {
  const store::JobId id = runner->id();
  const BatchVerifier& verifier = verifiers_.at(id);
  const uint32_t from = std::min(verifier.FirstRoundOf(lie.agent).value_or(lie.round), lie.round);
  // Of the round the agent started in, only its own results go when that is this round; an
  // earlier one was reduced with its results, so all of it is computed again.
  const bool whole_round = from < lie.round;
  std::vector<uint32_t> discard;
  if (!whole_round) discard = verifier.BatchesOf(lie.agent);
  const Batch& batch = *runner->scheduler().FindBatch(scheduler::MakeBatchId(lie.round, lie.index));
  const std::string why =
      "round " + std::to_string(ShownRound(lie.round)) + " batch " + std::to_string(lie.index) +
      " (shooter " + std::to_string(batch.shooter) + ", " + std::to_string(batch.ray_count) +
      " rays from " + std::to_string(batch.first_ray) + "): its result has SHA-256 " +
      DigestHex(lie.agent_digest) + ", the master's " + DigestHex(lie.master_digest);
  const std::string back = "the job goes back before round " + std::to_string(ShownRound(from)) +
                           " without its results (" +
                           (whole_round ? std::string("every result from then on")
                                        : std::to_string(discard.size()) + " of its results") +
                           " computed again)";
  LogLine(LogLevel::kWarning, "job " + std::to_string(id))
      << "verification failed: agent " << lie.agent << ": " << why << "; " << back;
  ++verify_counters_.rewinds;
  agents_.convict(id, lie.agent, why);
  DropRunner(id);
  const std::string event =
      "a result of agent " + lie.agent + " failed verification (" + why + "); " + back;
  store_.Run(
      [id, from, discard, whole_round, event](store::JobStore& s) -> Status {
        RADFARM_RETURN_IF_ERROR(s.RewindJob(id, from, discard, whole_round));
        Result<std::optional<store::JobRecord>> job = s.GetJob(id);
        RADFARM_RETURN_IF_ERROR(job);
        // Cancelled or paused meanwhile: it stays so, and resumes from the rewound store.
        if (*job && (*job)->state == store::JobState::kRunning) {
          RADFARM_RETURN_IF_ERROR(s.SetJobState(id, store::JobState::kQueued));
        }
        (void)s.AppendEvent(id, store::EventLevel::kWarning, event);
        return Ok{};
      },
      [this, id](Status s) {
        if (!s) {
          return HoldOrFail(
              id, Error{"cannot rewind after a failed verification: " + s.error(), s.error_kind()});
        }
        StartQueuedJobs();
      });
}

}  // namespace radfarm::daemon
