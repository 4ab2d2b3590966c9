// Building blocks of the project file parser and writer: typed field readers that report
// problems as ProjectError with a JSON path ("camera.position[1]: expected a number, got
// string \"x\""), exact float <-> JSON conversion, duplicate-key-aware parsing and the
// pretty printer. Internal to renderer/; the public API is project_file.h.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "renderer/project_error.h"

namespace glint::json_fields {

using Json = nlohmann::ordered_json;  // keeps keys in document / writing order

// Limits of the text that messages quote from a file: a key in a JSON path, a quoted name or
// string value, and the parts of a whole message (project_error.cpp error_message).
constexpr size_t kMaxQuotedKey = 64;
constexpr size_t kMaxQuotedString = 64;
// A document nested deeper than this (arrays and objects) is refused before it is parsed;
// a project needs 4 levels.
constexpr int kMaxJsonDepth = 256;

// `text` if it has at most `max` bytes, else its first and last bytes around "..." (max bytes
// in all, cut between UTF-8 sequences): "spheres[0].aaaaa...aaaaa".
std::string clip(std::string_view text, size_t max);

// "camera" + "up" -> "camera.up"; "" + "camera" -> "camera"; "spheres" + 3 -> "spheres[3]".
// A key longer than kMaxQuotedKey is clipped (a path names a place in an error message).
std::string child_path(const std::string& path, std::string_view key);
std::string index_path(const std::string& path, size_t index);

// A name in quotes for a message, clipped to kMaxQuotedString; invalid UTF-8 (possible in
// scenes built through the API) is shown replaced rather than thrown by nlohmann's dump.
std::string quote_name(const std::string& text);

// A short description of a value for error messages: "string \"abc\"", "number 1.5", "null".
std::string describe(const Json& value);

// The shortest text that reads back as the same float ("0.1" for 0.1f; "nan", "inf").
std::string float_text(float value);

[[noreturn]] void fail(const std::string& file, const std::string& path, std::string problem);

// Readers of single values; `path` names the value in errors.
float read_float(const Json& value, const std::string& file, const std::string& path);
glm::vec2 read_vec2(const Json& value, const std::string& file, const std::string& path);
glm::vec3 read_vec3(const Json& value, const std::string& file, const std::string& path);
// An integer (not a float with an integral value) in [min, max].
int64_t read_integer(const Json& value, int64_t min, int64_t max, const std::string& file,
                     const std::string& path);
std::string read_string(const Json& value, const std::string& file, const std::string& path);

// Whether `text` is well-formed UTF-8 (RFC 3629: no overlong forms, surrogates or values past
// U+10FFFF), which JSON text must be.
bool is_valid_utf8(std::string_view text);

// "must be an integer in [1, 16384] (got 0)": shared by the parser and validate_scene.
std::string integer_range_problem(int64_t min, int64_t max, const std::string& got);

// The fields of one JSON object. The constructor rejects non-objects and unknown keys.
// Every reader leaves `out` unchanged when the key is absent (the scene.h default).
class ObjectReader {
 public:
  ObjectReader(const Json& object, std::string path, const std::string& file,
               const std::vector<std::string_view>& allowed_keys);

  const Json* find(std::string_view key) const;  // nullptr when absent
  void require(std::string_view key) const;      // throws "missing required key"
  std::string path(std::string_view key) const { return child_path(path_, key); }

  void read(std::string_view key, float& out) const;
  void read(std::string_view key, glm::vec3& out) const;
  void read(std::string_view key, std::string& out) const;
  // A texture name or file: a non-empty string, or null for none (stored as "").
  void read_optional_string(std::string_view key, std::string& out) const;
  template <class Int>
  void read_integer(std::string_view key, int64_t min, int64_t max, Int& out) const {
    if (const Json* v = find(key))
      out = static_cast<Int>(json_fields::read_integer(*v, min, max, file_, path(key)));
  }
  // The array under `key`, or nullptr when absent; anything else than an array is an error.
  const Json* array(std::string_view key) const;

 private:
  const Json& object_;
  std::string path_;
  const std::string& file_;
};

// A float as JSON: the value of its shortest round-trip text (std::to_chars), stored as an
// integer when that text is one (40, not 40.0) and otherwise as a double (0.1f -> 0.1, not
// 0.10000000149011612). Reading it back as a float is exact (checked for every finite float).
Json float_to_json(float value);
Json vec_to_json(glm::vec2 v);
Json vec_to_json(glm::vec3 v);

// Parses JSON text; a syntax error or a duplicate key in an object throws ProjectError, and so
// does text that is not UTF-8 (UTF-16 and UTF-32 are named), nesting deeper than
// kMaxJsonDepth, and a NUL byte (nlohmann reads one as the end of the input, so a document
// followed by "\0garbage" would load). A UTF-8 byte order mark is accepted.
Json parse_text(const std::string& text, const std::string& file);

// 2-space indented JSON with a trailing newline; arrays of numbers (and arrays of those) stay
// on one line: "position": [0, 1, 5]. Throws nlohmann::json::type_error on invalid UTF-8.
std::string pretty_print(const Json& doc);

}  // namespace glint::json_fields
