#include "codec/job_solution.h"

#include <flatbuffers/flatbuffers.h>

#include <string>

#include "base/result.h"
#include "codec/decode_checks.h"
#include "job_solution_generated.h"

namespace radfarm::codec {
namespace {

constexpr std::string_view kKind = "job solution";

std::vector<Rgb> FromWire(const flatbuffers::Vector<const wire::SolutionColour*>& in) {
  std::vector<Rgb> out;
  out.reserve(in.size());
  for (flatbuffers::uoffset_t i = 0; i < in.size(); ++i) {
    const wire::SolutionColour c = StructAt(in, i);
    out.push_back({c.r(), c.g(), c.b()});
  }
  return out;
}

}  // namespace

std::vector<uint8_t> EncodeJobSolution(const JobSolution& solution) {
  flatbuffers::FlatBufferBuilder fbb(1024 + solution.bundle.size() + solution.scene.size() +
                                     solution.display.size() + solution.radiosity.size() * 48);
  const auto bundle = fbb.CreateVector(solution.bundle);
  std::vector<wire::SolutionColour> colours;
  colours.reserve(solution.radiosity.size());
  for (const Rgb& c : solution.radiosity) colours.push_back({c.r, c.g, c.b});
  const auto radiosity = fbb.CreateVectorOfStructs(colours);
  colours.clear();
  for (const Rgb& c : solution.unshot) colours.push_back({c.r, c.g, c.b});
  const auto unshot = fbb.CreateVectorOfStructs(colours);
  const SolveStats& s = solution.stats;
  const auto stats = wire::CreateSolutionStats(
      fbb, s.rays, s.rounds, s.seconds, s.rays_per_second, s.patches, s.unshot_fraction,
      s.escaped_rays, s.backface_hits, s.threads, s.seed, fbb.CreateString(s.sampler),
      fbb.CreateString(s.stop_reason), s.emitted_power, s.absorbed_power, s.escaped_power);
  flatbuffers::Offset<flatbuffers::Vector<uint8_t>> scene = 0;
  if (!solution.scene.empty()) scene = fbb.CreateVector(solution.scene);
  flatbuffers::Offset<flatbuffers::Vector<uint8_t>> display = 0;
  if (!solution.display.empty()) display = fbb.CreateVector(solution.display);
  fbb.Finish(wire::CreateJobSolutionBlob(fbb, bundle, radiosity, unshot, stats, scene, display),
             "RDJS");
  return {fbb.GetBufferPointer(), fbb.GetBufferPointer() + fbb.GetSize()};
}

Result<JobSolution> DecodeJobSolution(std::span<const uint8_t> blob) {
  std::vector<uint8_t> aligned;
  Result<const wire::JobSolutionBlob*> verified = VerifiedRoot<wire::JobSolutionBlob>(
      blob, kKind, "RDJS", &wire::VerifyJobSolutionBlobBuffer, &aligned);
  RADFARM_RETURN_IF_ERROR(verified);
  const wire::JobSolutionBlob* root = *verified;
  JobSolution solution;
  solution.bundle.assign(root->bundle()->begin(), root->bundle()->end());
  if (root->scene()) solution.scene.assign(root->scene()->begin(), root->scene()->end());
  if (root->display()) solution.display.assign(root->display()->begin(), root->display()->end());
  solution.radiosity = FromWire(*root->radiosity());
  solution.unshot = FromWire(*root->unshot());
  if (solution.radiosity.size() != solution.unshot.size()) {
    return FieldError(kKind, "unshot", "has a different size than radiosity");
  }
  // Finite, but either sign: with over-relaxation (SolverSettings::overrelaxation > 1) unshot
  // radiosity goes negative, and so may a patch's radiosity estimate where negative light's
  // Monte Carlo noise outweighs the light it received (docs/SOLVER.md, "Over-relaxation").
  for (size_t i = 0; i < solution.radiosity.size(); ++i) {
    if (!IsFinite(solution.radiosity[i]) || !IsFinite(solution.unshot[i])) {
      return FieldError(kKind, "patch " + std::to_string(i), "radiosity is not finite");
    }
  }
  const auto* st = root->stats();
  SolveStats& s = solution.stats;
  s.rays = st->rays();
  s.rounds = st->rounds();
  s.seconds = st->seconds();
  s.rays_per_second = st->rays_per_second();
  s.patches = st->patches();
  s.unshot_fraction = st->unshot_fraction();
  s.escaped_rays = st->escaped_rays();
  s.backface_hits = st->backface_hits();
  s.threads = st->threads();
  s.seed = st->seed();
  s.sampler = st->sampler() ? st->sampler()->str() : "";
  s.stop_reason = st->stop_reason() ? st->stop_reason()->str() : "";
  s.emitted_power = st->emitted_power();
  s.absorbed_power = st->absorbed_power();
  s.escaped_power = st->escaped_power();
  for (double v : {s.seconds, s.rays_per_second, s.unshot_fraction, s.emitted_power,
                   s.absorbed_power, s.escaped_power}) {
    if (!std::isfinite(v)) return FieldError(kKind, "stats", "has a non-finite number");
  }
  return solution;
}

}  // namespace radfarm::codec
