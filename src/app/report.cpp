#include "app/report.h"

#include <iostream>

#include "api/session.h"
#include "core/error.h"

namespace sombra {

void check_side_file_path(const std::filesystem::path& path) {
    const std::filesystem::path folder = path.parent_path().empty() ? "." : path.parent_path();
    std::error_code ec;
    if (!std::filesystem::is_directory(folder, ec))
        throw Error(path.string(), "folder '" + folder.string() + "' does not exist");
    if (std::filesystem::is_directory(path, ec)) throw Error(path.string(), "is a folder");
}

void print_warnings(const Diagnostics& diag, const Scene& scene, const RenderSettings& settings,
                    const RenderOptions& options, const std::string& input) {
    for (const std::string& w : diag.warnings) std::cerr << "sombra: warning: " << one_line_message(w) << '\n';
    // After the overrides: --integrator path silences some, --integrator direct may cause them.
    for (const std::string& w : render_warnings(scene, settings, options))
        std::cerr << "sombra: warning: " << one_line_message(input) << ": " << w << '\n';
}

}  // namespace sombra
