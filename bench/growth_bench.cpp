#include "growth_bench.h"

#include <filesystem>
#include <fstream>
#include <iostream>

#include "bench_util.h"
#include "core/error.h"
#include "io/quicklook.h"
#include "measure.h"

namespace sombra::bench {

namespace {

// One mesh's numbers: the table row and the CSV lines.
struct GrowthPoint {
    std::string name;
    double load_seconds = 0;
    std::uint64_t load_peak_rss = 0;  // the process's peak while loading (0: not measurable here)
    std::uint64_t peak_rss = 0;       // the process's peak so far, after the whole measurement
    SceneMeasurement m;
};

std::string megabytes(double bytes) { return fixed(bytes * 1e-6, 1); }

void write_csv(const std::string& path, const std::vector<GrowthPoint>& points, const EmbreeSettings& embree) {
    std::ofstream csv(path);
    csv << "mesh,triangles,load_seconds,accel,build_seconds,render_seconds,accel_bytes,rays,load_peak_rss_bytes,"
           "peak_rss_bytes\n";
    for (const GrowthPoint& p : points) {
        for (const BackendTiming& b : p.m.backends) {
            csv << p.name << ',' << p.m.triangles << ',' << p.load_seconds << ',' << accel_label(b.kind, embree) << ','
                << b.build_seconds << ',' << b.render_seconds << ',' << b.accel_bytes << ',' << b.rays << ','
                << p.load_peak_rss << ',' << b.peak_rss_bytes << '\n';
        }
    }
    if (!csv) throw Error(path, "could not write the CSV file");
}

}  // namespace

void run_growth_bench(const std::vector<std::string>& model_files, const GrowthOptions& o, std::ostream& out) {
    RenderSettings settings;
    settings.width = o.width;
    settings.height = o.height;
    settings.spp = 1;
    if (const std::string problem = render_settings_problem(settings); !problem.empty())
        throw Error("--width/--height", problem);

    std::vector<GrowthPoint> points;
    for (const std::string& file : model_files) {
        GrowthPoint p;
        p.name = std::filesystem::path(file).stem().string();
        std::cerr << "sombra-bench: " << p.name << ": loading\n";
        Diagnostics diag;
        const bool peak_reset = reset_peak_rss();
        const auto load_start = Clock::now();
        const Scene scene = make_quicklook_scene(file, diag).scene;
        p.load_seconds = seconds_since(load_start);
        p.load_peak_rss = peak_reset ? peak_rss_since_reset_bytes() : 0;
        std::cerr << "sombra-bench: " << p.name << ": " << thousands(scene.geometry.triangle_count())
                  << " triangles; checking the images agree, then " << o.reps << " rounds\n";
        p.m = measure_scene(scene, settings, o.reps, file, o.embree);
        p.peak_rss = peak_rss_bytes();
        points.push_back(std::move(p));
    }

    const std::vector<AccelKind> kinds = compared_accels();
    Table table;
    table.header = {"mesh", "triangles", "load s"};
    for (const char* what : {"build s", "render s", "MB", "bytes/tri"}) {
        for (const AccelKind kind : kinds) table.header.push_back(accel_label(kind, o.embree) + " " + what);
    }
    table.header.push_back("load peak MB");
    for (const AccelKind kind : kinds) table.header.push_back(accel_label(kind, o.embree) + " peak MB");
    table.header.push_back("peak RSS MB");
    table.right.assign(table.header.size(), true);
    table.right[0] = false;
    for (const GrowthPoint& p : points) {
        std::vector<std::string> row = {p.name, thousands(p.m.triangles), seconds(p.load_seconds)};
        for (const BackendTiming& b : p.m.backends) row.push_back(seconds(b.build_seconds));
        for (const BackendTiming& b : p.m.backends) row.push_back(seconds(b.render_seconds));
        for (const BackendTiming& b : p.m.backends) row.push_back(megabytes(double(b.accel_bytes)));
        for (const BackendTiming& b : p.m.backends) {
            row.push_back(p.m.triangles > 0 ? fixed(double(b.accel_bytes) / double(p.m.triangles), 1) : "–");
        }
        auto peak = [](std::uint64_t bytes) { return bytes > 0 ? megabytes(double(bytes)) : std::string("–"); };
        row.push_back(peak(p.load_peak_rss));
        for (const BackendTiming& b : p.m.backends) row.push_back(peak(b.peak_rss_bytes));
        row.push_back(megabytes(double(p.peak_rss)));
        table.rows.push_back(std::move(row));
    }
    out << to_markdown(table);
    if (!o.csv.empty()) write_csv(o.csv, points, o.embree);
}

}  // namespace sombra::bench
