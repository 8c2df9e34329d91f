#include "scene_bench.h"

#include <filesystem>
#include <iostream>

#include "bench_util.h"
#include "core/error.h"
#include "io/scene_json/scene_file.h"
#include "measure.h"

namespace sombra::bench {

namespace {

RenderSettings resolve(const RenderSettings& scene, const SceneBenchOptions& o, const std::string& name) {
    RenderSettings s = scene;
    if (o.width) s.width = *o.width;
    if (o.height) s.height = *o.height;
    if (const std::string problem = render_settings_problem(s); !problem.empty()) throw Error(name, problem);
    return s;
}

std::string bytes_per_triangle(std::size_t bytes, std::uint64_t triangles) {
    return triangles > 0 ? fixed(double(bytes) / double(triangles), 1) : "–";
}

}  // namespace

void run_scene_bench(const std::vector<std::string>& scene_files, const SceneBenchOptions& o, std::ostream& out) {
    Table table;
    table.header = {"scene",    "triangles", "image",     "accel",       "build s",
                    "render s", "Mrays/s",   "bytes/tri", "pixels equal"};
    table.right = {false, true, true, false, true, true, true, true, true};
    for (const std::string& file : scene_files) {
        const std::string name = std::filesystem::path(file).stem().string();
        std::cerr << "sombra-bench: " << name << ": loading\n";
        Diagnostics diag;
        const LoadedScene loaded = load_scene_file(file, diag);
        const Scene& scene = loaded.scene;
        const RenderSettings settings = resolve(loaded.settings, o, file);
        std::cerr << "sombra-bench: " << name << ": checking the images agree, then " << o.reps
                  << " rounds of build + render\n";
        const SceneMeasurement m = measure_scene(scene, settings, o.reps, file, o.embree);

        std::string image = std::to_string(settings.width);
        image.append("×").append(std::to_string(settings.height));
        if (settings.spp > 1) image.append(" ").append(std::to_string(settings.spp)).append(" spp");
        for (std::size_t k = 0; k < m.backends.size(); ++k) {
            const BackendTiming& b = m.backends[k];
            const bool first = k == 0;
            table.rows.push_back({first ? name : "", first ? thousands(m.triangles) : "", first ? image : "",
                                  accel_label(b.kind, o.embree), seconds(b.build_seconds), seconds(b.render_seconds),
                                  fixed(b.mrays_per_second(), 1), bytes_per_triangle(b.accel_bytes, m.triangles),
                                  first ? "" : fixed(100.0 * m.agreement.fraction(), 3) + " %"});
        }
        if (m.backends.size() == 2) {
            const BackendTiming& a = m.backends[0];
            const BackendTiming& b = m.backends[1];
            table.rows.push_back({"", "", "", "**bvh/embree**", ratio(a.build_seconds, b.build_seconds),
                                  ratio(a.render_seconds, b.render_seconds),
                                  ratio(a.mrays_per_second(), b.mrays_per_second()),
                                  ratio(double(a.accel_bytes), double(b.accel_bytes)), ""});
        }
    }
    out << to_markdown(table);
}

}  // namespace sombra::bench
