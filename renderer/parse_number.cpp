#include "renderer/parse_number.h"

#include <cerrno>
#include <cstdlib>

namespace glint {

std::optional<long> parse_integer(const std::string& text, long lo, long hi) {
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || errno != 0 || v < lo || v > hi) return std::nullopt;
  return v;
}

std::string integer_expected(const std::string& option, long lo, long hi, const std::string& text) {
  return option + " expects an integer from " + std::to_string(lo) + " to " + std::to_string(hi) +
         ", got '" + text + "'";
}

}  // namespace glint
