// Which AOVs (arbitrary output variables, spec §18, §25) a render gathers
// beside the image, as `--aov albedo,normal,depth,position,spp,variance,noisy,denoise`
// names them.
#pragma once

#include <algorithm>
#include <iterator>
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
    bool noisy = false;     // the image before denoising (with --denoise only; the film, not gathered)
    bool denoise = false;   // every layer the denoiser reads (denoise/denoise_layers.h)

    bool any() const { return albedo || normal || depth || position || spp || variance || denoise; }
    // Whether the samples must report their first hit.
    bool needs_first_hit() const { return albedo || normal || depth || position || denoise; }
};

// Each AOV's name as `--aov` and the EXR layers spell it, in the order
// spec §18 and §25 list them: the one place a new AOV is named.
struct AovName {
    bool AovSet::*member;
    const char* name;
};
inline constexpr AovName kAovNames[] = {{&AovSet::albedo, "albedo"}, {&AovSet::normal, "normal"},
                                        {&AovSet::depth, "depth"},   {&AovSet::position, "position"},
                                        {&AovSet::spp, "spp"},       {&AovSet::variance, "variance"},
                                        {&AovSet::noisy, "noisy"},   {&AovSet::denoise, "denoise"}};

// The set a comma-separated list names ("albedo,depth"); a name given twice
// counts once. On an unknown or empty name: nullopt, with that name in `bad`.
inline std::optional<AovSet> parse_aov_list(std::string_view list, std::string& bad) {
    AovSet set;
    for (;;) {
        const std::size_t comma = list.find(',');
        const std::string_view name = list.substr(0, comma);
        const auto named = std::find_if(std::begin(kAovNames), std::end(kAovNames),
                                        [name](const AovName& aov) { return name == aov.name; });
        if (named == std::end(kAovNames)) {
            bad = std::string(name);
            return std::nullopt;
        }
        set.*named->member = true;
        if (comma == std::string_view::npos) return set;
        list.remove_prefix(comma + 1);
    }
}

// The names of the AOVs in `set`, comma-separated in kAovNames' order ("albedo,depth").
inline std::string aov_list(const AovSet& set) {
    std::string list;
    for (const AovName& aov : kAovNames)
        if (set.*aov.member) list += std::string(list.empty() ? "" : ",") + aov.name;
    return list;
}

}  // namespace sombra
