#include "renderer/project_error.h"

#include "renderer/json_fields.h"

namespace glint {
namespace {

// The parts of a message are clipped (their middle replaced by "..."), so that a message stays
// within about 600 characters whatever the file holds: a file name, path or problem that
// quotes a 50 MB key or string would otherwise repeat it in full.
constexpr size_t kMaxMessageFile = 160;
constexpr size_t kMaxMessagePath = 120;
constexpr size_t kMaxMessageProblem = 300;

std::string error_message(const std::string& file, const std::string& path,
                          const std::string& problem) {
  std::string message;
  if (!file.empty()) message += json_fields::clip(file, kMaxMessageFile) + ": ";
  if (!path.empty()) message += json_fields::clip(path, kMaxMessagePath) + ": ";
  return message + json_fields::clip(problem, kMaxMessageProblem);
}

}  // namespace

ProjectError::ProjectError(std::string file_, std::string json_path_, std::string problem_)
    : std::runtime_error(error_message(file_, json_path_, problem_)),
      file(std::move(file_)),
      json_path(json_fields::clip(json_path_, kMaxMessagePath)),
      problem(json_fields::clip(problem_, kMaxMessageProblem)) {}

}  // namespace glint
