// What the scene-file tests share: a folder per test suite holding every
// mesh and image their scenes name, a scene path in it, loading scene text
// from there, and the scene text the tests build on (a camera and tri.obj,
// with a material, light, environment or objects of the test's own).
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "io/images/exr_test_file.h"
#include "io/scene_json/scene_file.h"

namespace sombra::testing {

class SceneFileTest : public ::testing::Test {
protected:
    static inline std::filesystem::path dir;
    static inline std::filesystem::path scene_path;

    // A fresh folder named after the suite and this process, with the files below.
    static void SetUpTestSuite() {
        const std::string suite = ::testing::UnitTest::GetInstance()->current_test_suite()->name();
        dir = std::filesystem::temp_directory_path() / ("sombra_" + suite + "_" + std::to_string(::getpid()));
        std::filesystem::create_directories(dir / "models");
        write(dir / "tri.obj", "v 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n");
        // The plane x + y = 1 with its normal at every corner.
        write(dir / "tilted.obj", "v 1 0 0\nv 0 1 0\nv 1 0 1\nvn 0.70710678 0.70710678 0\nf 1//1 2//1 3//1\n");
        // Two triangles with two MTL materials.
        write(dir / "two.mtl", "newmtl red\nKd 1 0 0\nnewmtl shiny\nKd 0.2 0.2 0.2\nKs 0.5 0.5 0.5\nNs 20\n");
        write(dir / "two.obj",
              "mtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nusemtl red\nf 1 2 3\nusemtl shiny\nf 2 4 3\n");
        // Each corner's normal points along its position (all distinct), and a uv per corner.
        write(dir / "normals.obj",
              "v 1 0 0\nv 0 1 0\nv 0 0 1\nvn 1 0 0\nvn 0 1 0\nvn 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\n"
              "f 1/1/1 2/2/2 3/3/3\n");
        write_exr(dir / "sky.exr", 4, 2, std::vector<float>(4 * 2 * 3, 0.5f));
        std::vector<float> ringing(4 * 2 * 3, 0.5f);
        ringing[3 * 5 + 1] = -2.5f;  // pixel (1, 1)
        ringing[3 * 6 + 0] = -0.5f;
        write_exr(dir / "ringing.exr", 4, 2, ringing);
        scene_path = dir / "scene.json";
        write(scene_path, "{}");
    }
    static void TearDownTestSuite() {
        std::error_code ec;
        std::filesystem::remove_all(dir, ec);
    }
    static void write(const std::filesystem::path& path, const std::string& text) {
        std::ofstream(path, std::ios::binary) << text;
    }

    static constexpr const char* kCamera = R"("camera": {"origin": [0, 0, 5], "look_at": [0, 0, 0]})";

    // A valid scene with `members` and objects `objects` (default: tri.obj).
    static std::string scene(const std::string& members, const std::string& objects = R"([{"file": "tri.obj"}])") {
        return "{" + members + (members.empty() ? "" : ", ") + kCamera + ", \"objects\": " + objects + "}";
    }
    static std::string with_camera(const std::string& camera) {
        return R"({"camera": )" + camera + R"(, "objects": [{"file": "tri.obj"}]})";
    }
    // The camera, `materials` when given, and the objects `objects` (JSON array elements).
    static std::string with_objects(const std::string& objects, const std::string& materials = "") {
        return std::string("{") + kCamera + ", " + (materials.empty() ? "" : "\"materials\": " + materials + ", ") +
               "\"objects\": [" + objects + "]}";
    }
    // tri.obj with the material `material`, named "m".
    static std::string with_material(const std::string& material) {
        return scene(R"("materials": {"m": )" + material + "}", R"([{"file": "tri.obj", "material": "m"}])");
    }
    // `light` (JSON array elements) as the scene's lights.
    static std::string with_light(const std::string& light) { return scene(R"("lights": [)" + light + "]"); }
    static std::string with_environment(const std::string& env, const std::string& more = "") {
        return scene(R"("environment": )" + env + more);
    }

    Scene load(const std::string& text) { return load_scene_text(text, scene_path, diag).scene; }
    RenderSettings settings_of(const std::string& text) { return load_scene_text(text, scene_path, diag).settings; }

    // The Error message of loading `text` ("" when it loads).
    std::string error_of(const std::string& text) {
        try {
            load(text);
        } catch (const Error& e) {
            return e.what();
        }
        return "";
    }

    // Scene text that must fail to load, and the start of its message after
    // the scene's path (e.g. ": /lights/0/direction: direction is zero").
    struct ErrorCase {
        std::string text, expected;
    };
    // Each case fails with one message starting with the scene's path and its `expected`.
    void expect_errors(const std::vector<ErrorCase>& cases) {
        const std::string name = scene_path.string();
        for (const ErrorCase& c : cases) {
            SCOPED_TRACE(c.text);
            const std::string message = error_of(c.text);
            EXPECT_EQ(message.rfind(name + c.expected, 0), 0u) << message;
        }
    }

    Diagnostics diag;
};

// The normal of triangle `t` by its winding (not unit length).
inline Vec3 winding_normal(const TriangleMesh& m, std::size_t t) {
    const Index3& c = m.triangles[t];
    return cross(m.positions[c[1]] - m.positions[c[0]], m.positions[c[2]] - m.positions[c[0]]);
}

}  // namespace sombra::testing
