// What a long editor session could leak, measured from inside the process: resident memory
// (VmRSS of /proc/self/status) and the OpenGL objects alive in the current context, counted
// name by name with glIs* (the driver gives no list). Used by the soak (tests/soak/soak.h).
#pragma once

#include <cstdint>
#include <string>

namespace glint::soak {

// Resident memory of this process in KiB, from /proc/self/status: VmRSS, and its anonymous
// (heap, mmapped memory: where a leak lands) and file-backed parts (pages of the executable and
// libraries, e.g. LLVM's code paged in when llvmpipe compiles a shader state it had not met:
// not a leak). 0 where a field is missing.
struct Resident {
  int64_t total_kib = 0, anon_kib = 0, file_kib = 0;
};
Resident resident();

// Bytes of the C heap in use (glibc's mallinfo2: allocated chunks plus mmapped blocks). Unlike
// RSS it does not hide a leak in memory that malloc already holds, nor count freed pages that
// malloc keeps: a leak of b bytes per frame shows as b per frame.
int64_t heap_in_use_bytes();
// Bytes malloc holds from the system (arena plus mmapped blocks), in use or free: where the
// heap in use is flat and this grows, RSS grows from memory that malloc keeps, not a leak.
int64_t heap_held_bytes();

struct GlObjectCounts {
  int buffers = 0, textures = 0, framebuffers = 0, vertex_arrays = 0;
  int programs = 0, shaders = 0, queries = 0;
  unsigned highest_probe_name = 0;  // the largest name a fresh object of any kind received
  int total() const {
    return buffers + textures + framebuffers + vertex_arrays + programs + shaders + queries;
  }
  bool operator==(const GlObjectCounts& o) const {
    return buffers == o.buffers && textures == o.textures && framebuffers == o.framebuffers &&
           vertex_arrays == o.vertex_arrays && programs == o.programs && shaders == o.shaders &&
           queries == o.queries;
  }
};

// Counts the live objects of each kind in the current context. A fresh object of each kind is
// created (and deleted again) to learn how far names have got; names 1 .. max(2 x that, 65536)
// are then asked about, which covers drivers that hand out the lowest free name (Mesa) and
// those that count upwards. Needs a current OpenGL 4.5 context.
GlObjectCounts count_gl_objects();

std::string describe(const GlObjectCounts& c);

}  // namespace glint::soak
