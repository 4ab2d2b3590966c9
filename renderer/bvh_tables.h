// The BVH of the uploaded geometry in the scene tables (renderer/bvh.h, renderer/scene_tables.h):
// built in full, or refitted when only shapes moved (an editor drag), and the figures the
// editor and `glint render --stats` show.
#pragma once

#include <cstddef>

#include <glm/glm.hpp>

#include "renderer/bvh.h"
#include "renderer/gpu_scene.h"

namespace glint {

class SceneTables;

struct BvhStats {
  size_t nodes = 0;
  int depth = 0;
  bool refit = false;   // the last update refitted the previous tree
  double seconds = 0;   // CPU time of the last build or refit
  int max_steps = 0;    // the traversal's step cap (loop_budget.h)
};

class BvhTables {
 public:
  // Whether the tables hold a tree of the uploaded geometry whose boxes are padded for a camera
  // `camera_extent` from the render origin (the largest of its coordinates' magnitudes).
  bool fits(float camera_extent) const { return valid_ && camera_extent <= extent_; }
  // The geometry was uploaded again: the tree no longer describes it.
  void invalidate() { valid_ = false; }
  // Refits the tree where only shapes moved (same counts) and it has not degraded much (SAH
  // cost within 1.5 times that of its build, Wald 2007's measure of tree quality), builds it
  // otherwise; uploads it into `tables`. Throws std::runtime_error if a table cannot hold it.
  void update(const PackedScene& packed, const glm::vec3& camera, SceneTables& tables);
  const BvhStats& stats() const { return stats_; }
  void set_max_steps(int steps) { stats_.max_steps = steps; }

 private:
  Bvh bvh_;                // of the uploaded geometry when valid_
  bool valid_ = false;
  float extent_ = 0;       // the ray extent its boxes are padded for
  double built_cost_ = 0;  // SAH cost after the last full build
  BvhStats stats_;
};

}  // namespace glint
