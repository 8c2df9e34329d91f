#include "tree_bench.h"

#include <filesystem>
#include <iostream>

#include "accel/bvh_binary.h"
#include "bench_util.h"
#include "io/scene_json/scene_file.h"

namespace sombra::bench {

namespace {

float half_area(Vec3 lo, Vec3 hi) {
    const Vec3 e = hi - lo;
    return e.x * e.y + e.y * e.z + e.z * e.x;
}

struct TreeShape {
    std::size_t references = 0;
    double sah = 0;
};

// The wide tree's SAH cost with the builder's own weights (a node visit
// and a block test cost 1 each): the expected node visits and block tests
// of a ray through the root's box, under the usual uniform-rays model, so
// the sum over nodes of area ÷ the root's area, and over leaves of that
// times their blocks.
TreeShape tree_shape(const Bvh& bvh) {
    TreeShape shape;
    if (bvh.nodes.empty()) return shape;
    constexpr int W = kBvhWidth;
    Vec3 root_lo{INFINITY}, root_hi{-INFINITY};
    const BvhWideNode& root = bvh.nodes[0];
    for (int i = 0; i < W; ++i) {
        if (!(root.bounds[i] <= root.bounds[W + i])) continue;
        root_lo = min(root_lo, Vec3{root.bounds[i], root.bounds[2 * W + i], root.bounds[4 * W + i]});
        root_hi = max(root_hi, Vec3{root.bounds[W + i], root.bounds[3 * W + i], root.bounds[5 * W + i]});
    }
    const double root_area = half_area(root_lo, root_hi);
    shape.sah = 1.0;  // the root node itself
    for (const BvhWideNode& node : bvh.nodes) {
        for (int i = 0; i < W; ++i) {
            if (!(node.bounds[i] <= node.bounds[W + i])) continue;
            const double area = half_area({node.bounds[i], node.bounds[2 * W + i], node.bounds[4 * W + i]},
                                          {node.bounds[W + i], node.bounds[3 * W + i], node.bounds[5 * W + i]}) /
                                root_area;
            shape.sah += area * (node.count[i] > 0 ? double((node.count[i] + 3) / 4) : 1.0);
            shape.references += node.count[i];
        }
    }
    return shape;
}

// The same cost for the binary tree before the collapse (bvh_binary.h).
double binary_sah(const BinaryBvh& binary) {
    if (binary.nodes.empty()) return 0;
    const double root_area = half_area(binary.nodes[0].bmin, binary.nodes[0].bmax);
    double sah = 0;
    std::vector<std::uint32_t> stack{0};
    while (!stack.empty()) {
        const BvhNode& n = binary.nodes[stack.back()];
        stack.pop_back();
        const double area = half_area(n.bmin, n.bmax) / root_area;
        if (n.count > 0) {
            sah += area * double((n.count + 3) / 4);
        } else {
            sah += area;
            stack.push_back(n.left_or_first);
            stack.push_back(n.left_or_first + 1);
        }
    }
    return sah;
}

}  // namespace

void run_tree_bench(const std::vector<std::string>& scene_files, int reps, std::ostream& out) {
    Table table;
    table.header = {"scene",  "triangles", "build s",  "references",     "nodes",
                    "blocks", "MB",        "SAH cost", "binary SAH cost"};
    table.right = {false, true, true, true, true, true, true, true, true};
    for (const std::string& file : scene_files) {
        const std::string name = std::filesystem::path(file).stem().string();
        std::cerr << "sombra-bench: " << name << ": loading, then " << reps << " builds\n";
        Diagnostics diag;
        const Scene scene = load_scene_file(file, diag).scene;
        std::vector<double> build_seconds;
        for (int rep = 0; rep < reps; ++rep) {
            const auto start = Clock::now();
            const Bvh bvh = make_bvh(scene.geometry);
            build_seconds.push_back(seconds_since(start));
        }
        const Bvh bvh = make_bvh(scene.geometry);
        const TreeShape shape = tree_shape(bvh);
        table.rows.push_back({name, thousands(scene.geometry.triangle_count()), seconds(median(build_seconds)),
                              thousands(shape.references), thousands(bvh.nodes.size()), thousands(bvh.blocks.size()),
                              fixed(double(bvh_memory_bytes(bvh)) / 1e6, 2), fixed(shape.sah, 2),
                              fixed(binary_sah(make_binary_bvh(scene.geometry)), 2)});
    }
    out << to_markdown(table);
}

}  // namespace sombra::bench
