// Spec §21's shards: `sombra render … --shard I/N -o part.exr` renders share
// I of the pixels (render/render.h: ShardSpec) into an EXR whose header says
// which share it is and of which render; `sombra merge part… -o OUT` checks
// that the parts are the N shares of one render and joins them into the
// image that render writes whole, bit for bit.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "api/render_options.h"
#include "image/image_io.h"
#include "render/render.h"
#include "render/render_settings.h"

namespace sombra {

// The header attributes of shard `shard` of a render of `input`:
// "sombra.shard" = "I/N" and "sombra.render" = what decides its pixels (the
// input file's content hash, the resolved settings, the options that change
// pixels, sombra's version; not the thread count, exposure or the output's
// name). Reads the input file to hash it. Throws Error.
// `kept`: the part of the shard's image that the merged image keeps, in the
// shard image's own pixels ("sombra.kept" = "X Y WIDTH HEIGHT"): with --crop
// and --denoise the shards split the window grown by the denoiser's reach,
// which merge denoises whole, then cuts to the crop.
std::vector<ImageAttribute> shard_attributes(const std::string& input, const RenderOptions& options,
                                             const RenderSettings& settings, ShardSpec shard,
                                             std::optional<PixelWindow> kept = std::nullopt);

// What merge_shards joined.
struct MergedShards {
    int count = 0;  // shards read
    int width = 0, height = 0;
};

// Checks that `parts` are the N shards of one render and writes the image
// that render writes whole, bit for bit, to `output` (AOV layers into an
// .exr only). Throws Error, with nothing written, for a part that is not a
// readable shard, shards of different renders or counts, a share missing
// or given twice. Shards that say what is kept (above) are cut to it, after
// denoising.
// With `denoise`, the merged image is denoised (spec §25) on `threads`
// (0 = all) from the denoiser's layers the shards carry; Error naming
// the first missing one.
MergedShards merge_shards(const std::vector<std::string>& parts, const std::filesystem::path& output,
                          DisplayTransform display, bool denoise = false, int threads = 0);

}  // namespace sombra
