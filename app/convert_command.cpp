#include "app/convert_command.h"

#include <cstdio>
#include <string>
#include <vector>

#include "app/command_line.h"
#include "renderer/project_error.h"
#include "renderer/scene_exchange.h"

namespace glint {
namespace {

const char* const kUsage =
    "usage: glint convert IN OUT [--spp N]\n"
    "\n"
    "Converts a scene between Glint (.glint), Mitsuba 3 (.xml) and pbrt-v4 (.pbrt), by the\n"
    "files' extensions. What the other format cannot hold, or holds differently, is named in a\n"
    "warning on stderr (README: Moving scenes between Glint, Mitsuba and pbrt); shapes and\n"
    "lights Glint does not model are counted. Asset paths are rewritten relative to OUT's\n"
    "folder; Mitsuba meshes that are not rectangles go to OUT_STEM-meshes/ beside OUT.\n"
    "  --spp N   the sample count written into a Mitsuba or pbrt scene (default 64; a Glint\n"
    "            scene has none: glint render --spp sets it)\n"
    "Exit codes: 0 converted (with or without warnings), 1 IN could not be read or OUT\n"
    "written, 2 bad arguments.\n";

struct Options {
  std::string input, output;
  int spp = 64;
};

Options parse(int argc, char** argv) {
  Options o;
  std::vector<std::string> files;
  for (int i = 0; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--spp") {
      if (i + 1 >= argc) throw UsageError{"--spp needs a value"};
      o.spp = int(parse_integer_option("--spp", argv[++i], 1, 1 << 20));
    } else if (a.size() > 1 && a[0] == '-') {
      throw UsageError{"unknown option " + a};
    } else {
      files.push_back(a);
    }
  }
  if (files.size() != 2) throw UsageError{"expected IN and OUT, got " + std::to_string(files.size()) + " file names"};
  for (const std::string& f : files)
    if (!scene_format_for(f))
      throw UsageError{f + ": unknown scene format: the name must end in .glint, .xml (Mitsuba 3) or .pbrt (pbrt-v4)"};
  o.input = files[0];
  o.output = files[1];
  return o;
}

}  // namespace

int run_convert_command(int argc, char** argv) {
  Options o;
  if (const int rc = parse_command_line("glint convert", kUsage, argc, argv, parse, o); rc >= 0) return rc;
  try {
    const ImportedScene imported = import_scene(o.input);
    for (const std::string& w : imported.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    ExportOptions options;
    options.samples_per_pixel = o.spp;
    const std::vector<std::string> warnings = export_scene(imported.scene, o.output, options);
    for (const std::string& w : warnings) std::fprintf(stderr, "warning: %s: %s\n", o.input.c_str(), w.c_str());
    const size_t total = imported.warnings.size() + warnings.size();
    std::printf("wrote %s (%s, %zu sphere%s, %zu quad%s, %zu warning%s)\n", o.output.c_str(),
                to_string(*scene_format_for(o.output)), imported.scene.spheres.size(),
                imported.scene.spheres.size() == 1 ? "" : "s", imported.scene.quads.size(),
                imported.scene.quads.size() == 1 ? "" : "s", total, total == 1 ? "" : "s");
    return 0;
  } catch (const ProjectError& e) {
    std::fprintf(stderr, "glint convert: %s\n", e.what());
    return 1;
  }
}

}  // namespace glint
