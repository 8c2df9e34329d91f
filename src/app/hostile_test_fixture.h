// What the hostile-input tests share (docs/robustness.md, "Hostile
// inputs"): the command-line fixture, scenes around its square (with a mesh,
// lights, a material or more members of the test's own), rendering them, and
// the checks of an error's WHERE and of a warning's line.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <string>

#include "cli_test_fixture.h"

namespace sombra::cli_test {

// Runs that must not allocate anything large: error paths read headers and counts, not claims.
inline constexpr long kSmallMemoryKib = 1L << 20;

// The square's four corners, for OBJ files that add to it.
inline const std::string kSquareVertices = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n";

// A small image, and a camera that frames the square.
inline const std::string kRender = R"({"width": 16, "height": 12})";
inline const std::string kCamera = R"({"origin": [0, 0, 4], "look_at": [0, 0, 0], "fov": 40})";

class HostileFixture : public CliFixture {
protected:
    // The fixture's scene with `mesh` in place of the square.
    std::string mesh_scene(const std::string& mesh) {
        return scene(R"({"width": 32, "height": 24})", R"({"origin": [0, 0, 4], "look_at": [0, 0, 0], "fov": 40})", "",
                     mesh);
    }
    // The fixture's scene with `extra` top-level members ("," first).
    std::string scene_with(const std::string& extra, const std::string& render = kRender) {
        return scene(render, kCamera, extra);
    }
    // The fixture's square with `lights` (JSON array elements) and no other light.
    std::string light_scene(const std::string& lights, const std::string& camera = kCamera) {
        return R"({"render": )" + kRender + R"(, "camera": )" + camera +
               R"(, "materials": {"grey": {"type": "diffuse", "kd": [0.5, 0.5, 0.5]}}, "lights": [)" + lights +
               R"(], "objects": [{"file": "square.obj", "material": "grey"}]})";
    }
    // A scene whose square uses material `m`.
    std::string material_scene(const std::string& material) {
        return R"({"render": )" + kRender + R"(, "camera": )" + kCamera + R"(, "materials": {"m": )" + material +
               R"(}, "objects": [{"file": "square.obj", "material": "m"}]})";
    }

    // Renders `scene_text` as s.json to out.png; `args` adds options.
    RunResult render(const std::string& scene_text, const std::string& args = "") {
        write_text(dir_ / "s.json", scene_text);
        return run("render s.json -o out.png --quiet --threads 2 " + args);
    }
    // Renders `scene_text` as s.json to out.pfm and returns the image; `args` adds options.
    Pfm render_scene(const std::string& scene_text, RunResult* result = nullptr, const std::string& args = "") {
        write_text(dir_ / "s.json", scene_text);
        const RunResult r = run("render s.json -o out.pfm --quiet --threads 2 " + args);
        EXPECT_EQ(r.status, 0) << r.err;
        if (result) *result = r;
        Pfm image = read_pfm(dir_ / "out.pfm");
        fs::remove(dir_ / "out.pfm");
        return image;
    }
    // The plain square's image: what a file that adds only dropped or invisible faces must give.
    Pfm reference() {
        Pfm image = render_scene(scene());
        EXPECT_GT(*std::max_element(image.rgb.begin(), image.rgb.end()), 0.05f) << "the reference image is black";
        return image;
    }

    // Exit 0, an image, and a "sombra: warning: WHERE: ..." line containing `fragment`.
    static void expect_warning(const RunResult& r, const std::string& where, const std::string& fragment) {
        EXPECT_EQ(r.status, 0) << r.err;
        EXPECT_EQ(r.err.find("sombra: error"), std::string::npos) << r.err;
        const std::size_t at = r.err.find("sombra: warning: " + where + ": ");
        ASSERT_NE(at, std::string::npos) << "expected a warning at " << where << " in: " << r.err;
        EXPECT_NE(r.err.substr(at, r.err.find('\n', at) - at).find(fragment), std::string::npos) << r.err;
    }
    // expect_input_error, and the line names `where` first.
    void expect_error_at(const RunResult& r, const std::string& where, const std::string& what,
                         const fs::path& output = "out.png") {
        expect_input_error(r, what, output);
        EXPECT_EQ(r.err.rfind("sombra: error: " + where + ": ", 0), 0u) << "expected WHERE " << where << ": " << r.err;
    }
    // How many times `part` occurs in `text`.
    static std::size_t count(const std::string& text, const std::string& part) {
        std::size_t n = 0;
        for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
        return n;
    }
};

}  // namespace sombra::cli_test
