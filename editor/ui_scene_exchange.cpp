// File > Import scene... and Export scene...: Mitsuba 3 and pbrt-v4 scenes through
// renderer/scene_exchange.h.
#include <cstdio>

#include "editor/ui.h"
#include "renderer/scene_exchange.h"

namespace glint {
namespace fs = std::filesystem;
namespace {

// Every warning on stderr; their count and the first in the status bar.
void report_warnings(EditorState& state, const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  if (warnings.empty()) return;
  show_note(state, std::to_string(warnings.size()) + (warnings.size() == 1 ? " warning" : " warnings") +
                       " (all on stderr), the first: " + warnings.front());
}

bool foreign_format(EditorState& state, const fs::path& file) {
  const auto format = scene_format_for(file);
  if (format && *format != SceneFormat::glint) return true;
  show_error(state, file.string() + ": the name must end in .xml (Mitsuba 3) or .pbrt (pbrt-v4)");
  return false;
}

}  // namespace

bool import_document(Document& doc, EditorState& state, const fs::path& file) {
  if (!foreign_format(state, file)) return false;
  try {
    ImportedScene imported = import_scene(file);
    doc = Document(std::move(imported.scene));  // untitled: Save asks where the .glint goes
    state.thumbnails.clear();
    show_message(state, "Imported " + file.string());
    report_warnings(state, imported.warnings);
    return true;
  } catch (const std::exception& e) {
    show_error(state, e.what());
    return false;
  }
}

bool export_document(const Document& doc, EditorState& state, const fs::path& file) {
  if (!foreign_format(state, file)) return false;
  try {
    const std::vector<std::string> warnings = export_scene(doc.scene, file);
    show_message(state, "Exported " + file.string());
    report_warnings(state, warnings);
    return true;
  } catch (const std::exception& e) {
    show_error(state, e.what());
    return false;
  }
}

}  // namespace glint
