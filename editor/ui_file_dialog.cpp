// The wait for a native file dialog (editor/file_dialogs.h): the editor keeps drawing, a modal
// keeps the user's input off it, and the answer is applied in the frame it arrives.
#include "editor/ui.h"

namespace glint {

namespace {
constexpr const char* kWaitPopup = "File dialog";
}

void poll_file_dialog(Document& doc, EditorState& state) {
  DocumentFlow& flow = state.flow;
  std::optional<std::string> answer;
  const bool answered = flow.dialog.poll(answer);
  if (answered) {
    if (answer) apply_chosen_file(doc, state, flow.dialog_purpose, *answer);
    else if (flow.dialog_purpose == FilePurpose::save_project_as) flow.pending = DocAction::none;
  }
  if (flow.dialog.running() && !ImGui::IsPopupOpen(kWaitPopup)) ImGui::OpenPopup(kWaitPopup);
  ImGui::SetNextWindowPos(ImGui::GetMainViewport()->GetCenter(), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  if (ImGui::BeginPopupModal(kWaitPopup, nullptr,
                             ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings)) {
    if (!flow.dialog.running()) ImGui::CloseCurrentPopup();
    ImGui::TextUnformatted("Choose the file in the file dialog (it may be behind this window).");
    ImGui::EndPopup();
  }
}

}  // namespace glint
