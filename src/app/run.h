// The whole run of `sombra render` (scene file → loaded scene → acceleration
// structure → integrator → film → image file) and of `sombra explain`.
#pragma once

#include "app/cli.h"

namespace sombra {

// Runs the render described by the options. Returns the process exit status:
// 0 on success, 1 when an input is wrong (after printing one line
// "sombra: error: WHERE: WHAT" to stderr). Warnings go to stderr as
// "sombra: warning: WHERE: WHAT".
int run_render(const CliOptions& options);

// Runs `sombra explain` (spec §14): prints the story of one sample of one
// pixel (text, or JSON with --json) to stdout and, with --svg, draws it.
// Exit status as run_render: 1 for a wrong input or a pixel or sample
// outside the image.
int run_explain(const CliOptions& options);

// Runs `sombra view` (spec §20): loads and builds as run_render does, then
// serves the render on 127.0.0.1 and prints the URL to open, until Ctrl-C
// (SIGINT) or SIGTERM, which end it at once with status 0. Exit status 1
// for a wrong input or a port that cannot be bound.
int run_view(const CliOptions& options);

// Runs `sombra merge` (spec §21): joins o.parts into o.output. Exit status
// 0, or 1 after one error line with nothing written.
int run_merge(const CliOptions& options);

// Runs `sombra denoise` (spec §25): o.input, an .exr with the denoiser's
// layers, denoised into o.output. Exit status 0, or 1 after one error line
// (a missing layer named) with nothing written.
int run_denoise(const CliOptions& options);

// Parses the command line and runs it: what main() does.
int run_sombra(int argc, const char* const* argv);

}  // namespace sombra
