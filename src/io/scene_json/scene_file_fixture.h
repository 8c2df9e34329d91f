// What the scene-file tests of each contract version share: a folder per
// test suite for the meshes and images their scenes name, a scene path in
// it, and loading scene text from there. Each suite's SetUpTestSuite calls
// make_folder and then writes its own files.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "io/scene_json/scene_file.h"

namespace sombra::testing {

class SceneFileTest : public ::testing::Test {
protected:
    static inline std::filesystem::path dir;
    static inline std::filesystem::path scene_path;

    // A fresh folder named after the suite and this process, with the
    // one-triangle tri.obj every suite's scenes use.
    static void make_folder(const std::string& suite) {
        dir = std::filesystem::temp_directory_path() / ("sombra_" + suite + "_" + std::to_string(::getpid()));
        std::filesystem::create_directories(dir);
        write(dir / "tri.obj", "v 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n");
        scene_path = dir / "scene.json";
    }
    static void TearDownTestSuite() {
        std::error_code ec;
        std::filesystem::remove_all(dir, ec);
    }
    static void write(const std::filesystem::path& path, const std::string& text) {
        std::ofstream(path, std::ios::binary) << text;
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

}  // namespace sombra::testing
