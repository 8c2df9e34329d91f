#include "distributed/mpi_render.h"

#include <tbb/info.h>
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <thread>
#include <vector>

#include "core/plugin.h"
#include "distributed/mpi_plugin.h"

namespace sombra {

namespace {

// The first of `names` set in the environment, as a number; `fallback` otherwise.
int env_int(std::initializer_list<const char*> names, int fallback) {
    for (const char* name : names)
        if (const char* value = std::getenv(name)) return std::atoi(value);
    return fallback;
}

// The MPI plugin's calls, or null with the reason in *why_not.
#ifdef SOMBRA_STATIC_PLUGINS
const SombraMpiApi* load_mpi_api(std::string*) { return sombra_mpi_api(); }  // compiled in
#else
const SombraMpiApi* load_mpi_api(std::string* why_not) {
    const std::optional<PluginSymbol> entry = find_plugin_symbol("libsombra_mpi.so", kSombraMpiEntry, why_not);
    if (!entry) return nullptr;
    const SombraMpiApi* api = reinterpret_cast<SombraMpiApiEntry>(entry->address)();
    if (api == nullptr || api->abi != kSombraMpiAbi) {
        if (why_not != nullptr) *why_not = entry->path + " belongs to another version of sombra";
        return nullptr;
    }
    return api;
}
#endif

constexpr int kReadyTag = 1;   // a worker's first request: no pixels yet
constexpr int kResultTag = 2;  // a block's floats, and a request for the next
constexpr int kWorkTag = 3;    // rank 0's answer: a block number, or −1 = no more

// Block b of `region`, the image or its --crop window (kShardBlock ×
// kShardBlock, row by row, as shards count them).
PixelWindow block_window(int b, const PixelWindow& region) {
    const int per_row = (region.width + kShardBlock - 1) / kShardBlock;
    const int x = (b % per_row) * kShardBlock, y = (b / per_row) * kShardBlock;
    return {region.x0 + x, region.y0 + y, std::min(kShardBlock, region.width - x),
            std::min(kShardBlock, region.height - y)};
}

int block_count(const PixelWindow& region) {
    return ((region.width + kShardBlock - 1) / kShardBlock) * ((region.height + kShardBlock - 1) / kShardBlock);
}

// A block's images and their floats a pixel, in an order both ends know:
// RGB, then the AOVs asked.
struct BlockImage {
    std::vector<float>* values;
    std::size_t channels;
};

std::vector<BlockImage> images_of(RenderOutput& r, const AovSet& a) {
    std::vector<BlockImage> images{{&r.film.rgb, 3}};
    const auto add = [&images](bool asked, std::vector<float>& values, std::size_t channels) {
        if (asked) images.push_back({&values, channels});
    };
    add(a.albedo, r.aovs.albedo, 3);
    add(a.normal, r.aovs.normal, 3);
    add(a.depth, r.aovs.depth, 1);
    add(a.position, r.aovs.position, 3);
    add(a.spp, r.aovs.spp, 1);
    add(a.variance, r.aovs.variance, 3);
    DenoiseLayers& d = r.aovs.denoise;
    add(a.denoise, d.variance, 3);
    for (int h = 0; h < 2; ++h) {
        add(a.denoise, d.color[h], 3);
        add(a.denoise, d.albedo[h], 3);
        add(a.denoise, d.normal[h], 3);
        add(a.denoise, d.depth[h], 1);
    }
    return images;
}

std::vector<float> pack(RenderOutput& block, const AovSet& aovs) {
    std::vector<float> floats;
    for (const BlockImage& image : images_of(block, aovs))
        floats.insert(floats.end(), image.values->begin(), image.values->end());
    return floats;
}

// Copies a block's packed floats into the region's arrays, each allocated
// on first use.
void place(RenderOutput& image, const RenderJob& job, const PixelWindow& region, const PixelWindow& w,
           const std::vector<float>& floats) {
    const auto width = static_cast<std::size_t>(region.width);
    std::size_t at = 0;
    for (const BlockImage& target : images_of(image, job.aovs)) {
        const std::size_t c = target.channels;
        std::vector<float>& values = *target.values;
        if (values.empty()) values.resize(width * static_cast<std::size_t>(region.height) * c);
        for (int row = 0; row < w.height; ++row) {
            const std::size_t to = ((static_cast<std::size_t>(w.y0 - region.y0 + row)) * width +
                                    static_cast<std::size_t>(w.x0 - region.x0)) *
                                   c;
            std::memcpy(&values[to], &floats[at], static_cast<std::size_t>(w.width) * c * sizeof(float));
            at += static_cast<std::size_t>(w.width) * c;
        }
    }
    if (job.aovs.denoise) {
        image.aovs.denoise.width = region.width;
        image.aovs.denoise.height = region.height;
    }
}

RenderOutput render_block(RenderJob& job, const PixelWindow& region, int b, RenderProgress& progress) {
    job.window = block_window(b, region);
    return render_image(job, progress);
}

// Test hook: SOMBRA_TEST_KILL_RANK=R makes rank R die by SIGKILL after its
// first block, as a crashed node would (app/mpi_render_test.cpp, through the command line).
void maybe_die_for_test(int rank) {
    const char* victim = std::getenv("SOMBRA_TEST_KILL_RANK");
    if (victim && std::atoi(victim) == rank) std::raise(SIGKILL);
}

RayCounters reduce_counters(const SombraMpiApi& mpi, const RayCounters& mine) {
    std::array<std::uint64_t, 4> local{mine.camera_rays, mine.shadow_rays, mine.bounce_rays, mine.nonfinite_samples};
    std::array<std::uint64_t, 4> total{};
    mpi.sum_on_rank0(local.data(), total.data(), 4);
    return {total[0], total[1], total[2], total[3]};
}

}  // namespace

LaunchedRanks launched_ranks() {
    return {env_int({"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"}, 0),
            env_int({"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}, 1)};
}

bool mpi_available(std::string* why_not) { return load_mpi_api(why_not) != nullptr; }

int MpiRun::threads_per_rank(int asked) const {
    if (asked > 0 || !active()) return asked;
    const int local = std::max(1, env_int({"OMPI_COMM_WORLD_LOCAL_SIZE", "MPI_LOCALNRANKS"}, 1));
    return std::max(1, tbb::info::default_concurrency() / local);
}

MpiRun::MpiRun() {
    if (launched_ranks().size <= 1) return;
    mpi_ = load_mpi_api(nullptr);  // run_render checked it is there (mpi_available)
    if (mpi_ == nullptr) return;
    // Only this (the main) thread calls MPI; rank 0's render thread does not.
    mpi_->init(&rank_, &size_);
}

MpiRun::~MpiRun() {
    if (active()) mpi_->finalize();
}

void MpiRun::abort(int status) const {
    if (active()) mpi_->abort(status);
    std::_Exit(status);
}

RayCounters MpiRun::sum(const RayCounters& mine) const {
    if (!active()) return mine;
    const RayCounters total = reduce_counters(*mpi_, mine);
    return rank_ == 0 ? total : mine;
}

RenderOutput MpiRun::render(RenderJob job, RenderProgress& progress) const {
    if (!active()) return render_image(job, progress);
    // The pixels rendered: the --crop window, or the whole image.
    const PixelWindow region = job.window.value_or(PixelWindow{0, 0, job.settings.width, job.settings.height});
    const int blocks = block_count(region);
    RenderOutput out;
    if (rank_ != 0) {
        // A worker: ask, render, send back (which asks again), until told −1.
        mpi_->send_floats(nullptr, 0, 0, kReadyTag);
        for (bool first = true;; first = false) {
            const int b = mpi_->receive_int(0, kWorkTag);
            if (b < 0) break;
            RenderOutput block = render_block(job, region, b, progress);
            if (block.cancelled) {
                out.cancelled = true;
                return out;
            }
            out.counters += block.counters;
            if (first) maybe_die_for_test(rank_);
            const std::vector<float> floats = pack(block, job.aovs);
            mpi_->send_floats(floats.data(), static_cast<int>(floats.size()), 0, kResultTag);
        }
        out.counters = sum(out.counters);
        return out;
    }

    // Rank 0: a thread renders blocks from the same counter the workers'
    // requests draw from, while this one answers them (MPI_THREAD_FUNNELED).
    out.film = Film(region.width, region.height);
    std::atomic<int> next{0};
    std::mutex placing;
    RayCounters local;
    std::thread renderer([&, job]() mutable {
        for (int b = next.fetch_add(1); b < blocks; b = next.fetch_add(1)) {
            RenderOutput block = render_block(job, region, b, progress);
            if (block.cancelled) return;
            local += block.counters;
            const std::vector<float> floats = pack(block, job.aovs);
            const std::lock_guard<std::mutex> lock(placing);
            place(out, job, region, *job.window, floats);
        }
    });
    std::vector<int> assigned(static_cast<std::size_t>(size_), -1);
    std::vector<float> floats;
    const std::uint64_t block_samples_per_pixel = static_cast<std::uint64_t>(job.settings.spp);
    for (int stopped = 0; stopped < size_ - 1 && !progress.cancel.load();) {
        int source = 0, tag = 0, count = 0;
        if (!mpi_->probe(&source, &tag, &count)) {
            // Polling with a nap, not a blocking receive: Open MPI's spins a core.
            std::this_thread::sleep_for(std::chrono::microseconds(200));
            continue;
        }
        floats.resize(static_cast<std::size_t>(count));
        mpi_->receive_floats(floats.data(), count, source, tag);
        if (tag == kResultTag) {
            const PixelWindow w = block_window(assigned[static_cast<std::size_t>(source)], region);
            {
                const std::lock_guard<std::mutex> lock(placing);
                place(out, job, region, w, floats);
            }
            progress.samples_done.fetch_add(static_cast<std::uint64_t>(w.width) * static_cast<std::uint64_t>(w.height) *
                                            block_samples_per_pixel);
        }
        int b = next.fetch_add(1);
        if (b >= blocks) {
            b = -1;
            ++stopped;
        }
        assigned[static_cast<std::size_t>(source)] = b;
        mpi_->send_int(b, source, kWorkTag);
    }
    renderer.join();
    out.cancelled = progress.cancel.load();
    if (out.cancelled) return out;
    out.counters = sum(local);
    // Every pixel took the spp (no time budget or threshold here).
    out.pixels = static_cast<std::uint64_t>(region.width) * static_cast<std::uint64_t>(region.height);
    out.samples = out.pixels * block_samples_per_pixel;
    out.min_pixel_spp = out.max_pixel_spp = static_cast<std::uint32_t>(job.settings.spp);
    out.passes = 1;
    return out;
}

}  // namespace sombra
