#include "renderer/json_fields.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <set>
#include <vector>

namespace glint::json_fields {

std::string clip(std::string_view text, size_t max) {
  constexpr std::string_view kEllipsis = "...";
  if (text.size() <= max) return std::string(text);
  if (max <= kEllipsis.size()) return std::string(kEllipsis.substr(0, max));
  auto continuation = [&](size_t i) { return (static_cast<unsigned char>(text[i]) & 0xc0) == 0x80; };
  const size_t keep = max - kEllipsis.size();
  size_t head = keep - keep / 2, tail = text.size() - keep / 2;
  while (head > 0 && continuation(head)) --head;          // text[head] starts a sequence
  while (tail < text.size() && continuation(tail)) ++tail;  // so does text[tail]
  return std::string(text.substr(0, head)) + std::string(kEllipsis) + std::string(text.substr(tail));
}

std::string child_path(const std::string& path, std::string_view key) {
  const std::string shown = clip(key, kMaxQuotedKey);
  return path.empty() ? shown : path + "." + shown;
}

std::string index_path(const std::string& path, size_t index) {
  return path + "[" + std::to_string(index) + "]";
}

std::string quote_name(const std::string& text) {
  return Json(clip(text, kMaxQuotedString)).dump(-1, ' ', false, Json::error_handler_t::replace);
}

std::string describe(const Json& value) {
  switch (value.type()) {
    case Json::value_t::null: return "null";
    case Json::value_t::boolean: return "boolean " + value.dump();
    case Json::value_t::string:
      return "string " + Json(clip(value.get_ref<const std::string&>(), kMaxQuotedString))
                             .dump(-1, ' ', false, Json::error_handler_t::replace);
    case Json::value_t::array: return "an array of " + std::to_string(value.size());
    case Json::value_t::object: return "an object";
    default: return "number " + value.dump();
  }
}

std::string float_text(float value) {
  char buffer[64];
  auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

void fail(const std::string& file, const std::string& path, std::string problem) {
  throw ProjectError(file, path, std::move(problem));
}

float read_float(const Json& value, const std::string& file, const std::string& path) {
  if (!value.is_number()) fail(file, path, "expected a number, got " + describe(value));
  const double d = value.get<double>();
  // Below 2^128 - 2^103 a double rounds to a finite float (FLT_MAX at most); JSON has no
  // NaN or infinity, so this is the only way to get a non-finite float from a file.
  // A literal beyond a double (1e999) parses as infinity, which dump() would show as null.
  if (!std::isfinite(d))
    fail(file, path, "out of range of a 32-bit float (got a number beyond the range of a double)");
  if (!(std::fabs(d) < 0x1.ffffffp127))
    fail(file, path, "out of range of a 32-bit float (got " + value.dump() + ")");
  return static_cast<float>(d);
}

template <int N>
static glm::vec<N, float> read_vec(const Json& value, const std::string& file,
                                   const std::string& path) {
  if (!value.is_array() || value.size() != N)
    fail(file, path, "expected an array of " + std::to_string(N) + " numbers, got " +
                         describe(value));
  glm::vec<N, float> v;
  for (int i = 0; i < N; ++i) v[i] = read_float(value[i], file, index_path(path, i));
  return v;
}

glm::vec2 read_vec2(const Json& value, const std::string& file, const std::string& path) {
  return read_vec<2>(value, file, path);
}

glm::vec3 read_vec3(const Json& value, const std::string& file, const std::string& path) {
  return read_vec<3>(value, file, path);
}

bool is_valid_utf8(std::string_view text) {
  size_t i = 0;
  while (i < text.size()) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c < 0x80) { ++i; continue; }
    size_t n;
    uint32_t cp;
    if (c >= 0xc2 && c <= 0xdf) { n = 1; cp = c & 0x1f; }
    else if (c >= 0xe0 && c <= 0xef) { n = 2; cp = c & 0x0f; }
    else if (c >= 0xf0 && c <= 0xf4) { n = 3; cp = c & 0x07; }
    else return false;
    if (text.size() - i <= n) return false;
    for (size_t k = 1; k <= n; ++k) {
      const unsigned char cc = static_cast<unsigned char>(text[i + k]);
      if ((cc & 0xc0) != 0x80) return false;
      cp = (cp << 6) | (cc & 0x3f);
    }
    // Overlong forms, UTF-16 surrogates and code points past U+10FFFF.
    if ((n == 2 && cp < 0x800) || (n == 3 && cp < 0x10000) || cp > 0x10ffff ||
        (cp >= 0xd800 && cp <= 0xdfff))
      return false;
    i += n + 1;
  }
  return true;
}

std::string integer_range_problem(int64_t min, int64_t max, const std::string& got) {
  return "must be an integer in [" + std::to_string(min) + ", " + std::to_string(max) +
         "] (got " + got + ")";
}

int64_t read_integer(const Json& value, int64_t min, int64_t max, const std::string& file,
                     const std::string& path) {
  if (!value.is_number_integer()) fail(file, path, "expected an integer, got " + describe(value));
  if (value.is_number_unsigned()) {
    const uint64_t u = value.get<uint64_t>();
    if (max < 0 || u > static_cast<uint64_t>(max) || static_cast<int64_t>(u) < min)
      fail(file, path, integer_range_problem(min, max, value.dump()));
    return static_cast<int64_t>(u);
  }
  const int64_t i = value.get<int64_t>();
  if (i < min || i > max) fail(file, path, integer_range_problem(min, max, value.dump()));
  return i;
}

std::string read_string(const Json& value, const std::string& file, const std::string& path) {
  if (!value.is_string()) fail(file, path, "expected a string, got " + describe(value));
  return value.get<std::string>();
}

ObjectReader::ObjectReader(const Json& object, std::string path, const std::string& file,
                           const std::vector<std::string_view>& allowed_keys)
    : object_(object), path_(std::move(path)), file_(file) {
  if (!object.is_object()) fail(file_, path_, "expected an object, got " + describe(object));
  for (const auto& item : object.items()) {
    if (std::find(allowed_keys.begin(), allowed_keys.end(), item.key()) != allowed_keys.end())
      continue;
    std::string expected;
    for (std::string_view key : allowed_keys)
      expected += (expected.empty() ? "" : ", ") + std::string(key);
    fail(file_, child_path(path_, item.key()), "unknown key (expected one of: " + expected + ")");
  }
}

const Json* ObjectReader::find(std::string_view key) const {
  auto it = object_.find(std::string(key));
  return it == object_.end() ? nullptr : &*it;
}

void ObjectReader::require(std::string_view key) const {
  if (!find(key)) fail(file_, path(key), "missing required key");
}

void ObjectReader::read(std::string_view key, float& out) const {
  if (const Json* v = find(key)) out = read_float(*v, file_, path(key));
}

void ObjectReader::read(std::string_view key, glm::vec3& out) const {
  if (const Json* v = find(key)) out = read_vec3(*v, file_, path(key));
}

void ObjectReader::read(std::string_view key, std::string& out) const {
  if (const Json* v = find(key)) out = read_string(*v, file_, path(key));
}

void ObjectReader::read_optional_string(std::string_view key, std::string& out) const {
  const Json* v = find(key);
  if (!v) return;
  if (v->is_null()) {
    out.clear();
  } else if (!v->is_string()) {
    fail(file_, path(key), "expected a string or null, got " + describe(*v));
  } else if (v->get<std::string>().empty()) {
    fail(file_, path(key), "must not be an empty string (use null for none)");
  } else {
    out = v->get<std::string>();
  }
}

const Json* ObjectReader::array(std::string_view key) const {
  const Json* v = find(key);
  if (v && !v->is_array()) fail(file_, path(key), "expected an array, got " + describe(*v));
  return v;
}

Json float_to_json(float value) {
  const std::string text = float_text(value);
  const char* begin = text.data();
  const char* end = text.data() + text.size();
  // Integral shortest text ("40", "16777216"; never longer than 14 digits) stays an integer.
  if (text != "-0" && text.find_first_not_of("-0123456789") == std::string::npos) {
    int64_t i = 0;
    std::from_chars(begin, end, i);
    return Json(i);
  }
  double d = 0;
  std::from_chars(begin, end, d);
  // Double rounding (text -> double -> float) misses for one float in two billion
  // (7.038531e-26f): store the float's exact value then, which is longer but exact.
  if (std::isfinite(value) && static_cast<float>(d) != value) d = value;
  return Json(d);  // non-finite values become null, which the loader rejects
}

Json vec_to_json(glm::vec2 v) { return Json::array({float_to_json(v.x), float_to_json(v.y)}); }

Json vec_to_json(glm::vec3 v) {
  return Json::array({float_to_json(v.x), float_to_json(v.y), float_to_json(v.z)});
}

namespace {

// nlohmann resolves a key given twice in one object silently (the last value wins), so this
// SAX handler builds the document with nlohmann's own DOM builder and reports duplicates with
// their JSON path on the way, and syntax errors. (The parser-callback API would do the same,
// but nlohmann's callback parser rescans the enclosing array at the end of every object:
// quadratic, minutes for 10^6 spheres.)
class DuplicateKeySax {
 public:
  DuplicateKeySax(const std::string& file, Json& out) : file_(file), dom_(out, true) {}

  bool null() { return value() && dom_.null(); }
  bool boolean(bool v) { return value() && dom_.boolean(v); }
  bool number_integer(Json::number_integer_t v) { return value() && dom_.number_integer(v); }
  bool number_unsigned(Json::number_unsigned_t v) { return value() && dom_.number_unsigned(v); }
  bool number_float(Json::number_float_t v, const Json::string_t& s) {
    return value() && dom_.number_float(v, s);
  }
  bool string(Json::string_t& v) { return value() && dom_.string(v); }
  bool binary(Json::binary_t& v) { return value() && dom_.binary(v); }
  bool start_object(std::size_t n) { return start(false) && dom_.start_object(n); }
  bool start_array(std::size_t n) { return start(true) && dom_.start_array(n); }
  bool end_object() { return end() && dom_.end_object(); }
  bool end_array() { return end() && dom_.end_array(); }
  bool key(Json::string_t& key) {
    Frame& f = frames_.back();
    f.key = key;
    if (!f.keys.insert(key).second) fail(file_, path_of(frames_.size()), "duplicate key");
    return dom_.key(key);
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) {
    // "[json.exception.parse_error.101] parse error at line 3, column 5: ..." -> drop the tag.
    std::string message = e.what();
    const auto end = message.find("] ");
    if (message.starts_with("[json.exception") && end != std::string::npos)
      message.erase(0, end + 2);
    fail(file_, "", "invalid JSON: " + message);
  }

 private:
  // One open array or object. Its JSON path is built from the frames only when an error is
  // reported: a path per frame would take memory quadratic in the depth.
  struct Frame {
    bool is_array;
    size_t index;     // of the next element, in an array
    std::string key;  // the last key read, in an object
    std::set<std::string> keys;
  };

  // The path of the current element of the first `count` frames ("" for the root).
  std::string path_of(size_t count) const {
    std::string path;
    for (size_t i = 0; i < count; ++i) {
      const Frame& f = frames_[i];
      // frames_[i] is open inside frames_[i - 1]'s current element, whose counter has not
      // advanced yet (value() runs when the element ends).
      path = f.is_array ? index_path(path, f.index) : child_path(path, f.key);
    }
    return path;
  }
  bool start(bool is_array) {
    frames_.push_back({is_array, 0, {}, {}});
    return true;
  }
  bool end() {
    frames_.pop_back();
    return value();
  }
  bool value() {
    if (!frames_.empty() && frames_.back().is_array) ++frames_.back().index;
    return true;
  }

  const std::string& file_;
  nlohmann::detail::json_sax_dom_parser<Json> dom_;
  std::vector<Frame> frames_;
};

bool is_number_row(const Json& v) {
  return v.is_array() &&
         std::all_of(v.begin(), v.end(), [](const Json& x) { return x.is_number(); });
}

// Arrays of numbers, and arrays of such arrays, are written on one line.
bool is_inline(const Json& v) {
  return is_number_row(v) ||
         (v.is_array() && std::all_of(v.begin(), v.end(), [](const Json& x) {
            return is_number_row(x) && !x.empty();
          }));
}

void write(const Json& v, int indent, std::string& out) {
  const std::string pad(indent + 2, ' ');
  if (v.is_object() && !v.empty()) {
    out += "{\n";
    size_t i = 0;
    for (const auto& item : v.items()) {
      out += pad + Json(item.key()).dump() + ": ";
      write(item.value(), indent + 2, out);
      out += ++i < v.size() ? ",\n" : "\n";
    }
    out += std::string(indent, ' ') + "}";
  } else if (v.is_array() && !v.empty()) {
    const bool one_line = is_inline(v);
    out += one_line ? "[" : "[\n";
    for (size_t i = 0; i < v.size(); ++i) {
      if (!one_line) out += pad;
      write(v[i], indent + 2, out);
      if (i + 1 < v.size()) out += one_line ? ", " : ",\n";
    }
    out += one_line ? "]" : "\n" + std::string(indent, ' ') + "]";
  } else {
    out += v.dump();  // scalars, {} and []
  }
}

// "line 3, column 5" of the byte at `at`, counted as nlohmann counts (columns in bytes).
std::string position_text(std::string_view text, size_t at) {
  size_t line = 1, line_start = 0;
  for (size_t i = 0; i < at; ++i)
    if (text[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
  return "line " + std::to_string(line) + ", column " + std::to_string(at - line_start + 1);
}

// The encoding that text which is not UTF-8 looks like: a UTF-16 or UTF-32 byte order mark, or
// the NUL bytes that those encodings give the first (ASCII) character; "" for neither.
std::string other_encoding(std::string_view t) {
  using namespace std::string_view_literals;
  auto starts = [&](std::string_view prefix) { return t.substr(0, prefix.size()) == prefix; };
  auto zero = [&](size_t i) { return i < t.size() && t[i] == 0; };
  auto other = [&](size_t i) { return i < t.size() && t[i] != 0; };
  if (starts("\xff\xfe\0\0"sv)) return "UTF-32 little-endian, with a byte order mark";
  if (starts("\0\0\xfe\xff"sv)) return "UTF-32 big-endian, with a byte order mark";
  if (starts("\xff\xfe"sv)) return "UTF-16 little-endian, with a byte order mark";
  if (starts("\xfe\xff"sv)) return "UTF-16 big-endian, with a byte order mark";
  if (other(0) && zero(1) && zero(2) && zero(3)) return "UTF-32 little-endian";
  if (zero(0) && zero(1) && zero(2) && other(3)) return "UTF-32 big-endian";
  if (other(0) && zero(1)) return "UTF-16 little-endian";
  if (zero(0) && other(1)) return "UTF-16 big-endian";
  return "";
}

// What nlohmann's parser does not check, in one pass over the bytes before it runs: the
// encoding, the nesting depth (with its position: arrays and objects nested 10^5 deep would
// otherwise be built before any check), and NUL bytes. Returns the position of a NUL byte
// outside any string, array or object, after the document's start, or npos: the parser takes
// it for the end of the input, so the text is refused as trailing content if it parses.
size_t check_text(const std::string& text, const std::string& file) {
  if (const std::string encoding = other_encoding(text); !encoding.empty())
    fail(file, "", "not UTF-8 (looks like " + encoding + "); a project file is JSON text in UTF-8");
  int depth = 0;
  bool in_string = false, escaped = false, started = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\0') {
      if (depth == 0 && !in_string && started) return i;
      fail(file, "", "invalid JSON: a NUL byte " + std::string(in_string ? "in a string " : "") +
                         "at " + position_text(text, i) +
                         (in_string ? " (write it as \\u0000)" : ""));
    }
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        fail(file, "", "invalid JSON: arrays and objects nested deeper than " +
                           std::to_string(kMaxJsonDepth) + " levels at " + position_text(text, i));
    } else if (c == ']' || c == '}') {
      depth = std::max(depth - 1, 0);  // an unbalanced one is the parser's syntax error
    }
    if (c != ' ' && c != '\t' && c != '\n' && c != '\r') started = true;
  }
  return std::string::npos;
}

}  // namespace

Json parse_text(const std::string& text, const std::string& file) {
  const size_t nul = check_text(text, file);
  Json doc;
  DuplicateKeySax parser(file, doc);
  Json::sax_parse(text, &parser);  // throws ProjectError on a syntax error or a duplicate key
  if (nul != std::string::npos)
    fail(file, "", "trailing content after the JSON document at " + position_text(text, nul) +
                       " (a NUL byte; only whitespace may follow the document)");
  return doc;
}

std::string pretty_print(const Json& doc) {
  std::string out;
  write(doc, 0, out);
  out += "\n";
  return out;
}

}  // namespace glint::json_fields
