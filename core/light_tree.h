// A bounding volume hierarchy over lights, so that a point's direct light costs about kLightCut
// light evaluations however many lights there are. DirectLight (core/direct_light.h)
// uses it above kExactLights lights; below, it sums every light as it always did.
//
// Each node bounds, for any receiving point x with unit normal n, the unoccluded irradiance all
// its lights can deliver (LightTree::Bound): power / pi times the receiver's and the emitter's
// cosine bounds over the node's box, over the squared distance to the box, and never more than
// the node's cap (a planar emitter's form factor is at most 1). The cut (Pick) is a greedy
// refinement as in lightcuts: split nodes, the near and strong first (the bound over d^4), until
// the cut holds kLightCut nodes; lights that reach the cut alone are evaluated exactly (weight
// 1), and each remaining node stands for one of its lights, chosen by descending with
// probability proportional to the children's bounds and weighted 1 / p. That is unbiased: a
// light that gives anything has a positive bound all the way down. The choice is a pure function
// of (x, n, key): the same whatever thread asks.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "core/patch_scene.h"
#include "core/punctual_light.h"
#include "core/vec3.h"

namespace radfarm {

// Above this many lights DirectLight samples through a LightTree; up to it, the exact sum.
inline constexpr size_t kExactLights = 64;
// The cut's size: lights evaluated per point, at most. The bounds cannot see slabs and walls, so
// far more lights look strong than are: on the building with many lights (bench/lights/) a
// smaller cut leaves several times the error.
inline constexpr uint32_t kLightCut = 64;

// What the tree knows of one light: where it is, which way it faces, how strong it is.
struct LightBounds {
  Bounds3 box;  // every point that emits
  // Per axis, the range of the emitting normals' components; [-1, 1]^3 for lights that shine
  // every way (punctual lights).
  Vec3 normal_lo{-1, -1, -1};
  Vec3 normal_hi{1, 1, 1};
  // Irradiance at distance d, head-on, is at most power / (pi d^2): sum over channels of Ke times
  // area for an emitter, of the intensity for a point or spot light.
  double power = 0;
  // Never more than this (channel sum); infinity where there is no cap (a point light).
  double cap = 0;
};

// The bounds of an emitter light: its patches, of one emission; `planar` where its form factor is
// that of one outline (at most 1), else each patch's form factor counts up to 1.
LightBounds EmitterLightBounds(const std::vector<const Patch*>& patches, bool planar);
// The bounds of a point or spot light (a spot's cone and a range are ignored: they only lower
// it). Not for suns, which have no position.
LightBounds PunctualLightBounds(const PunctualLight& light);

struct LightPick {
  uint32_t light;  // index into the LightBounds the tree was built from
  double weight;   // 1: evaluated exactly; 1 / p: stands for its node
};

class LightTree {
 public:
  explicit LightTree(const std::vector<LightBounds>& lights);

  // The lights to evaluate at x (unit normal n) and their weights, replacing *picks: the sum of
  // weight times contribution is an unbiased estimate of the sum over every light. Lights whose
  // bound is zero are left out (they give nothing).
  void Pick(const Vec3& x, const Vec3& n, uint64_t key, uint32_t cut,
            std::vector<LightPick>* picks) const;

  // Bound on the summed unoccluded irradiance (channel sum) of node `node`'s lights at x.
  double Bound(uint32_t node, const Vec3& x, const Vec3& n) const;
  // The tree's shape, for tests: the root is node 0; a leaf has no children (0, 0).
  uint32_t LeafOf(uint32_t light) const { return leaf_of_[light]; }
  std::pair<uint32_t, uint32_t> Children(uint32_t node) const {
    return {nodes_[node].left, nodes_[node].right};
  }
  size_t size() const { return nodes_.size(); }

 private:
  struct Node {
    LightBounds bounds;
    uint32_t left = 0, right = 0;  // children; 0 for a leaf (the root is no one's child)
    uint32_t light = 0;            // a leaf's light
  };
  double Priority(uint32_t node, double bound, const Vec3& x) const;
  uint32_t Build(const std::vector<LightBounds>& lights, std::vector<uint32_t>* order, size_t lo,
                 size_t hi);

  std::vector<Node> nodes_;
  std::vector<uint32_t> leaf_of_;
};

}  // namespace radfarm
