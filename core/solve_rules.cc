#include "core/solve_rules.h"

#include <string>

#include "core/direct_light.h"

namespace radfarm {
namespace {

std::string N(uint64_t n) { return std::to_string(n); }

std::string Plural(uint64_t n, const char* one, const char* many) {
  return N(n) + " " + (n == 1 ? one : many);
}

// Why the emitter patches are not in the start.
std::string WhyEmittersShoot(const DirectStartDecision& d, const SolverSettings& s) {
  switch (d.why) {
    case DirectStartDecision::kGatherOff:
      return "the final gather is off (gather_rays 0), and the start is priced against it";
    case DirectStartDecision::kNothingEmits:
      return "no patch emits";
    case DirectStartDecision::kManyEmitterPatches:
      return N(d.emitter_patches) + " of the " + N(d.patches) +
             " patches emit, more than a quarter (a furnace or a sky) and more than " +
             N(s.gather_rays / 16) + " (gather_rays / 16)";
    case DirectStartDecision::kManyLights:
      return Plural(d.lights, "light", "lights") + " per point need at least 16 points x " +
             N(kMinCappedLightRays) + " shadow rays each, more than the gather's " +
             N(s.gather_rays) + " rays (at most " + N(s.gather_rays / (16 * kMinCappedLightRays)) +
             " lights)";
    case DirectStartDecision::kBudget:
      return "the budget's share for it (" + N(d.allowance) + " shadow rays) does not give every " +
             "patch " + N(kMinCappedLightRays) + " rays per light";
    case DirectStartDecision::kEmitters:
    case DirectStartDecision::kEmittersCapped:
      break;
  }
  return {};
}

// The lights without a surface in words: "2 lamps", "the sky", "1 lamp and the sky".
std::string Surfaceless(const DirectStartDecision& d) {
  std::string out = d.lamps > 0 ? Plural(d.lamps, "lamp", "lamps") : "";
  if (d.sky) out += out.empty() ? "the sky" : " and the sky";
  return out;
}

}  // namespace

RuleOutcome DirectStartRule(const PatchScene& scene, const SolverSettings& settings) {
  const DirectStartDecision d = DecideDirectStart(scene, settings);
  RuleOutcome out;
  out.used = d.sections > 0;
  const std::string points = N(d.sections) + " x " + N(d.sections) + " points per patch";
  if (d.emitters) {
    std::string what =
        "from the direct light of " + Plural(d.emitter_patches, "emitter patch", "emitter patches");
    if (d.lamps > 0 || d.sky) what += " and " + Surfaceless(d);
    if (d.rays_per_light > 0) what += ", " + N(d.rays_per_light) + " shadow rays per light";
    out.why = what + ", at " + points;
    return out;
  }
  const std::string why = WhyEmittersShoot(d, settings);
  if (out.used) {  // lamps or the sky alone: they have no surface to shoot from
    out.why = "from the direct light of " + Surfaceless(d) + " alone, at " + points +
              "; the emitter patches shoot theirs: " + why;
  } else if (d.why == DirectStartDecision::kNothingEmits) {
    out.why = "not used: no patch emits and there is no lamp";
  } else {
    out.why = "not used: " + why + "; the emitter patches shoot their light in the rounds instead";
  }
  return out;
}

RuleOutcome DisplayRule(const PatchScene& scene, const SolverSettings& settings) {
  const RuleOutcome start = DirectStartRule(scene, settings);
  RuleOutcome out;
  out.used = start.used;
  if (out.used) {
    out.why =
        "at its own points: the direct light there, gathering near other surfaces and cuts where "
        "the light bends (the solve starts from the direct light)";
  } else {
    out.why =
        "the patches' averages, no rays of its own: the solve does not start from the "
        "direct light (" +
        start.why.substr(std::string("not used: ").size()) + ")";
  }
  return out;
}

}  // namespace radfarm
