#include "renderer/loop_shapes.h"

#include <algorithm>

namespace glint {

bool unrolls_loop(long spheres, long quads) {
  return spheres >= 0 && quads >= 0 && spheres <= kLoopShapesMax && quads <= kLoopShapesMax;
}

LoopShapesBlock loop_shapes_block(const std::vector<GpuSphere>& spheres,
                                  const std::vector<GpuQuad>& quads) {
  LoopShapesBlock block;
  std::copy_n(spheres.begin(), std::min<size_t>(spheres.size(), kLoopShapesMax), block.spheres);
  std::copy_n(quads.begin(), std::min<size_t>(quads.size(), kLoopShapesMax), block.quads);
  return block;
}

}  // namespace glint
