// Spec §21's shards: `sombra render … --shard I/N -o part.exr` renders share
// I of the pixels (render/render.h: ShardSpec) into an EXR whose header says
// which share it is and of which render; `sombra merge part… -o OUT` checks
// that the parts are the N shares of one render and joins them into the
// image that render writes whole, bit for bit.
#pragma once

#include <string>
#include <vector>

#include "app/cli.h"
#include "image/image_io.h"
#include "render/render_settings.h"

namespace sombra {

// The header attributes of a shard: "sombra.shard" = "I/N" and
// "sombra.render" = what decides its pixels (the input file's content hash,
// the resolved settings, the options that change pixels, sombra's version;
// not --threads, --exposure or the output's name). Reads the input file to hash it.
std::vector<ImageAttribute> shard_attributes(const CliOptions& options, const RenderSettings& settings);

// `sombra merge` (options.parts, options.output, options.exposure). Exit
// status 0, or 1 after one line "sombra: error: WHERE: WHAT" with nothing
// written: a part that is not a readable shard, shards of different
// renders or counts, a share missing or given twice.
int run_merge(const CliOptions& options);

}  // namespace sombra
