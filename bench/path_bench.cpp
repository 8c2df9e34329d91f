#include "path_bench.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <iterator>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "bench_util.h"
#include "core/error.h"
#include "image/atomic_file.h"
#include "io/scene_json/scene_file.h"
#include "render/camera.h"
#include "render/integrator.h"
#include "render/render.h"
#include "render/sampler.h"

namespace sombra::bench {

namespace {

// bvh and embree images must have the same mean to within this many
// standard errors, in every channel.
//
// Why a statistical test and not compare_films: Embree's hits differ from
// the BVH's in the last bits of t and the barycentrics, so a bounce leaves
// from a slightly different point, and whenever a path then crosses a
// decision (Russian roulette, a light choice, a shadow-ray grazing an edge)
// differently, the rest of that path is a different random path. The two
// images are then two estimates of the same image, equal in many pixels and
// uncorrelated noise in the others. The test: per pixel d = bvh − embree.
// Pixels draw their random numbers from independent keys, so the d are
// independent, and each has mean 0 when both backends find the same
// geometry; mean(d) / (sd(d)/√N) is then about standard normal. |z| > 4
// happens by chance about once in 16 000 channels. A backend that loses or
// invents hits (a hole, a leaking edge) biases d and shows as a large z once
// its effect exceeds the noise; smaller effects than that no test on noisy
// images can see.
constexpr double kMaxZ = 4.0;

struct PairedTest {
    double z[3] = {0, 0, 0};       // mean(d)/se per channel
    double mean_a[3] = {0, 0, 0};  // image means, for the message
    double mean_b[3] = {0, 0, 0};
    double worst() const { return std::max({std::fabs(z[0]), std::fabs(z[1]), std::fabs(z[2])}); }
};

PairedTest paired_test(const Film& a, const Film& b) {
    PairedTest t;
    const std::size_t n = a.rgb.size() / 3;
    if (n == 0 || a.rgb.size() != b.rgb.size()) return t;
    for (int c = 0; c < 3; ++c) {
        double sum = 0, sum_a = 0, sum_b = 0;
        for (std::size_t p = 0; p < n; ++p) {
            sum += double(a.rgb[3 * p + c]) - double(b.rgb[3 * p + c]);
            sum_a += a.rgb[3 * p + c];
            sum_b += b.rgb[3 * p + c];
        }
        const double mean = sum / double(n);
        double var = 0;
        for (std::size_t p = 0; p < n; ++p) {
            const double d = double(a.rgb[3 * p + c]) - double(b.rgb[3 * p + c]) - mean;
            var += d * d;
        }
        var = n > 1 ? var / double(n - 1) : 0;
        const double se = std::sqrt(var / double(n));
        t.z[c] = se > 0 ? mean / se : (mean == 0 ? 0 : 1e9);
        t.mean_a[c] = sum_a / double(n);
        t.mean_b[c] = sum_b / double(n);
    }
    return t;
}

RenderSettings path_settings(const RenderSettings& file_settings, int width, int height, int spp, int max_depth,
                             const std::string& name) {
    RenderSettings s = file_settings;
    s.width = width;
    s.height = height;
    s.spp = spp;
    s.integrator = IntegratorKind::Path;
    s.max_depth = max_depth;
    if (const std::string problem = render_settings_problem(s); !problem.empty()) throw Error(name, problem);
    return s;
}

struct Timed {
    double seconds = 0;
    RenderOutput output;
};

Timed timed_render(const RenderJob& job) {
    RenderProgress progress;
    const auto start = Clock::now();
    Timed t;
    t.output = render_image(job, progress);
    t.seconds = seconds_since(start);
    return t;
}

// Whole paths, one sample each, at every stride-th pixel: through the BVH
// and through the brute-force loop, with the same random numbers. The BVH's
// hits are bit-identical to brute's, so the radiance must agree.
ImageAgreement path_bvh_against_brute(const Scene& scene, const RenderSettings& settings, const Accel& bvh,
                                      const LightSet& lights, double rays_per_path) {
    const Camera camera = make_camera(scene.camera, settings.width, settings.height);
    return bvh_against_brute(
        scene.geometry, bvh, settings.width, settings.height, rays_per_path, 16, [&](const Accel& accel, int i, int j) {
            const Ray ray = camera_ray(camera, image_plane_s(float(i) + 0.5f, settings.width),
                                       image_plane_t(float(j) + 0.5f, settings.height));
            RayCounters counters;
            SampleStream samples{pixel_key(settings.seed, i, j, settings.width), 0, 1};
            return trace_path(IntegratorContext{&scene, &accel, &lights, settings.max_depth}, ray, samples, counters);
        });
}

std::string image_text(const RenderSettings& s) { return std::to_string(s.width) + "×" + std::to_string(s.height); }

}  // namespace

void run_path_bench(const std::vector<std::string>& scene_files, const PathBenchOptions& o, std::ostream& out) {
    const std::vector<AccelKind> kinds = compared_accels();
    Table table;
    table.header = {"scene",       "triangles", "image",     "spp",          "accel", "render s",
                    "rays/sample", "Mrays/s",   "samples/s", "pixels equal", "mean z"};
    table.right = {false, true, true, true, false, true, true, true, true, true, true};
    for (const std::string& file : scene_files) {
        const std::string name = std::filesystem::path(file).stem().string();
        std::cerr << "sombra-bench: " << name << ": loading\n";
        Diagnostics diag;
        const LoadedScene loaded = load_scene_file(file, diag);
        const Scene& scene = loaded.scene;
        const RenderSettings settings = path_settings(loaded.settings, o.width, o.height, o.spp, o.max_depth, file);
        const double samples = double(settings.width) * double(settings.height) * double(settings.spp);

        std::vector<Accel> accels;
        std::vector<RenderJob> jobs;
        accels.reserve(kinds.size());
        for (const AccelKind kind : kinds) accels.push_back(make_compared_accel(scene, kind, o.embree));
        for (const Accel& accel : accels) jobs.push_back(make_render_job(scene, accel, settings));

        // The checks, which also warm caches and thread pools for the rounds.
        std::cerr << "sombra-bench: " << name << ": path tracing " << image_text(settings) << " at " << settings.spp
                  << " spp, depth " << settings.max_depth << "; checking the backends agree\n";
        std::vector<RenderOutput> first;
        for (const RenderJob& job : jobs) first.push_back(timed_render(job).output);
        std::vector<std::uint64_t> rays;
        for (const RenderOutput& r : first) rays.push_back(r.counters.rays());
        std::vector<ImageAgreement> equal(kinds.size());
        std::vector<PairedTest> tests(kinds.size());
        for (std::size_t k = 1; k < kinds.size(); ++k) {
            equal[k] = compare_films(first[0].film, first[k].film);
            tests[k] = paired_test(first[0].film, first[k].film);
            if (tests[k].worst() > kMaxZ) {
                const PairedTest& t = tests[k];
                char text[256];
                std::snprintf(text, sizeof text,
                              "%s and %s path-traced images differ in mean by z = (%.1f, %.1f, %.1f) standard errors "
                              "(means %.5g %.5g %.5g against %.5g %.5g %.5g): not timing a wrong result",
                              accel_label(kinds[0], o.embree).c_str(), accel_label(kinds[k], o.embree).c_str(), t.z[0],
                              t.z[1], t.z[2], t.mean_a[0], t.mean_a[1], t.mean_a[2], t.mean_b[0], t.mean_b[1],
                              t.mean_b[2]);
                throw Error(file, text);
            }
        }
        const ImageAgreement brute =
            path_bvh_against_brute(scene, settings, accels[0], jobs[0].lights, double(rays[0]) / samples);
        if (brute.equal != brute.pixels) {
            throw Error(file, "bvh and brute paths disagree at " + thousands(brute.pixels - brute.equal) + " of " +
                                  thousands(brute.pixels) + " sampled pixels: not timing a wrong result");
        }
        first.clear();
        std::cerr << "sombra-bench: " << name << ": agree (bvh = brute on " << brute.pixels << " sampled paths); "
                  << o.reps << " timed renders per backend\n";

        std::vector<std::vector<double>> times(kinds.size());
        for (int rep = 0; rep < o.reps; ++rep) {
            for (std::size_t i = 0; i < kinds.size(); ++i) {
                const std::size_t k = rep % 2 == 0 ? i : kinds.size() - 1 - i;
                times[k].push_back(timed_render(jobs[k]).seconds);
            }
        }
        std::vector<double> render_s(kinds.size()), mrays(kinds.size()), sps(kinds.size());
        for (std::size_t k = 0; k < kinds.size(); ++k) {
            render_s[k] = median(times[k]);
            mrays[k] = render_s[k] > 0 ? double(rays[k]) / render_s[k] * 1e-6 : 0;
            sps[k] = render_s[k] > 0 ? samples / render_s[k] : 0;
            const bool head = k == 0;
            table.rows.push_back(
                {head ? name : "", head ? thousands(scene.geometry.triangle_count()) : "",
                 head ? image_text(settings) : "", head ? std::to_string(settings.spp) : "",
                 accel_label(kinds[k], o.embree), seconds(render_s[k]), fixed(double(rays[k]) / samples, 2),
                 fixed(mrays[k], 2), thousands(std::uint64_t(std::llround(sps[k]))),
                 head ? "" : fixed(100.0 * equal[k].fraction(), 2) + " %", head ? "" : fixed(tests[k].worst(), 2)});
        }
        if (kinds.size() == 2) {
            table.rows.push_back({"", "", "", "", "**bvh/embree**", ratio(render_s[0], render_s[1]),
                                  ratio(double(rays[0]), double(rays[1])), ratio(mrays[0], mrays[1]),
                                  ratio(sps[0], sps[1]), "", ""});
        }
    }
    out << to_markdown(table);
}

namespace {

// FNV-1a, 64 bits: the reference cache's key.
struct Hasher {
    std::uint64_t h = 0xcbf29ce484222325ull;
    void bytes(const void* data, std::size_t n) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
    }
    template <class T>
    void value(const T& v) {
        bytes(&v, sizeof v);
    }
    template <class T>
    void array(const std::vector<T>& v) {
        value(v.size());
        if (!v.empty()) bytes(v.data(), v.size() * sizeof(T));
    }
};

// Everything the reference image depends on: the scene file's text (camera,
// lights, background, materials), the loaded geometry and materials (the
// OBJ/MTL/PLY files behind it), the settings, and a format version. It does
// not cover the renderer's code: after a change to the integrator that
// changes what it converges to, delete build/bench/path-reference-*.
std::uint64_t reference_key(const std::string& file, const Scene& scene, const RenderSettings& s) {
    Hasher h;
    const char version[] = "sombra path reference v1";
    h.bytes(version, sizeof version);
    std::ifstream in(file, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    h.bytes(text.data(), text.size());
    const TriangleMesh& g = scene.geometry;
    h.array(g.positions);
    h.array(g.triangles);
    h.array(g.normals);
    h.array(g.normal_indices);
    h.array(g.material_ids);
    for (const Material& m : scene.materials) {
        h.value(m.type);
        h.value(m.kd);
        h.value(m.ks);
        h.value(m.shininess);
        h.value(m.ke);
        h.value(m.kr);
        h.value(m.kt);
        h.value(m.ior);
        h.value(m.roughness);
        h.value(m.emits_front_only);
    }
    for (const PunctualLight& l : scene.lights) {
        h.value(l.type);
        h.value(l.position);
        h.value(l.direction);
        h.value(l.intensity);
        h.value(l.cos_outer);
        h.value(l.cos_inner);
    }
    h.value(scene.camera.aperture_radius);
    h.value(scene.camera.focus_distance.value_or(0.0f));
    h.value(scene.background);
    h.value(s.width);
    h.value(s.height);
    h.value(s.spp);
    h.value(s.seed);
    h.value(s.max_depth);
    h.value(s.integrator);
    return h.h;
}

constexpr char kCacheMagic[8] = {'S', 'B', 'R', 'E', 'F', '0', '0', '1'};

bool read_reference(const std::filesystem::path& path, int width, int height, Film& film) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    char magic[8];
    std::int32_t w = 0, h = 0;
    in.read(magic, 8);
    in.read(reinterpret_cast<char*>(&w), 4);
    in.read(reinterpret_cast<char*>(&h), 4);
    if (!in || !std::equal(magic, magic + 8, kCacheMagic) || w != width || h != height) return false;
    Film f(width, height);
    in.read(reinterpret_cast<char*>(f.rgb.data()), std::streamsize(f.rgb.size() * sizeof(float)));
    if (!in) return false;
    film = std::move(f);
    return true;
}

// Written whole or not at all (image/atomic_file.h), so that an interrupted
// run never leaves a truncated reference for the next one to trust.
void write_reference(const std::filesystem::path& path, const Film& film) {
    std::filesystem::create_directories(path.parent_path().empty() ? "." : path.parent_path());
    write_file_atomically(path, [&film](const std::filesystem::path& temp) {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        const std::int32_t w = film.width, h = film.height;
        out.write(kCacheMagic, 8);
        out.write(reinterpret_cast<const char*>(&w), 4);
        out.write(reinterpret_cast<const char*>(&h), 4);
        out.write(reinterpret_cast<const char*>(film.rgb.data()), std::streamsize(film.rgb.size() * sizeof(float)));
        out.close();
        if (!out) throw std::runtime_error("cannot write the reference image");
    });
}

struct ErrorFigures {
    double rmse = 0;     // sqrt of the mean over pixels and channels of (x − ref)²
    double rel_mse = 0;  // mean over pixels and channels of (x − ref)² / (ref² + 0.01)
};

ErrorFigures error_against(const Film& image, const Film& reference) {
    ErrorFigures e;
    const std::size_t n = image.rgb.size();
    if (n == 0 || n != reference.rgb.size()) return e;
    double se = 0, rel = 0;
    for (std::size_t k = 0; k < n; ++k) {
        const double r = reference.rgb[k];
        const double d = double(image.rgb[k]) - r;
        se += d * d;
        rel += d * d / (r * r + 0.01);
    }
    e.rmse = std::sqrt(se / double(n));
    e.rel_mse = rel / double(n);
    return e;
}

std::string scientific(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", v);
    return text;
}

}  // namespace

void run_path_error_bench(const std::string& file, const PathErrorOptions& o, std::ostream& out) {
    const std::string name = std::filesystem::path(file).stem().string();
    std::cerr << "sombra-bench: " << name << ": loading\n";
    Diagnostics diag;
    const LoadedScene loaded = load_scene_file(file, diag);
    const Scene& scene = loaded.scene;
    const Accel bvh = make_accel(scene, AccelKind::Bvh);
    const double pixels = double(o.width) * double(o.height);

    RenderSettings ref_settings = path_settings(loaded.settings, o.width, o.height, o.reference_spp, o.max_depth, file);
    ref_settings.seed = 1;  // independent of the measured renders' seed 0
    const std::uint64_t key = reference_key(file, scene, ref_settings);
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(key));
    const std::filesystem::path cache = o.cache_dir / ("path-reference-" + name + "-" + hex + ".bin");
    Film reference;
    if (read_reference(cache, o.width, o.height, reference)) {
        std::cerr << "sombra-bench: " << name << ": reference from " << cache.string() << '\n';
    } else {
        std::cerr << "sombra-bench: " << name << ": rendering the reference, " << o.width << "×" << o.height << " at "
                  << o.reference_spp << " spp (cached as " << cache.string() << ")\n";
        const Timed t = timed_render(make_render_job(scene, bvh, ref_settings));
        std::cerr << "sombra-bench: " << name << ": reference took " << seconds(t.seconds) << " s\n";
        reference = t.output.film;
        write_reference(cache, reference);
    }

    Table table;
    table.header = {"render", "spp reached", "render s", "samples/s", "RMSE", "relMSE", "relMSE × s"};
    table.right = {false, true, true, true, true, true, true};
    double largest_rel_mse = 0;
    int largest_spp = 0;
    // One row: a render at `spp` (the most any pixel takes) under `limits`,
    // with a deadline `budget` seconds after its start when given.
    auto measure = [&](int spp, const SamplingLimits& limits, const std::string& label,
                       std::optional<double> budget = std::nullopt) {
        const RenderSettings s = path_settings(loaded.settings, o.width, o.height, spp, o.max_depth, file);
        RenderJob job = make_render_job(scene, bvh, s);
        job.limits = limits;
        if (budget)
            job.limits.deadline =
                Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(*budget));
        const Timed t = timed_render(job);
        const ErrorFigures e = error_against(t.output.film, reference);
        const double samples = double(t.output.samples);
        const double sps = t.seconds > 0 ? samples / t.seconds : 0;
        char reached[32];
        std::snprintf(reached, sizeof reached, t.output.min_pixel_spp == t.output.max_pixel_spp ? "%.0f" : "%.1f",
                      samples / pixels);
        table.rows.push_back({label, reached, seconds(t.seconds), thousands(std::uint64_t(std::llround(sps))),
                              scientific(e.rmse), scientific(e.rel_mse), scientific(e.rel_mse * t.seconds)});
        if (label == "fixed spp" && spp >= largest_spp) {
            largest_spp = spp;
            largest_rel_mse = e.rel_mse;
        }
    };
    // Warm-up (thread pool, caches), not reported.
    timed_render(make_render_job(scene, bvh, path_settings(loaded.settings, o.width, o.height, 1, o.max_depth, file)));
    for (const int spp : o.fixed_spp) {
        std::cerr << "sombra-bench: " << name << ": " << spp << " spp\n";
        measure(spp, {}, "fixed spp");
    }
    // The equal-time render: passes until the budget (spec §18's --time,
    // counted from the render's start here).
    std::cerr << "sombra-bench: " << name << ": equal time\n";
    measure(kMaxSpp, {}, "**equal time " + seconds(o.budget_seconds) + " s**", o.budget_seconds);
    // Adaptive sampling (--noise-threshold), up to the largest fixed spp.
    const int cap = o.fixed_spp.empty() ? 256 : *std::max_element(o.fixed_spp.begin(), o.fixed_spp.end());
    for (const double threshold : o.noise_thresholds) {
        std::cerr << "sombra-bench: " << name << ": adaptive, T = " << threshold << "\n";
        SamplingLimits adaptive;
        adaptive.noise_threshold = threshold;
        measure(cap, adaptive, "adaptive T = " + scientific(threshold) + ", ≤ " + std::to_string(cap) + " spp");
    }
    // The reference is noisy too: its MSE, by the 1/spp law from the largest
    // fixed render's, is part of every measured MSE (the two are independent).
    const int largest = o.fixed_spp.empty() ? 0 : *std::max_element(o.fixed_spp.begin(), o.fixed_spp.end());
    out << "Scene " << name << ", " << o.width << "×" << o.height << ", path, max depth " << o.max_depth
        << ", bvh; reference " << o.reference_spp << " spp (seed 1), renders seed 0.\n\n";
    out << to_markdown(table);
    if (largest > 0 && largest_rel_mse > 0) {
        out << "\nThe reference's own noise, estimated as relMSE(" << largest << " spp) × " << largest << " / "
            << o.reference_spp << " = " << scientific(largest_rel_mse * largest / o.reference_spp)
            << ", is included in each relMSE above (reference and render are independent, so their MSEs add).\n";
    }
}

}  // namespace sombra::bench
