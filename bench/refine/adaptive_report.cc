#include "bench/refine/adaptive_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "base/atomic_file.h"
#include "bench/plot.h"

namespace radfarm::bench {
namespace {

std::string Fmt(double v, const char* f = "%.4f") {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::vector<const Row*> Group(const StudyResult& s, const std::string& group) {
  std::vector<const Row*> out;
  for (const Row& r : s.rows) {
    if (r.group == group) out.push_back(&r);
  }
  return out;
}

void WritePlots(const ReportRun& run, const StudyResult& s) {
  const std::vector<const Row*> uniform = Group(s, "uniform");
  const std::vector<const Row*> adaptive = Group(s, "adaptive");
  for (bool by_time : {true, false}) {
    PlotSpec spec;
    spec.png_path = run.out_dir + "/benchmarks-adaptive-" + s.scene.name +
                    (by_time ? "-time.png" : "-patches.png");
    spec.title = s.scene.name + ": adaptive refinement against uniform meshes";
    spec.x_label = by_time ? "seconds (all cores)" : "patches";
    for (bool image : {false, true}) {
      PlotPanel panel{image ? "image error" : "net RMS relative patch error (lit)",
                      image ? "mean |I - Iref| / mean Iref" : "RMS relative error",
                      {}};
      auto point = [&](const Row& r) {
        return std::pair<double, double>{by_time ? r.seconds : double(r.patches),
                                         image ? r.image_error : r.patch_error.net};
      };
      PlotSeries u{"uniform", {}, true, 0, 0};
      for (const Row* r : uniform) u.points.push_back(point(*r));
      panel.series.push_back(u);
      for (double start : s.scene.adaptive_starts) {
        PlotSeries a{"adaptive from " + Fmt(start, "%g"), {}, true, 0, 0};
        for (const Row* r : adaptive) {
          if (r->start_size == start) a.points.push_back(point(*r));
        }
        panel.series.push_back(a);
      }
      for (const std::string group : {"floor", "sampler", "solver", "gather", "budget"}) {
        for (const Row* r : Group(s, group)) {
          panel.series.push_back({r->method, {point(*r)}, false, 0, 0});
        }
      }
      spec.panels.push_back(panel);
    }
    if (std::string err = WritePlot(spec); !err.empty()) std::fprintf(stderr, "%s\n", err.c_str());
  }
}

void WriteTable(const StudyResult& s, std::ostringstream& md) {
  md << "| method | setting | patches before | patches after | rays | seconds | patch error | "
        "reference noise | net patch error | image error | direct part | bounced part | "
        "display error |\n"
        "|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  auto part = [](double e) { return e < 0 ? std::string("-") : Fmt(e); };
  for (const Row& r : s.rows) {
    md << "| " << r.method << " | " << r.setting << " | " << r.patches_before << " | " << r.patches
       << " | " << r.rays << " | " << Fmt(r.seconds, "%.2f") << " | " << Fmt(r.patch_error.measured)
       << " | " << Fmt(r.patch_error.reference_noise) << " | " << Fmt(r.patch_error.net) << " | "
       << Fmt(r.image_error) << " | " << part(r.direct_image_error) << " | "
       << part(r.bounced_image_error) << " | " << part(r.display_image_error) << " |\n";
  }
}

// The meshing aim, on the image error: the best uniform mesh against the adaptive row that
// reaches its error with the fewest patches.
bool WriteMeshingAim(const StudyResult& s, std::ostringstream& md) {
  const std::vector<const Row*> uniform = Group(s, "uniform");
  const Row* best = nullptr;
  for (const Row* r : uniform) {
    if (best == nullptr || r->image_error < best->image_error) best = r;
  }
  if (best == nullptr) return false;
  const Row* match = nullptr;
  for (const Row* r : Group(s, "adaptive")) {
    if (r->image_error <= best->image_error && (!match || r->patches < match->patches)) match = r;
  }
  md << "- **" << s.scene.name << "**: best uniform mesh " << best->setting << ", image error "
     << Fmt(best->image_error) << " with " << best->patches << " patches in "
     << Fmt(best->seconds, "%.2f") << " s";
  if (const std::vector<const Row*> floor = Group(s, "floor"); !floor.empty()) {
    // How far below the best uniform mesh any mesh can go at these rays.
    md << " (the reference's own mesh, " << floor[0]->patches
       << " patches: " << Fmt(floor[0]->image_error) << ")";
  }
  md << ". ";
  if (match == nullptr) {
    md << "No adaptive row reaches it: **not met**.\n";
    return false;
  }
  const double ratio = double(best->patches) / double(match->patches);
  const bool met = ratio >= 2 && match->seconds < best->seconds;
  md << "Adaptive " << match->setting << " reaches " << Fmt(match->image_error) << " with "
     << match->patches << " elements (" << Fmt(ratio, "%.1f") << "x fewer) in "
     << Fmt(match->seconds, "%.2f") << " s (" << Fmt(best->seconds / match->seconds, "%.1f")
     << "x less time): " << (met ? "**met**" : "**not met**") << ".\n";
  return met;
}

void WriteOnePercentAim(const StudyResult& s, std::ostringstream& md) {
  md << "- Default settings of `" << s.scene.name << ".toml` (uniform patch size "
     << Fmt(s.scene.default_size, "%g") << ", Sobol, automatic rays, final gather), the same "
     << "mesh with more rays, and without the gather:";
  const Row* fastest = nullptr;
  for (const Row& r : s.rows) {
    const bool default_mesh = r.start_size == s.scene.default_size && r.refine_tolerance == 0;
    const bool shooting_only = r.method == "no final gather";
    if (!default_mesh || (r.group != "uniform" && r.group != "budget" && !shooting_only)) continue;
    md << " " << r.method << ": " << Fmt(100 * r.patch_error.net, "%.2f") << "% in "
       << Fmt(r.seconds, "%.2f") << " s;";
    if (r.patch_error.net <= 0.01 && (!fastest || r.seconds < fastest->seconds)) fastest = &r;
  }
  md << " 1% net RMS patch error in under 2 s: ";
  if (fastest == nullptr) {
    md << "**not met** by any of these rows.\n";
  } else {
    md << (fastest->seconds < 2 ? "**met**" : "**not met**") << " (first reached by "
       << fastest->method << " in " << Fmt(fastest->seconds, "%.2f") << " s).\n";
  }
}

// The image error a uniform mesh of `patches` patches would have: log-log interpolation between
// the uniform rows around it (NAN outside their range).
double UniformImageErrorAt(const StudyResult& s, double patches) {
  const std::vector<const Row*> uniform = Group(s, "uniform");
  for (size_t i = 0; i + 1 < uniform.size(); ++i) {
    const Row& a = *uniform[i];
    const Row& b = *uniform[i + 1];
    const double lo = std::min(a.patches, b.patches), hi = std::max(a.patches, b.patches);
    if (patches < lo || patches > hi || lo == hi) continue;
    const double t =
        std::log(patches / double(a.patches)) / std::log(double(b.patches) / double(a.patches));
    return std::exp(std::log(a.image_error) +
                    t * (std::log(b.image_error) - std::log(a.image_error)));
  }
  return NAN;
}

const Row* UniformAt(const StudyResult& s, double size) {
  for (const Row* r : Group(s, "uniform")) {
    if (r->start_size == size) return r;
  }
  return nullptr;
}

const Row* FindRow(const StudyResult& s, const std::string& group, const std::string& prefix) {
  for (const Row& r : s.rows) {
    if (r.group == group && r.method.rfind(prefix, 0) == 0) return &r;
  }
  return nullptr;
}

// The display's cost against the solve's, over the rows whose solve took at least 0.5 s (shorter
// ones are timer noise).
std::string DisplayShare(const std::vector<StudyResult>& studies) {
  std::vector<double> shares;
  for (const StudyResult& s : studies) {
    for (const Row& r : s.rows) {
      if (r.seconds >= 0.5) shares.push_back(r.display_seconds / r.seconds);
    }
  }
  if (shares.empty()) return "no row took 0.5 s or more";
  std::sort(shares.begin(), shares.end());
  return "over the rows that took 0.5 s or more, the display took a median " +
         Fmt(100 * shares[shares.size() / 2], "%.1f") + "% and at most " +
         Fmt(100 * shares.back(), "%.1f") + "% of the solve's time (one run each)";
}

void WriteDefaults(const std::vector<StudyResult>& studies, std::ostringstream& md) {
  md << "\n## Defaults\n\n";
  md << "- **Refinement** (`refine`): an adaptive row *beats uniform* when its image error is "
        "below that of a uniform mesh with as many patches (log-log interpolation between the "
        "uniform rows).";
  for (const StudyResult& s : studies) {
    int beats = 0, judged = 0;
    double best_gain = 0;
    std::string best;
    for (const Row* r : Group(s, "adaptive")) {
      const double uniform = UniformImageErrorAt(s, double(r->patches));
      if (!std::isfinite(uniform)) continue;
      ++judged;
      if (r->image_error < uniform) ++beats;
      if (uniform / r->image_error > best_gain) {
        best_gain = uniform / r->image_error;
        best = r->setting;
      }
    }
    md << " " << s.scene.name << ": " << beats << " of " << judged << " rows";
    if (!best.empty()) {
      md << " (best: " << best << ", " << Fmt(best_gain, "%.2f") << "x lower than uniform)";
    }
    md << ";";
  }
  md << " rows outside the uniform range are not judged. Refinement pays where the light has "
        "edges sharper than the mesh (the hard-shadow scene's small light). In rooms lit by one "
        "large area light the image error left is spread over every surface: the Gouraud "
        "image's error on smooth light (fall-off, the darkening toward corners), which a finer "
        "uniform mesh lowers everywhere and refinement only where an element's score passes "
        "the tolerance (the lowest tolerances refine nearly everywhere, as a uniform mesh "
        "would), and ray noise. So `refine` stays **off** by default, to be turned on for "
        "scenes with small lights or sharp shadows, starting from the patch size one would use "
        "without it (the rows from twice that size lose: their coarse elements miss the smooth "
        "light).\n";
  md << "- **`refine_tolerance` = 0.1** (the default): the score is the Gouraud image's error "
        "over the element as a fraction of its radiance, so a tolerance far below the ray noise "
        "(about 3% per element with the automatic rays) buys elements the noise then hides.";
  for (const StudyResult& s : studies) {
    const Row *a = nullptr, *b = nullptr;
    for (const Row* r : Group(s, "adaptive")) {
      if (r->start_size != s.scene.default_size) continue;
      if (r->refine_tolerance == 0.1) a = r;
      if (r->refine_tolerance == 0.01) b = r;
    }
    if (a && b) {
      md << " " << s.scene.name << " from " << Fmt(s.scene.default_size, "%g") << ": 0.1 -> 0.01 "
         << "takes " << a->patches << " -> " << b->patches << " elements and the image error "
         << Fmt(a->image_error) << " -> " << Fmt(b->image_error) << ";";
    }
  }
  md << " `min_element_size` defaults to the patch size / 4 and `max_elements` to 8x the "
        "initial patches (the rows here refine to the reference's size, below which they could "
        "not be judged).\n";
  md << "- **Sampler**: Sobol stays the default.";
  for (const StudyResult& s : studies) {
    const Row* sobol = UniformAt(s, s.scene.default_size);
    const Row* random = FindRow(s, "sampler", "random");
    const Row* grid = FindRow(s, "sampler", "grid 4");
    if (sobol && random && grid) {
      md << " " << s.scene.name << ": net patch error Sobol " << Fmt(sobol->patch_error.net)
         << ", random " << Fmt(random->patch_error.net) << " (same rays), grid "
         << Fmt(grid->patch_error.net) << " ("
         << Fmt(double(grid->rays) / double(sobol->rays), "%.1f") << "x the rays);";
    }
  }
  md << " the seed's method (1° grid, 20 shots) is far from converged at any mesh.\n";
  md << "- **Over-relaxation** (`overrelaxation`, default 1 = plain Southwell):";
  for (const StudyResult& s : studies) {
    const Row* plain = UniformAt(s, s.scene.default_size);
    if (!plain) continue;
    md << " " << s.scene.name << ": plain " << plain->rays << " rays, net patch error "
       << Fmt(plain->patch_error.net);
    for (const Row* r : Group(s, "solver")) {
      md << "; " << r->method << " " << r->rays << " rays, " << Fmt(r->patch_error.net);
    }
    md << ";";
  }
  md << " a Monte Carlo shot of overshot (negative) light costs rays like any other, so "
        "over-relaxation saves rounds and rays only where the unshot power converges slowly (high "
        "reflectance, see tests/core/overrelaxation_test.cc); it stays off by default unless "
        "these rows show it saving rays at equal error.\n";
  md << "- **Final gather** (`gather_rays`, default 2048):";
  for (const StudyResult& s : studies) {
    const Row* gathered = UniformAt(s, s.scene.default_size);
    const Row* shooting = FindRow(s, "gather", "no final gather");
    if (!gathered || !shooting) continue;
    md << " " << s.scene.name << ": without it " << Fmt(100 * shooting->patch_error.net, "%.2f")
       << "% net patch error in " << Fmt(shooting->seconds, "%.2f") << " s, with it "
       << Fmt(100 * gathered->patch_error.net, "%.2f") << "% in " << Fmt(gathered->seconds, "%.2f")
       << " s (image error " << Fmt(shooting->image_error) << " -> " << Fmt(gathered->image_error)
       << ");";
  }
  md << " a shot's noise on an element is that of the hits it receives, so small elements are "
        "noisy; a gather's is that of the element's own rays, the same for every element, and it "
        "averages the shooting noise of everything the element sees. The direct light, computed "
        "at the element, has no ray noise outside penumbrae. So the gather is on by default; a "
        "refining solve gathers from its restart point on (before it, refinement finds shadows "
        "from the light the emitters shoot).\n";
  md << "- **Rays** (automatic `shot_rays`, 384 per element, and 2048 gather rays per element): if "
        "the net patch error squared is "
        "a floor that rays do not lower plus ray noise falling as 1 / rays, the rows with more "
        "rays split the default mesh's error into the two:";
  for (const StudyResult& s : studies) {
    const Row* plain = UniformAt(s, s.scene.default_size);
    const Row* more = FindRow(s, "budget", "default, ");
    if (!plain || !more || !(more->rays > plain->rays)) continue;
    const double k = double(more->rays) / double(plain->rays);
    const double m1 = plain->patch_error.net, mk = more->patch_error.net;
    const double floor2 = std::max(0.0, (k * mk * mk - m1 * m1) / (k - 1));
    md << " " << s.scene.name << ": floor " << Fmt(100 * std::sqrt(floor2), "%.2f") << "%, noise "
       << Fmt(100 * std::sqrt(std::max(0.0, m1 * m1 - floor2)), "%.2f")
       << "% at the automatic rays;";
  }
  md << " the floor is discretisation: an element's light is computed from shooters taken as "
        "uniform over their area, which fails where light changes within an element (the "
        "blocks' contacts with the floor, the corners). Where it is near or above 1%, 1% RMS "
        "patch error is out of reach of more rays on that mesh; below it, the noise falls as "
        "1 / sqrt(rays).\n";
}

}  // namespace

void WriteAdaptiveReport(const ReportRun& run, const std::vector<StudyResult>& studies) {
  std::ostringstream md;
  md << "# Adaptive refinement: speed against error\n\n"
     << "Generated by `refine_bench` (bench/refine_bench.cc, bench/refine/); do not edit by hand: "
        "rerun it.\n\n"
     << "Machine: " << run.machine << ". " << (run.quick ? "**Quick run** (smoke sizes). " : "")
     << "Every row's time is the **median of " << (run.quick ? "1 run" : "3 runs")
     << "** (bit-identical solves) on all cores of a shared machine: compare within a table, "
        "not with other days.\n\n"
     << "## Method\n\n"
     << "- Every solve: a job's defaults unless named: sampler Sobol, tolerance 0.001, seed 1, "
        "the **final gather** (`gather_rays` 2048: the solve starts from the direct light "
        "computed at each element, shoots the bounced light with automatic `shot_rays` of 384 "
        "per element, at least 65536, then every element gathers with 2048 rays; "
        "core/progressive_solver.h). The grid rows and the seed's method do not gather: they "
        "shoot everything with 1024 rays per element. Refining rows shoot the rounds before "
        "their restart point with a quarter of that and gather after it, on the refined mesh "
        "(a refined mesh gets the rays of its element count).\n"
     << "- **Reference**: a uniform mesh at the adaptive runs' minimum element size, solved twice "
        "(seeds 1000003 and 2000003, tolerance 1e-4); their mean is the reference, half their "
        "difference its noise. The row *the reference's mesh* solves that mesh like the others "
        "(a job's defaults, seed 1): it shares the reference's discretisation, so its error is "
        "the noise of both, the floor under every row at these rays, and it is not a uniform "
        "row the aims compare with.\n"
     << "- **Patch error**: for each element, the reference over it (its bounced light, the "
        "reference radiosity less rho times the direct light, averaged at 16 points spread evenly "
        "over the element; plus rho times the direct light averaged over 6 x 6 jittered points "
        "of the element itself, so a penumbra counts where it falls and not where the "
        "reference mesh's 12.5 mm patches put it) against the element's radiosity: RMS of (B - "
        "Bref) / Bref over "
        "the lit elements (Bref >= 1% of the median; not the ceiling above a light hanging just "
        "under it, which no view sees), weighted by area. The **reference noise** "
        "is the same measure of the reference's half difference on those elements; the **net** "
        "error subtracts it in quadrature. It measures how well each element's value is "
        "computed, not the detail a coarse element cannot show.\n"
     << "- **Image error**: mean over pixels of |I - Iref| (linear, channel sum, Gouraud-shaded "
        "from vertex radiance as `radfarm render` shades it: where the solve started from the "
        "direct light, the display triangles are cut at their edge midpoints and every vertex "
        "and midpoint shows the direct light computed at it plus the rest averaged over its "
        "elements, moved by its elements' shortfall of Gouraud mean against mean light, "
        "`PatchMesh::SetSolution`; 256 x 256, 4 samples per pixel) "
        "over the mean of Iref: smeared "
        "shadows, Mach bands, leaks and blotches count. This is the measure meshes are compared "
        "by. **Iref** is not the reference mesh's own Gouraud image (a uniform mesh would then be "
        "judged by how much it looks like another uniform mesh): at every subpixel sample the "
        "light straight from the emitters is computed at the sample's surface point (the "
        "closed-form form factor of each light element times the share of 64 shadow rays to it "
        "that arrive), and only the rest of the reference radiosity (emission and light that "
        "bounced, which is smooth) is Gouraud-shaded from the reference mesh "
        "(bench/refine/reference_image.h).\n"
     << "- **Direct part, bounced part**: where the solve started from the direct light, the "
        "image error of each of the display's two parts shaded alone (the direct light computed "
        "at the vertices and midpoints and moved to the elements' mean direct light, against "
        "Iref's direct "
        "light per sample; the rest averaged over elements, without the move, against Iref's "
        "Gouraud-shaded rest), over the mean of the whole Iref "
        "(`MeasureImagePartErrors`). Refinement can only act on what an element's interpolation "
        "gets wrong where the light bends; a part whose error is spread evenly over every "
        "surface is lowered only by finer elements everywhere.\n"
     << "- **Display error**: where the solve started from the direct light, the image error "
        "when every element holds the reference's bounced light over it (at the 16 points the "
        "patch error uses) beside its own direct light, shaded as the row's solution is "
        "(`MeasureDisplayError`): the solve's noise and its element values' errors are gone, "
        "what is left is what the display's reconstruction costs against Iref's (itself a "
        "Gouraud image of the reference mesh's bounced light) and the reference's noise. On the "
        "reference's own mesh it shows how finely the image error can tell meshes apart.\n"
     << "- **Time**: `SolveRefining` wall time (meshing excluded, refinement included), the "
        "median of the row's runs. The vertex radiance and display mesh are not included: "
     << DisplayShare(studies) << ".\n\n";
  for (const StudyResult& s : studies) {
    WritePlots(run, s);
    md << "## " << s.scene.name << "\n\n"
       << "`scenes/" << s.scene.name << ".toml`'s scene and camera. Reference: patch size "
       << Fmt(s.scene.reference_size, "%g") << " (" << s.reference_patches
       << " patches), shot_rays " << s.scene.reference_shot_rays << " per solve, "
       << s.reference_rays << " rays in " << Fmt(s.reference_seconds, "%.1f") << " s.\n\n";
    WriteTable(s, md);
    md << "\n![" << s.scene.name << ": error against time](benchmarks-adaptive-" << s.scene.name
       << "-time.png)\n\n![" << s.scene.name << ": error against patch count](benchmarks-adaptive-"
       << s.scene.name << "-patches.png)\n\n";
  }
  md << "## Aims\n\nAdaptive meshing reaches the image error of the best uniform mesh with at "
        "least 2x fewer patches and less time:\n\n";
  for (const StudyResult& s : studies) WriteMeshingAim(s, md);
  md << "\nThe default settings reach 1% RMS patch error on the Cornell box in under 2 "
        "seconds:\n\n";
  for (const StudyResult& s : studies) {
    if (s.scene.name == "cornell-box") WriteOnePercentAim(s, md);
  }
  WriteDefaults(studies, md);
  md << "\nTotal run time " << Fmt(run.total_seconds, "%.0f") << " s"
     << (run.reference_cache ? " (references read from `--reference-cache` where solved before: "
                               "their rays and seconds are those of the run that solved them)"
                             : "")
     << ".\n";
  const std::string path = run.out_dir + "/BENCHMARKS-adaptive.md";
  if (Status written = WriteFileAtomically(path, md.str()); !written) {
    std::fprintf(stderr, "%s\n", written.error().c_str());
    return;
  }
  std::printf("wrote %s\n", path.c_str());
}

}  // namespace radfarm::bench
