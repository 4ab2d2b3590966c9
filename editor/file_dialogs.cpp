#include "editor/file_dialogs.h"

#include <cstdlib>
#include <cstring>

#include <tinyfiledialogs.h>

namespace glint {
namespace {

std::vector<const char*> c_strings(const std::vector<std::string>& v) {
  std::vector<const char*> out;
  for (const auto& s : v) out.push_back(s.c_str());
  return out;
}

}  // namespace

bool native_file_dialogs_available() {
  static const bool available = [] {
    // "tinyfd_query" makes tinyfd report its backend instead of showing anything:
    // 1 for a graphical one, 0 for console mode (which would read from the terminal).
    // GLINT_NO_NATIVE_DIALOGS=1 forces the typed-path prompt (tests, broken desktops).
    if (const char* off = std::getenv("GLINT_NO_NATIVE_DIALOGS"); off && *off && *off != '0') return false;
    tinyfd_silent = 1;
    char* r = tinyfd_openFileDialog("tinyfd_query", "", 0, nullptr, nullptr, 0);
    bool graphic = r == reinterpret_cast<char*>(1);  // the query returns 0 or 1 as a pointer
    const char* backend = tinyfd_response;
    // Message-only tools cannot pick files.
    for (const char* weak : {"xmessage", "gxmessage", "gmessage", "no_solution", "basicinput"})
      if (std::strcmp(backend, weak) == 0) graphic = false;
    return graphic;
  }();
  return available;
}

std::optional<std::string> native_open_dialog(const std::string& title, const std::string& start,
                                              const std::vector<std::string>& filters,
                                              const std::string& description) {
  auto f = c_strings(filters);
  const char* r = tinyfd_openFileDialog(title.c_str(), start.c_str(), static_cast<int>(f.size()),
                                        f.empty() ? nullptr : f.data(), description.c_str(), 0);
  if (!r || !*r) return std::nullopt;
  return std::string(r);
}

std::optional<std::string> native_save_dialog(const std::string& title, const std::string& start,
                                              const std::vector<std::string>& filters,
                                              const std::string& description) {
  auto f = c_strings(filters);
  const char* r = tinyfd_saveFileDialog(title.c_str(), start.c_str(), static_cast<int>(f.size()),
                                        f.empty() ? nullptr : f.data(), description.c_str());
  if (!r || !*r) return std::nullopt;
  return std::string(r);
}

}  // namespace glint
