// A copy of a texture kept on the GPU: the viewport shows the coarser level's image while the
// first pass of a finer level is traced in bands over several frames (viewport_renderer.h),
// instead of an empty image. Needs a current OpenGL 4.5 context.
#pragma once

namespace glint {

class HeldImage {
 public:
  HeldImage() = default;
  ~HeldImage();
  HeldImage(const HeldImage&) = delete;
  HeldImage& operator=(const HeldImage&) = delete;

  // Copies `texture` (level 0, any size and colour format); 0 or an empty texture releases.
  void keep(unsigned texture);
  void release();
  // The copy (linearly filtered), 0 when none is held.
  unsigned texture() const { return texture_; }

 private:
  unsigned texture_ = 0;
  int width_ = 0, height_ = 0, format_ = 0;
};

}  // namespace glint
