// glTF animation through the whole pipeline (spec §22): three pyramids
// whose nodes a file animates, loaded through a scene file at a frame (or
// moved there by set_scene_time), render as the same pyramids posed by
// hand in a static file do, up to float rounding at edges.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "io/gltf/gltf_instancing_test_files.h"
#include "io/polygon_test_files.h"
#include "io/scene_json/scene_file.h"
#include "render/render.h"
#include "scene/animation.h"

namespace sombra {
namespace {

using gltf_test::GltfFile;
using gltf_test::kFloat;
using testing::TempFolder;
using namespace gltf_test::instancing;

// `model` on a floor under a point light at frame `frame` (4 fps), moved to
// `time` seconds after loading when given; path traced, a fixed seed.
Film render(const GltfFile& model, int frame, std::optional<double> time = std::nullopt) {
    TempFolder dir;
    model.save(dir.path / "m.gltf");
    dir.write("floor.obj", "v -20 -0.01 -20\nv 20 -0.01 -20\nv 20 -0.01 20\nv -20 -0.01 20\nf 4 3 2 1\n");
    dir.write("s.json", R"({"render": {"width": 64, "height": 48, "spp": 4, "seed": 7, "integrator": "path",
                   "max_depth": 3},
        "animation": {"fps": 4, "frames": [)" +
                            std::to_string(frame) + ", " + std::to_string(frame + 4) + R"(]},
        "camera": {"origin": [0, 4, 9], "look_at": [0, 0.5, 0], "fov": 40},
        "materials": {"floor": {"type": "diffuse", "kd": [0.6, 0.6, 0.6]}},
        "lights": [{"position": [-2, 6, 5], "intensity": [40, 40, 40]}],
        "objects": [{"file": "m.gltf"}, {"file": "floor.obj", "material": "floor"}]})");
    Diagnostics diag;
    LoadedScene loaded = load_scene_file(dir.path / "s.json", diag);
    if (time) set_scene_time(loaded.scene, *time, "s.json");
    const Accel accel = make_accel(loaded.scene, AccelKind::Bvh);
    RenderProgress progress;
    return render_image(make_render_job(loaded.scene, accel, loaded.settings, 1), progress).film;
}

// Pixels differing by more than 1/255 in some channel (clamped to [0, 1]).
int pixels_off(const Film& a, const Film& b) {
    int off = 0;
    for (std::size_t p = 0; p < a.rgb.size() / 3; ++p) {
        float most = 0;
        for (std::size_t c = 0; c < 3; ++c)
            most = std::max(
                most, std::fabs(std::clamp(a.rgb[3 * p + c], 0.0f, 1.0f) - std::clamp(b.rgb[3 * p + c], 0.0f, 1.0f)));
        off += most > 1.0f / 255;
    }
    return off;
}

// The shared pyramid of shared_mesh_file, node 0 lifted from y = 0 to 2 and
// node 1 turned from 0° to 90° about +y over one second: at 0.5 s, node 0
// is at y = 1 and node 1 at 45°, kPlacements' own rotation.
GltfFile animated() {
    GltfFile f = shared_mesh_file();
    const auto sampler = [&f](const std::vector<float>& values, const char* type) {
        const int in = f.add_array(std::vector<float>{0, 1}, kFloat, 2, "SCALAR");
        const int out = f.add_array(values, kFloat, 2, type);
        f.doc["animations"][0]["samplers"].push_back({{"input", in}, {"output", out}});
        return int(f.doc["animations"][0]["samplers"].size()) - 1;
    };
    const int lift = sampler({-2.5f, 0, 0, -2.5f, 2, 0}, "VEC3");
    const int turn = sampler({0, 0, 0, 1, 0, 0.70710678f, 0, 0.70710678f}, "VEC4");
    f.doc["animations"][0]["channels"] = {{{"sampler", lift}, {"target", {{"node", 0}, {"path", "translation"}}}},
                                          {{"sampler", turn}, {"target", {{"node", 1}, {"path", "rotation"}}}}};
    return f;
}

TEST(GltfAnimationRender, AFrameRendersLikeTheFilePosedByHand) {
    GltfFile posed = copied_mesh_file();
    posed.doc["nodes"][0]["translation"] = {-2.5, 1, 0};
    const Film expected = render(posed, 0);
    const int pixels = 64 * 48;
    // Loaded at frame 2 (0.5 s), and loaded at frame 0 then moved to 0.5 s.
    EXPECT_LE(pixels_off(render(animated(), 2), expected), pixels / 200);
    EXPECT_LE(pixels_off(render(animated(), 0, 0.5), expected), pixels / 200);
    // The check can fail: the file at time 0 differs.
    EXPECT_GT(pixels_off(render(animated(), 0), expected), 50);
}

}  // namespace
}  // namespace sombra
