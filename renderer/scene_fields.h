// The fields of the scene's structs, listed once (as Mitsuba's `traverse` lists an object's
// parameters): each entry names the project file's key, the member, what kind of value it is
// and its value check. The project file's reader and writer (project_file.cpp), validate_scene
// (scene_validation.cpp) and the digests (scene_digest.cpp) walk these tables instead of
// listing the members again, so a field is read, written, checked and digested as soon as it is
// listed here. Table order is the file's key order (docs/DESIGN.md §6) and the order in which
// problems are reported.
//
// A member added to a struct of scene.h fails to compile below (the structured bindings of
// every_member_is_listed) until the table lists it and its count is raised.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "renderer/material_types.h"
#include "renderer/scene.h"
#include "renderer/texture_slots.h"

namespace glint {

// What a field is besides its C++ type.
enum FieldFlag : unsigned {
  kRequired = 1u << 0,     // the file must have the key (absent keys take the scene.h default)
  kNullable = 1u << 1,     // a string that is "" for none, written as null
  kLabel = 1u << 2,        // a name for the user only: not rendered, so in no digest
  kUniqueName = 1u << 3,   // non-empty and unique within its list; references look it up
  kAssetPath = 1u << 4,    // an image file relative to the project (rebased by Save As); the
                           // digest covers the file's size and modification time
  kTextureRef = 1u << 5,   // the name of a texture, or none
  kMaterialRef = 1u << 6,  // the name of a material
  kFilmSide = 1u << 7,     // read as any integer, checked with the other side by check_film_size
};

// The check of a number, applied to each component of a vector and each element of an array.
struct FieldCheck {
  enum Kind { none, finite, at_least, greater_than, unit_interval, open_interval_degrees, integer_in };
  Kind kind = none;
  double lo = 0, hi = 0;  // the bounds (exact for the floats and integers used here)
};
constexpr FieldCheck finite() { return {FieldCheck::finite}; }
constexpr FieldCheck at_least(double min) { return {FieldCheck::at_least, min}; }
constexpr FieldCheck greater_than(double min) { return {FieldCheck::greater_than, min}; }
constexpr FieldCheck unit_interval() { return {FieldCheck::unit_interval}; }
constexpr FieldCheck open_interval_degrees(double lo, double hi) {
  return {FieldCheck::open_interval_degrees, lo, hi};
}
constexpr FieldCheck integer_in(double min, double max) { return {FieldCheck::integer_in, min, max}; }

// One entry of a table: the key, the member of T, flags and check.
template <class T, class M>
struct Field {
  using Owner = T;
  using Type = M;
  const char* key;
  M T::*member;
  unsigned flags = 0;
  FieldCheck check = {};
  constexpr bool has(unsigned flag) const { return (flags & flag) != 0; }
};
template <class T, class M>
constexpr Field<T, M> field(const char* key, M T::*member, unsigned flags = 0) {
  return {key, member, flags, {}};
}
template <class T, class M>
constexpr Field<T, M> field(const char* key, M T::*member, FieldCheck check) {
  return {key, member, 0, check};
}
template <class T, class M>
constexpr Field<T, M> field(const char* key, M T::*member, unsigned flags, FieldCheck check) {
  return {key, member, flags, check};
}

// The names of an enum's values in the file, and what one is called in messages.
template <class E>
struct EnumNames;
template <>
struct EnumNames<MaterialType> {
  static constexpr const char* noun = "material type";
  static constexpr std::array values = all_material_types();
};
template <>
struct EnumNames<Tonemap> {
  static constexpr const char* noun = "tonemap";
  static constexpr std::array values = {Tonemap::filmic, Tonemap::linear};
};

template <class T>
struct FieldTable;  // visit(v) calls v(field) for each field of T, in file order

// The largest max_bounces (docs/DESIGN.md §6).
constexpr int kMaxBounces = 1024;

template <>
struct FieldTable<Camera> {
  template <class V>
  static constexpr void visit(V&& v) {
    v(field("position", &Camera::position, finite()));
    v(field("target", &Camera::target, finite()));
    v(field("up", &Camera::up, finite()));
    v(field("vfov_deg", &Camera::vfov_deg, open_interval_degrees(0, 180)));
    v(field("aperture_radius", &Camera::aperture_radius, at_least(0)));
    v(field("focus_distance", &Camera::focus_distance, greater_than(0)));
  }
};

template <>
struct FieldTable<Film> {
  template <class V>
  static constexpr void visit(V&& v) {
    v(field("width", &Film::width, kFilmSide));
    v(field("height", &Film::height, kFilmSide));
  }
};

template <>
struct FieldTable<RenderSettings> {
  template <class V>
  static constexpr void visit(V&& v) {
    v(field("max_bounces", &RenderSettings::max_bounces, integer_in(0, kMaxBounces)));
    v(field("seed", &RenderSettings::seed, integer_in(0, UINT32_MAX)));
  }
};

template <>
struct FieldTable<DisplaySettings> {
  template <class V>
  static constexpr void visit(V&& v) {
    v(field("exposure", &DisplaySettings::exposure, finite()));
    v(field("tonemap", &DisplaySettings::tonemap));
  }
};

template <>
struct FieldTable<Environment> {
  template <class V>
  static constexpr void visit(V&& v) {
    v(field("color", &Environment::color, at_least(0)));
    v(field("texture", &Environment::texture, kNullable | kAssetPath));
    v(field("intensity", &Environment::intensity, at_least(0)));
    v(field("rotation_deg", &Environment::rotation_deg, finite()));
  }
};

template <>
struct FieldTable<Texture> {
  static constexpr const char* noun = "texture";
  template <class V>
  static constexpr void visit(V&& v) {
    v(field("name", &Texture::name, kRequired | kUniqueName));
    v(field("path", &Texture::path, kRequired | kAssetPath));
  }
};

template <>
struct FieldTable<Material> {
  static constexpr const char* noun = "material";
  template <class V>
  static constexpr void visit(V&& v) {
    v(field("name", &Material::name, kRequired | kUniqueName));
    v(field("type", &Material::type));
    v(field("color", &Material::color, at_least(0)));
    v(field("color_texture", &Material::color_texture, kNullable | kTextureRef));
    v(field("emission", &Material::emission, at_least(0)));
    v(field("emission_texture", &Material::emission_texture, kNullable | kTextureRef));
    v(field("roughness", &Material::roughness, unit_interval()));
    v(field("roughness_texture", &Material::roughness_texture, kNullable | kTextureRef));
    v(field("ior", &Material::ior, greater_than(0)));
    v(field("opacity", &Material::opacity, unit_interval()));
  }
};

template <>
struct FieldTable<Sphere> {
  template <class V>
  static constexpr void visit(V&& v) {
    v(field("name", &Sphere::name, kLabel));
    v(field("center", &Sphere::center, kRequired, finite()));
    v(field("radius", &Sphere::radius, kRequired, greater_than(0)));
    v(field("material", &Sphere::material, kRequired | kMaterialRef));
  }
};

template <>
struct FieldTable<Quad> {
  template <class V>
  static constexpr void visit(V&& v) {
    v(field("name", &Quad::name, kLabel));
    v(field("material", &Quad::material, kRequired | kMaterialRef));
    v(field("corners", &Quad::corners, kRequired, finite()));
    v(field("uvs", &Quad::uvs, finite()));
  }
};

// A view's camera is an object of the Camera table (read, written and checked as `camera` is).
template <>
struct FieldTable<CameraView> {
  static constexpr const char* noun = "view";
  template <class V>
  static constexpr void visit(V&& v) {
    v(field("name", &CameraView::name, kRequired | kUniqueName | kLabel));
    v(field("camera", &CameraView::camera, kRequired));
  }
};

// The parts of a scene that the file holds, in file order: v(key, member of Scene) for each
// (objects and lists). base_dir is not in the file.
template <class V>
constexpr void visit_scene_parts(V&& v) {
  v("camera", &Scene::camera);
  v("film", &Scene::film);
  v("render", &Scene::render);
  v("display", &Scene::display);
  v("environment", &Scene::environment);
  v("textures", &Scene::textures);
  v("materials", &Scene::materials);
  v("spheres", &Scene::spheres);
  v("quads", &Scene::quads);
  v("views", &Scene::views);  // optional: left out of the file when empty
}

template <class T>
constexpr size_t field_count() {
  size_t n = 0;
  FieldTable<T>::visit([&](const auto&) { ++n; });
  return n;
}

constexpr size_t scene_part_count() {
  size_t n = 0;
  visit_scene_parts([&](const char*, auto) { ++n; });
  return n;
}

// A member that is an object of its own table (a view's camera), read, written and checked
// with that table.
template <class M>
constexpr bool kNestedObject = std::is_same_v<M, Camera>;

template <class T>
struct IsVector : std::false_type {};
template <class T>
struct IsVector<std::vector<T>> : std::true_type {};

// The material fields that name a texture (kTextureRef) are the texture slots of
// texture_slots.h, with the same keys and in the same order.
constexpr bool texture_refs_are_the_slots() {
  size_t slot = 0;
  bool same = true;
  FieldTable<Material>::visit([&](const auto& f) {
    if (!f.has(kTextureRef)) return;
    if constexpr (std::is_same_v<typename std::decay_t<decltype(f)>::Type, std::string>)
      same = same && slot < kTextureSlots.size() && f.member == kTextureSlots[slot].member &&
             std::string_view(f.key) == kTextureSlots[slot].key;
    else
      same = false;
    ++slot;
  });
  return same && slot == kTextureSlots.size();
}
static_assert(texture_refs_are_the_slots(), "a texture slot of Material is missing from renderer/texture_slots.h");

// A struct's members, one name each: a new member makes the binding fail to compile. The count
// beside each is that of its table.
[[maybe_unused]] inline void every_member_is_listed(const Scene& s) {
  [[maybe_unused]] const auto& [a, b, c, d, e, f, g, h, i, j, base_dir] = s;
  static_assert(scene_part_count() == 10);
  [[maybe_unused]] const auto& [c0, c1, c2, c3, c4, c5] = s.camera;
  static_assert(field_count<Camera>() == 6);
  [[maybe_unused]] const auto& [f0, f1] = s.film;
  static_assert(field_count<Film>() == 2);
  [[maybe_unused]] const auto& [r0, r1] = s.render;
  static_assert(field_count<RenderSettings>() == 2);
  [[maybe_unused]] const auto& [d0, d1] = s.display;
  static_assert(field_count<DisplaySettings>() == 2);
  [[maybe_unused]] const auto& [e0, e1, e2, e3] = s.environment;
  static_assert(field_count<Environment>() == 4);
  [[maybe_unused]] const auto& [t0, t1] = Texture{};
  static_assert(field_count<Texture>() == 2);
  [[maybe_unused]] const auto& [m0, m1, m2, m3, m4, m5, m6, m7, m8, m9] = Material{};
  static_assert(field_count<Material>() == 10);
  [[maybe_unused]] const auto& [s0, s1, s2, s3] = Sphere{};
  static_assert(field_count<Sphere>() == 4);
  [[maybe_unused]] const auto& [q0, q1, q2, q3] = Quad{};
  static_assert(field_count<Quad>() == 4);
  [[maybe_unused]] const auto& [v0, v1] = CameraView{};
  static_assert(field_count<CameraView>() == 2);
}

}  // namespace glint
