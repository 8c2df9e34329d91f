#include "app/report.h"

#include <iostream>

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
                    const std::string& input) {
    for (const std::string& w : diag.warnings) std::cerr << "sombra: warning: " << one_line_message(w) << '\n';
    // After the overrides: --integrator path silences it, --integrator direct may cause it.
    if (settings.integrator == IntegratorKind::Direct && needs_path_integrator(scene))
        std::cerr << "sombra: warning: " << one_line_message(input)
                  << ": the direct integrator lights with point, spot and directional lights only: quad lights "
                     "and the environment are only seen, mirror and glass reflect nothing from them; use "
                     "--integrator path\n";
    if (settings.integrator == IntegratorKind::Direct && uses_media(scene))
        std::cerr << "sombra: warning: " << one_line_message(input)
                  << ": the direct integrator ignores media (spec §26); use --integrator path\n";
}

}  // namespace sombra
