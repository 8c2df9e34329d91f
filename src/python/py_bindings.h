// The pieces of the _sombra module, each bound by its own file.
#pragma once

#include <pybind11/pybind11.h>

namespace sombra::python {

void bind_scene(pybind11::module_& m);    // Scene, load, load_text (py_scene.cpp)
void bind_render(pybind11::module_& m);   // render, explain (py_render.cpp)
void bind_arrays(pybind11::module_& m);   // write_image, to_png (py_arrays.cpp)
void bind_parts(pybind11::module_& m);    // Mesh, make_mesh, check_part: scenes from code (py_parts.cpp)
void bind_denoise(pybind11::module_& m);  // denoise (py_denoise.cpp)

}  // namespace sombra::python
