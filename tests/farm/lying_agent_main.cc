// radfarm-lying-agent (tests only): radfarm-agent's own main (agent/main.cc is compiled in) with
// a result tamper installed before main runs. It traces every batch correctly, then on a
// fraction of them moves a millionth of one hit patch's weight (at least 1) to another hit
// patch: the ray and weight totals still add up, so the result passes CheckBatchOutcome and
// only exact validation (daemon/jobs/batch_verifier.h) can tell. RADFARM_TEST_LIE_FRACTION (0..1,
// default 1) says on which share of batches, chosen from the batch itself, so it is reproducible;
// RADFARM_TEST_LIE_LATER=1 makes it honest in the first round it traces and lying in every later
// one: an agent whose honest results were already reduced when it is caught. (A fixed round would
// not do: which rounds an agent gets work in depends on how fast the others take the leases.)
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "agent/tracer_pool.h"

namespace {

double EnvNumber(const char* name, double otherwise) {
  const char* text = std::getenv(name);
  return text == nullptr ? otherwise : std::strtod(text, nullptr);
}

uint64_t Mix(uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

void Perturb(const radfarm::Batch& batch, radfarm::BatchResult& result) {
  static const double fraction = EnvNumber("RADFARM_TEST_LIE_FRACTION", 1);
  static const bool later = EnvNumber("RADFARM_TEST_LIE_LATER", 0) != 0;
  static std::atomic<int64_t> first_round{-1};
  int64_t expected = -1;
  first_round.compare_exchange_strong(expected, int64_t{batch.round});
  if (later && int64_t{batch.round} <= first_round.load()) return;
  const uint64_t h = Mix(Mix(Mix(batch.round) ^ batch.shooter) ^ batch.first_ray);
  if (double(h >> 11) * 0x1.0p-53 >= fraction) return;
  if (result.hits.size() < 2) return;  // nothing to move weight between: an honest answer
  auto& hits = result.hits;
  size_t from = 0;  // the heaviest hit gives
  for (size_t i = 1; i < hits.size(); ++i) {
    if (hits[i].weight > hits[from].weight) from = i;
  }
  const uint64_t delta = std::max<uint64_t>(1, hits[from].weight / 1000000);
  if (hits[from].weight <= delta) return;
  hits[from].weight -= delta;
  hits[from == 0 ? 1 : 0].weight += delta;
}

[[maybe_unused]] const bool installed = (radfarm::agent::SetResultTamperForTesting(&Perturb), true);

}  // namespace
