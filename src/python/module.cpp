// _sombra: the compiled half of `import sombra` (spec §19); sombra/__init__.py
// is the documented face of it.
#include <pybind11/pybind11.h>

#include <new>

#include "core/error.h"
#include "python/py_bindings.h"

namespace py = pybind11;

PYBIND11_MODULE(_sombra, m) {
    m.doc() = "sombra's renderer, bound for Python; use the package `sombra`, which documents it";
    m.attr("__version__") = SOMBRA_VERSION;
    // sombra.Error is a ValueError: a wrong input is a wrong value. Its text
    // is the command line's one line without "sombra: error: ".
    static py::exception<sombra::Error> error(m, "Error", PyExc_ValueError);
    // NOLINTNEXTLINE(performance-unnecessary-value-param): pybind11's translator type takes it by value
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const sombra::Error& e) {
            error(sombra::one_line_message(e.where() + ": " + e.message()).c_str());
        }
    });
    sombra::python::bind_parts(m);
    sombra::python::bind_scene(m);
    sombra::python::bind_render(m);
    sombra::python::bind_arrays(m);
    sombra::python::bind_denoise(m);
}
