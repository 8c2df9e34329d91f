// `sombra merge PART... -o OUT` (spec §21): the shards joined by
// distributed/shards.h, and one summary line.
#include <iostream>

#include "app/report.h"
#include "app/run.h"
#include "distributed/shards.h"

namespace sombra {

int run_merge(const CliOptions& o) {
    return reporting_errors(o.input, [&] {
        const MergedShards merged = merge_shards(o.parts, o.output, o.display, o.render.denoise, o.render.threads);
        if (!o.quiet)
            std::cerr << "sombra: merged " << merged.count << " shards into " << one_line_message(o.output) << " ("
                      << merged.width << "x" << merged.height << ")\n";
        return 0;
    });
}

}  // namespace sombra
