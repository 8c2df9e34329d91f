// Images between numpy and sombra: float vectors handed to numpy without a
// copy, and arrays from Python checked before any C++ reads them.
#pragma once

#include <pybind11/numpy.h>

#include <vector>

#include "image/image_io.h"

namespace sombra::python {

// A numpy float32 array of `shape` that owns `values` (moved, not copied).
pybind11::array_t<float> numpy_from(std::vector<float>&& values, const std::vector<pybind11::ssize_t>& shape);

// An RGB image from Python: a numpy array of a float dtype and shape
// (height, width, 3), within the image limits, without NaN; as contiguous
// float32 in `storage`. TypeError for a non-array or a dtype not float,
// Error("array", ...) for a wrong shape or a NaN.
ImageView image_from(const pybind11::handle& array, pybind11::array_t<float>& storage);

}  // namespace sombra::python
