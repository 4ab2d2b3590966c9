#include "renderer/bvh_tables.h"

#include <chrono>

#include "renderer/scene_tables.h"
#include "renderer/stopwatch.h"

namespace glint {

void BvhTables::update(const PackedScene& packed, const glm::vec3& camera, SceneTables& tables) {
  const auto start = std::chrono::steady_clock::now();
  const float extent = ray_extent(packed.spheres, packed.quads, camera);
  bool refit = !bvh_.primitives.empty() && refit_bvh(bvh_, packed.spheres, packed.quads, extent);
  if (refit && sah_cost(bvh_) > 1.5 * built_cost_) refit = false;
  if (!refit) {
    bvh_ = build_bvh(packed.spheres, packed.quads, extent);
    built_cost_ = sah_cost(bvh_);
  }
  extent_ = extent;
  valid_ = true;
  tables.check_size("the BVH's nodes", bvh_.nodes);
  tables.check_size("the BVH's primitive list", bvh_.primitives);
  tables.upload(SceneTable::bvh_nodes, bvh_.nodes);
  tables.upload(SceneTable::bvh_primitives, bvh_.primitives);
  stats_.nodes = bvh_.nodes.size();
  stats_.depth = bvh_.depth;
  stats_.refit = refit;
  stats_.seconds = seconds_since(start);
}

}  // namespace glint
