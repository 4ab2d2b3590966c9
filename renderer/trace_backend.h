// The two entry points of the path tracer (docs/DESIGN.md §3.3): the fragment shader
// (shaders/trace.frag: one full-screen triangle per pass, ping-pong render targets) and the
// compute shader (shaders/trace.comp: one dispatch per pass, the accumulation read and written
// in place as images). Both run shaders/trace_common.glsl and give the same image; which is
// faster depends on the device (renderer/backend_choice.h).
#pragma once

#include <memory>
#include <optional>
#include <string>

#include <epoxy/gl.h>

namespace glint {

class GlProgram;

enum class TraceBackend { fragment, compute };

const char* backend_name(TraceBackend backend);  // "fragment", "compute"
std::optional<TraceBackend> parse_backend(const std::string& name);

// Invocations per compute work group; 8x8 measured fastest on llvmpipe (bench/reports/THROUGHPUT.md).
struct WorkGroup {
  int x = 8;
  int y = 8;
  bool operator==(const WorkGroup&) const = default;
};
// "8x8" -> {8, 8}; nullopt unless both are 1..1024 and their product is at most 1024
// (GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS is at least 1024 in GL 4.5).
std::optional<WorkGroup> parse_work_group(const std::string& text);

// The trace program of `backend` with `defines` (the specialisation's `#define GLINT_NO_...`
// lines; "" for the generic program), compile and link issued but not waited for.
std::unique_ptr<GlProgram> start_trace_program(TraceBackend backend, WorkGroup group,
                                               const std::string& defines);
// The defines a compute program is compiled with besides the specialisation's: its work group.
std::string work_group_defines(WorkGroup group);

// The textures a trace pass reads and writes (RGBA32F, see shaders/trace_common.glsl).
struct TraceTargets {
  GLuint accumulation = 0;
  GLuint compensation = 0;
  GLuint variance = 0;
  GLuint variance_compensation = 0;
};
// Compute path: binds the four targets to image units 0-3, read and write, as
// shaders/trace.comp declares them.
void bind_trace_images(const TraceTargets& targets);
// One pass over width x height pixels: ceil(width / x) x ceil(height / y) groups (the shader
// skips the overhang; its u_tile_origin and u_tile_end place them in the image), then the barrier that makes its image stores visible to the next pass's
// image loads, the tonemap pass's texture fetches and read-back or clears of the textures.
void dispatch_trace(int width, int height, WorkGroup group);
// For a job on the program worker (renderer/program_worker.h): binds four 1x1 images of the
// pass's formats and dispatches one group with the program in use, so that the driver compiles
// there the code the renderer's first pass will look up (uniforms are the caller's).
void warm_up_compute_pass();

}  // namespace glint
