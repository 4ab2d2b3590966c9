#include "editor/file_dialogs.h"

#include <cstdlib>
#include <cstring>
#include <mutex>
#include <thread>

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

std::optional<std::string> run_native_dialog(const FileDialogRequest& r) {
  return r.save ? native_save_dialog(r.title, r.start, r.filters, r.description)
                : native_open_dialog(r.title, r.start, r.filters, r.description);
}

struct AsyncFileDialog::Shared {
  std::mutex mutex;
  bool done = false;
  std::optional<std::string> answer;
};

void AsyncFileDialog::start(FileDialogRequest request, Runner runner) {
  if (shared_) return;
  shared_ = std::make_shared<Shared>();
  if (!runner) runner = run_native_dialog;
  std::thread([shared = shared_, request = std::move(request), runner = std::move(runner)] {
    std::optional<std::string> answer;
    try {
      answer = runner(request);
    } catch (...) {  // a failed dialog counts as cancelled
    }
    std::lock_guard lock(shared->mutex);
    shared->answer = std::move(answer);
    shared->done = true;
  }).detach();
}

bool AsyncFileDialog::poll(std::optional<std::string>& answer) {
  const std::shared_ptr<Shared> shared = shared_;  // outlives the lock below
  if (!shared) return false;
  std::lock_guard lock(shared->mutex);
  if (!shared->done) return false;
  answer = std::move(shared->answer);
  shared_.reset();
  return true;
}

}  // namespace glint
