// libFuzzer target: a project file's bytes through the loader (parse, types, validation), and
// a loaded scene through save and load again. Any input must either load a scene that validates
// or throw ProjectError; anything else (a crash, a sanitizer report, another exception, a round
// trip that differs) is a finding. Image files are not opened (check_files false): reading the
// example assets for every input would cost most of the time, and fuzz_image covers the readers.
#include <cstdint>
#include <cstdlib>
#include <string>

#include "renderer/project_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const glint::Scene scene = glint::load_project_text(text, "fuzz.glint", GLINT_PROJECTS_DIR, false);
    if (!glint::validate_scene(scene, false).empty()) std::abort();  // a half-valid scene
    // What loads must save: the canonical text loads back to the same scene.
    const glint::Scene again = glint::load_project_text(glint::project_file_text(scene),
                                                        "again.glint", GLINT_PROJECTS_DIR, false);
    if (!(again == scene)) std::abort();
  } catch (const glint::ProjectError&) {
  }
  return 0;
}
