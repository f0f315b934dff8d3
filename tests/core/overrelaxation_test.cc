// Over-relaxed Southwell (SolverSettings::overrelaxation): omega = 1 is plain Southwell to the bit,
// omega > 1 converges to the same solution, keeps the energy account and the determinism contract.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "core/batch_tracer.h"
#include "core/progressive_solver.h"
#include "core/ray_caster.h"
#include "solve/local_solve.h"
#include "tests/core/test_scenes.h"

namespace radfarm {
namespace {

using testing::BitIdentical;
using testing::LitBox;

// FNV-1a over the bits of a solve's state.
class BitHash {
 public:
  void Add(const void* data, size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) hash_ = (hash_ ^ bytes[i]) * 1099511628211ull;
  }
  void Add(const std::vector<Rgb>& v) { Add(v.data(), v.size() * sizeof(Rgb)); }
  uint64_t value() const { return hash_; }

 private:
  uint64_t hash_ = 14695981039346656037ull;
};

uint64_t HashOf(const SolveResult& r) {
  BitHash h;
  h.Add(r.radiosity);
  h.Add(r.unshot);
  for (double d : {r.stats.emitted_power, r.stats.absorbed_power, r.stats.escaped_power,
                   r.stats.unshot_fraction}) {
    h.Add(&d, sizeof d);
  }
  h.Add(&r.stats.rays, sizeof r.stats.rays);
  h.Add(&r.stats.rounds, sizeof r.stats.rounds);
  return h.value();
}

// The hashes were recorded with the solver as it was before over-relaxation existed (main at
// 8894e74), so omega = 1 must keep every bit of plain Southwell: radiosity, unshot, energy, rays.
TEST(OverrelaxationTest, OmegaOneIsPlainSouthwellToTheBit) {
  SolverSettings s;
  s.shot_rays = 1 << 16;
  s.tolerance = 0.01;
  s.threads = 2;
  ASSERT_EQ(s.overrelaxation, 1.0);  // the default
  const SolveResult sobol = Solve(LitBox(), s);
  EXPECT_EQ(sobol.stats.rounds, 10u);
  EXPECT_EQ(sobol.stats.rays, 146013u);
  EXPECT_EQ(HashOf(sobol), 0x0b7587c8af91a2eeull);
  s.sampler = SamplerKind::kGrid;
  s.grid_step_degrees = 5;
  s.shooters_per_round = 4;
  const SolveResult grid = Solve(LitBox(), s);
  EXPECT_EQ(grid.stats.rounds, 118u);
  EXPECT_EQ(grid.stats.rays, 607824u);
  EXPECT_EQ(HashOf(grid), 0xfc717e9e49b6e66eull);
}

// The first round of a lone emitter: it shoots omega times its power and keeps 1 - omega of it
// (negative), its radiosity stays its emission, and the next round gives it rays by the magnitude
// of that negative unshot power, times omega.
TEST(OverrelaxationTest, ShooterKeepsOneMinusOmegaAndIsRankedByMagnitude) {
  const PatchScene scene = LitBox();
  const uint32_t light = 3 * 16 + 5;
  SolverSettings s;
  s.shot_rays = 1 << 16;
  s.overrelaxation = 1.5;
  ProgressiveSolver solver(scene, s);
  const RoundPlan first = solver.PlanRound(4096);
  ASSERT_EQ(first.shots.size(), 1u);
  EXPECT_EQ(first.shots[0].rays, uint64_t{3} << 15);  // omega * shot_rays: all the power, x 1.5
  const RayCaster caster(scene);
  BatchTracer runner(scene, caster, solver.sampler());
  std::vector<BatchResult> results;
  for (const Batch& b : first.batches) results.push_back(runner.Run(b));
  solver.ApplyRound(first, results);

  EXPECT_EQ(solver.unshot()[light], Rgb(-5, -5, -5));
  EXPECT_EQ(solver.radiosity()[light], Rgb(10, 10, 10));
  const double area = scene.patches[light].area;
  // 15 A per channel went out and all of it landed (closed box); receivers keep rho of it as
  // unshot. The light's -5 per channel counts by its magnitude in the convergence measure.
  EXPECT_LT(solver.SignedUnshotPower(), solver.energy().unshot);
  double received = 0;
  for (uint32_t i = 0; i < scene.patches.size(); ++i) {
    if (i != light) received += scene.patches[i].area * solver.unshot()[i].Sum();
  }
  EXPECT_NEAR(received, 15 * area * (0.7 + 0.5 + 0.3), 1e-12);
  EXPECT_NEAR(solver.energy().unshot, received + 15 * area, 1e-12);

  const RoundPlan second = solver.PlanRound(4096);
  const Shot* again = nullptr;
  for (const Shot& shot : second.shots) {
    if (shot.shooter == light) again = &shot;
  }
  ASSERT_NE(again, nullptr) << "negative unshot must be shot";
  // shot_rays * omega * |unshot power| / emitted = 65536 * 1.5 * 15 / 30, rounded up.
  EXPECT_NEAR(double(again->rays), 49152, 1);
}

// Runs `rounds` rounds of a solver by hand, calling `after` after each.
template <typename After>
void RunRounds(const PatchScene& scene, ProgressiveSolver* solver, int rounds, After after) {
  const RayCaster caster(scene);
  BatchTracer runner(scene, caster, solver->sampler());
  for (int round = 0; round < rounds; ++round) {
    const RoundPlan plan = solver->PlanRound(4096);
    if (plan.batches.empty()) return;
    std::vector<BatchResult> results;
    for (const Batch& b : plan.batches) results.push_back(runner.Run(b));
    solver->ApplyRound(plan, results);
    after();
  }
}

// Power A * B summed over each of the box's six faces (surface ids 0..5), per channel.
std::vector<Rgb> FacePower(const PatchScene& scene, const std::vector<Rgb>& radiosity) {
  std::vector<Rgb> out(6);
  for (size_t i = 0; i < scene.patches.size(); ++i) {
    const Patch& p = scene.patches[i];
    if (p.surface < 6) out[p.surface] += radiosity[i] * p.area;
  }
  return out;
}

// Furnace: a closed enclosure with uniform rho and E has B = E / (1 - rho) everywhere.
TEST(OverrelaxationTest, FurnaceConvergesToTheClosedFormAnswer) {
  const double rho = 0.9;
  const PatchScene scene = testing::MakeClosedBox({0, 0, 0}, {1, 1, 1}, 1,
                                                  testing::Surface{{rho, rho, rho}, {1, 1, 1}, 0});
  for (double omega : {1.0, 1.3, 1.5}) {
    SolverSettings s;
    s.shot_rays = 1 << 17;
    s.threads = 2;
    s.overrelaxation = omega;
    const SolveResult r = Solve(scene, s);
    EXPECT_EQ(r.stats.stop_reason, "converged") << omega;
    double worst = 0;
    for (const Rgb& b : r.radiosity) {
      ASSERT_TRUE(b.IsFinite());
      worst = std::max(worst, std::abs(b.g - 1 / (1 - rho)) * (1 - rho));
    }
    std::printf("furnace omega %g: worst relative error %.2e, %llu rounds, %llu rays\n", omega,
                worst, static_cast<unsigned long long>(r.stats.rounds),
                static_cast<unsigned long long>(r.stats.rays));
    EXPECT_LE(worst, 0.01) << omega;
  }
}

// Without a closed form: omega = 1.5 and omega = 1 agree on the power of every face of a lit box
// within the Monte Carlo noise.
TEST(OverrelaxationTest, LitBoxMatchesPlainSouthwell) {
  const PatchScene scene = LitBox();
  SolverSettings s;
  s.shot_rays = 1 << 19;
  // Well above the noise floor of |unshot| with omega = 1.5 (docs/SOLVER.md), about 3e-4.
  s.tolerance = 2e-3;
  s.threads = 2;
  const std::vector<Rgb> plain = FacePower(scene, Solve(scene, s).radiosity);
  s.overrelaxation = 1.5;
  s.seed = 2;  // other rays, so that the agreement is not one of shared noise
  const SolveResult over = Solve(scene, s);
  EXPECT_EQ(over.stats.stop_reason, "converged");
  const std::vector<Rgb> relaxed = FacePower(scene, over.radiosity);
  double worst = 0;
  for (int face = 0; face < 6; ++face) {
    for (int channel : {0, 1, 2}) {
      const auto get = [&](const Rgb& c) { return channel == 0 ? c.r : channel == 1 ? c.g : c.b; };
      worst = std::max(worst, std::abs(get(relaxed[face]) / get(plain[face]) - 1));
    }
  }
  std::printf("lit box: worst relative difference of a face's power %.2e\n", worst);
  EXPECT_LE(worst, 0.02);
}

// emitted == absorbed + signed unshot + escaped after every round, with negative unshot about.
TEST(OverrelaxationTest, EnergyAccountBalancesWithSignedUnshot) {
  PatchScene scene =
      testing::MakeClosedBox({0, 0, 0}, {1, 1, 1}, 3, testing::Surface{{0.7, 0.4, 0.2}, {}, 0});
  scene.patches.resize(scene.patches.size() - 9);  // open the +z face: some light escapes
  scene.patches[3 * 9 + 4].emission = {5, 4, 3};
  SolverSettings s;
  s.shot_rays = 1 << 16;
  s.overrelaxation = 1.6;
  ProgressiveSolver solver(scene, s);
  bool negative_seen = false;
  RunRounds(scene, &solver, 8, [&] {
    const EnergyAccount& e = solver.energy();
    const double signed_unshot = solver.SignedUnshotPower();
    EXPECT_NEAR(e.emitted, e.absorbed + signed_unshot + e.escaped, 1e-12 * e.emitted);
    EXPECT_GE(e.unshot, std::abs(signed_unshot));
    for (const Rgb& u : solver.unshot()) negative_seen |= u.Min() < 0;
  });
  EXPECT_EQ(solver.rounds_done(), 8u);
  EXPECT_TRUE(negative_seen);
  EXPECT_GT(solver.energy().escaped, 0);
}

// The determinism contract holds for omega > 1: thread count, batch size, batch order.
TEST(OverrelaxationTest, ThreadCountAndBatchCutNeverChangeTheResult) {
  const PatchScene scene = LitBox();
  SolverSettings s;
  s.shot_rays = 1 << 16;
  s.tolerance = 0.02;
  s.overrelaxation = 1.5;
  s.threads = 1;
  const SolveResult one = Solve(scene, s);
  s.threads = 2;
  const SolveResult two = Solve(scene, s);
  s.threads = 7;
  const SolveResult seven = Solve(scene, s);
  EXPECT_TRUE(BitIdentical(one.radiosity, two.radiosity));
  EXPECT_TRUE(BitIdentical(one.radiosity, seven.radiosity));
  EXPECT_TRUE(BitIdentical(one.unshot, seven.unshot));
  EXPECT_EQ(one.stats.rays, seven.stats.rays);

  const RayCaster caster(scene);
  ProgressiveSolver a(scene, s), b(scene, s);
  for (int round = 0; round < 4; ++round) {
    const RoundPlan plan_a = a.PlanRound(4096);
    const RoundPlan plan_b = b.PlanRound(777);
    BatchTracer runner(scene, caster, a.sampler());
    std::vector<BatchResult> results_a, results_b(plan_b.batches.size());
    for (const Batch& batch : plan_a.batches) results_a.push_back(runner.Run(batch));
    for (size_t k = plan_b.batches.size(); k-- > 0;) results_b[k] = runner.Run(plan_b.batches[k]);
    a.ApplyRound(plan_a, results_a);
    b.ApplyRound(plan_b, results_b);
    ASSERT_TRUE(BitIdentical(a.radiosity(), b.radiosity())) << "round " << round;
    ASSERT_TRUE(BitIdentical(a.unshot(), b.unshot())) << "round " << round;
  }
}

// Where light bounces many times (rho 0.99), over-relaxation reaches the tolerance in fewer
// rounds: the slowest mode decays by 1 - omega (1 - rho) a round instead of rho.
TEST(OverrelaxationTest, HighReflectanceNeedsFewerRounds) {
  PatchScene scene =
      testing::MakeClosedBox({0, 0, 0}, {1, 1, 1}, 1, testing::Surface{{0.99, 0.99, 0.99}, {}, 0});
  scene.patches[3].emission = {1, 1, 1};
  SolverSettings s;
  s.shot_rays = 1 << 14;
  s.tolerance = 0.01;
  s.threads = 2;
  const SolveResult plain = Solve(scene, s);
  s.overrelaxation = 1.3;
  const SolveResult over = Solve(scene, s);
  std::printf("rho 0.99: omega 1: %llu rounds, %llu rays; omega 1.3: %llu rounds, %llu rays\n",
              static_cast<unsigned long long>(plain.stats.rounds),
              static_cast<unsigned long long>(plain.stats.rays),
              static_cast<unsigned long long>(over.stats.rounds),
              static_cast<unsigned long long>(over.stats.rays));
  EXPECT_EQ(over.stats.stop_reason, "converged");
  EXPECT_LT(over.stats.rounds, plain.stats.rounds * 9 / 10);
}

// Restore takes the state but derives energy.unshot from it, as ApplyRound does.
TEST(OverrelaxationTest, RestoreRecomputesTheUnshotMagnitude) {
  const PatchScene scene = LitBox();
  SolverSettings s;
  s.shot_rays = 1 << 14;
  s.overrelaxation = 1.4;
  ProgressiveSolver solver(scene, s);
  RunRounds(scene, &solver, 2, [] {});
  ProgressiveSolver resumed(scene, s);
  EnergyAccount energy = solver.energy();
  energy.unshot = solver.SignedUnshotPower();  // e.g. a sum made without magnitudes
  resumed.Restore(solver.rounds_done(), solver.radiosity(), solver.unshot(), energy);
  EXPECT_EQ(resumed.energy().unshot, solver.energy().unshot);
  EXPECT_EQ(resumed.UnshotFraction(), solver.UnshotFraction());
}

}  // namespace
}  // namespace radfarm
