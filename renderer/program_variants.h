// The cache of trace programs specialised to a scene's ShaderFeatures (renderer/
// shader_features.h): at most kCapacity of them, least recently used evicted first, each built
// without blocking the caller (on the program worker, or by the driver in the background) and
// kept after a failed build so that it is not tried again (the generic program renders then).
#pragma once

#include <functional>
#include <list>
#include <memory>
#include <string>
#include <vector>

#include "renderer/shader_features.h"

namespace glint {

class GlProgram;
struct ProgramJob;

// One program being built.
class ProgramBuild {
 public:
  virtual ~ProgramBuild() = default;
  // Whether the build has finished, linked or not. Never waits.
  virtual bool done() = 0;
  // Waits until the build has finished (or until take() can finish it).
  virtual void wait() = 0;
  // Once done() or after wait(), called once: the linked program, or nullptr if the compile or
  // link failed.
  virtual std::unique_ptr<GlProgram> take() = 0;
};

// A build on the program worker (renderer/program_worker.h), `job` already submitted.
std::unique_ptr<ProgramBuild> worker_build(std::shared_ptr<ProgramJob> job);
// A build in the current context, its compile and link issued (GlProgram::start): done when the
// driver says so (GL_KHR_parallel_shader_compile; at once without it), finished by take().
std::unique_ptr<ProgramBuild> context_build(std::unique_ptr<GlProgram> started);

class ProgramVariants {
 public:
  static constexpr size_t kCapacity = 4;
  // Starts the build of the program with `defines` (the cache key).
  using StartBuild = std::function<std::unique_ptr<ProgramBuild>(const std::string& defines)>;
  explicit ProgramVariants(StartBuild start_build);
  ~ProgramVariants();

  // The exact variant (`defines`) if it is ready, else a ready one whose features cover
  // `features` (e.g. the previous scene's after a feature was removed), else nullptr (use the
  // generic program). The one chosen becomes the most recently used and `chosen` gets its
  // defines. Polls the builds on the way; never waits.
  GlProgram* choose(const ShaderFeatures& features, const std::string& defines, std::string& chosen);
  // Starts building `defines` unless it is cached (ready, building or failed), evicting the
  // least recently used one beyond kCapacity (a build under way like any other).
  void start_if_missing(const ShaderFeatures& features, const std::string& defines);
  // Waits for the build of `defines`, if cached and under way.
  void wait(const std::string& defines);

  enum class State { absent, building, ready, failed };
  State state(const std::string& defines) const;
  // The cache keys, most recently used first.
  std::vector<std::string> keys() const;

 private:
  struct Variant {
    ShaderFeatures features;
    std::string defines;  // the cache key
    std::unique_ptr<ProgramBuild> build;  // while it is being built
    std::unique_ptr<GlProgram> program;   // once built
    State state = State::building;
  };
  // Takes the program of a finished (or waited for) build.
  static void settle(Variant& v);
  // Settles v if its build has finished; never waits.
  static void poll(Variant& v);

  StartBuild start_build_;
  std::list<Variant> variants_;  // most recently used first
};

}  // namespace glint
