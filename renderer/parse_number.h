// Integers typed by a user (command-line options, the editor's options): decimal, the whole text,
// within a range. One rule and one message for `glint render`, `glint farm` and the editor.
#pragma once

#include <optional>
#include <string>

namespace glint {

// The decimal integer that is all of `text` (leading blanks and a sign allowed, as strtol
// reads it), from lo to hi; nullopt for anything else (empty, trailing characters, overflow).
std::optional<long> parse_integer(const std::string& text, long lo, long hi);

// "OPTION expects an integer from LO to HI, got 'TEXT'".
std::string integer_expected(const std::string& option, long lo, long hi, const std::string& text);

}  // namespace glint
