#include "bench/conclusions.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace radfarm::bench {
namespace {

constexpr SamplerKind kSamplers[] = {SamplerKind::kGrid, SamplerKind::kRandom, SamplerKind::kSobol};

// Every point of one sampler (its line, the grid's step and to-tolerance runs), sorted by time and
// reduced to the lower envelope: each kept point has a lower error than every faster one. A sampler
// is judged by its best setting for the time.
std::vector<const SweepPoint*> Line(const SceneSweep& sweep, SamplerKind sampler,
                                    ErrorMeasure measure) {
  std::vector<const SweepPoint*> all;
  for (const auto* points : {&sweep.points, &sweep.grid_steps, &sweep.grid_converged}) {
    for (const SweepPoint& p : *points) {
      if (p.settings.sampler == sampler && p.seconds > 0 && p.*measure > 0) all.push_back(&p);
    }
  }
  std::sort(all.begin(), all.end(), [&](const SweepPoint* a, const SweepPoint* b) {
    return a->seconds != b->seconds ? a->seconds < b->seconds : a->*measure < b->*measure;
  });
  std::vector<const SweepPoint*> envelope;
  for (const SweepPoint* p : all) {
    if (envelope.empty() || p->*measure < envelope.back()->*measure) envelope.push_back(p);
  }
  return envelope;
}

std::string Name(SamplerKind kind) { return std::string(SamplerName(kind)); }

std::string Format(const char* format, double a, double b = 0, double c = 0) {
  char text[256];
  std::snprintf(text, sizeof text, format, a, b, c);
  return text;
}

// "grid 0.56 (5.8×), random 0.11 (1.2×), sobol 0.097"
std::string Scores(const SceneVerdict& v) {
  double best = 0;
  for (const auto& [s, score] : v.scores) {
    if (s == v.best) best = score;
  }
  std::string text;
  for (const auto& [s, score] : v.scores) {
    text +=
        (text.empty() ? "" : ", ") + Name(s) + Format(v.common_time ? " %.3g" : " %.3g s", score);
    if (s != v.best && best > 0) text += Format(" (%.3g×)", score / best);
  }
  return text;
}

std::string Aim(bool met) { return met ? "met" : "**not met**"; }

// The aim's verdict on the two error measures.
std::string Aim(bool lit, bool all) {
  if (lit == all) return Aim(lit);
  return std::string(lit ? "met" : "**not met**") + " on the lit patches, " +
         (all ? "met" : "**not met**") + " over all patches";
}

// "**sobol** has the lowest error for the time" or "random and sobol tie (within 15%)".
std::string Leaders(const SceneVerdict& v) {
  if (v.leaders.size() == 1) return "**" + Name(v.best) + "** has the lowest error for the time";
  std::string names;
  for (size_t i = 0; i < v.leaders.size(); ++i) {
    names += (i == 0 ? "" : i + 1 == v.leaders.size() ? " and " : ", ") + Name(v.leaders[i]);
  }
  return names + Format(" tie, within %.0f%%", 100 * (kTieRatio - 1));
}

}  // namespace

double ErrorAtTime(const SceneSweep& sweep, SamplerKind sampler, ErrorMeasure measure,
                   double seconds) {
  const std::vector<const SweepPoint*> line = Line(sweep, sampler, measure);
  if (line.empty() || seconds < line.front()->seconds || seconds > line.back()->seconds) return -1;
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    const SweepPoint& a = *line[i];
    const SweepPoint& b = *line[i + 1];
    if (seconds > b.seconds) continue;
    if (b.seconds == a.seconds) return std::min(a.*measure, b.*measure);
    const double f = std::log(seconds / a.seconds) / std::log(b.seconds / a.seconds);
    return std::exp(std::log(a.*measure) + f * std::log(b.*measure / a.*measure));
  }
  return line.back()->*measure;
}

SceneVerdict JudgeScene(const SceneSweep& sweep, ErrorMeasure measure) {
  SceneVerdict verdict;
  verdict.scene = sweep.scene;
  double earliest_end = std::numeric_limits<double>::infinity();
  double latest_start = 0;
  for (SamplerKind s : kSamplers) {
    const auto line = Line(sweep, s, measure);
    if (line.empty()) continue;
    earliest_end = std::min(earliest_end, line.back()->seconds);
    latest_start = std::max(latest_start, line.front()->seconds);
  }
  verdict.common_time = latest_start <= earliest_end;
  verdict.seconds = earliest_end;
  double best = std::numeric_limits<double>::infinity();
  for (SamplerKind s : kSamplers) {
    const auto line = Line(sweep, s, measure);
    if (line.empty()) continue;
    double score = std::numeric_limits<double>::infinity();
    if (verdict.common_time) {
      score = ErrorAtTime(sweep, s, measure, verdict.seconds);
    } else {
      // Error² × time: constant for an estimator whose error falls as 1 / sqrt(time).
      for (const SweepPoint* p : line)
        score = std::min(score, p->*measure * p->*measure * p->seconds);
    }
    verdict.scores.push_back({s, score});
    if (score < best) {
      best = score;
      verdict.best = s;
    }
  }
  for (const auto& [s, score] : verdict.scores) {
    if (score <= kTieRatio * best) verdict.leaders.push_back(s);
  }
  return verdict;
}

std::vector<std::string> Conclusions(const BenchReport& report) {
  std::vector<std::string> out;
  // Samplers that lead (or tie for the lead) on every scene and measure.
  std::vector<SamplerKind> always(std::begin(kSamplers), std::end(kSamplers));
  std::string text;
  for (const SceneSweep& sweep : report.sweeps) {
    const SceneVerdict lit = JudgeScene(sweep, &SweepPoint::error_lit);
    const SceneVerdict all = JudgeScene(sweep, &SweepPoint::error);
    for (const SceneVerdict* v : {&lit, &all}) {
      std::erase_if(always, [&](SamplerKind s) {
        return std::find(v->leaders.begin(), v->leaders.end(), s) == v->leaders.end();
      });
    }
    text += "On " + sweep.scene + ", ";
    text += lit.common_time
                ? Format(
                      "at %.3g s (the longest time every sampler reaches; each sampler judged "
                      "by its best setting for that time) ",
                      lit.seconds)
                : std::string("where the lines do not overlap in time, by best error² × seconds, ");
    text += "the lit patches' errors are " + Scores(lit) + " (" + Leaders(lit) +
            "); over all patches " + Scores(all) + " (" + Leaders(all) + "). ";
  }
  const SamplerKind current = SolverSettings{}.sampler;
  if (std::find(always.begin(), always.end(), current) != always.end()) {
    text += Name(current) +
            " leads or ties for the lead on every scene and measure, so it should "
            "stay the default (`SolverSettings::sampler`).";
  } else if (!always.empty()) {
    text += Name(always.front()) +
            " leads or ties for the lead on every scene and measure, so it "
            "should be the default; today the default is " +
            Name(current) + ".";
  } else {
    text += "No sampler leads on every scene and measure, so the default (" + Name(current) +
            ") stays until more scenes decide.";
  }
  out.push_back(text);

  std::string grid;
  for (const SceneSweep& sweep : report.sweeps) {
    for (const SweepPoint& p : sweep.grid_converged) {
      grid += (grid.empty() ? "" : ", ") +
              Format("%.3g (%g°, ", p.error_lit, p.settings.grid_step_degrees) +
              Format("%.3g s) on ", p.seconds) + sweep.scene;
    }
  }
  if (!grid.empty()) {
    out.push_back(
        "Run to the tolerance without a ray budget, the grid ends at lit-patch errors of " + grid +
        ": it shoots from each patch's centre along fixed directions, a biased estimate "
        "whose error stops falling at a level the random samplers pass early.");
  }

  const RawThroughput& raw = report.raw;
  out.push_back(
      Format("The solver's ray loop (BatchRunner: sampling, tracing, counting) runs at %.0f%% of a "
             "bare rtcIntersect1 loop over the same rays on the same %g threads, and at %.0f%% "
             "when scheduled by the thread pool as Solve() does",
             100 * raw.runner_over_raw, raw.threads, 100 * raw.pool_over_raw) +
      " (aim: at least 90%: " + Aim(raw.pool_over_raw >= 0.9 && raw.runner_over_raw >= 0.9) + ")." +
      (raw.same_hits ? ""
                     : " **The raw loop's hits differ from the solver's**: the comparison is not "
                       "like for like."));

  const SeedWorkload& seed = report.seed;
  const SweepPoint& eq = seed.equal_time.point;
  out.push_back(
      Format("The seed paper's workload (its room, 20 shots of a 1° grid) takes %.3g s here on "
             "all cores and %.3g s on one thread, against 187 s on a Pentium 4: ",
             seed.seed.seconds, seed.one_thread_seconds) +
      Format("%.0f× and %.0f× faster. ", kSeedPaperSeconds / seed.seed.seconds,
             kSeedPaperSeconds / seed.one_thread_seconds) +
      Format("In about that time (%.3g s against %.3g s, timed alternately) the default "
             "sampler's error is ",
             eq.seconds, seed.seed_seconds_alongside) +
      Format("%.1f× lower on the lit patches (%.3g against %.3g) ", seed.error_ratio_lit,
             eq.error_lit, seed.seed.error_lit) +
      Format("and %.1f× lower over all patches (%.3g against %.3g)", seed.error_ratio, eq.error,
             seed.seed.error) +
      " (aim: at least 10×: " + Aim(seed.error_ratio_lit >= 10, seed.error_ratio >= 10) + ")." +
      (seed.at_floor
           ? " No budget of the default sampler is as fast as the seed workload: the "
             "min_shooter_rays rays every shooter casts in every round set a floor on its time."
           : "") +
      " The seed method's error is mostly the light it has not yet shot: " +
      Format("%.0f%% of the emitted power is still unshot after 20 shots.",
             100 * seed.seed.unshot_fraction));
  return out;
}

}  // namespace radfarm::bench
