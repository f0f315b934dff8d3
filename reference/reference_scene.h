// ReferenceScene: the input's triangles as the path tracer sees them, with no patch meshing. Each
// input polygon is split into triangles (a fan when convex, ear clipping otherwise) and put in one
// Embree BVH; materials, emitters, punctual lights and the sky are the input's.
//
// Sides, as the solver treats them: a triangle's front is the side its corners run
// counter-clockwise about; a one-sided material absorbs light arriving at its back and emits
// nothing there; a two-sided one reflects and emits on both sides alike.
//
// Precision: coordinates are moved to be centred on the origin before they go to Embree (single
// precision), as core/ray_caster.h does; rays leave a surface lifted by a scene-relative offset.
//
// Thread safety: after construction every method is const and may run on any number of threads.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "base/result.h"
#include "core/punctual_light.h"
#include "core/rgb.h"
#include "core/sky.h"
#include "core/vec3.h"
#include "input/input_scene.h"

namespace radfarm::reference {

struct Triangle {
  Vec3 a, ab, ac;  // corner a and the edges to b and c
  Vec3 normal;     // unit, the front's
  double area = 0;
  uint32_t material = 0;
  uint32_t face = 0;  // into InputScene::faces
};

struct SurfaceHit {
  static constexpr uint32_t kMiss = 0xffffffffu;
  uint32_t triangle = kMiss;
  Vec3 position;
  bool front = true;  // whether the ray met the triangle's front
};

class ReferenceScene {
 public:
  // Fails on a scene with no triangle of positive area. Two-sided materials must already be set
  // (the job's two_sided settings applied).
  static Result<std::unique_ptr<ReferenceScene>> Build(const InputScene& input);
  ~ReferenceScene();
  ReferenceScene(const ReferenceScene&) = delete;
  ReferenceScene& operator=(const ReferenceScene&) = delete;

  const std::vector<Triangle>& triangles() const { return triangles_; }
  const std::vector<Material>& materials() const { return materials_; }
  const std::vector<PunctualLight>& lights() const { return lights_; }
  const Sky& sky() const { return sky_; }
  double diagonal() const { return diagonal_; }

  // Closest hit along origin + t * direction, t > 0, the origin lifted off its surface along
  // `normal` (the side the ray leaves from).
  SurfaceHit Trace(const Vec3& origin, const Vec3& direction, const Vec3& normal) const;
  // Whether nothing lies between origin (lifted as by Trace) and `target` (which lies on a surface
  // or is a lamp's position): the segment stops a small fraction short of it.
  bool Unoccluded(const Vec3& origin, const Vec3& target, const Vec3& normal) const;

  // Emitting triangles, chosen with probability proportional to area times the channel sum of
  // their emitted radiance: emitter k is triangle emitters()[k].
  struct Emitter {
    uint32_t triangle = 0;
    double probability = 0;
  };
  const std::vector<Emitter>& emitters() const { return emitters_; }
  // The emitter for a uniform u in [0, 1) (binary search over the cumulative probabilities).
  const Emitter& PickEmitter(double u) const;
  // The probability of picking triangle t as an emitter (0 for one that does not emit).
  double EmitterProbability(uint32_t triangle) const { return emitter_probability_[triangle]; }

 private:
  ReferenceScene() = default;
  void BuildBvh();

  std::vector<Triangle> triangles_;
  std::vector<Material> materials_;
  std::vector<PunctualLight> lights_;
  Sky sky_;
  std::vector<Emitter> emitters_;
  std::vector<double> emitter_cdf_;          // upper ends, last = 1
  std::vector<double> emitter_probability_;  // per triangle
  Vec3 centre_;
  double diagonal_ = 0;
  double offset_ = 0;  // lift of a ray's origin off its surface

  struct Embree;
  std::unique_ptr<Embree> embree_;
};

// Applies a job's two-sided settings to the scene's materials, as `radfarm render` does
// (cli/scene_settings.h: the whole scene, then each [materials.NAME] table).
void ApplyJobTwoSided(bool all, const std::map<std::string, bool>& per_material, InputScene* scene);

}  // namespace radfarm::reference
