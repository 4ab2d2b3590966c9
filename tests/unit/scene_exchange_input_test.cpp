// The scene readers on files other programs wrote (renderer/mitsuba_scene.h, pbrt_scene.h,
// xml_reader.h): errors name the file, line and element; what Glint does not model is named or
// counted in a warning; the conventions hold for hand-written scenes.
#include <algorithm>
#include <fstream>

#include <gtest/gtest.h>

#include "renderer/mitsuba_scene.h"
#include "renderer/pbrt_scene.h"
#include "renderer/xml_reader.h"
#include "tests/temp_dir.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const ProjectError& e) {
    return e.what();
  }
  return "(no error)";
}

bool any_contains(const std::vector<std::string>& lines, const std::string& part) {
  return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return l.find(part) != std::string::npos; });
}
std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& l : lines) out += "  " + l + "\n";
  return out;
}

ImportedScene mitsuba(const std::string& body, const fs::path& base = ".") {
  return read_mitsuba_scene("<scene version=\"3.0.0\">\n" + body + "</scene>\n", "s.xml", base);
}
ImportedScene pbrt(const std::string& text) { return read_pbrt_scene(text, "s.pbrt", "."); }

TEST(XmlReader, ReadsElementsAttributesEntitiesAndLines) {
  const XmlElement root = parse_xml("<?xml version=\"1.0\"?>\n<!-- c -->\n<a x='1 &lt; 2' y=\"&#x41;&amp;\">\n  <b/>\n  <c z=\"\"></c>\n</a>\n", "f.xml");
  EXPECT_EQ(root.name, "a");
  EXPECT_EQ(root.line, 3);
  EXPECT_EQ(*root.attribute("x"), "1 < 2");
  EXPECT_EQ(*root.attribute("y"), "A&");
  ASSERT_EQ(root.children.size(), 2u);
  EXPECT_EQ(root.children[1].line, 5);
  EXPECT_EQ(*root.children[1].attribute("z"), "");
}

TEST(XmlReader, ErrorsNameTheFileAndLine) {
  EXPECT_EQ(error_of([] { parse_xml("<a>\n<b>\n</a>", "f.xml"); }), "f.xml: line 3: <b> (line 2) is closed by </a>");
  EXPECT_EQ(error_of([] { parse_xml("<a>\n  text\n</a>", "f.xml"); }), "f.xml: line 2: text inside <a> (scene files keep values in attributes)");
  EXPECT_EQ(error_of([] { parse_xml("<a x=\"1\" x=\"2\"/>", "f.xml"); }), "f.xml: line 1: <a> has attribute x twice");
  EXPECT_EQ(error_of([] { parse_xml("<a x=\"&nope;\"/>", "f.xml"); }), "f.xml: line 1: unknown entity &nope;");
  EXPECT_EQ(error_of([] { parse_xml("<!DOCTYPE a>\n<a/>", "f.xml"); }), "f.xml: line 1: document type declarations are not supported");
  EXPECT_EQ(error_of([] { parse_xml("<a/>\n<b/>", "f.xml"); }), "f.xml: line 2: content after the root element <a>");
  EXPECT_EQ(error_of([] { parse_xml("<a>", "f.xml"); }), "f.xml: line 1: <a> (line 1) is not closed");
  std::string deep;
  for (int i = 0; i < 100; ++i) deep += "<a>";
  EXPECT_NE(error_of([&] { parse_xml(deep, "f.xml"); }).find("nest more than 64 levels"), std::string::npos);
}

TEST(MitsubaReader, ErrorsNameTheFileLineAndElement) {
  EXPECT_EQ(error_of([] { mitsuba("<shape type=\"sphere\">\n  <ref id=\"nope\"/>\n</shape>\n"); }),
            "s.xml: line 3: <ref id=\"nope\">: no <bsdf id=\"nope\"> precedes it");
  EXPECT_EQ(error_of([] { mitsuba("<shape type=\"sphere\">\n  <float name=\"radius\" value=\"big\"/>\n</shape>\n"); }),
            "s.xml: line 3: <float name=\"radius\">: expected a number, got 'big'");
  EXPECT_EQ(error_of([] { mitsuba("<sensor type=\"perspective\"><float name=\"fov\" value=\"$fov\"/></sensor>\n"); }),
            "s.xml: line 2: <float name=\"fov\">: parameter $fov has no <default>");
  EXPECT_EQ(error_of([] { read_mitsuba_scene("<scen/>", "s.xml", "."); }), "s.xml: line 1: <scen>: the root element must be <scene>");
  EXPECT_EQ(error_of([] { mitsuba("<include filename=\"other.xml\"/>\n"); }),
            "s.xml: line 2: <include>: <include> is not supported: merge the files into one");
}

TEST(MitsubaReader, CountsShapesAndLightsGlintDoesNotModel) {
  test::TempDir dir;
  std::ofstream(dir / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 1\nv 2 2 2\nf 1 2 3\nf 2 4 3\nf 3 4 5\n";
  const ImportedScene s = mitsuba("<shape type=\"cube\"/>\n<shape type=\"cube\"/>\n<shape type=\"cylinder\"/>\n"
                                  "<shape type=\"obj\"><string name=\"filename\" value=\"tri.obj\"/></shape>\n"
                                  "<emitter type=\"point\"/>\n<shape type=\"sphere\"><float name=\"roughness\" value=\"1\"/></shape>\n",
                                  dir.path());
  EXPECT_EQ(s.scene.spheres.size(), 1u);
  EXPECT_TRUE(any_contains(s.warnings, "s.xml: not imported (Glint models spheres and quads): 2 <shape type=\"cube\">, 1 <shape type=\"cylinder\">, 1 mesh of 3 triangles (not a quad)"))
      << joined(s.warnings);
  EXPECT_TRUE(any_contains(s.warnings, "1 <emitter type=\"point\">")) << joined(s.warnings);
  EXPECT_TRUE(any_contains(s.warnings, "s.xml: line 7: <float name=\"roughness\">: not imported (Glint has no such setting)")) << joined(s.warnings);
}

TEST(MitsubaReader, ReadsHandWrittenConventions) {
  test::TempDir dir;
  // A quad as an OBJ of one 4-cornered face (Mitsuba flips its v by default), a rectangle with
  // Mitsuba's default front (+Z), fov along x (Mitsuba's default axis), a beckmann roughness.
  std::ofstream(dir / "q.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n";
  const ImportedScene s = mitsuba(
      "<bsdf type=\"roughconductor\" id=\"m\"><float name=\"alpha\" value=\"0.25\"/></bsdf>\n"
      "<sensor type=\"perspective\"><float name=\"fov\" value=\"90\"/>\n"
      "  <film type=\"hdrfilm\"><integer name=\"width\" value=\"200\"/><integer name=\"height\" value=\"100\"/></film></sensor>\n"
      "<shape type=\"obj\"><string name=\"filename\" value=\"q.obj\"/><ref id=\"m\"/></shape>\n"
      "<shape type=\"rectangle\" id=\"r\"/>\n",
      dir.path());
  ASSERT_EQ(s.scene.quads.size(), 2u);
  EXPECT_NEAR(s.scene.camera.vfov_deg, 2 * glm::degrees(std::atan(0.5)), 1e-4);
  EXPECT_NEAR(s.scene.materials[0].roughness, 0.5f, 1e-6);
  EXPECT_TRUE(any_contains(s.warnings, "its beckmann distribution is read as GGX")) << joined(s.warnings);
  EXPECT_TRUE(any_contains(s.warnings, "Mitsuba's default filter (gaussian)")) << joined(s.warnings);
  const Quad& obj = s.scene.quads[0];
  const auto origin = std::find(obj.corners.begin(), obj.corners.end(), glm::vec3(0, 0, 0));
  ASSERT_NE(origin, obj.corners.end());
  EXPECT_EQ(obj.uvs[origin - obj.corners.begin()], glm::vec2(0, 1));  // v flipped
  const Quad& rect = s.scene.quads[1];
  EXPECT_EQ(rect.name, "r");
  const glm::vec3 n = glm::cross(rect.corners[1] - rect.corners[0], rect.corners[2] - rect.corners[0]);
  EXPECT_GT(n.z, 0) << "Glint's front is the rectangle's +Z";
}

TEST(PbrtReader, ErrorsNameTheFileLineAndDirective) {
  EXPECT_EQ(error_of([] { pbrt("WorldBegin\nShape \"sphere\" \"float radius\" [ big ]\n"); }),
            "s.pbrt: line 2: Shape \"float radius\": expected a number, got 'big'");
  EXPECT_EQ(error_of([] { pbrt("WorldBegin\nNamedMaterial \"nope\"\n"); }),
            "s.pbrt: line 2: NamedMaterial: no MakeNamedMaterial \"nope\" precedes it");
  EXPECT_EQ(error_of([] { pbrt("WorldBegin\nFrobnicate 1\n"); }), "s.pbrt: line 2: Frobnicate: unknown directive");
  EXPECT_EQ(error_of([] { pbrt("Camera \"perspective\"\n"); }), "s.pbrt: no WorldBegin: the file describes no scene");
  EXPECT_EQ(error_of([] { pbrt("WorldBegin\nInclude \"more.pbrt\"\n"); }),
            "s.pbrt: line 2: Include: not supported: merge the included file into this one");
  EXPECT_EQ(error_of([] { pbrt("WorldBegin\nShape \"sphere\" \"float radius\" [ 1\n"); }),
            "s.pbrt: line 2: the file ends where ']' was expected");
  EXPECT_EQ(error_of([] { pbrt("WorldBegin\nTexture \"a\n"); }), "s.pbrt: line 2: a string is not closed by '\"'");
  // Found by fuzz_scene_exchange: a declaration without a name threw std::out_of_range.
  EXPECT_EQ(error_of([] { pbrt("Film \"rgb\" \"float \" [ 1 ]\n"); }),
            "s.pbrt: line 1: Film: a parameter is \"TYPE NAME\", got \"float \"");
}

// Found by fuzz_scene_exchange: a vertical tab or form feed between tokens is white space (it
// ended a word before any character was taken, and the tokenizer never moved on).
TEST(PbrtReader, EveryWhiteSpaceSeparatesTokens) {
  const ImportedScene s = pbrt("WorldBegin\v\fShape\v\"sphere\"\f\"float radius\" [\v2 ]\n");
  ASSERT_EQ(s.scene.spheres.size(), 1u);
  EXPECT_EQ(s.scene.spheres[0].radius, 2.0f);
}

TEST(PbrtReader, CountsShapesAndLightsGlintDoesNotModel) {
  const ImportedScene s = pbrt(
      "WorldBegin\nLightSource \"point\" \"rgb I\" [ 1 1 1 ]\nShape \"cylinder\"\nShape \"cylinder\"\n"
      "Shape \"trianglemesh\" \"point3 P\" [ 0 0 0 1 0 0 0 1 0 ] \"integer indices\" [ 0 1 2 ]\n"
      "Shape \"sphere\" \"float zmax\" [ 0.5 ]\n"
      "AttributeBegin\n  Material \"hair\"\n  Shape \"sphere\" \"float radius\" [ 2 ] \"float emission\" [ 1 ]\nAttributeEnd\n");
  EXPECT_EQ(s.scene.spheres.size(), 1u);
  EXPECT_TRUE(any_contains(s.warnings, "s.pbrt: not imported (Glint models spheres and quads): 2 Shape \"cylinder\", 1 partial sphere, 1 trianglemesh of 1 triangle (not a quad)"))
      << joined(s.warnings);
  EXPECT_TRUE(any_contains(s.warnings, "1 LightSource \"point\"")) << joined(s.warnings);
  EXPECT_TRUE(any_contains(s.warnings, "s.pbrt: line 8: Material: material type \"hair\" is read as a grey matte")) << joined(s.warnings);
  EXPECT_TRUE(any_contains(s.warnings, "s.pbrt: line 9: Shape: not imported (Glint has no such setting): \"float emission\"")) << joined(s.warnings);
}

TEST(PbrtReader, ReadsHandWrittenConventions) {
  // A plain LookAt (pbrt's own image is mirrored from Glint's), fov along the shorter axis of a
  // portrait film, remapped roughness, a one-sided area light, a bilinear patch.
  const ImportedScene s = pbrt(
      "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 60 ]\n"
      "Film \"rgb\" \"integer xresolution\" [ 100 ] \"integer yresolution\" [ 200 ]\nWorldBegin\n"
      "Material \"conductor\" \"rgb reflectance\" [ 0.5 0.5 0.5 ] \"float roughness\" [ 0.0625 ]\n"
      "AreaLightSource \"diffuse\" \"rgb L\" [ 2 2 2 ]\n"
      "Shape \"bilinearmesh\" \"point3 P\" [ 0 0 0  1 0 0  0 1 0  1 1 0 ]\n");
  EXPECT_EQ(s.scene.camera.position, glm::vec3(0, 0, 5));
  EXPECT_EQ(s.scene.camera.target, glm::vec3(0, 0, 0));
  EXPECT_NEAR(s.scene.camera.vfov_deg, 2 * glm::degrees(std::atan(2 * std::tan(glm::radians(30.0)))), 1e-4);
  EXPECT_TRUE(any_contains(s.warnings, "is Glint's mirrored left to right")) << joined(s.warnings);
  EXPECT_TRUE(any_contains(s.warnings, "a one-sided area light is read as Glint's")) << joined(s.warnings);
  ASSERT_EQ(s.scene.materials.size(), 1u);
  EXPECT_NEAR(s.scene.materials[0].roughness, 0.5f, 1e-6);  // alpha = sqrt(0.0625), r = sqrt(alpha)
  EXPECT_EQ(s.scene.materials[0].emission, glm::vec3(2));
  ASSERT_EQ(s.scene.quads.size(), 1u);
  EXPECT_EQ(s.scene.quads[0].corners[3], glm::vec3(1, 1, 0));
  EXPECT_EQ(s.scene.quads[0].uvs[0], glm::vec2(0, 1));  // pbrt's v runs the other way
}

}  // namespace
}  // namespace glint
