// GPU time of trace passes from GL_TIMESTAMP query pairs around each one, read without waiting
// where the results are in (GL_TIMESTAMP pairs, not GL_TIME_ELAPSED: Mesa 22's llvmpipe returns
// the time since boot for a context's first GL_TIME_ELAPSED query, and a pair never clashes with
// a caller's own query).
#pragma once

#include <vector>

#include <epoxy/gl.h>

namespace glint {

class TraceTimers {
 public:
  TraceTimers() = default;
  ~TraceTimers();
  TraceTimers(const TraceTimers&) = delete;
  TraceTimers& operator=(const TraceTimers&) = delete;

  // Around the draws of one pass (or band): a timestamp before and one after.
  void start();
  void stop();
  // Adds the passes whose timestamps are in (all of them, waiting, when `wait`) to seconds().
  void collect(bool wait);
  // GPU seconds of the passes collected since the last reset.
  double seconds() const { return seconds_; }
  // Forgets every pass, collected or not.
  void reset();

 private:
  std::vector<GLuint> queries_;  // timestamp pairs of passes not yet read, oldest first
  GLuint pass_[2] = {0, 0};      // the pair between start() and stop()
  double seconds_ = 0;
};

}  // namespace glint
