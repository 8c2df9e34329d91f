// Hostile files and paths through the real executable, one test per row of
// docs/robustness.md's "Hostile inputs" table: a mesh path that is a folder,
// missing or the scene, binary garbage, a line of hundreds of megabytes,
// names that are not UTF-8, an output into a missing folder.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <random>

#include "hostile_test_fixture.h"

namespace {

using namespace sombra::cli_test;

class HostileFiles : public HostileFixture {};

TEST_F(HostileFiles, MeshPathIsAFolderMissingOrTheScene) {
    fs::create_directories(dir_ / "folder.obj");
    const std::pair<const char*, const char*> cases[] = {
        {"folder.obj", "'folder.obj' is a folder, not a mesh file"},
        {"missing.obj", "cannot open 'missing.obj': no such file"},
        {"s.json", "'s.json' is the scene file itself, not a mesh"},
        {"./s.json", "'./s.json' is the scene file itself, not a mesh"},
        {"square.obj\\u0000.json", "the file name contains a NUL character"},
    };
    for (const auto& [file, what] : cases) {
        write_text(dir_ / "s.json", mesh_scene(file));
        expect_error_at(run("render s.json -o out.png"), "s.json: /objects/0/file", what);
    }
}

TEST_F(HostileFiles, BinaryGarbage) {
    std::mt19937 random(7);
    std::string garbage(1 << 20, '\0');
    for (char& c : garbage) c = static_cast<char>(random());
    for (const char* name : {"g.json", "g.obj", "g.ply"}) write_text(dir_ / name, garbage);
    expect_error_at(run("render g.json -o out.png"), "g.json:1:1", "syntax error");
    // Somewhere in a megabyte of noise a line starts "f ": it is the first thing wrong.
    expect_error_at(run("render g.obj -o out.png"), "g.obj:4288", "is not made of indices");
    expect_error_at(run("render g.ply -o out.png"), "g.ply:1", "not a PLY file");
    write_text(dir_ / "s.json", mesh_scene("g.obj"));
    expect_error_at(run("render s.json -o out.png"), "g.obj:4288", "is not made of indices");
    // A valid PLY header over a garbage body.
    write_text(dir_ / "h.ply",
               "ply\nformat binary_big_endian 1.0\nelement vertex 1000\nproperty double x\n"
               "property double y\nproperty double z\nelement face 1000\n"
               "property list uchar uint vertex_indices\nend_header\n" +
                   garbage);
    expect_error_at(run("render h.ply -o out.png"), "h.ply", "out of range");
}

TEST_F(HostileFiles, SingleLineOfHundredsOfMegabytes) {
    // Smaller under sanitizers, whose byte-by-byte checks make the loaders several times slower.
    const std::size_t line = kSanitized ? (30u << 20) : (300u << 20);
    const Pfm square = reference();
    {
        std::ofstream obj(dir_ / "long.obj", std::ios::binary);
        obj << kSquareVertices << '#' << std::string(line, 'x') << "\nf 1 2 3 4\n";
    }
    RunResult r;
    const Pfm image = render_scene(mesh_scene("long.obj"), &r, "--stats-json stats.json");
    fs::remove(dir_ / "long.obj");
    EXPECT_EQ(image.rgb, square.rgb);
    if (!kSanitized) {
        EXPECT_LT(r.seconds, 10.0);
        // The text once, tinyobjloader's copy of the line and its growth: about 2.6 times the file.
        EXPECT_LT(nlohmann::json::parse(read_text(dir_ / "stats.json"))["peak_rss_bytes"].get<double>(), 4.0 * line);
    }
    {
        std::ofstream json(dir_ / "long.json", std::ios::binary);
        // Past the 64 MiB that scene files are allowed, also when `line` is the sanitizers' 30 MB.
        const std::size_t note = std::max(line, std::size_t{65} << 20);
        json << R"({"render": {"width": 8, "height": 8}, "note": ")" << std::string(note, 'x') << "\"}";
    }
    expect_error_at(run("render long.json -o out.png", kSmallMemoryKib), "long.json",
                    "scene file is larger than 64 MiB");
}

TEST_F(HostileFiles, NonUtf8AndSpacedFileNames) {
    const fs::path folder = dir_ / "f\xff lder with spaces";
    fs::create_directories(folder);
    fs::copy_file(dir_ / "square.obj", folder / "m\xffsh with spaces.obj");
    fs::copy_file(dir_ / "square.obj", folder /
                                           "m\xc3\xb6"
                                           "bius strip.obj");  // UTF-8, as a scene may name it
    write_text(folder / "sc\xffne file.json", mesh_scene("m\xc3\xb6"
                                                         "bius strip.obj"));
    const std::string scene_arg = shell_quote("f\xff lder with spaces/sc\xffne file.json");
    const std::string output_arg = shell_quote("f\xff lder with spaces/\xff out.png");
    EXPECT_EQ(run("render " + scene_arg + " -o " + output_arg + " --quiet").status, 0);
    EXPECT_TRUE(fs::is_regular_file(folder / "\xff out.png"));
    EXPECT_EQ(run("render " + shell_quote("f\xff lder with spaces/m\xffsh with spaces.obj") + " -o " +
                  shell_quote("\xff quick look.pfm") + " --quiet")
                  .status,
              0);
    EXPECT_EQ(read_pfm(dir_ / "\xff quick look.pfm").width, 640);
    expect_no_temp_files();

    // Errors quote such names as given, on one line.
    expect_error_at(run("render " + shell_quote("gh\xffst file.json") + " -o out.png"), "gh\xffst file.json",
                    "cannot open scene file: no such file");
    expect_error_at(run("render " + scene_arg + " -o " + shell_quote("no such \xff/out.png")), "no such \xff/out.png",
                    "folder 'no such \xff' does not exist", "no such \xff/out.png");
    expect_error_at(run("render " + shell_quote("new\nline.json") + " -o out.png"), "new?line.json", "no such file");
    // JSON text is UTF-8: a scene cannot name a file whose name is not.
    write_text(dir_ / "s.json", mesh_scene("f\xff lder with spaces/m\xffsh with spaces.obj"));
    expect_error_at(run("render s.json -o out.png"), "s.json:3:41", "ill-formed UTF-8 byte");
}

TEST_F(HostileFiles, OutputIntoAMissingFolder) {
    // Found before rendering: this scene would take minutes.
    write_text(dir_ / "s.json", scene(R"({"width": 4096, "height": 4096, "spp": 65536})"));
    RunResult r = run("render s.json -o missing/out.png");
    expect_error_at(r, "missing/out.png", "folder 'missing' does not exist", "missing/out.png");
    EXPECT_LT(r.seconds, 5.0);
    r = run("render s.json -o out.png --stats-json missing/stats.json");
    expect_error_at(r, "missing/stats.json", "folder 'missing' does not exist");
    EXPECT_LT(r.seconds, 5.0);
}

}  // namespace
