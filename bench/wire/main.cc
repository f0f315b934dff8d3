// wire_bench: what a LeaseResult's hits cost on the wire, in protocol version 4 (a 16-byte struct
// a hit) and version 5 (packed varints, core/packed_hits.h): bytes a hit, and the CPU an agent
// spends encoding and sealing a job's results and the master opening and decoding them, through
// the real ProtocolSession on one thread. The batches are synthetic, as a shooting round makes
// them: `rays` Sobol rays (weight 1 each) of one shooter landing on patches drawn uniformly from
// `patches`, summed per patch and sorted, until a job's worth of hits; they go in frames of about
// 60 KiB, cut as the agent cuts them in each version. Prints a table and writes
// bench/results/wire_bench.json.
//
//   wire_bench [--json PATH] [--repetitions N]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "bench/bench_json.h"
#include "bench/machine_info.h"
#include "bench/stopwatch.h"
#include "protocol/frame_codec.h"
#include "protocol/limits.h"
#include "protocol/protocol_session.h"

namespace radfarm::bench {
namespace {

using protocol::ProtocolSession;

struct Case {
  const char* name;
  uint32_t patches;
  uint32_t rays;  // per batch
};

// The Cornell job's loopback farm moved 3.4 million hits (55.9 MB of version-4 frames).
constexpr uint64_t kJobHits = 3'400'000;

std::vector<protocol::BatchOutcome> MakeBatches(const Case& c) {
  std::mt19937_64 rng(c.patches * 7919ull + c.rays);
  std::uniform_int_distribution<uint32_t> patch(0, c.patches - 1);
  std::vector<protocol::BatchOutcome> batches;
  uint64_t hits = 0;
  std::vector<uint32_t> landed(c.rays);
  while (hits < kJobHits) {
    protocol::BatchOutcome r{{1, batches.size() + 1, 1}, {}, 0, 0, 0, 0, 0.01};
    for (uint32_t& p : landed) p = patch(rng);
    std::sort(landed.begin(), landed.end());
    for (uint32_t p : landed) {
      if (!r.hits.empty() && r.hits.back().patch == p) {
        ++r.hits.back().weight;
      } else {
        r.hits.push_back({p, 1});
      }
    }
    hits += r.hits.size();
    batches.push_back(std::move(r));
  }
  return batches;
}

// The frames an agent speaking `version` sends: about kResultFrameBytes each, by its estimate
// (agent/lease_worker.cc SendGroup).
std::vector<protocol::LeaseResultMsg> Frames(const std::vector<protocol::BatchOutcome>& batches,
                                             uint16_t version) {
  std::vector<protocol::LeaseResultMsg> frames(1);
  size_t bytes = 0;
  for (const protocol::BatchOutcome& r : batches) {
    const size_t cost = protocol::ResultFrameCost(r, version);
    if (bytes + cost > protocol::kResultFrameBytes && !frames.back().results.empty()) {
      frames.emplace_back();
      bytes = 0;
    }
    frames.back().results.push_back(r);
    bytes += cost;
  }
  return frames;
}

struct Pair {
  ProtocolSession master, agent;
};

Pair Connected(uint16_t agent_version) {
  const protocol::FarmSecret secret = *protocol::FarmSecret::FromBytes(std::vector<uint8_t>(32, 7));
  Pair p{
      ProtocolSession::ForMaster(secret, protocol::MasterConfig{}),
      ProtocolSession::ForAgent(
          secret, protocol::AgentConfig{"bench", 2, protocol::kMinProtocolVersion, agent_version})};
  auto reply = p.master.Accept(*protocol::DecodeFrame(*p.agent.Start()));
  reply = p.agent.Accept(*protocol::DecodeFrame(reply->reply));
  reply = p.master.Accept(*protocol::DecodeFrame(reply->reply));
  (void)p.agent.Accept(*protocol::DecodeFrame(reply->reply));
  if (!p.master.authenticated() || p.master.version() != agent_version) {
    std::fprintf(stderr, "wire_bench: handshake in version %d failed\n", agent_version);
    std::exit(1);
  }
  return p;
}

struct Timing {
  double bytes = 0, encode_seconds = 0, decode_seconds = 0;
};

// Frame by frame, as an agent sends and a master receives them: each sealed frame is opened and
// dropped before the next is made, so the allocator reuses the same memory (keeping a whole job's
// frames measured the kernel's page faults on 56 MB of fresh memory instead).
Timing Measure(const std::vector<protocol::LeaseResultMsg>& frames, uint16_t version) {
  Pair p = Connected(version);
  Timing t;
  for (const protocol::LeaseResultMsg& m : frames) {
    const Stopwatch encode;
    const std::vector<uint8_t> sealed = *p.agent.Encode(m);
    t.encode_seconds += encode.Seconds();
    const Stopwatch decode;
    Result<protocol::DecodedFrame> d = p.master.Decode(std::span(sealed).subspan(4));
    t.decode_seconds += decode.Seconds();
    if (!d) {
      std::fprintf(stderr, "wire_bench: %s\n", d.error().c_str());
      std::exit(1);
    }
    t.bytes += double(sealed.size());
  }
  return t;
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

int Main(int argc, char** argv) {
  std::string json_path = DefaultJsonPath("wire_bench");
  int repetitions = 5;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--json" && i + 1 < argc) {
      json_path = argv[++i];
    } else if (arg == "--repetitions" && i + 1 < argc) {
      repetitions = std::max(1, std::atoi(argv[++i]));
    } else {
      std::printf(
          "usage: wire_bench [--json PATH] [--repetitions N]\n"
          "  A job's LeaseResult hits (3.4 million, synthetic batches) encoded and sealed by an\n"
          "  agent session and opened and decoded by a master session, in protocol version 4\n"
          "  (16-byte structs) and 5 (packed varints): bytes and CPU a hit, medians of N\n"
          "  alternated repetitions (default 5). Writes bench/results/wire_bench.json.\n");
      return arg == "--help" || arg == "-h" ? 0 : 2;
    }
  }
  const MachineInfo machine = ReadMachineInfo(argc, argv);
  const Stopwatch total;
  const std::vector<Case> cases = {{"Cornell box (3,849 patches), 170-ray batches", 3849, 170},
                                   {"Cornell box, 2,048-ray batches", 3849, 2048},
                                   {"10^6 patches, 170-ray batches", 1'000'000, 170}};
  std::printf("%-46s %8s %10s %10s %12s %12s %12s %12s\n", "case", "hits", "B/hit v4", "B/hit v5",
              "agent v4 ms", "agent v5 ms", "master v4 ms", "master v5 ms");
  nlohmann::json runs = nlohmann::json::array();
  for (const Case& c : cases) {
    const std::vector<protocol::BatchOutcome> batches = MakeBatches(c);
    const std::vector<protocol::LeaseResultMsg> frames[2] = {Frames(batches, 4),
                                                             Frames(batches, 5)};
    uint64_t hits = 0;
    for (const auto& r : batches) hits += r.hits.size();
    std::vector<double> encode[2], decode[2];
    double bytes[2] = {0, 0};
    for (int rep = 0; rep < repetitions; ++rep) {
      for (int v = 0; v < 2; ++v) {
        const int which = rep % 2 == 0 ? v : 1 - v;  // alternate the order
        const Timing t = Measure(frames[which], uint16_t(4 + which));
        encode[which].push_back(t.encode_seconds);
        decode[which].push_back(t.decode_seconds);
        bytes[which] = t.bytes;
      }
    }
    const double h = double(hits);
    std::printf("%-46s %8llu %10.2f %10.2f %12.1f %12.1f %12.1f %12.1f\n", c.name,
                static_cast<unsigned long long>(hits), bytes[0] / h, bytes[1] / h,
                1e3 * Median(encode[0]), 1e3 * Median(encode[1]), 1e3 * Median(decode[0]),
                1e3 * Median(decode[1]));
    nlohmann::json versions = nlohmann::json::array();
    for (int v = 0; v < 2; ++v) {
      versions.push_back({{"version", 4 + v},
                          {"bytes", bytes[v]},
                          {"bytes_per_hit", bytes[v] / h},
                          {"frames", frames[v].size()},
                          {"agent_encode_seal_seconds", encode[v]},
                          {"master_open_decode_seconds", decode[v]},
                          {"agent_seconds_median", Median(encode[v])},
                          {"master_seconds_median", Median(decode[v])}});
    }
    runs.push_back({{"case", c.name},
                    {"patches", c.patches},
                    {"rays_per_batch", c.rays},
                    {"hits", hits},
                    {"batches", batches.size()},
                    {"versions", versions}});
  }
  nlohmann::json out{{"machine", MachineJson(machine)},
                     {"repetitions", repetitions},
                     {"result_frame_bytes", protocol::kResultFrameBytes},
                     {"runs", runs},
                     {"total_seconds", total.Seconds()}};
  out["load_average_end"] = ReadLoadAverage();
  WriteJson(json_path, out);
  std::printf("wrote %s\n", json_path.c_str());
  return 0;
}

}  // namespace
}  // namespace radfarm::bench

int main(int argc, char** argv) { return radfarm::bench::Main(argc, argv); }
