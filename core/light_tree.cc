#include "core/light_tree.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/counter_rng.h"

namespace radfarm {

namespace {

// Keeps the sampling's random numbers apart from every other use of a point's key.
constexpr uint64_t kPickStream = 0x6c69676874637574ull;

LightBounds Merge(const LightBounds& a, const LightBounds& b) {
  LightBounds m;
  m.box = a.box;
  m.box.Extend(b.box.lo);
  m.box.Extend(b.box.hi);
  m.normal_lo = {std::fmin(a.normal_lo.x, b.normal_lo.x), std::fmin(a.normal_lo.y, b.normal_lo.y),
                 std::fmin(a.normal_lo.z, b.normal_lo.z)};
  m.normal_hi = {std::fmax(a.normal_hi.x, b.normal_hi.x), std::fmax(a.normal_hi.y, b.normal_hi.y),
                 std::fmax(a.normal_hi.z, b.normal_hi.z)};
  m.power = a.power + b.power;
  m.cap = a.cap + b.cap;
  return m;
}

}  // namespace

LightBounds EmitterLightBounds(const std::vector<const Patch*>& patches, bool planar) {
  LightBounds b;
  b.normal_lo = {INFINITY, INFINITY, INFINITY};
  b.normal_hi = -b.normal_lo;
  for (const Patch* p : patches) {
    for (uint8_t c = 0; c < p->corner_count; ++c) b.box.Extend(p->corners[c]);
    b.normal_lo = {std::fmin(b.normal_lo.x, p->normal.x), std::fmin(b.normal_lo.y, p->normal.y),
                   std::fmin(b.normal_lo.z, p->normal.z)};
    b.normal_hi = {std::fmax(b.normal_hi.x, p->normal.x), std::fmax(b.normal_hi.y, p->normal.y),
                   std::fmax(b.normal_hi.z, p->normal.z)};
    b.power += p->emission.Sum() * p->area;
    b.cap += p->emission.Sum();
  }
  if (planar && !patches.empty()) b.cap = patches[0]->emission.Sum();
  return b;
}

LightBounds PunctualLightBounds(const PunctualLight& light) {
  LightBounds b;  // [-1, 1]^3 normals: it shines every way
  b.box.Extend(light.position);
  // A point's candela; a photometric lamp's mean candela over the sphere.
  b.power =
      light.kind == PunctualKind::kPhotometric ? PunctualPower(light) / 4 : light.intensity.Sum();
  b.cap = INFINITY;
  return b;
}

LightTree::LightTree(const std::vector<LightBounds>& lights) : leaf_of_(lights.size()) {
  if (lights.empty()) return;
  std::vector<uint32_t> order(lights.size());
  for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  nodes_.reserve(2 * lights.size() - 1);
  Build(lights, &order, 0, order.size());
}

// Median split of order[lo, hi) along the longest axis of the lights' centres.
uint32_t LightTree::Build(const std::vector<LightBounds>& lights, std::vector<uint32_t>* order,
                          size_t lo, size_t hi) {
  const auto index = static_cast<uint32_t>(nodes_.size());
  nodes_.emplace_back();
  if (hi - lo == 1) {
    const uint32_t light = (*order)[lo];
    nodes_[index].bounds = lights[light];
    nodes_[index].light = light;
    leaf_of_[light] = index;
    return index;
  }
  Bounds3 centres;
  for (size_t i = lo; i < hi; ++i) centres.Extend(lights[(*order)[i]].box.Centre());
  const Vec3 extent = centres.hi - centres.lo;
  const int axis =
      extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  const size_t mid = lo + (hi - lo) / 2;
  // Ties by index: the same tree whatever the sort's implementation.
  std::sort(order->begin() + lo, order->begin() + hi, [&](uint32_t a, uint32_t b) {
    const double ca = lights[a].box.Centre()[axis], cb = lights[b].box.Centre()[axis];
    return ca < cb || (ca == cb && a < b);
  });
  const uint32_t left = Build(lights, order, lo, mid);
  const uint32_t right = Build(lights, order, mid, hi);
  nodes_[index].left = left;
  nodes_[index].right = right;
  nodes_[index].bounds = Merge(nodes_[left].bounds, nodes_[right].bounds);
  return index;
}

double LightTree::Bound(uint32_t node, const Vec3& x, const Vec3& n) const {
  const LightBounds& b = nodes_[node].bounds;
  // Over the box, with y a point of it: d2 <= |y - x|^2, receiver >= n . (y - x) and
  // emitter >= N . (x - y) for every normal N in the node's ranges (each a sum of per-axis maxima
  // of products of intervals).
  double d2 = 0, receiver = 0, emitter = 0;
  for (int k = 0; k < 3; ++k) {
    const double lo = b.box.lo[k], hi = b.box.hi[k], xk = x[k];
    const double gap = std::fmax(0.0, std::fmax(lo - xk, xk - hi));
    d2 += gap * gap;
    receiver += std::fmax(n[k] * (lo - xk), n[k] * (hi - xk));
    const double t0 = xk - hi, t1 = xk - lo, n0 = b.normal_lo[k], n1 = b.normal_hi[k];
    emitter += std::fmax(std::fmax(n0 * t0, n0 * t1), std::fmax(n1 * t0, n1 * t1));
  }
  if (receiver <= 0 || emitter <= 0) return 0;  // every point behind x, or x behind every light
  if (d2 <= 0) return b.cap;
  const double d = std::sqrt(d2);
  const double head_on = b.power / (std::numbers::pi * d2);
  return std::fmin(b.cap, head_on * std::fmin(1.0, receiver / d) * std::fmin(1.0, emitter / d));
}

// The order in which the cut splits nodes: the bound over d^4, d the distance from x to the node's
// box, so that near lights are split out first. The bounds cannot see walls and floors, and a near
// light is the likelier to be seen: on the building with many lights, ordering by the bound alone
// left errors an order of magnitude above those of bound / d^4 (bench/lights/).
double LightTree::Priority(uint32_t node, double bound, const Vec3& x) const {
  const Bounds3& box = nodes_[node].bounds.box;
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double gap = std::fmax(0.0, std::fmax(box.lo[k] - x[k], x[k] - box.hi[k]));
    d2 += gap * gap;
  }
  return d2 > 0 ? bound / (d2 * d2) : INFINITY;
}

void LightTree::Pick(const Vec3& x, const Vec3& n, uint64_t key, uint32_t cut,
                     std::vector<LightPick>* picks) const {
  picks->clear();
  if (nodes_.empty()) return;
  struct Entry {
    double priority;
    double bound;
    uint32_t node;
  };
  // Highest priority on top; ties to the lower node, so the cut is a pure function of the point.
  const auto below = [](const Entry& a, const Entry& b) {
    return a.priority < b.priority || (a.priority == b.priority && a.node > b.node);
  };
  std::vector<Entry> heap;
  heap.reserve(2 * cut + 2);
  if (const double b = Bound(0, x, n); b > 0) heap.push_back({Priority(0, b, x), b, 0});
  size_t exact = 0;
  while (!heap.empty()) {
    const Entry top = heap.front();
    const Node& node = nodes_[top.node];
    const bool leaf = node.left == 0;
    // An unbounded node (the point inside a point light's box) is split whatever the cut's size.
    if (!leaf && exact + heap.size() >= cut && std::isfinite(top.bound)) break;
    std::pop_heap(heap.begin(), heap.end(), below);
    heap.pop_back();
    if (leaf) {
      picks->push_back({node.light, 1.0});
      ++exact;
      continue;
    }
    for (const uint32_t child : {node.left, node.right}) {
      if (const double b = Bound(child, x, n); b > 0) {
        heap.push_back({Priority(child, b, x), b, child});
        std::push_heap(heap.begin(), heap.end(), below);
      }
    }
  }
  // Each node left in the cut: one of its lights, by its bound's share at every level.
  for (const Entry& e : heap) {
    const CounterRng rng(HashWords(key, kPickStream, e.node));
    uint32_t at = e.node, depth = 0;
    double p = 1;
    while (nodes_[at].left != 0) {
      const Node& node = nodes_[at];
      const double bl = Bound(node.left, x, n), br = Bound(node.right, x, n);
      const double total = bl + br;
      if (!(total > 0)) break;  // nothing below gives light
      if (rng.Uniform(depth++) * total < bl) {
        at = node.left;
        p *= bl / total;
      } else {
        at = node.right;
        p *= br / total;
      }
    }
    if (nodes_[at].left == 0) picks->push_back({nodes_[at].light, 1.0 / p});
  }
}

}  // namespace radfarm
