#include "core/plugin.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <vector>

namespace sombra {

namespace {

namespace fs = std::filesystem;

// The folders plugins may be in, relative to the folder of the file this
// code was loaded from (set by src/CMakeLists.txt: installed and build-tree
// layouts, for the executable and for the Python module), ':'-separated.
#ifndef SOMBRA_PLUGIN_SEARCH
#define SOMBRA_PLUGIN_SEARCH "."
#endif

std::vector<fs::path> plugin_folders() {
    std::vector<fs::path> folders;
    if (const char* dir = std::getenv("SOMBRA_PLUGIN_DIR"); dir != nullptr && *dir != '\0') return {fs::path(dir)};
    Dl_info info{};
    if (::dladdr(reinterpret_cast<void*>(&plugin_folders), &info) == 0 || info.dli_fname == nullptr) return folders;
    std::error_code ec;
    fs::path self = fs::canonical(info.dli_fname, ec);
    if (ec) self = info.dli_fname;
    const std::string search = SOMBRA_PLUGIN_SEARCH;
    for (std::size_t start = 0; start <= search.size();) {
        const std::size_t end = std::min(search.find(':', start), search.size());
        if (end > start) folders.push_back((self.parent_path() / search.substr(start, end - start)).lexically_normal());
        start = end + 1;
    }
    return folders;
}

}  // namespace

std::optional<PluginSymbol> find_plugin_symbol(const std::string& file, const char* symbol, std::string* why_not) {
    std::string looked;
    for (const fs::path& folder : plugin_folders()) {
        const fs::path path = folder / file;
        std::error_code ec;
        if (!fs::is_regular_file(path, ec)) {
            looked += (looked.empty() ? "" : ", ") + folder.string();
            continue;
        }
        void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (handle == nullptr) {
            const char* error = ::dlerror();
            if (why_not != nullptr)
                *why_not = "cannot load " + path.string() + ": " + (error ? error : "unknown error");
            return std::nullopt;
        }
        void* address = ::dlsym(handle, symbol);
        if (address == nullptr) {
            if (why_not != nullptr) *why_not = path.string() + " has no " + symbol + ": not a sombra plugin";
            return std::nullopt;
        }
        return PluginSymbol{address, path.string()};
    }
    if (why_not != nullptr) *why_not = file + " is not in " + (looked.empty() ? "any folder" : looked);
    return std::nullopt;
}

}  // namespace sombra
