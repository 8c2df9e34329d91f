// The whole run of `sombra render`: scene file → loaded scene → acceleration
// structure → integrator → film → image file.
#pragma once

#include "app/cli.h"

namespace sombra {

// Runs the render described by the options. Returns the process exit status:
// 0 on success, 1 when an input is wrong (after printing one line
// "sombra: error: WHERE: WHAT" to stderr). Warnings go to stderr as
// "sombra: warning: WHERE: WHAT".
int run_render(const CliOptions& options);

// Parses the command line and runs it: what main() does.
int run_sombra(int argc, const char* const* argv);

}  // namespace sombra
