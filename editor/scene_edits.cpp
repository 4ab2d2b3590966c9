// Scene edits on plain values (see scene_edits.h). Every function keeps a valid scene valid:
// names unique per kind, references follow renames, nothing dangles after a delete.
#include "editor/scene_edits.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <system_error>

#include "editor/object_placement.h"
#include "renderer/texture_slots.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

template <class T>
bool name_taken(const std::vector<T>& items, const std::string& name, int except = -1) {
  for (size_t i = 0; i < items.size(); ++i)
    if (static_cast<int>(i) != except && items[i].name == name) return true;
  return false;
}

// base, base_2, base_3, ...; a base that already ends in _N counts on from its stem, so that
// duplicating "ball_2" gives "ball_3" rather than "ball_2_2".
template <class T>
std::string unique_name(const std::vector<T>& items, std::string base, const char* fallback) {
  if (base.empty()) base = fallback;
  if (!name_taken(items, base)) return base;
  std::string stem = base;
  const size_t underscore = base.rfind('_');
  if (underscore != std::string::npos && underscore > 0 && underscore + 1 < base.size() &&
      std::all_of(base.begin() + static_cast<long>(underscore) + 1, base.end(),
                  [](unsigned char c) { return std::isdigit(c); }))
    stem = base.substr(0, underscore);
  for (int n = 2;; ++n) {
    std::string candidate = stem + "_" + std::to_string(n);
    if (!name_taken(items, candidate)) return candidate;
  }
}

template <class T>
bool in_range(const std::vector<T>& items, int index) {
  return index >= 0 && static_cast<size_t>(index) < items.size();
}

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

struct View {
  glm::vec3 forward, right, up;
};

// The camera's orthonormal frame (as make_camera_frame builds it), with fallbacks for a
// degenerate camera so that edits never produce NaNs.
View camera_view(const Camera& c) {
  glm::vec3 f = c.target - c.position;
  f = glm::length(f) > 0 && finite(f) ? glm::normalize(f) : glm::vec3(0, 0, -1);
  glm::vec3 r = glm::cross(f, c.up);
  if (!(glm::length(r) > 1e-6f) || !finite(r)) r = glm::cross(f, std::abs(f.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0));
  r = glm::normalize(r);
  return {f, r, glm::cross(r, f)};
}

// Where new objects go: at the focus distance along the view (at least 1 unit away).
float placement_distance(const Camera& c) {
  const float d = c.focus_distance;
  return std::isfinite(d) ? std::max(d, 1.0f) : 1.0f;
}

glm::vec3 quad_center(const Quad& q) {
  return (q.corners[0] + q.corners[1] + q.corners[2] + q.corners[3]) * 0.25f;
}

// The rotation matrix of intrinsic X-Y-Z Euler angles: R = Rx(a) Ry(b) Rz(c).
glm::mat3 euler_xyz(glm::vec3 deg) {
  const glm::vec3 r = glm::radians(deg);
  const float ca = std::cos(r.x), sa = std::sin(r.x), cb = std::cos(r.y), sb = std::sin(r.y),
              cc = std::cos(r.z), sc = std::sin(r.z);
  // glm::mat3 is column-major: m[col][row].
  glm::mat3 m;
  m[0] = {cb * cc, ca * sc + sa * sb * cc, sa * sc - ca * sb * cc};
  m[1] = {-cb * sc, ca * cc - sa * sb * sc, sa * cc + ca * sb * sc};
  m[2] = {sb, -sa * cb, ca * cb};
  return m;
}

}  // namespace

std::string unique_sphere_name(const Scene& scene, const std::string& base) {
  return unique_name(scene.spheres, base, "sphere");
}
std::string unique_quad_name(const Scene& scene, const std::string& base) {
  return unique_name(scene.quads, base, "quad");
}
std::string unique_material_name(const Scene& scene, const std::string& base) {
  return unique_name(scene.materials, base, "material");
}
std::string unique_texture_name(const Scene& scene, const std::string& base) {
  return unique_name(scene.textures, base, "texture");
}

bool is_neutral(const Material& m) {
  return m.type == MaterialType::matte && m.color.x == m.color.y && m.color.y == m.color.z &&
         m.color.x > 0.05f && m.color.x < 0.95f && m.color_texture.empty() && m.emission == glm::vec3(0) &&
         m.emission_texture.empty() && m.opacity == 1;
}

std::string default_material(Scene& scene) {
  // A neutral grey matte one: "default" if it is neutral, else the first neutral one.
  for (const Material& m : scene.materials)
    if (m.name == "default" && is_neutral(m)) return m.name;
  for (const Material& m : scene.materials)
    if (is_neutral(m)) return m.name;
  Material m;
  m.name = unique_material_name(scene, "default");
  m.type = MaterialType::matte;
  m.color = {0.8f, 0.8f, 0.8f};
  scene.materials.push_back(m);
  return m.name;
}

int add_sphere(Scene& scene) {
  const View v = camera_view(scene.camera);
  const float d = placement_distance(scene.camera);
  Sphere s;
  s.name = unique_sphere_name(scene, "sphere");
  s.radius = d * 0.1f;
  s.center = free_sphere_center(scene, scene.camera.position + v.forward * d, s.radius, v.right, v.up);
  s.material = default_material(scene);
  scene.spheres.push_back(s);
  return static_cast<int>(scene.spheres.size()) - 1;
}

int add_quad(Scene& scene) {
  const View view = camera_view(scene.camera);
  const AxisFrame v = nearest_axis_frame(view.forward, view.up);
  const float d = placement_distance(scene.camera);
  const float h = d * 0.1f;  // half the side, so it is as large as a new sphere
  const glm::vec3 c = scene.camera.position + view.forward * d;
  Quad q;
  q.name = unique_quad_name(scene, "quad");
  q.material = default_material(scene);
  // p0 top-left, p2 top-right (u), p1 bottom-left (v down, as image rows): the texture reads
  // upright and the normal cross(p1 - p0, p2 - p0) = cross(-up, right) points at the camera.
  const glm::vec3 p0 = c - v.right * h + v.up * h;
  q.corners = {p0, p0 - v.up * (2 * h), p0 + v.right * (2 * h),
               p0 + v.right * (2 * h) - v.up * (2 * h)};
  scene.quads.push_back(q);
  return static_cast<int>(scene.quads.size()) - 1;
}

int add_material(Scene& scene, MaterialType type) {
  Material m;
  m.name = unique_material_name(scene, to_string(type));
  m.type = type;
  if (type == MaterialType::glossy) m.roughness = 0.2f;
  if (type == MaterialType::transparent || type == MaterialType::refractive) m.color = {1, 1, 1};
  scene.materials.push_back(m);
  return static_cast<int>(scene.materials.size()) - 1;
}

int add_texture(Scene& scene, const std::filesystem::path& file) {
  std::error_code ec;
  const fs::path base = fs::absolute(scene.base_dir.empty() ? fs::current_path(ec) : scene.base_dir, ec)
                            .lexically_normal();
  const fs::path abs = fs::absolute(file, ec).lexically_normal();
  // Reuse an entry that already names this file.
  for (size_t i = 0; i < scene.textures.size(); ++i) {
    const fs::path existing =
        fs::absolute(resolve_asset_path(scene, scene.textures[i].path), ec).lexically_normal();
    if (existing == abs || (fs::exists(abs, ec) && fs::equivalent(existing, abs, ec)))
      return static_cast<int>(i);
  }
  // Relative when below base_dir (lexically, then through symlinks), else absolute.
  auto below = [](const fs::path& p, const fs::path& dir) -> std::optional<fs::path> {
    const fs::path rel = p.lexically_relative(dir);
    if (rel.empty() || *rel.begin() == "..") return std::nullopt;
    return rel;
  };
  std::optional<fs::path> rel = below(abs, base);
  if (!rel) {
    const fs::path cb = fs::weakly_canonical(base, ec), cf = fs::weakly_canonical(abs, ec);
    if (!ec) rel = below(cf, cb);
  }
  Texture t;
  t.path = rel ? rel->generic_string() : abs.generic_string();
  t.name = unique_texture_name(scene, file.stem().string());
  scene.textures.push_back(t);
  return static_cast<int>(scene.textures.size()) - 1;
}

int duplicate(Scene& scene, Selection what) {
  const glm::vec3 right = camera_view(scene.camera).right;
  constexpr float kBeside = 1.25f;  // the object's width and a quarter: beside it, a gap between
  switch (what.kind) {
    case SelectionKind::sphere: {
      if (!in_range(scene.spheres, what.index)) return -1;
      Sphere s = scene.spheres[static_cast<size_t>(what.index)];
      s.name = unique_sphere_name(scene, s.name);
      s.center += right * (2 * s.radius * kBeside);
      scene.spheres.push_back(s);
      return static_cast<int>(scene.spheres.size()) - 1;
    }
    case SelectionKind::quad: {
      if (!in_range(scene.quads, what.index)) return -1;
      Quad q = scene.quads[static_cast<size_t>(what.index)];
      q.name = unique_quad_name(scene, q.name);
      // Its width across the view; a quad seen edge-on has none there: its largest extent then.
      const glm::vec3 c = quad_center(q);
      float width = 0, extent = 0;
      for (const glm::vec3& p : q.corners) {
        width = std::max(width, 2 * std::abs(glm::dot(p - c, right)));
        extent = std::max(extent, 2 * glm::length(p - c));
      }
      if (width < 0.05f * extent) width = extent;
      for (glm::vec3& p : q.corners) p += right * (width * kBeside);
      scene.quads.push_back(q);
      return static_cast<int>(scene.quads.size()) - 1;
    }
    case SelectionKind::material: {
      if (!in_range(scene.materials, what.index)) return -1;
      Material m = scene.materials[static_cast<size_t>(what.index)];
      m.name = unique_material_name(scene, m.name);
      scene.materials.push_back(m);
      return static_cast<int>(scene.materials.size()) - 1;
    }
    case SelectionKind::texture: {
      if (!in_range(scene.textures, what.index)) return -1;
      Texture t = scene.textures[static_cast<size_t>(what.index)];
      t.name = unique_texture_name(scene, t.name);
      scene.textures.push_back(t);
      return static_cast<int>(scene.textures.size()) - 1;
    }
    default: return -1;
  }
}

std::vector<std::string> material_users(const Scene& scene, const std::string& material) {
  std::vector<std::string> users;
  for (const Sphere& s : scene.spheres)
    if (s.material == material) users.push_back("sphere " + s.name);
  for (const Quad& q : scene.quads)
    if (q.material == material) users.push_back("quad " + q.name);
  return users;
}

Selection remove(Scene& scene, Selection what) {
  const size_t i = static_cast<size_t>(what.index);
  switch (what.kind) {
    case SelectionKind::sphere:
      if (!in_range(scene.spheres, what.index)) return what;
      scene.spheres.erase(scene.spheres.begin() + what.index);
      return {};
    case SelectionKind::quad:
      if (!in_range(scene.quads, what.index)) return what;
      scene.quads.erase(scene.quads.begin() + what.index);
      return {};
    case SelectionKind::material: {
      if (!in_range(scene.materials, what.index)) return what;
      const std::string name = scene.materials[i].name;
      scene.materials.erase(scene.materials.begin() + what.index);
      bool used = false;
      for (const Sphere& s : scene.spheres) used = used || s.material == name;
      for (const Quad& q : scene.quads) used = used || q.material == name;
      if (used) {
        // The default is taken after the erase: a neutral remaining material, or a new grey
        // one (objects always keep a material).
        const std::string replacement = default_material(scene);
        for (Sphere& s : scene.spheres)
          if (s.material == name) s.material = replacement;
        for (Quad& q : scene.quads)
          if (q.material == name) q.material = replacement;
      }
      return {};
    }
    case SelectionKind::texture: {
      if (!in_range(scene.textures, what.index)) return what;
      const std::string name = scene.textures[i].name;
      scene.textures.erase(scene.textures.begin() + what.index);
      for (Material& m : scene.materials)
        for (const TextureSlot& slot : kTextureSlots)
          if (m.*slot.member == name) (m.*slot.member).clear();
      return {};
    }
    default: return what;  // the environment and the camera cannot be deleted
  }
}

bool rename(Scene& scene, Selection what, const std::string& name) {
  if (name.empty()) return false;
  const size_t i = static_cast<size_t>(what.index);
  switch (what.kind) {
    case SelectionKind::sphere:
      if (!in_range(scene.spheres, what.index) || name_taken(scene.spheres, name, what.index))
        return false;
      scene.spheres[i].name = name;
      return true;
    case SelectionKind::quad:
      if (!in_range(scene.quads, what.index) || name_taken(scene.quads, name, what.index))
        return false;
      scene.quads[i].name = name;
      return true;
    case SelectionKind::material: {
      if (!in_range(scene.materials, what.index) || name_taken(scene.materials, name, what.index))
        return false;
      const std::string old = scene.materials[i].name;
      scene.materials[i].name = name;
      for (Sphere& s : scene.spheres)
        if (s.material == old) s.material = name;
      for (Quad& q : scene.quads)
        if (q.material == old) q.material = name;
      return true;
    }
    case SelectionKind::texture: {
      if (!in_range(scene.textures, what.index) || name_taken(scene.textures, name, what.index))
        return false;
      const std::string old = scene.textures[i].name;
      scene.textures[i].name = name;
      for (Material& m : scene.materials)
        for (const TextureSlot& slot : kTextureSlots)
          if (m.*slot.member == old) m.*slot.member = name;
      return true;
    }
    default: return false;
  }
}

std::string name_of(const Scene& scene, Selection what) {
  const size_t i = static_cast<size_t>(what.index);
  switch (what.kind) {
    case SelectionKind::sphere: return in_range(scene.spheres, what.index) ? scene.spheres[i].name : "";
    case SelectionKind::quad: return in_range(scene.quads, what.index) ? scene.quads[i].name : "";
    case SelectionKind::material:
      return in_range(scene.materials, what.index) ? scene.materials[i].name : "";
    case SelectionKind::texture:
      return in_range(scene.textures, what.index) ? scene.textures[i].name : "";
    case SelectionKind::environment: return "environment";
    case SelectionKind::camera: return "camera";
    default: return "";
  }
}

std::optional<Selection> find_object(const Scene& scene, const std::string& name) {
  for (size_t i = 0; i < scene.spheres.size(); ++i)
    if (scene.spheres[i].name == name) return Selection{SelectionKind::sphere, static_cast<int>(i)};
  for (size_t i = 0; i < scene.quads.size(); ++i)
    if (scene.quads[i].name == name) return Selection{SelectionKind::quad, static_cast<int>(i)};
  return std::nullopt;
}

std::optional<glm::vec3> selection_center(const Scene& scene, Selection what) {
  if (what.kind == SelectionKind::sphere && in_range(scene.spheres, what.index))
    return scene.spheres[static_cast<size_t>(what.index)].center;
  if (what.kind == SelectionKind::quad && in_range(scene.quads, what.index))
    return quad_center(scene.quads[static_cast<size_t>(what.index)]);
  return std::nullopt;
}

std::optional<BoundingSphere> selection_bounds(const Scene& scene, Selection what) {
  if (what.kind == SelectionKind::sphere && in_range(scene.spheres, what.index)) {
    const Sphere& s = scene.spheres[static_cast<size_t>(what.index)];
    return BoundingSphere{s.center, s.radius};
  }
  if (what.kind == SelectionKind::quad && in_range(scene.quads, what.index)) {
    const Quad& q = scene.quads[static_cast<size_t>(what.index)];
    const glm::vec3 c = quad_center(q);
    float r = 0;
    for (const glm::vec3& p : q.corners) r = std::max(r, glm::length(p - c));
    return BoundingSphere{c, r};
  }
  return std::nullopt;
}

void translate(Scene& scene, Selection what, glm::vec3 delta) {
  if (!finite(delta)) return;
  if (what.kind == SelectionKind::sphere && in_range(scene.spheres, what.index))
    scene.spheres[static_cast<size_t>(what.index)].center += delta;
  if (what.kind == SelectionKind::quad && in_range(scene.quads, what.index))
    for (glm::vec3& p : scene.quads[static_cast<size_t>(what.index)].corners) p += delta;
}

glm::mat3 quad_frame(const Quad& quad) {
  // Orthonormalise (exact for rectangles).
  const glm::vec3 ex = quad.corners[2] - quad.corners[0];
  const glm::vec3 ey = quad.corners[1] - quad.corners[0];
  const float lx = glm::length(ex);
  if (!(lx > 0) || !std::isfinite(lx)) return glm::mat3(1);
  const glm::vec3 x = ex / lx;
  glm::vec3 y = ey - x * glm::dot(ey, x);
  if (!(glm::length(y) > 0) || !finite(y)) return glm::mat3(1);
  y = glm::normalize(y);
  return glm::mat3(x, y, glm::cross(x, y));
}

QuadPlacement quad_placement(const Quad& quad) {
  QuadPlacement out;
  out.center = quad_center(quad);
  out.size = {glm::length(quad.corners[2] - quad.corners[0]), glm::length(quad.corners[1] - quad.corners[0])};
  if (!(out.size.x > 0) || !(out.size.y > 0)) return out;
  // The Euler angles of R = Rx Ry Rz whose columns are the frame's axes.
  const glm::mat3 frame = quad_frame(quad);
  const glm::vec3 x = frame[0], y = frame[1], z = frame[2];
  float a, b, c;
  b = std::asin(std::clamp(z.x, -1.0f, 1.0f));  // R[row 0][col 2]
  if (std::abs(z.x) < 0.99999f) {
    a = std::atan2(-z.y, z.z);  // -R12, R22
    c = std::atan2(-y.x, x.x);  // -R01, R00
  } else {  // gimbal lock: only a + c (or a - c) is defined; put it all in a
    c = 0;
    a = std::atan2(y.z, y.y);  // R21, R11
  }
  out.rotation_deg = glm::degrees(glm::vec3(a, b, c));
  // Angles within rounding of zero (atan2(-0, x) is -0, and an axis-aligned quad's frame is
  // off by an ulp) read as +0, so the panel never shows "-0.0 deg".
  // A half turn reads as +180, whichever sign atan2 gave it.
  for (int k = 0; k < 3; ++k) {
    if (std::abs(out.rotation_deg[k]) < 1e-3f) out.rotation_deg[k] = 0.0f;
    if (out.rotation_deg[k] < -180 + 1e-3f) out.rotation_deg[k] = 180.0f;
  }
  return out;
}

void set_quad_placement(Quad& quad, const QuadPlacement& placement) {
  // Invalid input (zero or negative size, non-finite values) keeps the quad as it was, so the
  // scene stays valid whatever the UI fields hold.
  if (!finite(placement.center) || !finite(placement.rotation_deg) ||
      !(placement.size.x > 0) || !(placement.size.y > 0) || !std::isfinite(placement.size.x) ||
      !std::isfinite(placement.size.y))
    return;
  const glm::mat3 r = euler_xyz(placement.rotation_deg);
  const glm::vec3 x = r[0] * placement.size.x, y = r[1] * placement.size.y;
  const glm::vec3 p0 = placement.center - 0.5f * x - 0.5f * y;
  quad.corners = {p0, p0 + y, p0 + x, p0 + x + y};
}

}  // namespace glint
