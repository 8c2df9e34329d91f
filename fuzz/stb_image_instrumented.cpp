// Debian's libstb.so is built without coverage or sanitizers, like
// libtinyobjloader.so (see tinyobjloader_instrumented.cpp): the fuzz targets
// compile the same header's image decoders here, so that the fuzzer sees
// inside them and ASan checks their reads. Its definitions, in the
// executable, take precedence over the shared library's.
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>
