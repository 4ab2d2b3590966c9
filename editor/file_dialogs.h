// Native file dialogs through tinyfiledialogs (zenity, kdialog, ...), and whether any exist.
// Where none does, the UI shows its own typed-path prompt instead (ui_menu.cpp): tinyfd's
// console fallback would block on the terminal.
#pragma once

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

}  // namespace glint
