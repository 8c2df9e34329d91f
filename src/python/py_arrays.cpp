// sombra.write_image and sombra.to_png, and the checks every array from
// Python passes: a wrong dtype, shape or a NaN is an exception, never a read
// past the end.
#include "python/py_arrays.h"

#include <cmath>
#include <memory>
#include <string>

#include "core/error.h"
#include "core/image_limits.h"
#include "image/display_transform.h"
#include "image/image_io.h"
#include "python/py_bindings.h"

namespace py = pybind11;

namespace sombra::python {

py::array_t<float> numpy_from(std::vector<float>&& values, const std::vector<py::ssize_t>& shape) {
    auto* owned = new std::vector<float>(std::move(values));
    py::capsule free_when_done(owned, [](void* p) { delete static_cast<std::vector<float>*>(p); });
    return py::array_t<float>(shape, owned->data(), free_when_done);
}

ImageView image_from(const py::handle& array, py::array_t<float>& storage) {
    if (!py::isinstance<py::array>(array))
        throw py::type_error("image: expected a numpy array of shape (height, width, 3), not " +
                             std::string(py::str(py::type::of(array).attr("__name__"))));
    const auto a = py::reinterpret_borrow<py::array>(array);
    // Any float dtype (float16 to float64, either byte order) is read as the float32 values it rounds to.
    if (a.dtype().kind() != 'f')
        throw py::type_error("image: expected a float dtype, not " + std::string(py::str(a.dtype())));
    std::string shape;
    for (py::ssize_t i = 0; i < a.ndim(); ++i) shape += (i ? ", " : "") + std::to_string(a.shape(i));
    if (a.ndim() != 3 || a.shape(2) != 3) throw Error("image", "shape (" + shape + ") is not (height, width, 3)");
    if (a.shape(0) < 1 || a.shape(1) < 1 || a.shape(0) > kMaxImageSide || a.shape(1) > kMaxImageSide ||
        a.shape(0) * a.shape(1) > kMaxPixels)
        throw Error("image", "shape (" + shape + "): each side must be between 1 and " + std::to_string(kMaxImageSide) +
                                 ", at most " + std::to_string(kMaxPixels) + " pixels");
    storage = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(a);
    if (!storage) throw py::error_already_set();
    const float* rgb = storage.data();
    const std::size_t count = static_cast<std::size_t>(storage.size());
    for (std::size_t i = 0; i < count; ++i)
        if (std::isnan(rgb[i]))
            throw Error("image", "NaN at pixel (" + std::to_string(i / 3 % a.shape(1)) + ", " +
                                     std::to_string(i / 3 / a.shape(1)) + ") (column, row)");
    return ImageView{static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)), rgb};
}

void bind_arrays(py::module_& m) {
    m.def(
        "write_image",
        [](const std::string& path, const py::handle& array, float exposure, const std::string& tonemap) {
            const DisplayTransform display{exposure, tonemap_option(tonemap)};
            if (display.tonemap != Tonemap::None && !is_eight_bit(image_format_for(path)))
                throw Error(path, "tonemap applies to 8-bit outputs (.png, .jpg); this format keeps linear radiance");
            py::array_t<float> storage;
            const ImageView image = image_from(array, storage);
            py::gil_scoped_release release;
            write_image(path, image, display);
        },
        py::arg("path"), py::arg("array"), py::arg("exposure") = 0.0f, py::arg("tonemap") = "none");
    m.def(
        "to_png",
        [](const py::handle& array, float exposure, const std::string& tonemap) {
            const DisplayTransform display{exposure, tonemap_option(tonemap)};
            py::array_t<float> storage;
            const ImageView image = image_from(array, storage);
            std::vector<std::uint8_t> bytes;
            {
                py::gil_scoped_release release;
                bytes = encode_png_bytes(image, display);
            }
            return py::bytes(reinterpret_cast<const char*>(bytes.data()), bytes.size());
        },
        py::arg("array"), py::arg("exposure") = 0.0f, py::arg("tonemap") = "none");
}

}  // namespace sombra::python
