// Hostile inputs through the real executable, one test per row of the table
// in docs/robustness.md: each ends in one "sombra: error:" line and exit 1,
// or in warnings and a correct image, within seconds and bounded memory.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <random>
#include <vector>

#include "cli_test_fixture.h"

namespace {

using namespace sombra::cli_test;

// Runs that must not allocate anything large: error paths read headers and counts, not claims.
constexpr long kSmallMemoryKib = 1L << 20;

// The square's four corners, for OBJ files that add to it.
const std::string kSquareVertices = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n";

class Hostile : public CliFixture {
protected:
    // The fixture's scene with `mesh` in place of the square.
    std::string mesh_scene(const std::string& mesh) {
        return scene(R"({"width": 32, "height": 24})", R"({"origin": [0, 0, 4], "look_at": [0, 0, 0], "fov": 40})", "",
                     mesh);
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
};

TEST_F(Hostile, PlyHeaderClaimingBillionsOfElements) {
    const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
    write_text(dir_ / "a.ply",
               "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\n" + xyz + "end_header\nabc");
    expect_error_at(run("render a.ply -o out.png", kSmallMemoryKib), "a.ply",
                    "element 'vertex' claims 4000000000 entries of at least 12 bytes, but only 3 bytes are left");
    write_text(dir_ / "b.ply", "ply\nformat ascii 1.0\nelement vertex 3000000000\n" + xyz + "end_header\n0 0 0\n");
    expect_error_at(run("render b.ply -o out.png", kSmallMemoryKib), "b.ply:8",
                    "element 'vertex' claims 3000000000 entries");
    // Once aborted the process: the face count reached vector::reserve before any check.
    write_text(dir_ / "c.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\n" + xyz +
                                   "element face 18446744073709551615\nproperty list uchar int vertex_indices\n"
                                   "end_header\n" +
                                   std::string(36, '\0'));
    expect_error_at(run("render c.ply -o out.png", kSmallMemoryKib), "c.ply",
                    "element 'face' claims 18446744073709551615 entries");
    write_text(dir_ / "d.ply",
               "ply\nformat ascii 1.0\nelement vertex 99999999999999999999999\n" + xyz + "end_header\n");
    expect_error_at(run("render d.ply -o out.png"), "d.ply:3", "is not a non-negative integer");
}

TEST_F(Hostile, ObjFaceIndexZero) {
    write_text(dir_ / "z.obj", kSquareVertices + "f 1 2 3\nf 0 1 2\n");
    expect_error_at(run("render z.obj -o out.png"), "z.obj:6", "face index 0 is not allowed (OBJ indices start at 1)");
    write_text(dir_ / "n.obj", kSquareVertices + "vn 0 0 1\nf 1//1 2//0 3//1\n");
    expect_error_at(run("render n.obj -o out.png"), "n.obj:6", "normal index 0 is not allowed");
}

TEST_F(Hostile, ObjFaceIndexOutOfRange) {
    write_text(dir_ / "a.obj", kSquareVertices + "f 1 2 5\n");
    expect_error_at(run("render a.obj -o out.png"), "a.obj:5", "face index 5 out of range (the file has 4 vertices)");
    // tinyobjloader's atoi wraps these to 2 and -1, both valid: read as given they are far out of range.
    write_text(dir_ / "b.obj", kSquareVertices + "f 1 4294967298 3\n");
    expect_error_at(run("render b.obj -o out.png"), "b.obj:5",
                    "face index 4294967298 out of range (the file has 4 vertices)");
    write_text(dir_ / "c.obj", kSquareVertices + "f 1 2 99999999999999999999\n");
    expect_error_at(run("render c.obj -o out.png"), "c.obj:5", "face index 99999999999999999999 out of range");
    write_text(dir_ / "d.obj", kSquareVertices + "f 1 2 " + std::string(100000, '7') + "\n");
    const RunResult r = run("render d.obj -o out.png");
    expect_error_at(r, "d.obj:5", "face index 777777777777777777777777... out of range");
    EXPECT_LT(r.err.size(), 200u) << "the message quotes the whole number";
}

TEST_F(Hostile, ObjNegativeFaceIndexPastTheStart) {
    write_text(dir_ / "a.obj", kSquareVertices + "f -1 -2 -5\n");
    expect_error_at(run("render a.obj -o out.png"), "a.obj:5",
                    "face index -5 out of range (counting back from the 4 vertices before it)");
    // Relative to the vertices read so far, not to the file's total.
    write_text(dir_ / "b.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n");
    expect_error_at(run("render b.obj -o out.png"), "b.obj:3",
                    "face index -3 out of range (counting back from the 2 vertices before it)");
    write_text(dir_ / "c.obj", kSquareVertices + "f -4 -3 -2 -1\n");  // the square, relatively
    EXPECT_EQ(run("render c.obj -o out.png --quiet").status, 0);
}

TEST_F(Hostile, NanOrInfCoordinates) {
    const Pfm square = reference();
    write_text(dir_ / "bad.obj", kSquareVertices +
                                     "v nan 0 0\nv 0 inf 0\nv 1e39 0 0\nv 0 0 -1.#IND\n"
                                     "f 1 2 3 4\nf 1 2 5\nf 2 3 6\nf 3 4 7\nf 1 3 8\n");
    RunResult r;
    const Pfm image = render_scene(mesh_scene("bad.obj"), &r);
    expect_warning(r, "bad.obj", "dropped 4 triangles touching 4 vertices with non-finite (nan/inf) coordinates");
    EXPECT_EQ(image.rgb, square.rgb);

    // The same in a binary PLY: a NaN float.
    std::string ply =
        "ply\nformat binary_little_endian 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
        "property float z\nelement face 3\nproperty list uchar int vertex_indices\nend_header\n";
    const float vertices[15] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0, std::nanf(""), 0, 0};
    ply.append(reinterpret_cast<const char*>(vertices), sizeof vertices);
    for (const std::vector<int>& face : std::vector<std::vector<int>>{{0, 1, 2}, {0, 2, 3}, {0, 1, 4}}) {
        ply += char(3);
        ply.append(reinterpret_cast<const char*>(face.data()), 12);
    }
    write_text(dir_ / "bad.ply", ply);
    EXPECT_EQ(render_scene(mesh_scene("bad.ply"), &r).rgb, square.rgb);
    expect_warning(r, "bad.ply", "dropped 1 triangle touching 1 vertex with non-finite");

    write_text(dir_ / "all.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    expect_error_at(run("render all.obj -o out.png"), "all.obj",
                    "no triangles left: every triangle touches a non-finite vertex");
    // JSON has no NaN; an overflowing number is a syntax error at its position.
    write_text(dir_ / "s.json", scene(R"({"width": 32, "height": 1e999})"));
    expect_error_at(run("render s.json -o out.png"), "s.json:1:36", "number overflow parsing '1e999'");
}

TEST_F(Hostile, DegenerateAndZeroAreaTriangles) {
    const Pfm square = reference();
    // Repeated corners, three collinear corners on the square's diagonal, and all corners on one point.
    write_text(dir_ / "degenerate.obj", kSquareVertices + "v 0 0 0\nf 1 2 3 4\nf 1 1 2\nf 3 3 3\nf 1 5 3\nf 5 5 5\n");
    for (const char* accel : {"bvh", "brute"}) {
        RunResult r;
        const Pfm image =
            render_scene(mesh_scene("degenerate.obj"), &r, std::string("--stats-json stats.json --accel ") + accel);
        EXPECT_EQ(image.rgb, square.rgb) << accel;
        const auto stats = nlohmann::json::parse(read_text(dir_ / "stats.json"));
        EXPECT_EQ(stats["triangles"], 6) << accel;  // counted, never hit
        EXPECT_EQ(stats["nonfinite_samples"], 0) << accel;
    }
}

TEST_F(Hostile, MeshWithNoFaces) {
    write_text(dir_ / "points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n");
    expect_error_at(run("render points.obj -o out.png"), "points.obj",
                    "no triangles (3 vertices, no face with 3 or more corners)");
    write_text(dir_ / "empty.obj", "");
    expect_error_at(run("render empty.obj -o out.png"), "empty.obj", "no triangles (0 vertices");
    write_text(dir_ / "nofaces.ply",
               "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
               "property float z\nelement face 0\nproperty list uchar int vertex_indices\n"
               "end_header\n0 0 0\n1 0 0\n0 1 0\n");
    expect_error_at(run("render nofaces.ply -o out.png"), "nofaces.ply", "no triangles (3 vertices");
    write_text(dir_ / "s.json", mesh_scene("points.obj"));
    expect_error_at(run("render s.json -o out.png"), "points.obj", "no triangles");
}

TEST_F(Hostile, ImageSizeZeroOrNegative) {
    for (const char* render : {R"({"width": 0, "height": 24})", R"({"width": -5, "height": 24})"}) {
        write_text(dir_ / "s.json", scene(render));
        expect_error_at(run("render s.json -o out.png"), "s.json: /render/width", "must be between 1 and 32768");
    }
    write_text(dir_ / "s.json", scene(R"({"width": 32, "height": -1})"));
    expect_error_at(run("render s.json -o out.png"), "s.json: /render/height", "must be between 1 and 32768");
    write_text(dir_ / "s.json", scene());
    expect_error_at(run("render s.json -o out.png --width 0"), "--width", "width must be between 1 and 32768");
    expect_error_at(run("render s.json -o out.png --width -4"), "--width", "width must be between 1 and 32768");
    expect_error_at(run("render s.json -o out.png --height=-4"), "--height", "height must be between 1 and 32768");
}

TEST_F(Hostile, ImageBeyondTheSizeLimits) {
    write_text(dir_ / "s.json", scene(R"({"width": 32769, "height": 1})"));
    expect_error_at(run("render s.json -o out.png"), "s.json: /render/width", "must be between 1 and 32768");
    write_text(dir_ / "s.json", scene(R"({"width": 32768, "height": 16385})"));
    expect_error_at(run("render s.json -o out.png"), "s.json: /render",
                    "image of 32768x16385 pixels exceeds the limit of 268435456 pixels");
    write_text(dir_ / "s.json", scene());
    expect_error_at(run("render s.json -o out.png --width 40000"), "--width", "width must be between 1 and 32768");
    expect_error_at(run("render s.json -o out.png --width 32768 --height 32768"), "--height",
                    "exceeds the limit of 268435456 pixels");
    // Too large even to hold: a command-line error (exit 2), like any number the parser cannot store.
    const RunResult r = run("render s.json -o out.png --width 99999999999");
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(r.err.rfind("sombra: error: command line: ", 0), 0u) << r.err;
    // The longest side the limits allow renders.
    write_text(dir_ / "s.json", scene(R"({"width": 32768, "height": 2})"));
    ASSERT_EQ(run("render s.json -o out.pfm --quiet --threads 2").status, 0);
    EXPECT_EQ(read_pfm(dir_ / "out.pfm").width, 32768);
}

TEST_F(Hostile, FilmTooLargeForTheMemory) {
    if (kSanitized) GTEST_SKIP() << "sanitizers reserve more address space than the limit this test sets";
    // 2^28 pixels: within the limits, but its 3 GiB of film do not fit in 1 GiB.
    write_text(dir_ / "s.json", scene(R"({"width": 16384, "height": 16384})"));
    expect_error_at(run("render s.json -o out.png --threads 2", kSmallMemoryKib), "s.json", "out of memory");
}

TEST_F(Hostile, SppZeroNegativeOrBeyondTheLimit) {
    for (const char* spp : {"0", "-3", "65537"}) {
        write_text(dir_ / "s.json", scene(std::string(R"({"width": 32, "height": 24, "spp": )") + spp + "}"));
        expect_error_at(run("render s.json -o out.png"), "s.json: /render/spp", "must be between 1 and 65536");
        write_text(dir_ / "s.json", scene());
        expect_error_at(run(std::string("render s.json -o out.png --spp=") + spp), "--spp",
                        "spp must be between 1 and 65536");
    }
    // The limit itself is allowed.
    EXPECT_EQ(run("render s.json -o out.png --quiet --width 1 --height 1 --spp 65536").status, 0);
}

TEST_F(Hostile, MeshPathIsAFolderMissingOrTheScene) {
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

TEST_F(Hostile, BinaryGarbage) {
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

TEST_F(Hostile, SingleLineOfHundredsOfMegabytes) {
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

TEST_F(Hostile, NonUtf8AndSpacedFileNames) {
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

TEST_F(Hostile, OutputIntoAMissingFolder) {
    // Found before rendering: this scene would take minutes.
    write_text(dir_ / "s.json", scene(R"({"width": 4096, "height": 4096, "spp": 65536})"));
    RunResult r = run("render s.json -o missing/out.png");
    expect_error_at(r, "missing/out.png", "folder 'missing' does not exist", "missing/out.png");
    EXPECT_LT(r.seconds, 5.0);
    r = run("render s.json -o out.png --stats-json missing/stats.json");
    expect_error_at(r, "missing/stats.json", "folder 'missing' does not exist");
    EXPECT_LT(r.seconds, 5.0);
}

TEST_F(Hostile, MissingMtlFile) {
    write_text(dir_ / "plain.obj", kSquareVertices + "f 1 2 3 4\n");
    write_text(dir_ / "mtl.obj", "mtllib nothere.mtl\n" + kSquareVertices + "usemtl red\nf 1 2 3 4\n");
    const std::string camera = R"({"origin": [0, 0, 4], "look_at": [0, 0, 0], "fov": 40})";
    // No "material" override: the faces take the OBJ's own, here the default.
    auto without_override = [&](const std::string& mesh) {
        std::string text = scene(R"({"width": 32, "height": 24})", camera, "", mesh);
        text.erase(text.find(R"(, "material": "grey")"), std::strlen(R"(, "material": "grey")"));
        return text;
    };
    const Pfm plain = render_scene(without_override("plain.obj"));
    RunResult r;
    const Pfm image = render_scene(without_override("mtl.obj"), &r);
    expect_warning(r, "mtl.obj", "material file 'nothere.mtl' not found beside the OBJ");
    EXPECT_EQ(image.rgb, plain.rgb);
    EXPECT_GT(*std::max_element(image.rgb.begin(), image.rgb.end()), 0.05f);
}

}  // namespace
