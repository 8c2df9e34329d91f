#include "scene/mesh_edges.h"

#include <algorithm>
#include <bit>
#include <unordered_map>
#include <utility>
#include <vector>

namespace sombra {

namespace {

// A position's bits, for welding equal positions (−0 and +0 are the same point).
struct PositionKey {
    std::uint32_t x, y, z;
    bool operator==(const PositionKey&) const = default;
};
PositionKey key_of(Vec3 p) {
    return {std::bit_cast<std::uint32_t>(p.x + 0.0f), std::bit_cast<std::uint32_t>(p.y + 0.0f),
            std::bit_cast<std::uint32_t>(p.z + 0.0f)};
}
struct PositionHash {
    std::size_t operator()(const PositionKey& k) const {
        std::uint64_t h = k.x * 0x9e3779b97f4a7c15ull;
        h ^= (h >> 29) + k.y * 0xbf58476d1ce4e5b9ull;
        h ^= (h >> 31) + k.z * 0x94d049bb133111ebull;
        return static_cast<std::size_t>(h ^ (h >> 32));
    }
};

}  // namespace

std::size_t open_edge_count(const TriangleMesh& mesh, std::uint32_t first, std::uint32_t count) {
    std::unordered_map<PositionKey, std::uint32_t, PositionHash> welded;
    std::unordered_map<std::uint64_t, std::uint32_t> edge_uses;
    welded.reserve(count);
    edge_uses.reserve(std::size_t{count} * 3 / 2);
    auto vertex = [&](std::uint32_t index) {
        return welded.try_emplace(key_of(mesh.positions[index]), static_cast<std::uint32_t>(welded.size()))
            .first->second;
    };
    for (std::uint32_t t = first; t < first + count; ++t) {
        const Index3& corners = mesh.triangles[t];
        const std::uint32_t v[3] = {vertex(corners[0]), vertex(corners[1]), vertex(corners[2])};
        if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) continue;
        for (int k = 0; k < 3; ++k) {
            const auto [a, b] = std::minmax(v[k], v[(k + 1) % 3]);
            ++edge_uses[std::uint64_t{a} << 32 | b];
        }
    }
    return static_cast<std::size_t>(
        std::count_if(edge_uses.begin(), edge_uses.end(), [](const auto& e) { return e.second == 1; }));
}

}  // namespace sombra
