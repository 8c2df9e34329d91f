// Optional parts that live in plugins of their own (libsombra_mpi.so: MPI),
// so that the sombra executable and the Python module link none of their
// libraries and the .deb needs none of them (packaging/CMakeLists.txt). A
// plugin is looked for in the folder of sombra's plugins, found from where
// the code asking for it was loaded (the executable, or the Python module):
// installed (<libdir>/sombra/plugins) or in the build tree (build/<preset>/plugins);
// SOMBRA_PLUGIN_DIR names another folder, the only one looked in then.
#pragma once

#include <optional>
#include <string>

namespace sombra {

struct PluginSymbol {
    void* address = nullptr;  // the symbol's, in the plugin (loaded for the process's lifetime)
    std::string path;         // the plugin file it came from
};

// `symbol` of the plugin `file` ("libsombra_mpi.so"), or nothing, with the
// folders looked in (or why the file found could not be loaded) in
// `*why_not`.
std::optional<PluginSymbol> find_plugin_symbol(const std::string& file, const char* symbol, std::string* why_not);

}  // namespace sombra
