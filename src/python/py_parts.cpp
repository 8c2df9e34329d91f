// Scenes from code (spec §19): meshes from numpy arrays, made and checked
// when Scene.add_mesh is called, and the scene file's sections (materials,
// lights, camera, render, transforms, background) checked when they are
// set, each by the scene-file reader's own function for that key, so that a
// bad value raises there with the message a scene file would get.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "io/array_mesh.h"
#include "io/scene_json/scene_json.h"
#include "python/py_bindings.h"
#include "python/py_scene.h"

namespace py = pybind11;

namespace sombra::python {

namespace {

// Names a scene from code in messages, as a file name does for a scene file.
const std::string kSceneName = "<scene>";

std::string shape_of(const py::array& a) {
    std::string shape;
    for (py::ssize_t i = 0; i < a.ndim(); ++i) shape += (i ? ", " : "") + std::to_string(a.shape(i));
    return "(" + shape + (a.ndim() == 1 ? ",)" : ")");
}

// `what` as a numpy array of shape (N, columns) whose dtype is of `kind`
// ('f' floating, 'i' integer); TypeError for another type or dtype,
// Error(what, ...) for another shape.
py::array expect_array(const py::handle& value, const char* what, py::ssize_t columns, char kind) {
    if (!py::isinstance<py::array>(value))
        throw py::type_error(std::string(what) + ": expected a numpy array, not " +
                             std::string(py::str(py::type::of(value).attr("__name__"))));
    auto a = py::reinterpret_borrow<py::array>(value);
    const char k = a.dtype().kind();
    if (kind == 'f' ? k != 'f' : k != 'i' && k != 'u')
        throw py::type_error(std::string(what) + ": expected " + (kind == 'f' ? "a float" : "an integer") +
                             " dtype, not " + std::string(py::str(a.dtype())));
    if (a.ndim() != 2 || a.shape(1) != columns)
        throw Error(what, "shape " + shape_of(a) + " is not (N, " + std::to_string(columns) + ")");
    return a;
}

template <class T>
std::vector<T> rows_of(const py::handle& value, const char* what, py::ssize_t columns) {
    const auto a =
        py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(expect_array(value, what, columns, 'f'));
    std::vector<T> out(static_cast<std::size_t>(a.shape(0)));
    const float* p = a.data();
    for (std::size_t i = 0; i < out.size(); ++i, p += columns) {
        if constexpr (std::is_same_v<T, Vec3>)
            out[i] = Vec3{p[0], p[1], p[2]};
        else
            out[i] = Vec2{p[0], p[1]};
    }
    return out;
}

std::shared_ptr<LoadedMesh> make_mesh(const py::handle& positions, const py::handle& indices, const py::handle& normals,
                                      const py::handle& uvs, const std::string& where) {
    std::vector<Vec3> p = rows_of<Vec3>(positions, "positions", 3);
    const py::array a = expect_array(indices, "indices", 3, 'i');
    // Unsigned indices are read as such: 2^64 - 1 must not wrap to -1 in the message.
    std::vector<std::uint32_t> corners(static_cast<std::size_t>(a.size()));
    auto check_all = [&](const auto* q) {
        for (std::size_t k = 0; k < corners.size(); ++k) {
            if (q[k] < 0 || static_cast<std::uint64_t>(q[k]) > std::numeric_limits<std::uint32_t>::max() - 1)
                throw Error(where, "indices[" + std::to_string(k / 3) + "] holds " + std::to_string(q[k]) +
                                       ", not a vertex index");
            corners[k] = static_cast<std::uint32_t>(q[k]);
        }
    };
    if (a.dtype().kind() == 'u')
        check_all(py::array_t<std::uint64_t, py::array::c_style | py::array::forcecast>::ensure(a).data());
    else
        check_all(py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(a).data());
    std::vector<Vec3> n = normals.is_none() ? std::vector<Vec3>{} : rows_of<Vec3>(normals, "normals", 3);
    std::vector<Vec2> t = uvs.is_none() ? std::vector<Vec2>{} : rows_of<Vec2>(uvs, "uvs", 2);
    Diagnostics diag;
    py::gil_scoped_release release;  // a million triangles take a moment
    return std::make_shared<LoadedMesh>(
        make_array_mesh(where, std::move(p), corners, std::move(n), std::move(t), diag));
}

// Checks one section given as JSON text at `pointer`, by the reader's
// function for it; returns what Python shows of it (the settings for
// "render"), or None.
// `name` names the scene in messages; `folder` anchors relative texture and
// environment paths (a scene from code's: the working directory).
py::object check_part(const std::string& kind, const std::string& text, const std::string& pointer,
                      const std::string& name, const std::string& folder) {
    Diagnostics diag;
    const SceneJson s{name, diag};
    const Json v = parse_scene_json(text, name);
    if (kind == "render") {
        return settings_dict(read_render(s, v, pointer));
    }
    if (kind == "camera") {
        (void)read_camera(s, v, pointer);
    } else if (kind == "materials") {
        std::vector<Texture> textures;
        SceneTextures textures_folder{folder, &textures};
        (void)read_materials(s, v, pointer, textures_folder);
    } else if (kind == "lights") {
        (void)read_lights(s, v, pointer);
    } else if (kind == "transform") {
        (void)read_transform(s, v, pointer);
    } else if (kind == "media") {
        (void)read_media(s, v, pointer);
    } else if (kind == "background") {
        (void)read_rgb(s, v, pointer);
    } else if (kind == "environment") {
        py::gil_scoped_release release;  // reading a large map takes a moment
        (void)read_environment(s, v, pointer, folder);
    } else {
        throw std::invalid_argument("check_part: unknown kind " + kind);
    }
    return py::none();
}

}  // namespace

void bind_parts(py::module_& m) {
    py::class_<LoadedMesh, std::shared_ptr<LoadedMesh>>(m, "Mesh").def_property_readonly(
        "triangle_count", [](const LoadedMesh& mesh) { return mesh.mesh.triangle_count(); });
    m.def("make_mesh", &make_mesh, py::arg("positions"), py::arg("indices"), py::arg("normals"), py::arg("uvs"),
          py::arg("where"));
    m.def("check_part", &check_part, py::arg("kind"), py::arg("text"), py::arg("pointer"), py::arg("name") = kSceneName,
          py::arg("folder") = ".");
}

}  // namespace sombra::python
