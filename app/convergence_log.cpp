#include "app/convergence_log.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "renderer/gpu_renderer.h"
#include "renderer/render_session.h"

namespace glint {

Image load_reference(const std::string& path, int width, int height) {
  ImageInfo info = probe_image(path);  // throws ImageError naming the file
  if (!info.high_dynamic_range)
    throw std::runtime_error(path + ": a reference must be linear radiance (.exr or .hdr), "
                             "not an 8-bit display image");
  if (info.width != width || info.height != height)
    throw std::runtime_error(path + ": the reference is " + std::to_string(info.width) + "x" +
                             std::to_string(info.height) + " but the render is " +
                             std::to_string(width) + "x" + std::to_string(height));
  return load_image(path, ColorEncoding::linear);
}

ConvergenceLog::ConvergenceLog(std::string path, Image reference)
    : path_(std::move(path)), reference_(std::move(reference)), file_(std::fopen(path_.c_str(), "w")) {
  if (!file_) fail();
  write_line("spp,seconds,gpu_seconds,relmse,estimated_relmse,relmse_trimmed,mape,mean_bias,nonfinite");
}

ConvergenceLog::~ConvergenceLog() {
  if (file_) std::fclose(file_);
}

void ConvergenceLog::after_step(const RenderSession& session, GpuRenderer& renderer) {
  if (!session.at_checkpoint()) return;
  const double gpu = renderer.trace_gpu_seconds();
  const Image accumulation = renderer.read_accumulation();
  last_ = compare_images(accumulation, reference_);
  const ErrorEstimate estimate = renderer.estimate_error();
  char row[288];
  std::snprintf(row, sizeof row, "%lld,%.6f,%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.0f",
                static_cast<long long>(session.samples()), session.seconds(), gpu, last_.relmse,
                estimate.known() ? estimate.relmse : std::nan(""), last_.relmse_trimmed, last_.mape,
                last_.mean_bias, nonfinite_count(accumulation));
  write_line(row);
}

std::string ConvergenceLog::close() {
  std::FILE* file = file_;
  file_ = nullptr;
  if (std::fclose(file) != 0) fail();
  char line[160];
  std::snprintf(line, sizeof line, " (last row: relMSE %.4g, trimmed %.4g, bias %+.4g)", last_.relmse,
                last_.relmse_trimmed, last_.mean_bias);
  return "wrote " + path_ + line;
}

void ConvergenceLog::write_line(const std::string& line) {
  if (std::fputs(line.c_str(), file_) == EOF || std::fputc('\n', file_) == EOF || std::fflush(file_) != 0) fail();
}

void ConvergenceLog::fail() const {
  throw std::runtime_error(path_ + ": cannot write the log: " + std::strerror(errno));
}

}  // namespace glint
