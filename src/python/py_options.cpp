#include "python/py_options.h"

#include <pybind11/stl.h>

#include <algorithm>
#include <climits>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"

namespace py = pybind11;

namespace sombra::python {

namespace {

// The option's name as the command line spells it: "max_depth" → "--max-depth".
std::string option_name(std::string key) {
    std::replace(key.begin(), key.end(), '_', '-');
    return "--" + key;
}

// A Python int as a long long; nullopt when it does not fit.
std::optional<long long> long_long_of(const py::handle& value) {
    int overflow = 0;
    const long long v = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
    if (overflow == 0 && v == -1 && PyErr_Occurred()) throw py::error_already_set();
    if (overflow != 0) return std::nullopt;
    return v;
}

// A Python int within [lowest, highest]; beyond them, which no option's own
// range reaches, an error naming the option and the value as given.
std::int64_t whole_number(const std::string& key, const py::handle& value, std::int64_t lowest, std::int64_t highest) {
    const std::optional<long long> v = long_long_of(value);
    if (!v || *v < lowest || *v > highest)
        throw Error(option_name(key), "out of range: " + std::string(py::str(value)));
    return *v;
}

int int_option(const std::string& key, const py::handle& value) {
    return static_cast<int>(whole_number(key, value, INT_MIN, INT_MAX));
}

}  // namespace

int int_value(const py::handle& value) {
    const std::optional<long long> v = long_long_of(value);
    if (!v) return py::int_(0) < py::reinterpret_borrow<py::int_>(value) ? INT_MAX : INT_MIN;
    return static_cast<int>(std::clamp<long long>(*v, INT_MIN, INT_MAX));
}

RenderOptions render_options_from(const py::dict& options) {
    RenderOptions r;
    SettingOverrides& s = r.overrides;
    for (const auto& [key_handle, value] : options) {
        const std::string key = py::cast<std::string>(key_handle);
        if (key == "width") {
            s.width = int_option(key, value);
        } else if (key == "height") {
            s.height = int_option(key, value);
        } else if (key == "spp") {
            s.spp = int_option(key, value);
        } else if (key == "seed") {
            if (py::cast<py::int_>(value) < py::int_(0))
                throw Error("--seed", "must be a non-negative integer, not " + std::string(py::str(value)));
            const unsigned long long seed = PyLong_AsUnsignedLongLong(value.ptr());
            if (seed == static_cast<unsigned long long>(-1) && PyErr_Occurred()) {
                PyErr_Clear();
                throw Error("--seed", "must be below 2^64, not " + std::string(py::str(value)));
            }
            s.seed = seed;
        } else if (key == "integrator") {
            s.integrator = integrator_option(py::cast<std::string>(value));
        } else if (key == "max_depth") {
            s.max_depth = int_option(key, value);
        } else if (key == "max_volume_depth") {
            s.max_volume_depth = int_option(key, value);
        } else if (key == "texture_filter") {
            s.texture_filter = texture_filter_option(py::cast<std::string>(value));
        } else if (key == "threads") {
            r.threads = int_option(key, value);
        } else if (key == "accel") {
            r.accel = accel_option(py::cast<std::string>(value));
        } else if (key == "light_tree") {
            r.light_selection = light_selection_option(py::cast<std::string>(value));
        } else if (key == "frame") {
            r.frame = whole_number(key, value, INT64_MIN, INT64_MAX);
        } else if (key == "time") {
            r.time_budget = py::cast<double>(value);
        } else if (key == "noise_threshold") {
            r.noise_threshold = py::cast<double>(value);
        } else if (key == "min_spp") {
            r.min_spp = int_option(key, value);
        } else if (key == "crop") {
            const py::sequence corners = py::cast<py::sequence>(value);
            if (corners.size() != 4) throw Error("--crop", "expected (x0, y0, x1, y1): 4 whole numbers");
            int c[4];
            for (int k = 0; k < 4; ++k) c[k] = int_option(key, corners[static_cast<std::size_t>(k)]);
            if (c[0] < 0 || c[1] < 0 || c[2] <= c[0] || c[3] <= c[1])
                throw Error("--crop", "expected X0 Y0 X1 Y1 with 0 <= X0 < X1 and 0 <= Y0 < Y1, not " +
                                          std::to_string(c[0]) + " " + std::to_string(c[1]) + " " +
                                          std::to_string(c[2]) + " " + std::to_string(c[3]));
            r.crop = PixelWindow{c[0], c[1], c[2] - c[0], c[3] - c[1]};
        } else if (key == "denoise") {
            r.denoise = py::cast<bool>(value);
        } else if (key == "aov") {
            std::string list;
            for (const std::string& name : py::cast<std::vector<std::string>>(value))
                list += (list.empty() ? "" : ",") + name;
            r.aovs = aov_option(list);
        } else {
            throw py::type_error("unexpected option '" + key + "'");
        }
    }
    check_render_options(r);
    return r;
}

}  // namespace sombra::python
