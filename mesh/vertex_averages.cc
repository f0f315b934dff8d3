#include "mesh/vertex_averages.h"

#include "mesh/border_extrapolation.h"

namespace radfarm {

std::vector<Rgb> VertexAverages(const DisplayTopology& topology, const PatchScene& scene,
                                const std::vector<Rgb>& per_patch) {
  std::vector<Rgb> sum(topology.vertex_count());
  std::vector<double> weight(topology.vertex_count(), 0.0);
  topology.ForEachVertexPatch([&](uint32_t vertex, uint32_t patch) {
    const double area = scene.patches[patch].area;
    sum[vertex] += per_patch[patch] * area;
    weight[vertex] += area;
  });
  for (size_t v = 0; v < sum.size(); ++v) sum[v] = weight[v] > 0 ? sum[v] / weight[v] : Rgb();
  return sum;
}

std::vector<Rgb> SmoothVertexValues(const DisplayTopology& topology, const PatchScene& scene,
                                    const std::vector<Rgb>& per_patch) {
  std::vector<Rgb> values = VertexAverages(topology, scene, per_patch);
  ExtrapolateBorders(topology.rings, &values);
  return values;
}

}  // namespace radfarm
