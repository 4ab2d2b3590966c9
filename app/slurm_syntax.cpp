#include "app/slurm_syntax.h"

#include <cstdint>
#include <sstream>

namespace glint {
namespace {

bool all_digits(const std::string& s) {
  return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
}

std::string range_text(int first, int last) {
  return first == last ? std::to_string(first) : std::to_string(first) + "-" + std::to_string(last);
}

// The runs of consecutive indices, as [first, last] pairs.
std::vector<std::pair<int, int>> runs(const std::vector<int>& sorted) {
  std::vector<std::pair<int, int>> r;
  for (int i : sorted) {
    if (!r.empty() && i == r.back().second + 1) r.back().second = i;
    else r.push_back({i, i});
  }
  return r;
}

}  // namespace

std::optional<std::string> job_id_problem(const std::string& text) {
  if (!all_digits(text) || text.size() > 10 || text[0] == '0' || std::stoull(text) > UINT32_MAX)
    return "a Slurm job id is a number from 1 to 4294967295";
  return std::nullopt;
}

std::optional<std::string> partition_problem(const std::string& text) {
  const std::string why =
      "a partition is one or more names separated by commas, of letters, digits, '_', '-' and '.'";
  if (text.empty() || text.size() > 64) return why + ", at most 64 characters";
  size_t start = 0;
  while (start <= text.size()) {
    size_t comma = text.find(',', start);
    if (comma == std::string::npos) comma = text.size();
    const std::string name = text.substr(start, comma - start);
    if (name.empty() || name[0] == '-' ||
        name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.") !=
            std::string::npos)
      return why;
    start = comma + 1;
  }
  return std::nullopt;
}

std::string array_ranges(const std::vector<int>& sorted_indices) {
  std::string s;
  for (const auto& [first, last] : runs(sorted_indices)) s += (s.empty() ? "" : ",") + range_text(first, last);
  return s;
}

std::vector<std::vector<int>> split_array(const std::vector<int>& sorted_indices, size_t max_chars) {
  std::vector<std::vector<int>> groups;
  size_t length = 0;
  for (const auto& [first, last] : runs(sorted_indices)) {
    const size_t add = range_text(first, last).size();
    if (groups.empty() || length + 1 + add > max_chars) {
      groups.emplace_back();
      length = add;
    } else {
      length += 1 + add;
    }
    for (int i = first; i <= last; ++i) groups.back().push_back(i);
  }
  return groups;
}

std::string dependency_list(const std::vector<std::string>& afterok, const std::vector<std::string>& afterany) {
  std::string s;
  for (const auto& [type, jobs] : {std::pair{"afterok", &afterok}, {"afterany", &afterany}}) {
    if (jobs->empty()) continue;
    s += (s.empty() ? "" : ",") + std::string(type);
    for (const std::string& id : *jobs) s += ":" + id;
  }
  return s;
}

std::optional<std::string> slurm_filename_literal(const std::string& path) {
  if (path.find('\\') != std::string::npos) return std::nullopt;
  std::string s;
  for (char c : path) s += c == '%' ? std::string("%%") : std::string(1, c);
  return s;
}

std::vector<QueuedJob> parse_squeue_lines(const std::string& output) {
  std::vector<QueuedJob> jobs;
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string id, state, extra;
    if (!(words >> id >> state) || (words >> extra)) continue;
    if (state.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZ_") != std::string::npos) continue;
    QueuedJob q;
    q.state = state;
    const size_t underscore = id.find('_');
    q.job = id.substr(0, underscore);
    if (job_id_problem(q.job)) continue;
    if (underscore != std::string::npos) {
      const std::string task = id.substr(underscore + 1);
      if (!all_digits(task) || task.size() > 9) continue;  // "[0-3]": not split by -r; not ours
      q.task = std::stoi(task);
    }
    jobs.push_back(q);
  }
  return jobs;
}

}  // namespace glint
