#include "display/solved_display.h"

#include "core/direct_light.h"
#include "core/display_budget.h"

namespace radfarm {

Display SolvedDisplay(const PatchMesh& mesh, const std::vector<Rgb>& radiosity,
                      const std::vector<Rgb>& direct_light, const SolverSettings& solver,
                      const DisplayProgress& progress) {
  const PatchScene& scene = mesh.patch_scene();
  const DisplayTopology topology = mesh.display_topology();
  std::vector<Rgb> direct = direct_light;
  if (direct.empty()) direct = StartingDirectLight(scene, solver);
  if (direct.empty()) return {AveragedDisplay(topology, scene, radiosity), {}};
  const DisplaySettings settings{solver.seed, solver.threads, EmittersInDirectStart(scene, solver),
                                 DirectLightRaysPerLight(scene, solver),
                                 DisplayRayAllowance(solver)};
  return ShadeDisplay({topology, scene, mesh.patch_size(), radiosity, direct}, settings, progress);
}

}  // namespace radfarm
