// The offer of the unsaved work a crashed run left (state.recovery, see recent_and_recovery.h): a modal
// with Recover (the work becomes the open document, unsaved) and Discard (the file goes).
#include "editor/ui.h"
#include "editor/ui_context.h"

namespace glint {
namespace {

const char* const kRecoveryPopup = "Recover unsaved work?";

}  // namespace

void draw_recovery_offer(Document& doc, EditorState& state) {
  if (!state.recovery) return;
  // Dear ImGui 1.86 asserts when a window appears for the first time while a modal is open, so
  // the offer opens at the end of a frame, after every panel has begun. It also waits while
  // another popup is open (the error of a project that failed to open): opening a popup at the
  // same level would close that one.
  if (!ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId)) ImGui::OpenPopup(kRecoveryPopup);
  if (!ImGui::BeginPopupModal(kRecoveryPopup, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
  const Recovery& r = *state.recovery;
  const std::string name = r.original.empty() ? "an untitled project" : r.original.string();
  ImGui::TextUnformatted("Glint did not exit cleanly last time.");
  ImGui::Text("Unsaved changes of %s can be recovered.", name.c_str());
  ImGui::Spacing();
  const std::filesystem::path dir = r.file.parent_path();  // r goes with the answer
  if (ImGui::Button("Recover", ImVec2(ui_units(110), 0))) {
    doc = open_recovery(r);
    state.thumbnails.clear();
    show_message(state, "Recovered the unsaved changes of " + name);
    ImGui::CloseCurrentPopup();
    state.recovery.reset();
    discard_recovery(dir);  // this run's autosave writes the recovered work again
  }
  ImGui::SameLine();
  if (ImGui::Button("Discard", ImVec2(ui_units(110), 0))) {
    ImGui::CloseCurrentPopup();
    state.recovery.reset();
    discard_recovery(dir);
  }
  ImGui::EndPopup();
}

}  // namespace glint
