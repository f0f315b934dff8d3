#include "daemon/jobs/batch_verifier.h"

#include <algorithm>

#include "protocol/scene_transfer.h"

namespace radfarm::daemon {
namespace {

void Put(std::vector<uint8_t>& out, uint64_t v) {
  for (int b = 0; b < 8; ++b) out.push_back(static_cast<uint8_t>(v >> (8 * b)));
}

uint64_t Mix(uint64_t x) {  // SplitMix64's finaliser
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

}  // namespace

ResultDigest DigestOf(const BatchResult& result) {
  std::vector<uint8_t> bytes;
  bytes.reserve(48 + 12 * result.hits.size());
  Put(bytes, result.hits.size());
  for (const PatchHits& h : result.hits) {
    Put(bytes, h.patch);
    Put(bytes, h.weight);
  }
  for (uint64_t v :
       {result.escaped_weight, result.escaped_rays, result.back_weight, result.back_rays}) {
    Put(bytes, v);
  }
  return protocol::HashScene(bytes);
}

std::string DigestHex(const ResultDigest& digest) { return protocol::HashToHex(digest); }

double SampleValue(uint64_t seed, int64_t job, uint32_t round, std::string_view agent,
                   uint32_t index) {
  uint64_t h = Mix(seed);
  h = Mix(h ^ static_cast<uint64_t>(job));
  h = Mix(h ^ round);
  for (char c : agent) h = Mix(h ^ static_cast<uint8_t>(c));
  h = Mix(h ^ (uint64_t{index} << 8) ^ agent.size());
  return double(h >> 11) * 0x1.0p-53;
}

BatchVerifier::BatchVerifier(double fraction, uint64_t seed, int64_t job)
    : fraction_(std::clamp(fraction, 0.0, 1.0)), seed_(seed), job_(job) {}

void BatchVerifier::StartRound(uint32_t round) {
  round_ = round;
  picked_ = false;
  entries_.clear();
  lowest_.assign(names_.size(), std::nullopt);
  pending_ = 0;
}

uint32_t BatchVerifier::AgentIndex(const std::string& agent) {
  const auto [it, added] = agent_index_.try_emplace(agent, static_cast<uint32_t>(names_.size()));
  if (added) {
    names_.push_back(agent);
    first_round_.push_back(round_);
    lowest_.emplace_back();
  }
  return it->second;
}

bool BatchVerifier::OnAccepted(uint32_t index, const std::string& agent,
                               const std::function<ResultDigest()>& digest) {
  if (!enabled()) return false;
  const uint32_t a = AgentIndex(agent);
  Entry& e = entries_[index];
  e = {a, {}, Check::kNone};
  const double value = SampleValue(seed_, job_, round_, agent, index);
  const bool sampled = value < fraction_;
  // Only the lowest-valued unsampled result of an agent can be picked at the round's end
  // (PicksAtRoundEnd takes the least (value, batch)), so only a new lowest needs its digest.
  const bool lowest = !sampled && (!lowest_[a] || std::pair(value, index) < *lowest_[a]);
  if (sampled || lowest) {
    e.digest = digest();
    ++digests_;
  }
  if (lowest) lowest_[a] = {value, index};
  if (!sampled) return false;
  e.check = Check::kPending;
  ++pending_;
  return true;
}

std::vector<uint32_t> BatchVerifier::PicksAtRoundEnd() {
  std::vector<uint32_t> picks;
  if (!enabled() || picked_) return picks;
  picked_ = true;
  // Per agent: whether one of its results is checked, else its lowest-valued batch (lowest_,
  // whose digest OnAccepted kept).
  std::vector<bool> covered(names_.size(), false);
  for (const auto& [index, e] : entries_)
    covered[e.agent] = covered[e.agent] || e.check != Check::kNone;
  for (size_t a = 0; a < names_.size(); ++a) {
    if (covered[a] || !lowest_[a]) continue;
    picks.push_back(lowest_[a]->second);
    entries_[lowest_[a]->second].check = Check::kPending;
    ++pending_;
  }
  std::sort(picks.begin(), picks.end());
  return picks;
}

std::optional<Mismatch> BatchVerifier::OnVerified(uint32_t index, const ResultDigest& master) {
  const auto it = entries_.find(index);
  if (it == entries_.end() || it->second.check != Check::kPending) return std::nullopt;
  Entry& e = it->second;
  --pending_;
  ++verified_;
  if (e.digest == master) {
    e.check = Check::kAgreed;
    return std::nullopt;
  }
  ++mismatched_;
  e.check = Check::kAgreed;  // decided: the caller discards the round
  return Mismatch{names_[e.agent], round_, index, e.digest, master};
}

std::optional<uint32_t> BatchVerifier::FirstRoundOf(const std::string& agent) const {
  const auto it = agent_index_.find(agent);
  if (it == agent_index_.end()) return std::nullopt;
  return first_round_[it->second];
}

std::vector<uint32_t> BatchVerifier::BatchesOf(const std::string& agent) const {
  std::vector<uint32_t> batches;
  const auto it = agent_index_.find(agent);
  if (it == agent_index_.end()) return batches;
  for (const auto& [index, e] : entries_) {
    if (e.agent == it->second) batches.push_back(index);
  }
  std::sort(batches.begin(), batches.end());
  return batches;
}

}  // namespace radfarm::daemon
