// `glint render --reference REF --log OUT.csv`: the convergence log, one row per checkpoint of
// the render's session (1, 2, 4, ... samples per pixel and the final count), with the error
// against the reference and the error estimated without it.
#pragma once

#include <cstdio>
#include <string>

#include "renderer/image.h"
#include "renderer/image_metrics.h"

namespace glint {

class GpuRenderer;
class RenderSession;

// The reference of --reference: a linear image of exactly the render's size. Throws naming the
// file (ImageError, or std::runtime_error for an 8-bit image or another size).
Image load_reference(const std::string& path, int width, int height);

// The log file, its header written at once, with every write checked: a full disk or /dev/full
// fails the command with the OS reason instead of losing rows silently.
class ConvergenceLog {
 public:
  ConvergenceLog(std::string path, Image reference);
  ~ConvergenceLog();
  ConvergenceLog(const ConvergenceLog&) = delete;
  ConvergenceLog& operator=(const ConvergenceLog&) = delete;

  // After a step of the session: a row when it ended on a checkpoint (a read-back of the image,
  // outside the session's clock).
  void after_step(const RenderSession& session, GpuRenderer& renderer);
  // Closes the file (throws when its last write fails) and returns the summary line: "wrote
  // OUT.csv (last row: relMSE ..., trimmed ..., bias ...)".
  std::string close();

 private:
  // Writes and flushes one line (so a long render can be watched, and an interrupted one keeps
  // its rows).
  void write_line(const std::string& line);
  [[noreturn]] void fail() const;

  std::string path_;
  Image reference_;
  std::FILE* file_;
  ImageMetrics last_;
};

}  // namespace glint
