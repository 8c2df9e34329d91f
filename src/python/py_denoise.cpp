// sombra.denoise (spec §25): the layers render(..., aov=["denoise"]) returns,
// checked before any C++ reads them, denoised with the GIL released.
#include "python/py_denoise.h"

#include <pybind11/numpy.h>

#include <atomic>
#include <cstddef>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/image_limits.h"
#include "denoise/denoise.h"
#include "python/py_arrays.h"
#include "python/py_bindings.h"
#include "python/py_options.h"
#include "python/py_watched.h"

namespace py = pybind11;

namespace sombra::python {

namespace {

// One layer of DenoiseLayers: its name without the channel, its values and
// how many a pixel.
struct NamedLayer {
    std::string name;
    std::vector<float>* values;
    int stride;
};

// The layers of `layers` in for_each_denoise_channel's order.
std::vector<NamedLayer> named_layers(DenoiseLayers& layers) {
    std::vector<NamedLayer> named;
    for_each_denoise_channel(layers, [&named](const std::string& channel, std::vector<float>& values, int component,
                                              int stride) {
        if (component == 0) named.push_back({channel.substr(0, channel.rfind('.')), &values, stride});
    });
    return named;
}

std::string shape_text(const py::array& a) {
    std::string shape;
    for (py::ssize_t i = 0; i < a.ndim(); ++i) shape += (i ? ", " : "") + std::to_string(a.shape(i));
    return "(" + shape + (a.ndim() == 1 ? ",)" : ")");
}

// The layers from the dict, each a float array of the first one's height and
// width; TypeError for a non-array or a dtype not float, Error naming the
// layer for one missing or of another shape. Their values are checked later.
DenoiseLayers layers_from(const py::dict& given) {
    DenoiseLayers layers;
    for (const NamedLayer& layer : named_layers(layers)) {
        const std::string where = "layers['" + layer.name + "']";
        if (!given.contains(layer.name))
            throw Error("layers", "no layer '" + layer.name +
                                      "': the denoiser reads the layers render(..., "
                                      "aov=[\"denoise\"]) returns");
        const py::object value = given[py::str(layer.name)];
        if (!py::isinstance<py::array>(value))
            throw py::type_error(where + ": expected a numpy array, not " +
                                 std::string(py::str(py::type::of(value).attr("__name__"))));
        const auto a = py::reinterpret_borrow<py::array>(value);
        if (a.dtype().kind() != 'f')
            throw py::type_error(where + ": expected a float dtype, not " + std::string(py::str(a.dtype())));
        if (layers.width == 0 && a.ndim() >= 2) {
            if (a.shape(0) < 1 || a.shape(1) < 1 || a.shape(0) > kMaxImageSide || a.shape(1) > kMaxImageSide ||
                a.shape(0) * a.shape(1) > kMaxPixels)
                throw Error(where, "shape " + shape_text(a) + ": each side must be between 1 and " +
                                       std::to_string(kMaxImageSide) + ", at most " + std::to_string(kMaxPixels) +
                                       " pixels");
            layers.height = static_cast<int>(a.shape(0));
            layers.width = static_cast<int>(a.shape(1));
        }
        const std::string size =
            layers.width == 0 ? "height, width" : std::to_string(layers.height) + ", " + std::to_string(layers.width);
        const std::string wanted = "(" + size + (layer.stride == 3 ? ", 3)" : ")");
        const bool fits = a.ndim() == (layer.stride == 3 ? 3 : 2) && a.shape(0) == layers.height &&
                          a.shape(1) == layers.width && (layer.stride == 1 || a.shape(2) == 3);
        if (!fits) throw Error(where, "shape " + shape_text(a) + " is not " + wanted);
        const auto floats = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(a);
        if (!floats) throw py::error_already_set();
        layer.values->assign(floats.data(), floats.data() + floats.size());
    }
    return layers;
}

py::array_t<float> denoise(const py::dict& given, const py::dict& options) {
    DenoiseLayers layers = layers_from(given);
    check_denoise_layers(layers, "layers");
    const int threads = render_options_from(options).threads;
    RenderProgress watched;
    std::vector<float> image;
    run_watched([&] { image = denoise_image(layers, threads, &watched.cancel); }, watched, 0, py::none());
    return numpy_from(std::move(image), {layers.height, layers.width, 3});
}

}  // namespace

void add_denoise_layers(py::dict& out, DenoiseLayers&& layers) {
    const py::ssize_t h = layers.height, w = layers.width;
    for (const NamedLayer& layer : named_layers(layers)) {
        if (layer.stride == 3)
            out[py::str(layer.name)] = numpy_from(std::move(*layer.values), {h, w, 3});
        else
            out[py::str(layer.name)] = numpy_from(std::move(*layer.values), {h, w});
    }
}

void bind_denoise(py::module_& m) { m.def("denoise", &denoise, py::arg("layers"), py::arg("options")); }

}  // namespace sombra::python
