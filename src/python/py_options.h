// Python's keyword options (spec §19) as the library's typed options
// (api/render_options.h): the package checked their Python types; here
// their values are converted and checked as the command line checks its
// words, and a problem names the option as the command line spells it.
#pragma once

#include <pybind11/pybind11.h>

#include "api/render_options.h"

namespace sombra::python {

// A Python int as a C++ int, clamped to int's range: a value beyond it then
// fails its own range check with the usual message.
int int_value(const pybind11::handle& value);

// From a dict {"width": 64, "integrator": "path", "aov": ["albedo"], ...}
// whose keys the package has checked. Throws Error for a value out of range.
RenderOptions render_options_from(const pybind11::dict& options);

}  // namespace sombra::python
