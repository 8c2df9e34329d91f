// sombra.Scene and how one is read: a scene file or model (load) or scene
// JSON text (load_text, which Scene.from_dict sends its dict through), with
// the overrides checked as the command line checks them (python/py_options.h).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <string>
#include <vector>

#include "io/scene_input.h"
#include "io/scene_json/scene_file.h"
#include "python/py_bindings.h"
#include "python/py_options.h"
#include "python/py_scene.h"

namespace py = pybind11;

namespace sombra::python {

namespace {

// The overrides are converted and checked before the (possibly long) load.
template <class Read>
std::shared_ptr<PyScene> read_scene(const std::string& source, const py::dict& overrides, Read&& read) {
    const RenderOptions options = render_options_from(overrides);
    Diagnostics diag;
    LoadedScene loaded;
    {
        py::gil_scoped_release release;  // other Python threads go on while a big model loads
        loaded = read(diag);
    }
    auto scene = std::make_shared<PyScene>();
    scene->loaded.settings = resolve_settings(loaded.settings, options.overrides);
    scene->loaded.scene = std::move(loaded.scene);
    scene->source = source;
    scene->warnings = diag.warnings;
    return scene;
}

std::shared_ptr<PyScene> load(const std::string& path, const py::dict& overrides) {
    return read_scene(path, overrides, [&path](Diagnostics& diag) { return load_input(path, diag); });
}

// `name` names the text in messages; its folder anchors relative mesh paths.
// `meshes`: those the text's objects name as {"mesh": i} (a scene from code).
// `cache`: the mesh files read before for the same Scene (an edited one).
std::shared_ptr<PyScene> load_text(const std::string& text, const std::string& name, const py::dict& overrides,
                                   const std::vector<std::shared_ptr<LoadedMesh>>& meshes,
                                   const std::shared_ptr<MeshFileCache>& cache) {
    std::vector<const LoadedMesh*> given;
    for (const auto& m : meshes) given.push_back(m.get());
    return read_scene(name, overrides,
                      [&](Diagnostics& diag) { return load_scene_text(text, name, diag, given, cache.get()); });
}

}  // namespace

py::dict settings_dict(const RenderSettings& r) {
    py::dict d;
    d["width"] = r.width;
    d["height"] = r.height;
    d["spp"] = r.spp;
    d["seed"] = r.seed;
    d["integrator"] = std::string(integrator_name(r.integrator));
    d["max_depth"] = r.max_depth;
    d["max_volume_depth"] = r.max_volume_depth;
    d["texture_filter"] = std::string(texture_filter_name(r.texture_filter));
    return d;
}

py::list vec3_list(Vec3 v) { return py::cast(std::vector<float>{v.x, v.y, v.z}); }

// The camera as a scene file's "camera" object would give it (spec §3, §17);
// a glTF file's orthographic camera (spec §24), which scene files cannot
// write, as "orthographic": {"ymag": half-height} in place of "fov".
py::dict camera_dict(const CameraSpec& c) {
    py::dict d;
    const bool orthographic = c.projection == CameraSpec::Projection::Orthographic;
    if (c.look_at) {
        d["origin"] = vec3_list(c.look_at->origin);
        d["look_at"] = vec3_list(c.look_at->look_at);
        d["up"] = vec3_list(c.look_at->up);
        if (!orthographic) d["fov"] = c.look_at->fov_degrees;
    } else if (c.basis) {
        d["origin"] = vec3_list(c.basis->origin);
        d["left"] = vec3_list(c.basis->left);
        d["up"] = vec3_list(c.basis->up);
        d["forward"] = vec3_list(c.basis->forward);
    }
    if (orthographic) {
        py::dict o;
        o["ymag"] = c.ortho_half_height;
        d["orthographic"] = o;
    }
    if (c.aperture_radius > 0) d["aperture_radius"] = c.aperture_radius;
    if (c.focus_distance) d["focus_distance"] = *c.focus_distance;
    return d;
}

void bind_scene(py::module_& m) {
    py::class_<PyScene, std::shared_ptr<PyScene>>(m, "Scene")
        .def_property_readonly("render_settings", [](const PyScene& s) { return settings_dict(s.loaded.settings); })
        .def_property_readonly("camera", [](const PyScene& s) { return camera_dict(s.loaded.scene.camera); })
        .def_readonly("source", &PyScene::source)
        .def_readonly("warnings", &PyScene::warnings)
        .def_property_readonly("triangle_count", [](const PyScene& s) { return stored_triangle_count(s.loaded.scene); })
        .def_property_readonly("instanced_triangle_count",
                               [](const PyScene& s) { return drawn_triangle_count(s.loaded.scene); });
    // Opaque: what a Scene read from a file or a dict keeps between edits.
    py::class_<MeshFileCache, std::shared_ptr<MeshFileCache>>(m, "MeshCache")
        .def(py::init<>())
        .def("__len__", [](const MeshFileCache& c) { return c.meshes.size(); });
    m.def("load", &load, py::arg("path"), py::arg("overrides"));
    m.def("load_text", &load_text, py::arg("text"), py::arg("name"), py::arg("overrides"),
          py::arg("meshes") = std::vector<std::shared_ptr<LoadedMesh>>{},
          py::arg("cache") = std::shared_ptr<MeshFileCache>{});
    m.def(
        "read_scene_text", [](const std::string& path) { return read_scene_text(path); }, py::arg("path"));
}

}  // namespace sombra::python
