// What the subcommands share around the library's calls (api/): checking a
// side file before the work, printing warnings, and turning what a run
// throws into the one error line of spec §1.
#pragma once

#include <filesystem>
#include <iostream>
#include <new>
#include <string>

#include "api/render_options.h"
#include "core/error.h"
#include "render/render_settings.h"
#include "scene/scene.h"

namespace sombra {

// Checks, before any work, that a side file (statistics, explain's SVG) can
// be written: its folder exists and the path is not a folder. Throws Error.
void check_side_file_path(const std::filesystem::path& path);

// Prints the loader's warnings and the render's (render_warnings: the
// direct integrator's limits, no emitter, adaptive sampling that cannot
// adapt) to stderr; `input` names the scene.
void print_warnings(const Diagnostics& diag, const Scene& scene, const RenderSettings& settings,
                    const RenderOptions& options, const std::string& input);

// Runs `body` (returning the exit status) and turns what it throws into the
// one line of spec §1, "sombra: error: WHERE: WHAT", and exit status 1
// (a UsageError: "command line: WHERE: WHAT", exit status 2);
// `input` names the scene when the error has no place of its own.
template <class Body>
int reporting_errors(const std::string& input, Body&& body) {
    try {
        return body();
    } catch (const UsageError& e) {
        std::cerr << "sombra: error: command line: " << one_line_message(e.where() + ": " + e.message()) << '\n';
        return 2;
    } catch (const Error& e) {
        std::cerr << "sombra: error: " << one_line_message(e.where() + ": " + e.message()) << '\n';
    } catch (const std::bad_alloc&) {
        std::cerr << "sombra: error: " << one_line_message(input) << ": out of memory\n";
    } catch (const std::exception& e) {
        // A bug, not the input's fault; still one line and no image.
        std::cerr << "sombra: error: " << one_line_message(input) << ": internal error: " << one_line_message(e.what())
                  << '\n';
    }
    return 1;
}

}  // namespace sombra
