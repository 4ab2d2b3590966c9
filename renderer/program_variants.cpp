#include "renderer/program_variants.h"

#include <chrono>
#include <exception>
#include <thread>

#include "renderer/gl_program.h"
#include "renderer/program_worker.h"

namespace glint {
namespace {

class WorkerBuild final : public ProgramBuild {
 public:
  explicit WorkerBuild(std::shared_ptr<ProgramJob> job) : job_(std::move(job)) {}
  bool done() override { return job_->done(); }
  void wait() override {
    while (!job_->done()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  std::unique_ptr<GlProgram> take() override { return std::move(job_->program); }

 private:
  std::shared_ptr<ProgramJob> job_;  // dropped with the build: the worker then deletes the program
};

class ContextBuild final : public ProgramBuild {
 public:
  explicit ContextBuild(std::unique_ptr<GlProgram> program) : program_(std::move(program)) {}
  bool done() override { return program_->ready(); }
  void wait() override {}  // take() waits in finish()
  std::unique_ptr<GlProgram> take() override {
    try {
      program_->finish();
      return std::move(program_);
    } catch (const std::exception&) {
      return nullptr;
    }
  }

 private:
  std::unique_ptr<GlProgram> program_;
};

}  // namespace

std::unique_ptr<ProgramBuild> worker_build(std::shared_ptr<ProgramJob> job) {
  return std::make_unique<WorkerBuild>(std::move(job));
}

std::unique_ptr<ProgramBuild> context_build(std::unique_ptr<GlProgram> started) {
  return std::make_unique<ContextBuild>(std::move(started));
}

ProgramVariants::ProgramVariants(StartBuild start_build) : start_build_(std::move(start_build)) {}

ProgramVariants::~ProgramVariants() = default;

void ProgramVariants::settle(Variant& v) {
  v.program = v.build->take();
  v.build.reset();
  v.state = v.program ? State::ready : State::failed;  // a failed one is kept, not built again
}

void ProgramVariants::poll(Variant& v) {
  if (v.build && v.build->done()) settle(v);
}

GlProgram* ProgramVariants::choose(const ShaderFeatures& features, const std::string& defines,
                                   std::string& chosen) {
  auto best = variants_.end();
  for (auto it = variants_.begin(); it != variants_.end(); ++it) {
    poll(*it);
    if (it->state != State::ready || !covers(it->features, features)) continue;
    if (it->defines == defines) {
      best = it;
      break;
    }
    if (best == variants_.end()) best = it;
  }
  if (best == variants_.end()) return nullptr;
  variants_.splice(variants_.begin(), variants_, best);  // most recently used
  chosen = best->defines;
  return best->program.get();
}

void ProgramVariants::start_if_missing(const ShaderFeatures& features, const std::string& defines) {
  if (state(defines) != State::absent) return;
  if (variants_.size() >= kCapacity) variants_.pop_back();
  Variant v;
  v.features = features;
  v.defines = defines;
  v.build = start_build_(defines);
  variants_.push_back(std::move(v));
}

void ProgramVariants::wait(const std::string& defines) {
  for (Variant& v : variants_)
    if (v.defines == defines && v.build) {
      v.build->wait();
      settle(v);
    }
}

ProgramVariants::State ProgramVariants::state(const std::string& defines) const {
  for (const Variant& v : variants_)
    if (v.defines == defines) return v.state;
  return State::absent;
}

std::vector<std::string> ProgramVariants::keys() const {
  std::vector<std::string> keys;
  for (const Variant& v : variants_) keys.push_back(v.defines);
  return keys;
}

}  // namespace glint
