// libFuzzer target: a project file's bytes through the loader (parse, types, validation), and
// a loaded scene through save and load again, all in memory: load_project_text, then
// save_project_text (what save_project would write beside it, with its UTF-8 check), then
// load_project_text of that text. Any input must either load a scene that validates or throw
// ProjectError; anything else (a crash, a sanitizer report, another exception, a save that
// fails, a round trip that differs) is a finding. Nothing touches the file system per input:
// image files are not opened (check_files false; fuzz_image covers the readers) and the scene
// is saved to the folder it was loaded from, so asset paths are not rebased; absolute ones are
// written relative to that folder (relative_asset_paths), which looks the folder up once.
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "renderer/project_file.h"
#include "renderer/scene_validation.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::filesystem::path dir = GLINT_PROJECTS_DIR;
  static const std::filesystem::path file = dir / "fuzz.glint";
  const std::string text(reinterpret_cast<const char*>(data), size);
  glint::Scene scene;
  try {
    scene = glint::load_project_text(text, "fuzz.glint", dir, false);
  } catch (const glint::ProjectError&) {
    return 0;  // refused with a message: fine
  }
  if (!glint::validate_scene(scene, false).empty()) std::abort();  // a half-valid scene
  // What loads must save, and the saved text must load back to the scene save meant to write:
  // the same scene, with absolute asset paths made relative to the folder.
  const std::string saved = glint::save_project_text(scene, file);  // throws: a finding
  const glint::Scene again = glint::load_project_text(saved, "again.glint", dir, false);
  if (!(again == glint::relative_asset_paths(scene, dir))) std::abort();
  // Saving again changes nothing.
  if (glint::save_project_text(again, file) != saved) std::abort();
  return 0;
}
