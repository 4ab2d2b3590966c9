// Native file dialogs through tinyfiledialogs (zenity, kdialog, ...), and whether any exist.
// Where none does, the UI shows its own typed-path prompt instead (ui_menu.cpp): tinyfd's
// console fallback would block on the terminal.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace glint {

// True when tinyfd finds a graphical dialog backend (asked once, with "tinyfd_query").
bool native_file_dialogs_available();

// nullopt on cancel. `filters` like {"*.glint"}.
std::optional<std::string> native_open_dialog(const std::string& title, const std::string& start,
                                              const std::vector<std::string>& filters,
                                              const std::string& description);
std::optional<std::string> native_save_dialog(const std::string& title, const std::string& start,
                                              const std::vector<std::string>& filters,
                                              const std::string& description);

// One native dialog's question.
struct FileDialogRequest {
  bool save = false;
  std::string title, start, description;
  std::vector<std::string> filters;
};
// Asks it with native_open_dialog or native_save_dialog (blocks until the user answers).
std::optional<std::string> run_native_dialog(const FileDialogRequest& request);

// A native dialog on a thread of its own, polled once a frame, so that the window keeps
// redrawing while the user chooses (tinyfd blocks until the dialog closes). The thread is
// detached: an editor that quits meanwhile does not wait for the dialog.
class AsyncFileDialog {
 public:
  using Runner = std::function<std::optional<std::string>(const FileDialogRequest&)>;
  // Starts `runner` (run_native_dialog when empty) with `request`; ignored while one runs.
  void start(FileDialogRequest request, Runner runner = {});
  bool running() const { return shared_ != nullptr; }
  // Once the dialog has closed: its answer (nullopt: cancelled), handed out once; until then,
  // and when none runs, false.
  bool poll(std::optional<std::string>& answer);

 private:
  struct Shared;
  std::shared_ptr<Shared> shared_;
};

}  // namespace glint
