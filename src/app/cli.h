// The command line of spec §1, parsed into plain options.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "api/render_options.h"
#include "image/image_io.h"

namespace sombra {

// Which subcommand runs.
enum class Command {
    Render,   // sombra render: the image
    Explain,  // sombra explain: the story of one pixel's sample (spec §14)
    View,     // sombra view: the render in a browser, refining live (spec §20)
    Merge,    // sombra merge: the shards of one render joined into its image (spec §21)
    Denoise,  // sombra denoise: an .exr written with --aov denoise, denoised (spec §25)
};

struct CliOptions {
    Command command = Command::Render;
    std::string input;  // scene .json, or a model .obj/.ply/.gltf/.glb for the quick look
    std::string output = "render.png";
    RenderOptions render;        // what is rendered and how: the library's options (api/render_options.h)
    DisplayTransform display;    // 8-bit outputs only (PNG, JPEG): --exposure, --tonemap
    std::string stats_json;      // empty = none
    std::string display_server;  // --display-server HOST:PORT (tev); empty = none
    // --shard I/N (spec §21): render share I of N of the pixels; count 1 = all.
    int shard_index = 0, shard_count = 1;
    bool sharded = false;  // --shard given (0/1 included: a shard of one, for merge)
    // Spec §22: frames first … last (render.frame is one frame), written to
    // the output name with its '#'s replaced by the frame number.
    std::optional<std::int64_t> first_frame, last_frame;
    // sombra merge PART... -o OUT [--exposure E] [--denoise]
    std::vector<std::string> parts;
    bool quiet = false;

    // sombra explain SCENE X Y [--sample K] [--json] [--svg FILE]
    int pixel_x = 0, pixel_y = 0;  // column, row (spec §3); checked against the image size after loading
    int sample = 0;                // which of the pixel's samples; checked against spp after loading
    bool json = false;             // print JSON instead of text
    std::string svg;               // empty = no picture

    // sombra view SCENE [--port P]
    int port = 0;  // 0 = a free port the system picks
};

// What parsing decided: run a render, or exit now with `exit_code` after
// `message` was printed (help, version, or a command-line error).
struct CliParse {
    std::optional<CliOptions> options;
    int exit_code = 0;
};

// The most frames one --frames range may hold.
inline constexpr std::int64_t kMaxFrameCount = 1000000;

// `output` with each run of '#' replaced by `frame`, zero-padded to the
// run's length ("out_####.png", 7 → "out_0007.png"); unchanged without '#'.
std::string frame_file_name(const std::string& output, std::int64_t frame);

// Parses argv. Prints help/version to stdout and command-line errors as one
// line "sombra: error: command line: ..." to stderr (exit code 2).
CliParse parse_command_line(int argc, const char* const* argv);

}  // namespace sombra
