#include "renderer/trace_timers.h"

#include <cstddef>

namespace glint {

TraceTimers::~TraceTimers() { reset(); }

void TraceTimers::start() {
  if (pass_[0]) glDeleteQueries(2, pass_);  // a pass that never stopped (an exception)
  glCreateQueries(GL_TIMESTAMP, 2, pass_);
  glQueryCounter(pass_[0], GL_TIMESTAMP);
}

void TraceTimers::stop() {
  glQueryCounter(pass_[1], GL_TIMESTAMP);
  queries_.insert(queries_.end(), pass_, pass_ + 2);
  pass_[0] = pass_[1] = 0;
}

// Queries finish in submission order, so the first unfinished pass ends the scan.
void TraceTimers::collect(bool wait) {
  size_t done = 0;
  for (; done + 1 < queries_.size(); done += 2) {
    GLint available = 0;
    if (!wait) glGetQueryObjectiv(queries_[done + 1], GL_QUERY_RESULT_AVAILABLE, &available);
    if (!wait && !available) break;
    GLuint64 begin = 0, end = 0;
    glGetQueryObjectui64v(queries_[done], GL_QUERY_RESULT, &begin);
    glGetQueryObjectui64v(queries_[done + 1], GL_QUERY_RESULT, &end);
    seconds_ += end > begin ? static_cast<double>(end - begin) * 1e-9 : 0.0;
  }
  if (done > 0) glDeleteQueries(static_cast<GLsizei>(done), queries_.data());
  queries_.erase(queries_.begin(), queries_.begin() + static_cast<std::ptrdiff_t>(done));
}

void TraceTimers::reset() {
  if (!queries_.empty()) glDeleteQueries(static_cast<GLsizei>(queries_.size()), queries_.data());
  queries_.clear();
  if (pass_[0]) glDeleteQueries(2, pass_);
  pass_[0] = pass_[1] = 0;
  seconds_ = 0;
}

}  // namespace glint
