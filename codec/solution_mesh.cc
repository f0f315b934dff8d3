#include "codec/solution_mesh.h"

#include <string>
#include <utility>

#include "codec/patch_scene_codec.h"

namespace radfarm::codec {

Result<SolutionMesh> MeshOfSolution(const JobSolution& solution, const JobBundle& bundle) {
  // The warnings were shown when the job was submitted.
  Result<PatchMesh> mesh = PatchMesh::Build(bundle.scene, bundle.job.mesh, nullptr);
  if (!mesh.ok()) return Error{"meshing the job's scene again: " + mesh.error()};
  const size_t initial_patches = mesh->patch_scene().patches.size();
  if (!solution.scene.empty()) {
    if (!bundle.job.refine.enabled) {
      return Error{"the job solution holds a refined mesh, but the job does not refine"};
    }
    Result<PatchScene> scene = DecodePatchScene(solution.scene);
    if (!scene.ok()) return Error{"the refined scene in the solution: " + scene.error()};
    PatchMesh refined = mesh->Rebuilt(PatchMesh::PiecesOf(*scene));
    if (refined.patch_scene().patches.size() != scene->patches.size()) {
      return Error{"the refined scene in the solution has " +
                   std::to_string(scene->patches.size()) + " elements, rebuilt " +
                   std::to_string(refined.patch_scene().patches.size())};
    }
    *mesh = std::move(refined);
  }
  const size_t patches = mesh->patch_scene().patches.size();
  if (solution.radiosity.size() != patches || solution.unshot.size() != patches) {
    return Error{"the job solution holds " + std::to_string(solution.radiosity.size()) +
                 " radiosities and " + std::to_string(solution.unshot.size()) +
                 " unshot values, but the scene meshes into " + std::to_string(patches) +
                 " patches"};
  }
  return SolutionMesh{std::move(*mesh), initial_patches};
}

}  // namespace radfarm::codec
