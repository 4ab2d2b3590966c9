// Mitsuba 3 BSDFs -> Glint materials (mitsuba_values.h): the inverse of mitsuba_writer.cpp's
// choices, and the nearest Glint type, with a warning, for the others.
#include <cmath>

#include "renderer/json_fields.h"
#include "renderer/mitsuba_values.h"

namespace glint::mitsuba {

namespace {

// Mitsuba's named indices of refraction (its documentation's table, the common ones).
std::optional<double> named_ior(const std::string& name) {
  static const std::pair<const char*, double> table[] = {
      {"vacuum", 1.0},         {"air", 1.000277},          {"water", 1.333},   {"acetone", 1.36},
      {"ethanol", 1.361},      {"fused quartz", 1.458},    {"pyrex", 1.470},   {"acrylic glass", 1.49},
      {"polypropylene", 1.49}, {"bk7", 1.5046},            {"sodium chloride", 1.544},
      {"amber", 1.55},         {"pet", 1.5750},            {"diamond", 2.419}};
  for (const auto& [n, v] : table)
    if (name == n) return v;
  return std::nullopt;
}

double ior(Context& ctx, Props& p, const std::string& name, double fallback) {
  const XmlElement* c = p.find(name);
  if (!c) return fallback;
  const std::string value = ctx.required(*c, "value");
  if (c->name == "string") {
    if (const auto v = named_ior(value)) return *v;
    ctx.fail(*c, "unknown index of refraction '" + json_fields::clip(value, 40) + "'");
  }
  if (c->name != "float") ctx.fail(*c, "expected <float name=\"" + name + "\">");
  return numbers(ctx, *c, value, 1, 1)[0];
}

// Glint's roughness r for Mitsuba's alpha = r^2 (GGX).
float roughness(Context& ctx, Props& p, const XmlElement& bsdf, double fallback_alpha) {
  const std::string distribution = p.string("distribution", "beckmann");
  if (distribution != "ggx") ctx.warn(bsdf, "its " + distribution + " distribution is read as GGX");
  double alpha = p.number("alpha", fallback_alpha);
  if (p.find("alpha_u") || p.find("alpha_v")) {
    alpha = p.number("alpha_u", fallback_alpha);
    if (p.number("alpha_v", fallback_alpha) != alpha) ctx.warn(bsdf, "anisotropic roughness is read as alpha_u (Glint's is isotropic)");
  }
  p.skip({"sample_visible"});
  return float(std::sqrt(std::max(0.0, alpha)));
}

// The colour property: an rgb value, or a texture (colour white, the texture's name set).
glm::vec3 colour(Context& ctx, Props& p, const std::string& name, glm::vec3 fallback, Material& m,
                 const std::function<std::string(const XmlElement&)>& texture) {
  for (const XmlElement& c : p.element().children) {
    const std::string* n = c.attribute("name");
    if (!n || *n != name || (c.name != "texture" && c.name != "ref")) continue;
    p.find(name);
    m.color_texture = texture(c);
    return glm::vec3(1);
  }
  return p.colour(name, fallback);
}

}  // namespace

Material read_bsdf(Context& ctx, const XmlElement& bsdf, const std::function<std::string(const XmlElement&)>& texture) {
  Props p(ctx, bsdf);
  const std::string type = p.type();
  Material m;
  if (type == "twosided" || type == "mask") {
    if (type == "mask") m.opacity = float(p.number("opacity", 0.5));
    const XmlElement* inner = p.child("bsdf");
    if (!inner) ctx.fail(bsdf, "needs a nested <bsdf>");
    if (type == "twosided" && p.child("bsdf")) ctx.warn(bsdf, "its second side is not imported (Glint's surfaces look alike from both sides)");
    const float opacity = m.opacity;
    m = read_bsdf(ctx, *inner, texture);
    m.opacity *= opacity;
  } else if (type == "diffuse") {
    m.type = MaterialType::matte;
    m.color = colour(ctx, p, "reflectance", glm::vec3(0.5f), m, texture);
  } else if (type == "conductor" || type == "roughconductor") {
    m.type = MaterialType::reflective;
    const std::string metal = p.string("material", "none");
    if (metal != "none" || p.find("eta") || p.find("k"))
      ctx.warn(bsdf, "its metal's complex index of refraction is read as Glint's mirror of colour specular_reflectance (Schlick)");
    m.color = colour(ctx, p, "specular_reflectance", glm::vec3(1), m, texture);
    m.roughness = type == "roughconductor" ? roughness(ctx, p, bsdf, 0.1) : 0.0f;
  } else if (type == "plastic" || type == "roughplastic") {
    m.type = MaterialType::glossy;
    m.color = colour(ctx, p, "diffuse_reflectance", glm::vec3(0.5f), m, texture);
    m.ior = float(ior(ctx, p, "int_ior", 1.49) / ior(ctx, p, "ext_ior", 1.000277));
    m.roughness = type == "roughplastic" ? roughness(ctx, p, bsdf, 0.1) : 0.0f;
    p.skip({"nonlinear"});
    ctx.warn(bsdf, "read as Glint's glossy (a clear coat over a diffuse base, which splits them differently)");
  } else if (type == "dielectric" || type == "roughdielectric" || type == "thindielectric") {
    m.type = type == "thindielectric" ? MaterialType::transparent : MaterialType::refractive;
    m.ior = float(ior(ctx, p, "int_ior", 1.5046) / ior(ctx, p, "ext_ior", 1.000277));
    m.color = colour(ctx, p, "specular_transmittance", glm::vec3(1), m, texture);
    if (p.colour("specular_reflectance", glm::vec3(1)) != glm::vec3(1))
      ctx.warn(bsdf, "its specular_reflectance is not imported (Glint's glass reflects by Fresnel alone)");
    m.roughness = type == "roughdielectric" ? roughness(ctx, p, bsdf, 0.1) : 0.0f;
    if (type == "thindielectric") ctx.warn(bsdf, "read as Glint's transparent (thin glass with Schlick's Fresnel, no inter-reflections)");
  } else {
    ctx.warn(bsdf, "read as a grey matte (Glint has no such material)");
    m.color = glm::vec3(0.5f);
    p.skip_all();
  }
  p.finish();
  return m;
}

}  // namespace glint::mitsuba
