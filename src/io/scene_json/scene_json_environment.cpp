// The "environment" section (spec §10): an equirectangular map that replaces
// the background, with sombra's "clamp_negative" extension for maps whose
// resampling rang below 0.
#include <cmath>

#include "core/format.h"
#include "io/images/hdr_image.h"
#include "io/scene_json/scene_json.h"

namespace sombra {

namespace fs = std::filesystem;

EnvironmentMap read_environment(const SceneJson& s, const Json& v, std::string_view pointer, const fs::path& folder) {
    expect_keys(s, v, pointer, {"file", "scale", "rotate_y", "clamp_negative"});
    EnvironmentMap env;
    const std::string file_pointer = json_child(pointer, "file");
    env.file = read_string(s, require_member(s, v, pointer, "file"), file_pointer);
    if (env.file.empty()) json_fail(s, file_pointer, "expected a file name, not an empty string");
    if (env.file.find('\0') != std::string::npos) json_fail(s, file_pointer, "the file name contains a NUL character");

    if (const Json* scale = find_member(v, "scale")) {
        const std::string p = json_child(pointer, "scale");
        env.scale = read_float(s, *scale, p);
        if (env.scale < 0) json_fail(s, p, "scale must be non-negative");
    }
    if (const Json* rotate = find_member(v, "rotate_y"))
        env.rotate_y_degrees = read_float(s, *rotate, json_child(pointer, "rotate_y"));
    HdrReadOptions options;
    if (const Json* clamp = find_member(v, "clamp_negative")) {
        if (!clamp->is_boolean()) json_fail(s, json_child(pointer, "clamp_negative"), "expected true or false");
        options.clamp_negative = clamp->get<bool>();
    }
    options.negative_hint = "; add \"clamp_negative\": true to the environment to read negative values as 0";

    const fs::path path = folder / fs::path(env.file);
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (!fs::exists(status))
        json_fail(s, file_pointer, "cannot open '" + env.file + "': no such file " + looked_for(path));
    if (!fs::is_regular_file(status)) json_fail(s, file_pointer, "'" + env.file + "' is not a regular file");

    std::size_t clamped = 0;
    env.image = read_hdr_image(path, options, &clamped);  // its errors name the image file
    if (clamped > 0)
        s.diag.warn(path.string(), std::to_string(clamped) + " negative values read as 0 (\"clamp_negative\": true)");
    return env;
}

}  // namespace sombra
