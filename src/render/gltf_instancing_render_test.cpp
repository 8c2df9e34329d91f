// glTF instancing through the whole pipeline (spec §23): a pyramid three
// nodes share (one mirrored) and five EXT_mesh_gpu_instancing instances,
// loaded through a scene file, render with the direct and the path
// integrator as the same placements with the mesh copied do (those stay
// flattened in the world geometry), up to float rounding at edges.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "io/gltf/gltf_instancing_test_files.h"
#include "io/polygon_test_files.h"
#include "io/scene_json/scene_file.h"
#include "render/render.h"

namespace sombra {
namespace {

using gltf_test::GltfFile;
using testing::TempFolder;
using namespace gltf_test::instancing;

constexpr int kSpp = 4;

// `model` on a floor, lit by a point light, seen from `camera` (JSON), with
// `integrator` ("path glass": the path integrator with the model made of
// glass, whose outside the winding says); a fixed seed, so both files draw
// the same samples.
Film render(const GltfFile& model, const std::string& camera, std::string integrator) {
    const bool glass = integrator == "path glass";
    if (glass) integrator = "path";
    TempFolder dir;
    model.save(dir.path / "m.gltf");
    dir.write("floor.obj", "v -20 -0.01 -20\nv 20 -0.01 -20\nv 20 -0.01 20\nv -20 -0.01 20\nf 4 3 2 1\n");
    dir.write("s.json", R"({"render": {"width": 64, "height": 48, "spp": )" + std::to_string(kSpp) +
                            R"(, "seed": 7, "integrator": ")" + integrator + R"(", "max_depth": 4},
        "camera": )" + camera +
                            R"(,
        "materials": {"floor": {"type": "diffuse", "kd": [0.6, 0.6, 0.6]},
                      "glass": {"type": "dielectric", "ior": 1.5}},
        "lights": [{"position": [-2, 6, 5], "intensity": [40, 40, 40]}],
        "objects": [{"file": "m.gltf")" +
                            (glass ? R"(, "material": "glass")" : "") +
                            R"(}, {"file": "floor.obj", "material": "floor"}]})");
    Diagnostics diag;
    const LoadedScene loaded = load_scene_file(dir.path / "s.json", diag);
    const Accel accel = make_accel(loaded.scene, AccelKind::Bvh);
    RenderProgress progress;
    return render_image(make_render_job(loaded.scene, accel, loaded.settings, 1), progress).film;
}

struct Difference {
    int off = 0;      // pixels differing by more than 1/255 in some channel (clamped to [0, 1])
    float worst = 0;  // the largest such difference
    int lit = 0;      // pixels of `a` with some red
};
Difference compare(const Film& a, const Film& b) {
    Difference d;
    const std::size_t pixels = a.rgb.size() / 3;
    for (std::size_t p = 0; p < pixels; ++p) {
        float most = 0;
        for (std::size_t c = 0; c < 3; ++c)
            most = std::max(
                most, std::fabs(std::clamp(a.rgb[3 * p + c], 0.0f, 1.0f) - std::clamp(b.rgb[3 * p + c], 0.0f, 1.0f)));
        d.lit += a.rgb[3 * p] > 0.02f;
        d.worst = std::max(d.worst, most);
        if (most > 1.0f / 255) ++d.off;
    }
    return d;
}

// Instanced and copied renders agree: at least 99.5 % of the pixels within
// 1/255 in every channel (clamped to [0, 1], as an 8-bit image shows
// them), and the rest within 1/kSpp + 1/255. Those are pixels where a ray
// grazes an edge: the instance's ray, carried into the mesh's coordinates,
// and the copy's world-space triangle round differently, so one of the kSpp
// samples may hit the other surface (or its path continue elsewhere), and
// one sample of a pixel clamped to [0, 1] moves it by at most 1/kSpp.
// (Measured: every pixel within 6e-6.)
void expect_alike(const Film& instanced, const Film& copied) {
    ASSERT_EQ(instanced.rgb.size(), copied.rgb.size());
    const Difference d = compare(instanced, copied);
    const int pixels = int(instanced.rgb.size() / 3);
    EXPECT_GT(d.lit, pixels / 4);  // the comparison sees something
    EXPECT_LE(d.off, pixels / 200) << d.off << " of " << pixels << " pixels differ by more than 1/255";
    if (d.off > 0) {
        EXPECT_LE(d.worst, 1.0f / kSpp + 1.0f / 255);
    }
}

const char* const kThreeCamera = R"({"origin": [0, 4, 9], "look_at": [0, 0.5, 0], "fov": 40})";
const char* const kFiveCamera = R"({"origin": [3, 4, 10], "look_at": [3, 1, -1], "fov": 45})";

TEST(GltfInstancingRender, SharedMeshRendersLikeCopies) {
    for (const char* integrator : {"direct", "path", "path glass"}) {
        SCOPED_TRACE(integrator);
        const Film shared = render(shared_mesh_file(), kThreeCamera, integrator);
        const Film copied = render(copied_mesh_file(), kThreeCamera, integrator);
        expect_alike(shared, copied);
    }
    // The check can fail: the copies without their mirror differ.
    GltfFile unmirrored = copied_mesh_file();
    unmirrored.doc["nodes"][2]["scale"] = {1, 1, 1};
    EXPECT_GT(
        compare(render(shared_mesh_file(), kThreeCamera, "direct"), render(unmirrored, kThreeCamera, "direct")).off,
        50);
}

TEST(GltfInstancingRender, GpuInstancesRenderLikeCopies) {
    for (const char* integrator : {"direct", "path", "path glass"}) {
        SCOPED_TRACE(integrator);
        const Film instanced = render(gpu_instanced_file(), kFiveCamera, integrator);
        const Film copied = render(gpu_copies_file(), kFiveCamera, integrator);
        expect_alike(instanced, copied);
    }
}

}  // namespace
}  // namespace sombra
