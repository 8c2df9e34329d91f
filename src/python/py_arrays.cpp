// sombra.write_image and sombra.to_png, and the checks every array from
// Python passes: a wrong dtype, shape or a NaN is an exception, never a read
// past the end.
#include "python/py_arrays.h"

#include <cctype>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>

#include "core/error.h"
#include "core/image_limits.h"
#include "image/display_transform.h"
#include "image/image_io.h"
#include "io/images/texture_image.h"
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

namespace {

// An image file as linear RGB floats (height, width, 3): PFM, or what
// textures read (PNG, JPEG and the like decoded from sRGB, EXR, HDR).
py::array_t<float> read_image_array(const std::string& path) {
    std::vector<float> rgb;
    int width = 0, height = 0;
    {
        py::gil_scoped_release release;
        std::string ext = std::filesystem::path(path).extension().string();
        for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        if (ext == ".pfm") {
            PfmImage image = read_pfm(path);
            width = image.width;
            height = image.height;
            rgb = std::move(image.rgb);
        } else {
            const Texture t = read_texture_file(path, TextureEncoding::Color);
            width = t.width;
            height = t.height;
            const auto pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
            const auto channels = static_cast<std::size_t>(t.channels);
            rgb.resize(pixels * 3);
            // Grey fills the three channels; alpha is dropped.
            for (std::size_t p = 0; p < pixels; ++p)
                for (std::size_t c = 0; c < 3; ++c) rgb[3 * p + c] = t.texels[p * channels + (channels >= 3 ? c : 0)];
        }
    }
    return numpy_from(std::move(rgb), {height, width, 3});
}

}  // namespace

void bind_arrays(py::module_& m) {
    m.def("read_image", &read_image_array, py::arg("path"));
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
