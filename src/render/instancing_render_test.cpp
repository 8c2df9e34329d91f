// Spec §23 through the whole pipeline: a scene file whose objects carry
// "instances" renders as the same scene with each instance written out as
// its own object (a flattened copy), direct and path traced. The objects
// exercise what shading reads in an instance: smooth vertex normals, a
// texture through uvs, a mirror (winding), a non-uniform scale (normals),
// and an alpha cut-out (traversal and shadow rays).
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "io/images/image_test_files.h"
#include "io/polygon_test_files.h"
#include "io/scene_json/scene_file.h"
#include "render/render.h"

namespace sombra {
namespace {

using testing::TempFolder;

// A UV sphere of radius 0.5 with vertex normals and texture coordinates.
std::string sphere_obj() {
    constexpr int kRings = 8, kSegments = 12;
    std::ostringstream out;
    for (int r = 0; r <= kRings; ++r)
        for (int s = 0; s <= kSegments; ++s) {
            const double theta = M_PI * r / kRings, phi = 2 * M_PI * s / kSegments;
            const double x = std::sin(theta) * std::cos(phi), y = std::cos(theta), z = std::sin(theta) * std::sin(phi);
            out << "v " << 0.5 * x << ' ' << 0.5 * y << ' ' << 0.5 * z << "\nvn " << x << ' ' << y << ' ' << z
                << "\nvt " << double(s) / kSegments << ' ' << 1 - double(r) / kRings << '\n';
        }
    for (int r = 0; r < kRings; ++r)
        for (int s = 0; s < kSegments; ++s) {
            const int a = r * (kSegments + 1) + s + 1, b = a + kSegments + 1;
            out << "f " << a << '/' << a << '/' << a << ' ' << b << '/' << b << '/' << b << ' ' << b + 1 << '/' << b + 1
                << '/' << b + 1 << ' ' << a + 1 << '/' << a + 1 << '/' << a + 1 << '\n';
        }
    return out.str();
}

struct Placed {
    std::string file, material, transform;
    std::vector<std::string> instances;  // transform lists
};

// The scene with each object's instances as a list (`instanced`), or each
// instance as an object of its own with the two lists joined.
std::string scene_text(const std::vector<Placed>& objects, bool instanced, const std::string& render) {
    std::string text = R"({
  "render": )" + render +
                       R"(,
  "camera": {"origin": [0.3, 1.6, 4.5], "look_at": [0, 0.2, 0], "up": [0, 1, 0], "fov": 45},
  "materials": {"floor": {"type": "diffuse", "kd": [0.7, 0.7, 0.7]},
                "checker": {"type": "diffuse", "kd": {"texture": "checker.png"}},
                "glass": {"type": "dielectric", "ior": 1.5},
                "leaf": {"type": "phong", "kd": [0.2, 0.6, 0.2], "ks": [0.3, 0.3, 0.3], "shininess": 20,
                         "alpha": {"texture": "strip.png"}}},
  "lights": [{"position": [1.5, 3, 2], "intensity": [12, 12, 12]},
             {"type": "quad", "corner": [-1.5, 2.5, -1], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "radiance": [3, 3, 3]}],
  "objects": [{"file": "floor.obj", "material": "floor"})";
    for (const Placed& o : objects) {
        const auto object = [&](const std::string& transform, const std::string& instances) {
            text += ",\n    {\"file\": \"" + o.file + "\", \"material\": \"" + o.material +
                    "\", \"transform\": " + transform + instances + "}";
        };
        if (instanced) {
            std::string list;
            for (const std::string& i : o.instances) list += (list.empty() ? "" : ", ") + i;
            object(o.transform, ", \"instances\": [" + list + "]");
        } else {
            for (const std::string& i : o.instances) {
                // Two JSON lists joined: the object's steps, then the instance's.
                const std::string joined = o.transform.substr(0, o.transform.size() - 1) + ", " + i.substr(1);
                object(joined, "");
            }
        }
    }
    return text + "]}";
}

const std::vector<Placed> kObjects{
    {"sphere.obj",
     "checker",
     R"([{"rotate": {"axis": [0, 1, 0], "degrees": 30}}])",
     {R"([{"translate": [-1.2, 0.5, 0]}])", R"([{"scale": [-1, 1, 1]}, {"translate": [0, 0.5, 0.3]}])",
      R"([{"scale": [1.6, 0.6, 0.9]}, {"rotate": {"axis": [1, 0, 1], "degrees": 50}}, {"translate": [1.2, 0.45, 0]}])"}},
    // Glass tells the sides apart (spec §11): a mirrored instance must keep them.
    {"sphere.obj",
     "glass",
     R"([{"scale": [1, 1, 0.8]}])",
     {R"([{"scale": [-0.7, 0.7, 0.7]}, {"translate": [-0.4, 0.35, 1.3]}])", R"([{"translate": [0.6, 0.35, 1.4]}])"}},
    {"leaf.obj",
     "leaf",
     R"([{"rotate": {"axis": [1, 0, 0], "degrees": -90}}])",
     {R"([{"translate": [-0.6, 1.4, 0.8]}])", R"([{"scale": [-0.8, 0.8, 0.8]}, {"translate": [0.7, 1.3, 0.9]}])"}},
};

class InstancingRender : public ::testing::Test {
protected:
    void SetUp() override {
        tmp_.write("floor.obj", "v -4 0 -4\nv 4 0 -4\nv 4 0 4\nv -4 0 4\nf 1 4 3 2\n");
        tmp_.write("sphere.obj", sphere_obj());
        tmp_.write("leaf.obj",
                   "v -0.5 -0.5 0\nv 0.5 -0.5 0\nv 0.5 0.5 0\nv -0.5 0.5 0\n"
                   "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n");
        testing::write_png_file(tmp_.path / "checker.png", 4, 4, 3, 8,
                                {200, 40, 40, 40,  40,  200, 200, 40,  40,  40, 40, 200, 40,  40,  200, 200,
                                 40,  40, 40, 40,  200, 200, 40,  40,  200, 40, 40, 40,  40,  200, 200, 40,
                                 40,  40, 40, 200, 40,  40,  200, 200, 40,  40, 40, 40,  200, 200, 40,  40});
        testing::write_png_file(tmp_.path / "strip.png", 8, 1, 1, 8, {255, 255, 0, 0, 0, 0, 255, 255});
    }

    Film render(bool instanced, const std::string& settings, int threads = 2) {
        const std::string name = instanced ? "instanced.json" : "copies.json";
        tmp_.write(name, scene_text(kObjects, instanced, settings));
        Diagnostics diag;
        const LoadedScene loaded = load_scene_file(tmp_.path / name, diag);
        EXPECT_EQ(loaded.scene.instances.size(), instanced ? 7u : 0u);
        const Accel accel = make_accel(loaded.scene, AccelKind::Bvh);
        const RenderJob job = make_render_job(loaded.scene, accel, loaded.settings, threads);
        RenderProgress progress;
        return render_image(job, progress).film;
    }

    TempFolder tmp_;
};

// Pixels where the flattened image is locally smooth (no neighbour differs
// by more than `edge`) are "inside" a surface: there both renders must agree
// to rounding; pixels at silhouettes and shadow edges may see another
// triangle or object after rounding, and are only counted.
struct Agreement {
    int inside = 0, inside_off = 0, edges = 0;
};
Agreement compare(const Film& copies, const Film& instanced, float edge, float tolerance) {
    Agreement a;
    for (int j = 1; j + 1 < copies.height; ++j)
        for (int i = 1; i + 1 < copies.width; ++i) {
            const Vec3 c = copies.at(i, j);
            float spread = 0;
            for (int dj = -1; dj <= 1; ++dj)
                for (int di = -1; di <= 1; ++di)
                    spread = std::max(spread, max_component(abs(copies.at(i + di, j + dj) - c)));
            if (spread > edge) {
                ++a.edges;
                continue;
            }
            ++a.inside;
            if (max_component(abs(instanced.at(i, j) - c)) > tolerance * std::max(1.0f, max_component(c)))
                ++a.inside_off;
        }
    return a;
}

TEST_F(InstancingRender, DirectRendersAsFlattenedCopies) {
    const std::string settings = R"({"width": 96, "height": 64, "spp": 1, "integrator": "direct"})";
    const Film copies = render(false, settings), instanced = render(true, settings);
    // Smooth regions: a camera ray hits the same triangle at a point within
    // rounding (~1e-6 relative); the shading varies slowly, so 1e-3 is ample.
    const Agreement a = compare(copies, instanced, 0.05f, 1e-3f);
    EXPECT_GT(a.inside, 4000);
    EXPECT_EQ(a.inside_off, 0) << a.inside_off << " of " << a.inside << " smooth pixels differ";
}

TEST_F(InstancingRender, PathTracedRendersAsFlattenedCopies) {
    const std::string settings =
        R"({"width": 64, "height": 48, "spp": 4, "integrator": "path", "max_depth": 3, "seed": 5})";
    const Film copies = render(false, settings), instanced = render(true, settings);
    // The same sample numbers drive both renders, so paths stay together
    // until rounding sends a bounce across an edge: then the pixel changes
    // by a whole path's contribution. Such pixels must stay rare; the image
    // means agree far within their noise (a quarter percent).
    const Agreement a = compare(copies, instanced, 0.25f, 1e-3f);
    EXPECT_LT(a.inside_off, a.inside / 50) << a.inside_off << " of " << a.inside;
    double sum_copies = 0, sum_instanced = 0;
    for (std::size_t k = 0; k < copies.rgb.size(); ++k) {
        sum_copies += copies.rgb[k];
        sum_instanced += instanced.rgb[k];
    }
    EXPECT_NEAR(sum_instanced / sum_copies, 1.0, 2.5e-3);
}

TEST_F(InstancingRender, ThreadCountDoesNotChangeTheImage) {
    const std::string settings = R"({"width": 48, "height": 32, "spp": 2, "integrator": "path", "seed": 2})";
    const Film one = render(true, settings, 1), three = render(true, settings, 3);
    EXPECT_EQ(one.rgb, three.rgb);
}

}  // namespace
}  // namespace sombra
