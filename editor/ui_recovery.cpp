// The offer of the unsaved work that sessions which did not exit cleanly left
// (state.recoveries, see recent_and_recovery.h): a modal per recovery, one after the other,
// with Recover (the work becomes the open document, unsaved) and Discard (the files go).
#include <ctime>

#include "editor/ui.h"
#include "editor/ui_context.h"

namespace glint {
namespace {

const char* const kRecoveryPopup = "Recover unsaved work?";

// "2024-05-01 14:03" in local time, or "" when unknown.
std::string local_time_text(std::time_t t) {
  std::tm tm {};
  char text[32];
  if (t <= 0 || !localtime_r(&t, &tm) || !std::strftime(text, sizeof text, "%Y-%m-%d %H:%M", &tm)) return "";
  return text;
}

}  // namespace

void draw_recovery_offer(Document& doc, EditorState& state) {
  if (state.recoveries.empty()) return;
  // Recovering replaces the open document: while it has unsaved changes (an earlier recovery,
  // say) the next offer waits until they are saved or given up. At a clean exit an offer not
  // yet answered stays for the next start.
  if (doc.dirty() && !ImGui::IsPopupOpen(kRecoveryPopup)) return;
  // Dear ImGui 1.86 asserts when a window appears for the first time while a modal is open, so
  // the offer opens at the end of a frame, after every panel has begun. It also waits while
  // another popup is open (the error of a project that failed to open): opening a popup at the
  // same level would close that one.
  if (!ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId)) ImGui::OpenPopup(kRecoveryPopup);
  if (!ImGui::BeginPopupModal(kRecoveryPopup, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
  const Recovery& r = state.recoveries.front();
  const std::string name = r.original.empty() ? "an untitled project" : r.original.string();
  const std::string when = local_time_text(r.written);
  ImGui::TextUnformatted("A Glint session did not exit cleanly.");
  ImGui::Text("Unsaved changes of %s%s can be recovered.", name.c_str(),
              when.empty() ? "" : (", autosaved " + when + ",").c_str());
  if (const size_t more = state.recoveries.size() - 1; more == 1)
    ImGui::TextUnformatted("1 more session left unsaved work; it is offered after this one.");
  else if (more > 1)
    ImGui::Text("%zu more sessions left unsaved work; each is offered after this one.", more);
  ImGui::Spacing();
  if (ImGui::Button("Recover", ImVec2(ui_units(110), 0))) {
    doc = open_recovery(r);
    state.thumbnails.clear();
    discard_recovery(r);  // this run's autosave writes the recovered work again
    state.recoveries.erase(state.recoveries.begin());
    std::string message = "Recovered the unsaved changes of " + name;
    if (!state.recoveries.empty()) message += "; the next recovery is offered once this is saved";
    show_message(state, message);
    ImGui::CloseCurrentPopup();
  }
  ImGui::SameLine();
  if (ImGui::Button("Discard", ImVec2(ui_units(110), 0))) {
    discard_recovery(r);
    state.recoveries.erase(state.recoveries.begin());
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
}

}  // namespace glint
