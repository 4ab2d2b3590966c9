// The sampler layout that keeps llvmpipe's compiled trace shaders independent of what other
// programs left in the sampler slots (shaders/lib/trace_scene_tables.glsl, "The samplers, in a
// fixed order"): checked on the shader sources, since breaking it shows only as an editor
// frame that waits for a compile (gl.GlProgramWorker.NoFrameWaitsForAStructuralEditsProgram).
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace {

std::string shader_source(const std::string& name) {
  std::ifstream in(std::string(GLINT_SOURCE_DIR) + "/shaders/" + name);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

struct SamplerDeclaration {
  std::string type;
  std::string name;
  size_t position;
};

std::vector<SamplerDeclaration> sampler_declarations(const std::string& source) {
  static const std::regex declaration(R"(uniform\s+(\w*sampler\w*)\s+(\w+)\s*;)");
  std::vector<SamplerDeclaration> found;
  for (auto it = std::sregex_iterator(source.begin(), source.end(), declaration);
       it != std::sregex_iterator(); ++it)
    found.push_back({(*it)[1], (*it)[2], static_cast<size_t>(it->position())});
  return found;
}

// Every sampler of the library is read in every_sampler(), and the buffer textures come after
// every 2-D sampler.
TEST(TraceSamplerSlots, EverySamplerIsReadAndBufferTexturesComeLast) {
  const std::string common = shader_source("lib/trace_scene_tables.glsl");
  const std::vector<SamplerDeclaration> samplers = sampler_declarations(common);
  ASSERT_GE(samplers.size(), 11u) << "the environment, two texel textures, eight tables";
  const size_t body = common.find("vec4 every_sampler() {");
  ASSERT_NE(body, std::string::npos);
  const std::string every = common.substr(body, common.find("\n}", body) - body);
  bool buffer_seen = false;
  for (const SamplerDeclaration& s : samplers) {
    EXPECT_NE(every.find("texelFetch(" + s.name + ","), std::string::npos)
        << s.name << " is not read in every_sampler()";
    const bool buffer = s.type.find("Buffer") != std::string::npos;
    EXPECT_FALSE(buffer_seen && !buffer) << s.name << " (2-D) is declared after a buffer texture";
    buffer_seen = buffer_seen || buffer;
  }
}

// The entry points declare their own samplers (all 2-D, all read by main) before the library's,
// so that they take the first slots; the compute shader has none (images are not samplers).
TEST(TraceSamplerSlots, EntryPointsDeclareTheirSamplersFirst) {
  for (const char* name : {"trace.frag", "trace.comp", "aov.frag"}) {
    const std::string source = shader_source(name);
    const size_t include = source.find("#include \"trace_common.glsl\"");
    ASSERT_NE(include, std::string::npos) << name;
    for (const SamplerDeclaration& s : sampler_declarations(source)) {
      EXPECT_LT(s.position, include) << name << ": " << s.name << " is declared after the library";
      EXPECT_EQ(s.type.find("Buffer"), std::string::npos) << name << ": " << s.name;
    }
  }
  EXPECT_EQ(sampler_declarations(shader_source("trace.frag")).size(), 4u);
}

}  // namespace
