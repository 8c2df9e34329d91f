// Which AOVs (arbitrary output variables, spec §18, §25) a render gathers
// beside the image, as `--aov albedo,normal,depth,position,spp,variance` names them.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace sombra {

struct AovSet {
    bool albedo = false;
    bool normal = false;
    bool depth = false;
    bool position = false;
    bool spp = false;
    bool variance = false;  // the estimated variance of each pixel's mean, per channel (spec §25)

    bool any() const { return albedo || normal || depth || position || spp || variance; }
    // Whether the samples must report their first hit.
    bool needs_first_hit() const { return albedo || normal || depth || position; }
};

// The set a comma-separated list names ("albedo,depth"); a name given twice
// counts once. On an unknown or empty name: nullopt, with that name in `bad`.
inline std::optional<AovSet> parse_aov_list(std::string_view list, std::string& bad) {
    AovSet set;
    for (;;) {
        const std::size_t comma = list.find(',');
        const std::string_view name = list.substr(0, comma);
        if (name == "albedo")
            set.albedo = true;
        else if (name == "normal")
            set.normal = true;
        else if (name == "depth")
            set.depth = true;
        else if (name == "position")
            set.position = true;
        else if (name == "spp")
            set.spp = true;
        else if (name == "variance")
            set.variance = true;
        else {
            bad = std::string(name);
            return std::nullopt;
        }
        if (comma == std::string_view::npos) return set;
        list.remove_prefix(comma + 1);
    }
}

}  // namespace sombra
