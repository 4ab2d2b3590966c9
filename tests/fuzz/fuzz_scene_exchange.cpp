// libFuzzer target: a scene file's bytes through the Mitsuba 3 XML reader (first byte even) or
// the pbrt-v4 reader (odd), and a scene read that way through the writer of the same format.
// Any input must either read or throw ProjectError; anything else (a crash, a sanitizer report,
// another exception) is a finding. Mesh files named by a Mitsuba scene resolve against the
// examples' folder (which has none: such inputs are refused with a message).
#include <cstdint>
#include <filesystem>
#include <string>

#include "renderer/mitsuba_scene.h"
#include "renderer/pbrt_scene.h"
#include "renderer/project_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  static const std::filesystem::path dir = GLINT_PROJECTS_DIR;
  const bool mitsuba = data[0] % 2 == 0;
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    const glint::ImportedScene imported = mitsuba ? glint::read_mitsuba_scene(text, "fuzz.xml", dir)
                                                  : glint::read_pbrt_scene(text, "fuzz.pbrt", dir);
    if (mitsuba) glint::write_mitsuba_scene(imported.scene, "fuzz", {});
    else glint::write_pbrt_scene(imported.scene, "fuzz", {});
  } catch (const glint::ProjectError&) {
  }
  return 0;
}
