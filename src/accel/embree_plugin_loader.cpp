// Finds libsombra_embree.so (core/plugin.h) for `--accel embree`, or, with
// SOMBRA_STATIC_PLUGINS, takes the table compiled in.
#include <string>

#include "accel/embree_plugin.h"
#include "core/error.h"
#include "core/plugin.h"

namespace sombra {

#ifdef SOMBRA_STATIC_PLUGINS

const EmbreeApi& embree_plugin() { return *sombra_embree_api(); }  // compiled in (src/CMakeLists.txt)

#else

const EmbreeApi& embree_plugin() {
    std::string why;
    const std::optional<PluginSymbol> entry = find_plugin_symbol("libsombra_embree.so", kEmbreeEntry, &why);
    const EmbreeApi* api = entry ? reinterpret_cast<EmbreeApiEntry>(entry->address)() : nullptr;
    if (entry && (api == nullptr || api->abi != kEmbreeApiAbi))
        why = entry->path + " belongs to another build of sombra";
    if (api == nullptr || api->abi != kEmbreeApiAbi)
        throw Error("--accel", "embree: the Embree plugin " + why + " (install the sombra-embree package)");
    return *api;
}

#endif

}  // namespace sombra
