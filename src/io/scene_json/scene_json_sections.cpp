// The sections of a scene file: render settings, camera and transforms
// (lights: scene_json_lights.cpp; materials: scene_json_materials.cpp),
// validated as spec §2–§8 ask.
#include "io/scene_json/scene_json.h"

#include <cmath>
#include <cstdio>
#include <optional>

#include "core/format.h"
#include "core/vec3d.h"

namespace sombra {
namespace {

// |det| / (product of column lengths) below this counts as singular: 0 for a
// flattening matrix, 1 for any rotation or scale, whatever its size.
constexpr double kSingularRatio = 1e-6;

std::string degrees_text(double degrees) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f", degrees);
    return buf;
}

Vec3 read_nonzero_vec3(const SceneJson& s, const Json& object, std::string_view pointer, std::string_view key) {
    const std::string p = json_child(pointer, key);
    const Vec3 v = read_vec3(s, require_member(s, object, pointer, key), p);
    if (length(to_double(v)) == 0) json_fail(s, p, "camera vector '" + std::string(key) + "' is zero");
    return v;
}

CameraBasis read_camera_basis(const SceneJson& s, const Json& v, std::string_view pointer) {
    CameraBasis b;
    b.origin = read_vec3(s, require_member(s, v, pointer, "origin"), json_child(pointer, "origin"));
    b.left = read_nonzero_vec3(s, v, pointer, "left");
    b.up = read_nonzero_vec3(s, v, pointer, "up");
    b.forward = read_nonzero_vec3(s, v, pointer, "forward");
    const struct {
        const char* a_name;
        Vec3 a;
        const char* b_name;
        Vec3 b;
    } pairs[] = {
        {"left", b.left, "up", b.up}, {"left", b.left, "forward", b.forward}, {"up", b.up, "forward", b.forward}};
    for (const auto& pair : pairs) {
        const Vec3d a = to_double(pair.a), c = to_double(pair.b);
        const double cosine = dot(a, c) / (length(a) * length(c));
        if (std::fabs(cosine) > kAngleTolerance) {
            const double angle = std::acos(std::fmax(-1.0, std::fmin(1.0, cosine))) * (180.0 / 3.14159265358979323846);
            json_fail(s, pointer,
                      std::string("camera vectors '") + pair.a_name + "' and '" + pair.b_name +
                          "' are not perpendicular (angle " + degrees_text(angle) + "°)");
        }
    }
    return b;
}

CameraLookAt read_camera_look_at(const SceneJson& s, const Json& v, std::string_view pointer) {
    CameraLookAt c;
    c.origin = read_vec3(s, require_member(s, v, pointer, "origin"), json_child(pointer, "origin"));
    c.look_at = read_vec3(s, require_member(s, v, pointer, "look_at"), json_child(pointer, "look_at"));
    if (const Json* up = find_member(v, "up")) c.up = read_vec3(s, *up, json_child(pointer, "up"));
    if (const Json* fov = find_member(v, "fov")) c.fov_degrees = read_float(s, *fov, json_child(pointer, "fov"));

    const Vec3d o = to_double(c.origin), t = to_double(c.look_at), up = to_double(c.up);
    const Vec3d view = t - o;
    // The renderer normalises in float: the view direction must survive that.
    if (length(view) == 0 || length(c.look_at - c.origin) == 0)
        json_fail(s, json_child(pointer, "look_at"), "'look_at' is the same point as 'origin'");
    if (length(up) == 0) json_fail(s, json_child(pointer, "up"), "camera vector 'up' is zero");
    if (nearly_parallel(up, view))
        json_fail(s, json_child(pointer, "up"), "'up' is parallel to the view direction ('look_at' - 'origin')");
    if (!(c.fov_degrees > 0 && c.fov_degrees < 180))
        json_fail(s, json_child(pointer, "fov"), "fov must lie strictly between 0 and 180 degrees");
    return c;
}

// The thin lens of spec §17: aperture_radius ≥ 0 (0, the default, is the
// pinhole) and focus_distance > 0, which the basis form must give when the
// aperture is open (the look-at form defaults to |look_at − origin|).
void read_lens(const SceneJson& s, const Json& v, std::string_view pointer, CameraSpec& camera) {
    if (const Json* r = find_member(v, "aperture_radius")) {
        const std::string p = json_child(pointer, "aperture_radius");
        camera.aperture_radius = read_float(s, *r, p);
        if (!(camera.aperture_radius >= 0)) json_fail(s, p, "aperture_radius must be >= 0");
    }
    if (const Json* d = find_member(v, "focus_distance")) {
        const std::string p = json_child(pointer, "focus_distance");
        camera.focus_distance = read_float(s, *d, p);
        if (!(*camera.focus_distance > 0)) json_fail(s, p, "focus_distance must be > 0");
    }
    if (camera.basis && camera.aperture_radius > 0 && !camera.focus_distance)
        json_fail(s, pointer, "a basis-form camera with 'aperture_radius' > 0 needs 'focus_distance'");
}

Transform read_matrix(const SceneJson& s, const Json& v, std::string_view pointer) {
    if (!v.is_array() || v.size() != 16) json_fail(s, pointer, "expected an array of 16 numbers (row-major 4x4)");
    Transform t;
    for (std::size_t i = 0; i < 16; ++i) t.m[i] = read_float(s, v[i], json_child(pointer, i));
    // Exact: these are integers written by hand or by a script, not computed.
    if (t.m[12] != 0 || t.m[13] != 0 || t.m[14] != 0 || t.m[15] != 1)
        json_fail(s, pointer, "the matrix's last row must be [0, 0, 0, 1]");
    return t;
}

Transform read_step(const SceneJson& s, const std::string& op, const Json& v, std::string_view pointer) {
    if (op == "scale") {
        Vec3 scale;
        if (v.is_number())
            scale = Vec3(read_float(s, v, pointer));
        else if (v.is_array())
            scale = read_vec3(s, v, pointer);
        else
            json_fail(s, pointer, "expected a number or an array of 3 numbers");
        if (scale.x == 0 || scale.y == 0 || scale.z == 0)
            json_fail(s, pointer, "scale must be non-zero (it would flatten the object)");
        return make_scale(scale);
    }
    if (op == "rotate") {
        expect_keys(s, v, pointer, {"axis", "degrees"});
        const std::string axis_pointer = json_child(pointer, "axis");
        const Vec3 axis = read_vec3(s, require_member(s, v, pointer, "axis"), axis_pointer);
        if (length(to_double(axis)) == 0) json_fail(s, axis_pointer, "rotation axis is zero");
        const float degrees = read_float(s, require_member(s, v, pointer, "degrees"), json_child(pointer, "degrees"));
        return make_rotate(axis, degrees);
    }
    if (op == "translate") return make_translate(read_vec3(s, v, pointer));
    if (op == "matrix") return read_matrix(s, v, pointer);
    json_fail(s, pointer, "unknown transform step '" + op + "' (expected 'scale', 'rotate', 'translate' or 'matrix')");
}

// Why t cannot carry geometry, or "" when it can.
std::string transform_problem(const Transform& t) {
    for (float x : t.m)
        if (!std::isfinite(x)) return "transform overflows (its matrix has non-finite entries)";
    const double det = determinant3(t);
    double column_lengths = 1;
    for (int c = 0; c < 3; ++c) column_lengths *= length(Vec3d{t.m[c], t.m[4 + c], t.m[8 + c]});
    if (!(column_lengths > 0) || std::fabs(det) < kSingularRatio * column_lengths)
        return "transform is not invertible (determinant " + format_number(det) + ")";
    return {};
}

}  // namespace

RenderSettings read_render(const SceneJson& s, const Json& v, std::string_view pointer) {
    // "medium" names one of the scene's media: load_scene_text reads it.
    expect_keys(s, v, pointer,
                {"width", "height", "spp", "seed", "integrator", "max_depth", "max_volume_depth", "texture_filter",
                 "medium"});
    RenderSettings r;
    if (const Json* w = find_member(v, "width"))
        r.width = static_cast<int>(read_integer(s, *w, json_child(pointer, "width"), 1, kMaxImageSide));
    if (const Json* h = find_member(v, "height"))
        r.height = static_cast<int>(read_integer(s, *h, json_child(pointer, "height"), 1, kMaxImageSide));
    if (const Json* spp = find_member(v, "spp"))
        r.spp = static_cast<int>(read_integer(s, *spp, json_child(pointer, "spp"), 1, kMaxSpp));
    if (const Json* seed = find_member(v, "seed")) r.seed = read_unsigned(s, *seed, json_child(pointer, "seed"));
    if (const Json* integrator = find_member(v, "integrator")) {
        const std::string p = json_child(pointer, "integrator");
        const std::string& name = read_string(s, *integrator, p);
        const std::optional<IntegratorKind> kind = parse_integrator(name);
        if (!kind) json_fail(s, p, "unknown integrator '" + name + "' (expected 'direct' or 'path')");
        r.integrator = *kind;
    }
    if (const Json* depth = find_member(v, "max_depth"))
        r.max_depth = static_cast<int>(read_integer(s, *depth, json_child(pointer, "max_depth"), 0, kMaxDepth));
    if (const Json* depth = find_member(v, "max_volume_depth"))
        r.max_volume_depth =
            static_cast<int>(read_integer(s, *depth, json_child(pointer, "max_volume_depth"), 0, kMaxVolumeDepth));
    if (const Json* filter = find_member(v, "texture_filter")) {
        const std::string p = json_child(pointer, "texture_filter");
        const std::string& name = read_string(s, *filter, p);
        const std::optional<TextureFilter> filter_kind = parse_texture_filter(name);
        if (!filter_kind) json_fail(s, p, "unknown texture filter '" + name + "' (expected 'bilinear' or 'mipmap')");
        r.texture_filter = *filter_kind;
    }
    if (const std::string problem = render_settings_problem(r); !problem.empty()) json_fail(s, pointer, problem);
    return r;
}

CameraSpec read_camera(const SceneJson& s, const Json& v, std::string_view pointer) {
    expect_keys(s, v, pointer,
                {"origin", "left", "up", "forward", "look_at", "fov", "aperture_radius", "focus_distance", "medium"});
    const bool basis_form = find_member(v, "left") || find_member(v, "forward");
    const bool look_at_form = find_member(v, "look_at") || find_member(v, "fov");
    if (basis_form && look_at_form)
        json_fail(s, pointer,
                  "camera mixes the basis form ('left', 'up', 'forward') with the look-at form ('look_at', 'fov')");
    if (!basis_form && !look_at_form)
        json_fail(s, pointer, "camera needs 'look_at' (look-at form) or 'left', 'up' and 'forward' (basis form)");
    CameraSpec camera;
    if (basis_form)
        camera.basis = read_camera_basis(s, v, pointer);
    else
        camera.look_at = read_camera_look_at(s, v, pointer);
    read_lens(s, v, pointer, camera);
    return camera;
}

Transform read_transform(const SceneJson& s, const Json& v, std::string_view pointer) {
    expect_array(s, v, pointer);
    Transform t;
    for (std::size_t i = 0; i < v.size(); ++i) {
        const std::string p = json_child(pointer, i);
        const Json& step = v[i];
        expect_object(s, step, p);
        if (step.size() != 1)
            json_fail(s, p,
                      "a transform step has exactly one key ('scale', 'rotate', 'translate' or 'matrix'), found " +
                          std::to_string(step.size()));
        const std::string& op = step.begin().key();
        const std::string op_pointer = json_child(p, op);
        const Transform step_transform = read_step(s, op, step.begin().value(), op_pointer);
        if (const std::string problem = transform_problem(step_transform); !problem.empty())
            json_fail(s, op_pointer, problem);
        t = compose(t, step_transform);
    }
    if (const std::string problem = transform_problem(t); !problem.empty()) json_fail(s, pointer, problem);
    return t;
}

}  // namespace sombra
