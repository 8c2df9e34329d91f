// Debian's libtinyobjloader.so is built without coverage or sanitizers, which
// would leave the fuzzer blind inside the OBJ/MTL parser and ASan unable to
// check its reads. The fuzz targets compile the same header's implementation
// here instead: its definitions, in the executable, take precedence over the
// shared library's. (Same header, same float real_t: the same code.)
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
