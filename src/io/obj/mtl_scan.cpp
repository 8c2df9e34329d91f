#include "io/obj/mtl_scan.h"

namespace sombra {

std::vector<MtlPbrKeys> scan_mtl_pbr_keys(std::string_view text) {
    const auto blank = [](char c) { return c == ' ' || c == '\t'; };
    std::vector<MtlPbrKeys> out;
    MtlPbrKeys current;
    bool named = false;
    std::size_t begin = 0;
    while (begin < text.size()) {
        std::size_t end = text.find_first_of("\r\n", begin);
        if (end == std::string_view::npos) end = text.size();
        std::string_view line = text.substr(begin, end - begin);
        begin = end + (end + 1 < text.size() && text[end] == '\r' && text[end + 1] == '\n' ? 2 : 1);
        while (!line.empty() && blank(line.back())) line.remove_suffix(1);
        while (!line.empty() && blank(line.front())) line.remove_prefix(1);
        if (line.size() < 3) continue;
        if (line.starts_with("newmtl") && line.size() > 6 && blank(line[6])) {
            if (named) out.push_back(current);
            current = MtlPbrKeys{};
            // LoadMtl reads the name as a C string: it ends at a NUL byte.
            const std::string_view rest = line.substr(7);
            named = !rest.empty() && rest.front() != '\0';
        } else if (line[0] == 'P' && blank(line[2])) {
            if (line[1] == 'r') current.roughness = true;
            if (line[1] == 'm') current.metallic = true;
        }
    }
    out.push_back(current);  // LoadMtl always adds the last one
    return out;
}

}  // namespace sombra
