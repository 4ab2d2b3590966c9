#include "renderer/json_fields.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <set>
#include <vector>

namespace glint::json_fields {

std::string child_path(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}

std::string index_path(const std::string& path, size_t index) {
  return path + "[" + std::to_string(index) + "]";
}

std::string describe(const Json& value) {
  switch (value.type()) {
    case Json::value_t::null: return "null";
    case Json::value_t::boolean: return "boolean " + value.dump();
    case Json::value_t::string: {
      std::string text = value.dump(-1, ' ', false, Json::error_handler_t::replace);
      if (text.size() > 42) text = text.substr(0, 40) + "...\"";
      return "string " + text;
    }
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
                           std::initializer_list<std::string_view> allowed_keys)
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

// Follows the parser's events to know the JSON path of each key, so that a key given twice in
// one object (which nlohmann would silently resolve to the last value) is reported.
class DuplicateKeyCheck {
 public:
  explicit DuplicateKeyCheck(const std::string& file) : file_(file) {}

  bool operator()(int, Json::parse_event_t event, Json& parsed) {
    using E = Json::parse_event_t;
    switch (event) {
      case E::object_start:
      case E::array_start:
        frames_.push_back({event == E::array_start, 0, {}, {}, element_path()});
        break;
      case E::key: {
        Frame& f = frames_.back();
        f.key = parsed.get<std::string>();
        if (!f.keys.insert(f.key).second) fail(file_, child_path(f.path, f.key), "duplicate key");
        break;
      }
      case E::object_end:
      case E::array_end: frames_.pop_back(); next_element(); break;
      case E::value: next_element(); break;
    }
    return true;
  }

 private:
  struct Frame {
    bool is_array;
    size_t index;
    std::string key;
    std::set<std::string> keys;
    std::string path;
  };

  std::string element_path() const {
    if (frames_.empty()) return "";
    const Frame& parent = frames_.back();
    return parent.is_array ? index_path(parent.path, parent.index)
                           : child_path(parent.path, parent.key);
  }
  void next_element() {
    if (!frames_.empty() && frames_.back().is_array) ++frames_.back().index;
  }

  const std::string& file_;
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

}  // namespace

Json parse_text(const std::string& text, const std::string& file) {
  try {
    return Json::parse(text, DuplicateKeyCheck(file));
  } catch (const Json::exception& e) {
    // "[json.exception.parse_error.101] parse error at line 3, column 5: ..." -> drop the tag.
    std::string message = e.what();
    const auto end = message.find("] ");
    if (message.starts_with("[json.exception") && end != std::string::npos)
      message.erase(0, end + 2);
    fail(file, "", "invalid JSON: " + message);
  }
}

std::string pretty_print(const Json& doc) {
  std::string out;
  write(doc, 0, out);
  out += "\n";
  return out;
}

}  // namespace glint::json_fields
