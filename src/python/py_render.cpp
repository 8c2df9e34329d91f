// sombra.render and sombra.explain: the keyword options as the library's
// typed options (python/py_options.h), the render run through the library
// (api/session.h) on a thread of its own (python/py_watched.h).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "accel/accel.h"
#include "api/session.h"
#include "core/error.h"
#include "explain/explain.h"
#include "image/display_transform.h"
#include "python/py_arrays.h"
#include "python/py_bindings.h"
#include "python/py_denoise.h"
#include "python/py_options.h"
#include "python/py_scene.h"
#include "python/py_watched.h"
#include "render/render.h"

namespace py = pybind11;

namespace sombra::python {

namespace {

// A scene's render lock: shared, so renders of one scene run together;
// but an animated scene is moved to the asked frame first (spec §22), and
// holds its lock alone while it renders at that moment.
struct RenderLock {
    std::shared_lock<std::shared_mutex> shared;
    std::unique_lock<std::shared_mutex> alone;
};
RenderLock lock_at_frame(PyScene& scene, const RenderSettings& settings, const RenderOptions& options);

// The scene, read-locked for a render; its mip pyramids built first (under
// the write lock, once) when the settings ask for them.
std::shared_lock<std::shared_mutex> lock_for_render(PyScene& scene, const RenderSettings& settings) {
    if (settings.texture_filter == TextureFilter::Mipmap) {
        const std::unique_lock write(scene.access);
        if (!scene.mip_pyramids_built) {
            prepare_textures(scene.loaded.scene, settings);
            scene.mip_pyramids_built = true;
        }
    }
    return std::shared_lock(scene.access);
}

RenderLock lock_at_frame(PyScene& scene, const RenderSettings& settings, const RenderOptions& options) {
    if (!scene.loaded.scene.animation) return {lock_for_render(scene, settings), {}};
    std::unique_lock alone(scene.access);
    if (settings.texture_filter == TextureFilter::Mipmap && !scene.mip_pyramids_built) {
        prepare_textures(scene.loaded.scene, settings);
        scene.mip_pyramids_built = true;
    }
    move_to_frame(scene.loaded.scene, options.frame, scene.source);
    return {{}, std::move(alone)};
}

py::object render(const std::shared_ptr<PyScene>& scene, const py::dict& options, const py::object& progress) {
    const auto start = std::chrono::steady_clock::now();
    const RenderOptions o = render_options_from(options);
    const RenderSettings settings = resolve_render_settings(scene->loaded.settings, o);
    RenderProgress watched;
    RenderOutput rendered;
    Film noisy;
    std::vector<std::string> warnings;
    const PixelWindow image = o.crop.value_or(PixelWindow{0, 0, settings.width, settings.height});
    // The pixels rendered: a crop under denoise is rendered grown by the denoiser's reach.
    const PixelWindow area = o.crop && o.denoise ? denoise_window(*o.crop, settings.width, settings.height) : image;
    const std::uint64_t total = static_cast<std::uint64_t>(area.width) * static_cast<std::uint64_t>(area.height) *
                                static_cast<std::uint64_t>(settings.spp);
    run_watched(
        [&] {
            const RenderLock lock = lock_at_frame(*scene, settings, o);
            const Scene& s = scene->loaded.scene;
            warnings = render_warnings(s, settings, o);
            const Accel accel = make_accel(s, o.accel);
            const RenderJob job = make_job(s, accel, settings, o, start);
            rendered = render_image(job, watched);
            if (o.denoise && !rendered.cancelled) noisy = denoise_render(rendered, job, o, &watched.cancel);
        },
        watched, total, progress);
    const py::ssize_t w = image.width, h = image.height;  // the --crop window's size (spec §27)
    py::dict out;
    out["color"] = numpy_from(std::move(rendered.film.rgb), {h, w, 3});
    auto add = [&out, w, h](const char* name, std::vector<float>& layer, py::ssize_t channels) {
        if (layer.empty()) return;
        if (channels == 3)
            out[name] = numpy_from(std::move(layer), {h, w, 3});
        else
            out[name] = numpy_from(std::move(layer), {h, w});
    };
    add("albedo", rendered.aovs.albedo, 3);
    add("normal", rendered.aovs.normal, 3);
    add("depth", rendered.aovs.depth, 1);
    add("position", rendered.aovs.position, 3);
    add("spp", rendered.aovs.spp, 1);
    add("variance", rendered.aovs.variance, 3);
    if (o.aovs.noisy) add("noisy", noisy.rgb, 3);
    if (o.aovs.denoise) add_denoise_layers(out, std::move(rendered.aovs.denoise));
    out["warnings"] = warnings;
    out["spp_reached"] = static_cast<double>(rendered.samples) / static_cast<double>(w * h);
    out["passes"] = rendered.passes;
    return out;
}

// explain's story as JSON and, when `display` is given, its SVG picture
// (empty otherwise), as `sombra explain --json --svg` writes them.
py::tuple explain(const std::shared_ptr<PyScene>& scene, const py::int_& column, const py::int_& row,
                  const py::int_& sample_index, const py::dict& options, const py::object& picture) {
    const int x = int_value(column), y = int_value(row), sample = int_value(sample_index);
    const RenderOptions o = render_options_from(options);
    std::optional<DisplayTransform> display;
    if (!picture.is_none()) {
        const auto [exposure, tonemap] = py::cast<std::pair<float, std::string>>(picture);
        display = DisplayTransform{exposure, tonemap_option(tonemap)};
    }
    const RenderSettings settings = resolve_settings(scene->loaded.settings, o.overrides);
    // A pixel beyond int's range is outside every image; the message shows it as given.
    if (!py::int_(x).equal(column) || !py::int_(y).equal(row))
        throw Error("pixel (" + std::string(py::repr(column)) + ", " + std::string(py::repr(row)) + ")",
                    "outside the " + std::to_string(settings.width) + "x" + std::to_string(settings.height) + " image");
    check_explain_pixel(x, y, sample, settings);
    // Under denoise the whole image as render(denoise=True) makes it, and the
    // weights that made this pixel of it (the picture shows that render, as
    // the command line's does); for a picture alone a quick render; on a
    // thread Ctrl-C can stop.
    const RenderSettings render_settings = o.denoise ? resolve_render_settings(scene->loaded.settings, o) : settings;
    RenderProgress watched;
    std::string story, svg;
    const int picture_samples = o.denoise ? render_settings.spp : picture_spp(render_settings);
    const std::uint64_t total = !o.denoise && !display ? 0
                                                       : static_cast<std::uint64_t>(render_settings.width) *
                                                             static_cast<std::uint64_t>(render_settings.height) *
                                                             static_cast<std::uint64_t>(picture_samples);
    run_watched(
        [&] {
            const RenderLock lock = lock_at_frame(*scene, render_settings, o);
            const Scene& s = scene->loaded.scene;
            const Accel accel = make_accel(s, o.accel);
            const RenderJob job = make_job(s, accel, render_settings, o, std::chrono::steady_clock::now());
            const SampleRecord record = record_pixel_sample(job, x, y, sample);
            std::optional<DenoiseStory> denoised;
            RenderOutput rendered;
            if (o.denoise || display) {
                RenderJob whole = job;
                if (!o.denoise) whole.settings.spp = picture_samples;
                rendered = render_image(whole, watched);
                if (rendered.cancelled) return;
            }
            if (o.denoise) {
                const std::size_t p = (static_cast<std::size_t>(y) * static_cast<std::size_t>(render_settings.width) +
                                       static_cast<std::size_t>(x)) *
                                      3;
                denoised = DenoiseStory{explain_denoised_pixel(rendered.aovs.denoise, x, y, o.threads),
                                        {rendered.film.rgb[p], rendered.film.rgb[p + 1], rendered.film.rgb[p + 2]}};
            }
            const ExplainContext context{s, job, scene->source, denoised ? &*denoised : nullptr};
            story = explain_json(context, record);
            if (display)
                svg = explain_svg(context, record,
                                  ImageView{rendered.film.width, rendered.film.height, rendered.film.rgb.data()},
                                  *display);
        },
        watched, total, py::none());
    return py::make_tuple(story, svg);
}

}  // namespace

void bind_render(py::module_& m) {
    m.def("render", &render, py::arg("scene"), py::arg("options"), py::arg("progress") = py::none());
    m.def("explain", &explain, py::arg("scene"), py::arg("x"), py::arg("y"), py::arg("sample"), py::arg("options"),
          py::arg("picture") = py::none());
}

}  // namespace sombra::python
