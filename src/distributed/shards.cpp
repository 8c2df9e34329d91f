#include "distributed/shards.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <fstream>
#include <map>
#include <optional>
#include <span>
#include <system_error>
#include <utility>

#include "core/error.h"
#include "denoise/denoise.h"
#include "render/render.h"

namespace sombra {

namespace {

constexpr const char* kShardAttribute = "sombra.shard";
constexpr const char* kRenderAttribute = "sombra.render";
constexpr const char* kKeptAttribute = "sombra.kept";

// FNV-1a, 64 bits, over the file's bytes: an identity, not a defence.
std::string content_hash(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path, "cannot read it to name the render its shard belongs to");
    std::uint64_t h = 14695981039346656037ull;
    char buffer[1 << 16];
    while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
        for (std::streamsize k = 0; k < in.gcount(); ++k) {
            h ^= static_cast<unsigned char>(buffer[k]);
            h *= 1099511628211ull;
        }
    }
    char hex[17];
    for (int k = 15; k >= 0; --k, h >>= 4) hex[k] = "0123456789abcdef"[h & 15u];
    hex[16] = '\0';
    return hex;
}

std::optional<ShardSpec> parse_shard(const std::string& text) {
    const auto slash = text.find('/');
    ShardSpec s{-1, 0};
    if (slash == std::string::npos ||
        std::from_chars(text.data(), text.data() + slash, s.index).ptr != text.data() + slash ||
        std::from_chars(text.data() + slash + 1, text.data() + text.size(), s.count).ptr != text.data() + text.size() ||
        s.count < 1 || s.index < 0 || s.index >= s.count)
        return std::nullopt;
    return s;
}

// The first item ("seed 3", "input 0a1b…") where two renders' descriptions differ.
std::string first_difference(const std::string& a, const std::string& b) {
    const auto items = [](const std::string& text) {
        std::vector<std::string> out;
        std::size_t start = 0;
        for (std::size_t k = 0; k <= text.size(); ++k)
            if (k == text.size() || text[k] == ',' || text[k] == ';') {
                out.push_back(text.substr(start, k - start));
                start = k + 2;  // past ", " or "; "
                k = std::min(k + 1, text.size());
            }
        return out;
    };
    const std::vector<std::string> x = items(a), y = items(b);
    for (std::size_t k = 0; k < std::min(x.size(), y.size()); ++k)
        if (x[k] != y[k]) return x[k] + " against " + y[k];
    return a + " against " + b;
}

const std::string* attribute(const ExrChannels& exr, const char* name) {
    for (const ImageAttribute& a : exr.attributes)
        if (a.name == name) return &a.value;
    return nullptr;
}

// The window "sombra.kept" names inside a width × height shard image; none
// without the attribute. Throws Error for one that is malformed or outside.
std::optional<PixelWindow> kept_window(const ExrChannels& exr, const std::string& path) {
    const std::string* text = attribute(exr, kKeptAttribute);
    if (!text) return std::nullopt;
    PixelWindow w{};
    const char* at = text->data();
    const char* end = text->data() + text->size();
    for (int* value : {&w.x0, &w.y0, &w.width, &w.height}) {
        while (at != end && *at == ' ') ++at;
        const auto [next, ec] = std::from_chars(at, end, *value);
        if (ec != std::errc()) throw Error(path, "damaged shard: unreadable sombra.kept '" + *text + "'");
        at = next;
    }
    if (at != end || w.x0 < 0 || w.y0 < 0 || w.width < 1 || w.height < 1 || w.width > exr.width - w.x0 ||
        w.height > exr.height - w.y0)
        throw Error(path, "damaged shard: sombra.kept '" + *text + "' is not a window of its " +
                              std::to_string(exr.width) + "x" + std::to_string(exr.height) + " pixels");
    return w;
}

struct Part {
    std::string path;
    ShardSpec shard;
    ExrChannels exr;
};

Part read_part(const std::string& path) {
    Part part{path, {}, read_exr_channels(path)};
    const std::string* shard = attribute(part.exr, kShardAttribute);
    const std::string* render = attribute(part.exr, kRenderAttribute);
    const std::optional<ShardSpec> spec = shard ? parse_shard(*shard) : std::nullopt;
    if (!spec || !render) throw Error(path, "not a shard written by 'sombra render --shard I/N'");
    part.shard = *spec;
    return part;
}

}  // namespace

std::vector<ImageAttribute> shard_attributes(const std::string& input, const RenderOptions& o, const RenderSettings& s,
                                             ShardSpec shard, std::optional<PixelWindow> kept) {
    const std::string render =
        std::string("sombra ") + SOMBRA_VERSION + "; input " + content_hash(input) + "; " + std::to_string(s.width) +
        "x" + std::to_string(s.height) + ", spp " + std::to_string(s.spp) + ", seed " + std::to_string(s.seed) + ", " +
        std::string(integrator_name(s.integrator)) + ", max_depth " + std::to_string(s.max_depth) +
        ", texture_filter " + std::string(texture_filter_name(s.texture_filter)) + ", accel " +
        std::string(accel_name(o.accel)) + ", light_tree " + std::string(light_selection_name(o.light_selection)) +
        (o.time_budget ? ", time " + std::to_string(*o.time_budget) : std::string()) +
        (o.crop ? ", crop " + std::to_string(o.crop->x0) + " " + std::to_string(o.crop->y0) + " " +
                      std::to_string(o.crop->x0 + o.crop->width) + " " + std::to_string(o.crop->y0 + o.crop->height)
                : std::string()) +
        ", aov [" + aov_list(o.aovs) + "]";
    std::vector<ImageAttribute> attributes{
        {kShardAttribute, std::to_string(shard.index) + "/" + std::to_string(shard.count)}, {kRenderAttribute, render}};
    if (kept)
        attributes.push_back({kKeptAttribute, std::to_string(kept->x0) + " " + std::to_string(kept->y0) + " " +
                                                  std::to_string(kept->width) + " " + std::to_string(kept->height)});
    return attributes;
}

MergedShards merge_shards(const std::vector<std::string>& paths, const std::filesystem::path& output,
                          DisplayTransform display, bool denoise, int threads) {
    check_output_path(output);
    std::vector<Part> parts;
    for (const std::string& path : paths) parts.push_back(read_part(path));
    const Part& first = parts.front();
    const int count = first.shard.count;
    std::map<int, const Part*> by_index;
    for (const Part& p : parts) {
        if (*attribute(p.exr, kRenderAttribute) != *attribute(first.exr, kRenderAttribute))
            throw Error(p.path, "a shard of another render than " + first.path + "'s (" +
                                    first_difference(*attribute(p.exr, kRenderAttribute),
                                                     *attribute(first.exr, kRenderAttribute)) +
                                    ")");
        if (p.shard.count != count)
            throw Error(p.path, "one of " + std::to_string(p.shard.count) + " shards, but " + first.path +
                                    " is one of " + std::to_string(count));
        if (p.exr.width != first.exr.width || p.exr.height != first.exr.height || p.exr.names != first.exr.names)
            throw Error(p.path, "its size or channels differ from " + first.path + "'s");
        if (kept_window(p.exr, p.path) != kept_window(first.exr, first.path))
            throw Error(p.path, "it keeps another window (sombra.kept) than " + first.path);
        if (const auto [it, added] = by_index.emplace(p.shard.index, &p); !added)
            throw Error(p.path, "shard " + std::to_string(p.shard.index) + "/" + std::to_string(count) +
                                    " given twice (also " + it->second->path + ")");
    }
    for (int i = 0; i < count; ++i)
        if (!by_index.count(i))
            throw Error(first.path, "shard " + std::to_string(i) + "/" + std::to_string(count) +
                                        " of this render is missing (" + std::to_string(parts.size()) + " of " +
                                        std::to_string(count) + " given)");

    // Every pixel from the shard that rendered it.
    int width = first.exr.width, height = first.exr.height;
    std::vector<std::vector<float>> channels(first.exr.names.size(),
                                             std::vector<float>(static_cast<std::size_t>(width) * height));
    for (const Part& p : parts)
        for (int j = 0; j < height; ++j)
            for (int i = 0; i < width; ++i) {
                if (!shard_owns(p.shard, width, i, j)) continue;
                const std::size_t k = static_cast<std::size_t>(j) * width + i;
                for (std::size_t c = 0; c < channels.size(); ++c) channels[c][k] = p.exr.values[c][k];
            }
    std::vector<float> rgb(static_cast<std::size_t>(width) * height * 3, 0.0f);
    for (std::size_t c = 0; c < channels.size(); ++c) {
        const std::string& name = first.exr.names[c];
        const int rgb_channel = name == "R" ? 0 : name == "G" ? 1 : name == "B" ? 2 : -1;
        if (rgb_channel >= 0)
            for (std::size_t k = 0; k < channels[c].size(); ++k) rgb[3 * k + rgb_channel] = channels[c][k];
    }
    if (denoise) {
        const DenoiseLayers denoise_input = denoise_layers_from(first.exr.names, channels, width, height, first.path);
        check_denoise_layers(denoise_input, first.path);
        rgb = denoise_image(denoise_input, threads);
    }
    if (const std::optional<PixelWindow> kept = kept_window(first.exr, first.path)) {
        const PixelWindow whole{0, 0, width, height};
        rgb = window_values(rgb, whole, *kept);
        for (std::vector<float>& values : channels) values = window_values(values, whole, *kept);
        width = kept->width;
        height = kept->height;
    }
    std::vector<ImageChannel> layers;
    for (std::size_t c = 0; c < channels.size(); ++c) {
        const std::string& name = first.exr.names[c];
        if (name != "R" && name != "G" && name != "B") layers.push_back({name, channels[c].data(), 1});
    }
    // The AOV layers go into an .exr output only, as `render --aov` allows only that.
    const bool exr = image_format_for(output) == ImageFormat::Exr;
    write_image(output, ImageView{width, height, rgb.data()}, display,
                exr ? std::span<const ImageChannel>(layers) : std::span<const ImageChannel>());
    return MergedShards{static_cast<int>(parts.size()), width, height};
}

}  // namespace sombra
