// Writes the procedural assets that the example projects use, and the generated large scene:
//   glint-make-assets [--help] [--] OUTPUT_FOLDER [SPHERE_FIELD.glint]
// Colour textures are stored sRGB-encoded (8-bit PNG), roughness maps as linear grey, the sky as
// a linear Radiance .hdr. The output is deterministic, so re-running it changes no file.
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "renderer/image.h"
#include "renderer/procedural_assets.h"
#include "renderer/project_file.h"

namespace {

// Linear colour to the sRGB-encoded values that an 8-bit colour texture stores; alpha stays linear.
glint::Image encode_srgb(glint::Image image) {
  for (size_t i = 0; i < image.pixels.size(); i += 4)
    for (int c = 0; c < 3; ++c) image.pixels[i + c] = glint::linear_to_srgb(image.pixels[i + c]);
  return image;
}

// projects/sphere_field.glint: 100 x 100 spheres on a floor under the generated sky, for the BVH
// (renderer/bvh.h) and the scaling bench. Positions and radii are multiples of 1/64 (exact in
// float, printed in a few digits) from a fixed integer hash, so the file is small and the same
// on every machine.
glint::Scene sphere_field() {
  using glint::Material;
  using glint::MaterialType;
  glint::Scene s;
  s.camera.position = {0, 9, 34};
  s.camera.target = {0, 0, 6};
  s.camera.vfov_deg = 45;
  s.camera.aperture_radius = 0;
  s.camera.focus_distance = 30;
  s.film = {640, 360};
  s.render.max_bounces = 6;
  s.environment.color = {1, 1, 1};
  s.environment.texture = "assets/sky.hdr";
  s.environment.rotation_deg = 60;
  auto material = [&](const char* name, MaterialType type, glm::vec3 color, float roughness,
                      glm::vec3 emission = glm::vec3(0)) {
    Material m;
    m.name = name;
    m.type = type;
    m.color = color;
    m.roughness = roughness;
    m.emission = emission;
    s.materials.push_back(m);
  };
  material("floor", MaterialType::matte, {0.5f, 0.5f, 0.5f}, 0);
  material("red", MaterialType::matte, {0.75f, 0.25f, 0.125f}, 0);
  material("blue", MaterialType::glossy, {0.125f, 0.25f, 0.75f}, 0.25f);
  material("gold", MaterialType::reflective, {0.875f, 0.625f, 0.25f}, 0.25f);
  material("mirror", MaterialType::reflective, {0.875f, 0.875f, 0.875f}, 0);
  material("glass", MaterialType::transparent, {0.875f, 1, 0.875f}, 0);
  material("lamp", MaterialType::matte, {0.5f, 0.5f, 0.5f}, 0, {4, 3, 1.5f});
  const char* kinds[] = {"red", "blue", "gold", "mirror", "glass", "red", "blue", "lamp"};
  uint32_t state = 12345u;
  auto next = [&](uint32_t range) {  // xorshift32: the same sequence everywhere
    state ^= state << 13;
    state ^= state >> 17;
    state ^= state << 5;
    return state % range;
  };
  for (int i = 0; i < 100; ++i)
    for (int j = 0; j < 100; ++j) {
      glint::Sphere sp;
      sp.name = "s" + std::to_string(i * 100 + j);
      const float r = (12 + static_cast<float>(next(16))) / 64;  // 0.1875 .. 0.4219
      sp.center = {(static_cast<float>(j) - 49.5f) + (static_cast<float>(next(33)) - 16) / 64, r,
                   (static_cast<float>(i) - 79.5f) + (static_cast<float>(next(33)) - 16) / 64};
      sp.radius = r;
      sp.material = kinds[next(8)];
      if (std::string(sp.material) == "lamp" && next(4) != 0) sp.material = "red";
      s.spheres.push_back(sp);
    }
  glint::Quad floor;
  floor.name = "floor";
  floor.material = "floor";
  floor.corners = {glm::vec3(-60, 0, -90), glm::vec3(-60, 0, 40), glm::vec3(60, 0, -90), glm::vec3(60, 0, 40)};
  floor.uvs = {glm::vec2(0, 0), glm::vec2(0, 13), glm::vec2(12, 0), glm::vec2(12, 13)};
  s.quads.push_back(floor);
  return s;
}

// The project text with one sphere per line (the pretty-printed form takes seven lines and
// twice the bytes per sphere); everything else as save_project writes it. Loads to the same scene.
std::string compact_project_text(const glint::Scene& scene) {
  glint::Scene rest = scene;
  rest.spheres.clear();
  std::string text = glint::project_file_text(rest);
  const std::string empty = "\"spheres\": []";
  const size_t at = text.find(empty);
  if (at == std::string::npos) throw std::runtime_error("no spheres array in the project text");
  const nlohmann::ordered_json all = glint::scene_to_json(scene);
  std::string lines = "\"spheres\": [\n";
  for (size_t i = 0; i < all["spheres"].size(); ++i)
    lines += "    " + all["spheres"][i].dump() + (i + 1 < all["spheres"].size() ? ",\n" : "\n");
  lines += "  ]";
  return text.replace(at, empty.size(), lines);
}

constexpr const char* kUsage =
    "usage: glint-make-assets [--help] [--] OUTPUT_FOLDER [SPHERE_FIELD.glint]\n"
    "Writes the procedural textures and sky of the example projects into OUTPUT_FOLDER\n"
    "(created if missing) and, when SPHERE_FIELD.glint is given, the generated large scene.\n"
    "  -h, --help  print this help and exit\n"
    "  --          end of options (for a folder whose name starts with '-')\n";

// The positional arguments, or the exit status when there is nothing to generate: 0 after
// --help, 2 for an unknown option or a wrong number of arguments (a message on stderr).
struct Arguments {
  std::vector<std::string> positional;
  int exit_status = -1;
};

Arguments parse_arguments(int argc, char** argv) {
  Arguments args;
  bool options = true;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (options && arg == "--") {
      options = false;
    } else if (options && (arg == "--help" || arg == "-h")) {
      std::fputs(kUsage, stdout);
      args.exit_status = 0;
      return args;
    } else if (options && arg.size() > 1 && arg[0] == '-') {
      std::fprintf(stderr, "glint-make-assets: unknown option %s (see --help)\n", arg.c_str());
      args.exit_status = 2;
      return args;
    } else {
      args.positional.push_back(arg);
    }
  }
  if (args.positional.empty() || args.positional.size() > 2) {
    std::fprintf(stderr, "glint-make-assets: expected OUTPUT_FOLDER [SPHERE_FIELD.glint], got %zu "
                         "arguments\n%s", args.positional.size(), kUsage);
    args.exit_status = 2;
  }
  return args;
}

}  // namespace

int main(int argc, char** argv) {
  const Arguments args = parse_arguments(argc, argv);
  if (args.exit_status >= 0) return args.exit_status;
  namespace gp = glint::procedural;
  const std::filesystem::path out = args.positional[0];
  try {
    std::filesystem::create_directories(out);
    auto write = [&](const char* name, const glint::Image& image) {
      glint::save_image(out / name, image);
      std::printf("wrote %s\n", (out / name).string().c_str());
    };
    write("wood_color.png", encode_srgb(gp::wood_color()));
    write("wood_roughness.png", gp::wood_roughness());
    write("leather_color.png", encode_srgb(gp::leather_color()));
    write("leather_roughness.png", gp::leather_roughness());
    write("metal_color.png", encode_srgb(gp::metal_color()));
    write("metal_roughness.png", gp::metal_roughness());
    write("checker.png", encode_srgb(gp::checker_with_holes()));
    write("sky.hdr", gp::sky());
    if (args.positional.size() == 2) {
      const std::string& scene_file = args.positional[1];
      std::ofstream file(scene_file, std::ios::binary);
      file << compact_project_text(sphere_field());
      if (!file.flush()) throw std::runtime_error("cannot write " + scene_file);
      std::printf("wrote %s\n", scene_file.c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
