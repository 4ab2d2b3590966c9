// The implementations of stb_image, stb_image_write and tinyexr, compiled from Debian's headers
// into the fuzz targets so that the decoders are instrumented too (coverage for libFuzzer,
// AddressSanitizer): Debian's libstb.a and libtinyexr.so are not, so fuzzing through them could
// only find crashes, not out-of-bounds reads, and gave libFuzzer no coverage of the decoders.
// The normal build links Debian's libraries (CMakeLists.txt).
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image.h>
#include <stb_image_write.h>

#define TINYEXR_IMPLEMENTATION
#include <tinyexr.h>
