#include "renderer/project_file.h"

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>

#include "renderer/atomic_file.h"
#include "renderer/json_fields.h"
#include "renderer/scene_fields.h"
#include "renderer/scene_validation.h"

namespace glint {

namespace fs = std::filesystem;
using json_fields::Json;
using json_fields::ObjectReader;
using json_fields::child_path;
using json_fields::index_path;

namespace {

// ---- Parsing: structure and types, field by field of scene_fields.h's tables. Values are
// checked afterwards by validate_scene. ----

// The keys of T's table, for ObjectReader's unknown-key check and message.
template <class T>
const std::vector<std::string_view>& keys_of() {
  static const std::vector<std::string_view> keys = [] {
    std::vector<std::string_view> k;
    FieldTable<T>::visit([&](const auto& f) { k.push_back(f.key); });
    return k;
  }();
  return keys;
}

// "matte, reflective, glossy or transparent"
template <class E>
std::string enum_choices() {
  std::string text;
  const auto& values = EnumNames<E>::values;
  for (size_t i = 0; i < values.size(); ++i)
    text += (i == 0 ? "" : i + 1 == values.size() ? " or " : ", ") + std::string(to_string(values[i]));
  return text;
}

template <class E>
E enum_from_string(const std::string& text, bool& ok) {
  for (E value : EnumNames<E>::values)
    if (text == to_string(value)) return ok = true, value;
  ok = false;
  return E{};
}

template <class T>
T parse_object(const Json& j, const std::string& path, const std::string& file);

// One field of `out` from the object `r` reads; the scene.h default stays when it is absent.
template <class F, class T>
void read_field(const ObjectReader& r, const F& f, T& out, const std::string& file) {
  using M = typename F::Type;
  M& value = out.*f.member;
  if constexpr (std::is_same_v<M, std::string>) {
    if (f.has(kNullable)) r.read_optional_string(f.key, value);
    else r.read(f.key, value);
  } else if constexpr (std::is_same_v<M, float> || std::is_same_v<M, glm::vec3>) {
    r.read(f.key, value);
  } else if constexpr (std::is_enum_v<M>) {
    if (const Json* v = r.find(f.key)) {
      const std::string text = json_fields::read_string(*v, file, r.path(f.key));
      bool ok = false;
      value = enum_from_string<M>(text, ok);
      if (!ok)
        json_fields::fail(file, r.path(f.key),
                          std::string("unknown ") + EnumNames<M>::noun + " " +
                              json_fields::quote_name(text) + " (expected " + enum_choices<M>() + ")");
    }
  } else if constexpr (std::is_integral_v<M>) {
    r.read_integer(f.key, static_cast<int64_t>(f.check.lo), static_cast<int64_t>(f.check.hi), value);
  } else if constexpr (kNestedObject<M>) {
    if (const Json* v = r.find(f.key)) value = parse_object<M>(*v, r.path(f.key), file);
  } else {  // std::array<glm::vec3, 4> or std::array<glm::vec2, 4>: quad corners and uvs
    const Json* rows = r.find(f.key);
    if (!rows) return;
    if (!rows->is_array() || rows->size() != value.size())
      json_fields::fail(file, r.path(f.key), "expected an array of 4 points, got " +
                                                 json_fields::describe(*rows));
    for (size_t i = 0; i < value.size(); ++i) {
      const Json& row = (*rows)[i];
      const std::string path = index_path(r.path(f.key), i);
      if constexpr (std::is_same_v<M, std::array<glm::vec3, 4>>)
        value[i] = json_fields::read_vec3(row, file, path);
      else
        value[i] = json_fields::read_vec2(row, file, path);
    }
  }
}

// An object of the file: unknown keys, then the required ones, then each field, in table order.
template <class T>
T parse_object(const Json& j, const std::string& path, const std::string& file) {
  ObjectReader r(j, path, file, keys_of<T>());
  FieldTable<T>::visit([&](const auto& f) {
    if (f.has(kRequired)) r.require(f.key);
  });
  T out;
  FieldTable<T>::visit([&](const auto& f) { read_field(r, f, out, file); });
  return out;
}

// The film's sides are read as any integer first (saturated to int64), then checked together
// with a memory estimate (check_film_size).
template <>
Film parse_object<Film>(const Json& j, const std::string& path, const std::string& file) {
  ObjectReader r(j, path, file, keys_of<Film>());
  Film film;
  std::array<int64_t, field_count<Film>()> sides{};
  size_t n = 0;
  FieldTable<Film>::visit([&](const auto& f) {
    static_assert(std::is_same_v<typename std::decay_t<decltype(f)>::Type, int>);
    const Json* v = r.find(f.key);
    int64_t& side = sides[n++];
    side = film.*f.member;
    if (!v) return;
    if (!v->is_number_integer())
      json_fields::fail(file, r.path(f.key), "expected an integer, got " + json_fields::describe(*v));
    side = v->is_number_unsigned() && v->get<uint64_t>() > uint64_t(INT64_MAX) ? INT64_MAX
                                                                                : v->get<int64_t>();
  });
  if (const auto problem = check_film_size(sides[0], sides[1]))
    json_fields::fail(file, problem->json_path, problem->problem);
  n = 0;
  FieldTable<Film>::visit([&](const auto& f) { film.*f.member = static_cast<int>(sides[n++]); });
  return film;
}

// The largest list of T in a file (scene_validation.h).
template <class T>
constexpr size_t list_limit() {
  if constexpr (std::is_same_v<T, Sphere>) return kMaxSpheres;
  else if constexpr (std::is_same_v<T, Quad>) return kMaxQuads;
  else if constexpr (std::is_same_v<T, CameraView>) return kMaxCameraViews;
  else return SIZE_MAX;
}

// Reads the array under `key` of the root object, one element at a time; an array longer
// than its limit is refused before any element is read.
template <class T>
void parse_list(const ObjectReader& root, const char* key, std::vector<T>& out,
                const std::string& file) {
  const Json* items = root.array(key);
  if (items && items->size() > list_limit<T>())
    json_fields::fail(file, key, std::is_same_v<T, CameraView>
                                     ? too_many_views_problem(items->size())
                                     : too_many_problem(items->size(), list_limit<T>(), key));
  if (items)
    for (size_t i = 0; i < items->size(); ++i)
      out.push_back(parse_object<T>((*items)[i], index_path(key, i), file));
}

// ---- Writing: every field of every table, in table order. ----

template <class T>
Json object_to_json(const T& object);

template <class M>
Json value_to_json(const M& value, unsigned flags) {
  if constexpr (std::is_same_v<M, std::string>) {
    return (flags & kNullable) && value.empty() ? Json(nullptr) : Json(value);
  } else if constexpr (std::is_same_v<M, float>) {
    return json_fields::float_to_json(value);
  } else if constexpr (std::is_same_v<M, glm::vec2> || std::is_same_v<M, glm::vec3>) {
    return json_fields::vec_to_json(value);
  } else if constexpr (std::is_enum_v<M>) {
    return to_string(value);
  } else if constexpr (std::is_integral_v<M>) {
    return value;
  } else if constexpr (kNestedObject<M>) {
    return object_to_json(value);
  } else {  // arrays of points
    Json rows = Json::array();
    for (const auto& row : value) rows.push_back(json_fields::vec_to_json(row));
    return rows;
  }
}

template <class T>
Json object_to_json(const T& object) {
  Json j = Json::object();
  FieldTable<T>::visit([&](const auto& f) { j[f.key] = value_to_json(object.*f.member, f.flags); });
  return j;
}

// Calls fn(json_path, text) for every string field of the scene, in file order, with `flag`
// (or every string when flag is 0). S is Scene or const Scene.
template <class S, class Fn>
void for_each_string(S& scene, unsigned flag, Fn&& fn) {
  auto object = [&](const std::string& path, auto& o) {
    using T = std::remove_const_t<std::remove_reference_t<decltype(o)>>;
    FieldTable<T>::visit([&](const auto& f) {
      if constexpr (std::is_same_v<typename std::decay_t<decltype(f)>::Type, std::string>)
        if (flag == 0 || f.has(flag)) fn(child_path(path, f.key), o.*f.member);
    });
  };
  visit_scene_parts([&](const char* key, auto member) {
    auto& part = scene.*member;
    if constexpr (IsVector<std::remove_const_t<std::remove_reference_t<decltype(part)>>>::value) {
      for (size_t i = 0; i < part.size(); ++i) object(index_path(key, i), part[i]);
    } else {
      object(key, part);
    }
  });
}

// A relative asset path rewritten for a new folder; both folders are absolute.
std::string rebase_path(const std::string& path, const fs::path& from, const fs::path& to) {
  if (path.empty() || fs::path(path).is_absolute()) return path;
  std::error_code ec;
  const fs::path target = (from / path).lexically_normal();
  const fs::path relative = fs::relative(target, to, ec);
  return (ec || relative.empty() ? target : relative).generic_string();
}

// An absolute asset path as seen from `folder` (absolute, symbolic links resolved); the path
// itself when it has no relative form (another root name).
std::string relative_to_folder(const std::string& path, const fs::path& folder) {
  fs::path target(path);
  if (path.empty() || !target.is_absolute()) return path;
  std::error_code ec;
  // A `..` inside the path climbs from wherever its links lead: resolve it before comparing.
  const bool climbs = std::any_of(target.begin(), target.end(), [](const fs::path& part) { return part == ".."; });
  if (climbs) {
    const fs::path resolved = fs::weakly_canonical(target, ec);
    if (ec) return path;
    target = resolved;
  }
  const fs::path relative = target.lexically_normal().lexically_relative(folder);
  return relative.empty() ? path : relative.generic_string();
}

fs::path folder_identity(const fs::path& folder) {
  const fs::path absolute = fs::absolute(folder.empty() ? fs::current_path() : folder);
  std::error_code ec;
  fs::path canonical = fs::weakly_canonical(absolute, ec);
  if (ec) canonical = absolute.lexically_normal();
  return canonical.has_filename() ? canonical : canonical.parent_path();
}

}  // namespace

Scene scene_from_json(const nlohmann::ordered_json& doc, const std::string& file,
                      const fs::path& base_dir, bool check_files) {
  using json_fields::fail;
  if (!doc.is_object()) fail(file, "", "expected a JSON object, got " + json_fields::describe(doc));
  // Format and version first: another kind of JSON file gets a clear message, not "unknown key".
  const auto format = doc.find("format");
  if (format == doc.end())
    fail(file, "format", "missing (a Glint project has \"format\": \"glint-project\")");
  if (*format != "glint-project")
    fail(file, "format", "expected \"glint-project\", got " + json_fields::describe(*format));
  const auto version = doc.find("version");
  if (version == doc.end()) fail(file, "version", "missing required key");
  if (*version != 1)
    fail(file, "version",
         "unsupported version " + version->dump() + " (this program reads version 1)");

  std::vector<std::string_view> root_keys = {"format", "version"};
  visit_scene_parts([&](const char* key, auto) { root_keys.push_back(key); });
  ObjectReader root(doc, "", file, root_keys);
  Scene s;
  s.base_dir = base_dir;
  visit_scene_parts([&](const char* key, auto member) {
    auto& part = s.*member;
    using Part = std::remove_reference_t<decltype(part)>;
    if constexpr (IsVector<Part>::value) {
      parse_list(root, key, part, file);
    } else if (const Json* j = root.find(key)) {
      part = parse_object<Part>(*j, key, file);
    }
  });

  const auto problems = validate_scene(s, check_files);
  if (!problems.empty()) fail(file, problems.front().json_path, problems.front().problem);
  return s;
}

Scene scene_from_json(const nlohmann::json& doc, const std::string& file_label,
                      const fs::path& base_dir, bool check_files) {
  return scene_from_json(nlohmann::ordered_json(doc), file_label, base_dir, check_files);
}

nlohmann::ordered_json scene_to_json(const Scene& s) {
  Json j;
  j["format"] = "glint-project";
  j["version"] = 1;
  visit_scene_parts([&](const char* key, auto member) {
    const auto& part = s.*member;
    using Part = std::remove_const_t<std::remove_reference_t<decltype(part)>>;
    if constexpr (std::is_same_v<Part, std::vector<CameraView>>) {
      // Optional: a project without views is written as before (and older versions read it).
      if (part.empty()) return;
    }
    if constexpr (IsVector<Part>::value) {
      Json& list = j[key] = Json::array();
      for (const auto& item : part) list.push_back(object_to_json(item));
    } else {
      j[key] = object_to_json(part);
    }
  });
  return j;
}

std::string project_file_text(const Scene& scene) {
  return json_fields::pretty_print(scene_to_json(scene));
}

Scene rebase_asset_paths(const Scene& scene, const fs::path& new_base_dir) {
  Scene out = scene;
  out.base_dir = new_base_dir;
  // The same path is the same folder: no file system calls (the fuzz target saves every input).
  if (scene.base_dir == new_base_dir) return out;
  const fs::path from = folder_identity(scene.base_dir), to = folder_identity(new_base_dir);
  if (from == to) return out;  // same folder: keep the paths exactly as they are
  for_each_string(out, kAssetPath,
                  [&](const std::string&, std::string& path) { path = rebase_path(path, from, to); });
  return out;
}

Scene relative_asset_paths(const Scene& scene, const fs::path& folder) {
  Scene out = scene;
  bool any_absolute = false;
  for_each_string(out, kAssetPath, [&](const std::string&, std::string& path) {
    any_absolute = any_absolute || fs::path(path).is_absolute();
  });
  if (!any_absolute) return out;  // no file system calls for the common case
  const fs::path from = folder_identity(folder);
  for_each_string(out, kAssetPath,
                  [&](const std::string&, std::string& path) { path = relative_to_folder(path, from); });
  return out;
}

Scene load_project_text(const std::string& text, const std::string& file_label,
                        const fs::path& base_dir, bool check_files) {
  return scene_from_json(json_fields::parse_text(text, file_label), file_label, base_dir,
                         check_files);
}

// The JSON path of the first string of the scene that is not valid UTF-8, or "".
static std::string first_non_utf8_string(const Scene& s) {
  std::string bad;
  for_each_string(s, 0, [&](const std::string& path, const std::string& text) {
    if (bad.empty() && !json_fields::is_valid_utf8(text)) bad = path;
  });
  return bad;
}

static std::string project_size_problem(uintmax_t size) {
  return "file is too large (" + std::to_string(size) + " bytes, the limit is " +
         std::to_string(kMaxProjectBytes) + " = " + bytes_text(double(kMaxProjectBytes)) + ")";
}

Scene load_project(const fs::path& file) {
  const std::string label = file.string();
  std::error_code ec;
  if (!fs::exists(file, ec) && !ec) throw ProjectError(label, "", "no such file");
  if (fs::is_directory(file, ec)) throw ProjectError(label, "", "is a folder, not a project file");
  // A FIFO or device (a project named /dev/zero, or a link to it) would block or never end.
  const bool regular = fs::is_regular_file(file, ec);
  if (ec) throw ProjectError(label, "", "cannot open: " + ec.message());  // a symlink loop, say
  if (!regular) throw ProjectError(label, "", "not a regular file (a device, FIFO or socket)");
  const auto size = fs::file_size(file, ec);
  if (!ec && size > kMaxProjectBytes) throw ProjectError(label, "", project_size_problem(size));
  std::ifstream in(file, std::ios::binary);
  if (!in) throw ProjectError(label, "", std::string("cannot open: ") + std::strerror(errno));
  // Read at most one byte past the limit: the file may grow after file_size.
  std::string text;
  text.reserve(ec ? 0 : static_cast<size_t>(size));
  char buffer[65536];
  while (text.size() <= kMaxProjectBytes && in.read(buffer, sizeof buffer).gcount() > 0)
    text.append(buffer, static_cast<size_t>(in.gcount()));
  if (in.bad()) throw ProjectError(label, "", "cannot read the file");
  if (text.size() > kMaxProjectBytes) throw ProjectError(label, "", project_size_problem(text.size()));
  try {
    return load_project_text(text, label, fs::absolute(file).parent_path(), true);
  } catch (const ProjectError&) {
    throw;
  } catch (const std::exception& e) {  // a safety net: nothing else escapes as another type
    throw ProjectError(label, "", e.what());
  }
}

std::string save_project_text(const Scene& scene, const fs::path& file) {
  const std::string label = file.string();
  try {
    const fs::path folder = fs::absolute(file).parent_path();
    const Scene rebased = relative_asset_paths(rebase_asset_paths(scene, folder), folder);
    // JSON text is UTF-8: a path from a folder named in another encoding cannot be stored.
    if (const std::string bad = first_non_utf8_string(rebased); !bad.empty())
      throw ProjectError(label, bad, "is not valid UTF-8, which a JSON file cannot hold "
                                     "(rename the file or folder)");
    return project_file_text(rebased);
  } catch (const ProjectError&) {
    throw;
  } catch (const std::exception& e) {  // invalid UTF-8 in a name, or a filesystem error
    throw ProjectError(label, "", std::string("cannot write the scene: ") + e.what());
  }
}

void save_project(const Scene& scene, const fs::path& file) {
  const std::string text = save_project_text(scene, file);
  try {
    write_file_atomically(file, text.data(), text.size());
  } catch (const FileWriteError& e) {
    throw ProjectError(file.string(), "", e.problem);
  }
}

}  // namespace glint
