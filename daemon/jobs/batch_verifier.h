// BatchVerifier: exact validation of one job's accepted results. A batch's result
// depends only on (seed, round, batch, scene) (core/batch.h), so the master computing a batch
// again must get the agent's bits; an agent whose results authenticate but differ lied or is
// broken.
//
// Which results are checked: each accepted result of the round is noted with its agent and the
// SHA-256 of its bits (DigestOf). A seeded fraction is verified as it arrives (SampleValue below
// `fraction`: keyed by a secret of this master, the job, the round, the agent and the batch, so
// an agent cannot tell which of its results will be checked); when the round is complete, each
// agent that contributed but had none sampled gets one picked the same way (PicksAtRoundEnd). The
// daemon reduces the round only once every verification of it agreed (JobRounds, the per-round
// barrier), so a round with a caught lie never reaches the solver or a checkpoint.
//
// Loop thread only; pure (no clock, no I/O): the daemon computes the batches.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/batch.h"

namespace radfarm::daemon {

using ResultDigest = std::array<uint8_t, 32>;

// SHA-256 of every field of `result`, little-endian: equal digests mean equal bits.
ResultDigest DigestOf(const BatchResult& result);
std::string DigestHex(const ResultDigest& digest);

// A value in [0, 1) that is a pure function of its inputs (SplitMix64 over them): a batch is
// sampled when its value is below the fraction.
double SampleValue(uint64_t seed, int64_t job, uint32_t round, std::string_view agent,
                   uint32_t index);

struct Mismatch {
  std::string agent;
  uint32_t round = 0;
  uint32_t index = 0;
  ResultDigest agent_digest{};
  ResultDigest master_digest{};
};

class BatchVerifier {
 public:
  // `fraction` in [0, 1]; 0 turns verification off (nothing is sampled or picked).
  BatchVerifier(double fraction, uint64_t seed, int64_t job);

  bool enabled() const { return fraction_ > 0; }
  // A new round: the last one's notes go.
  void StartRound(uint32_t round);
  uint32_t round() const { return round_; }
  // An accepted result of batch `index` of the round, computed by `agent`: true when the master
  // is to verify it now (it is then pending).
  bool OnAccepted(uint32_t index, const std::string& agent, const ResultDigest& digest) {
    return OnAccepted(index, agent, [&] { return digest; });
  }
  // The same, with the digest computed only if it may be compared: the result is sampled now,
  // or is so far its agent's lowest-valued batch (the one PicksAtRoundEnd would pick). A SHA-256
  // of every accepted result cost the master more than the rest of accepting it.
  bool OnAccepted(uint32_t index, const std::string& agent,
                  const std::function<ResultDigest()>& digest);
  // Digests computed since this verifier was made (the counts tests check).
  uint64_t digests() const { return digests_; }
  // The round is complete: for each agent with results but none verified or pending, its batch
  // with the lowest SampleValue, now pending. Only the first call of a round picks.
  std::vector<uint32_t> PicksAtRoundEnd();
  // The master's digest of batch `index`: nullopt when the agent's bits agree.
  std::optional<Mismatch> OnVerified(uint32_t index, const ResultDigest& master);
  size_t pending() const { return pending_; }
  // The first round `agent` had a result accepted in since this verifier was made, if any.
  std::optional<uint32_t> FirstRoundOf(const std::string& agent) const;
  // `agent`'s accepted batches of the current round.
  std::vector<uint32_t> BatchesOf(const std::string& agent) const;

  uint64_t verified() const { return verified_; }
  uint64_t mismatched() const { return mismatched_; }

 private:
  enum class Check { kNone, kPending, kAgreed };
  struct Entry {
    uint32_t agent = 0;  // into names_
    ResultDigest digest{};
    Check check = Check::kNone;
  };
  uint32_t AgentIndex(const std::string& agent);

  double fraction_;
  uint64_t seed_;
  int64_t job_;
  uint32_t round_ = 0;
  bool picked_ = false;                          // PicksAtRoundEnd ran this round
  std::unordered_map<uint32_t, Entry> entries_;  // by batch index, the current round
  std::vector<std::string> names_;
  std::map<std::string, uint32_t, std::less<>> agent_index_;
  std::vector<uint32_t> first_round_;  // by agent index
  // By agent index, this round: its lowest (SampleValue, batch) not sampled, the round-end pick.
  std::vector<std::optional<std::pair<double, uint32_t>>> lowest_;
  uint64_t digests_ = 0;
  size_t pending_ = 0;
  uint64_t verified_ = 0;
  uint64_t mismatched_ = 0;
};

}  // namespace radfarm::daemon
