// What tinyobjloader's MTL reader does not tell: whether a material states
// the PBR extension's `Pr` and `Pm` (it reads their values, 0 when absent,
// but keeps no record of them), which decides whether the material is spec
// §11's pbr.
#pragma once

#include <string_view>
#include <vector>

namespace sombra {

struct MtlPbrKeys {
    bool roughness = false;  // a `Pr` line
    bool metallic = false;   // a `Pm` line
};

// For each material of an MTL text, in the order tinyobjloader's LoadMtl
// adds them, whether it has a `Pr` and a `Pm` line. Lines are split and
// trimmed as LoadMtl splits and trims them (at \n, \r or \r\n; blanks and
// tabs around), and a material is added where LoadMtl adds one: at each
// `newmtl` after a named one, and at the end.
std::vector<MtlPbrKeys> scan_mtl_pbr_keys(std::string_view text);

}  // namespace sombra
