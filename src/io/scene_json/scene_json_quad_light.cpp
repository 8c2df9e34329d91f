// Quad lights (spec §10): read from "lights", then made into two triangles
// with an emit-from-the-front material, which join the scene as an object does.
#include "io/scene_json/scene_json.h"

namespace sombra {

QuadLight read_quad_light(const SceneJson& s, const Json& v, std::string_view pointer) {
    expect_keys(s, v, pointer, {"type", "corner", "edge1", "edge2", "radiance"});
    QuadLight q;
    q.pointer = std::string(pointer);
    q.corner = read_vec3(s, require_member(s, v, pointer, "corner"), json_child(pointer, "corner"));
    q.edge1 = read_vec3(s, require_member(s, v, pointer, "edge1"), json_child(pointer, "edge1"));
    q.edge2 = read_vec3(s, require_member(s, v, pointer, "edge2"), json_child(pointer, "edge2"));
    q.radiance = read_rgb(s, require_member(s, v, pointer, "radiance"), json_child(pointer, "radiance"));

    const Vec3d a = to_double(q.edge1), b = to_double(q.edge2);
    if (length(a) == 0) json_fail(s, json_child(pointer, "edge1"), "quad light edge 'edge1' is zero");
    if (length(b) == 0) json_fail(s, json_child(pointer, "edge2"), "quad light edge 'edge2' is zero");
    if (nearly_parallel(a, b))
        json_fail(s, pointer, "quad light edges 'edge1' and 'edge2' are parallel (the quad has no area)");
    // The triangles are built in float: their corners must stay finite and distinct.
    const Vec3 far = q.corner + q.edge1 + q.edge2;
    if (!is_finite(far) || !(length(cross(q.edge1, q.edge2)) > 0))
        json_fail(s, pointer, "quad light is too large or too small to be represented");
    return q;
}

LoadedMesh make_quad_light_mesh(const QuadLight& q) {
    LoadedMesh out;
    const Vec3 p = q.corner;
    out.mesh.positions = {p, p + q.edge1, p + q.edge1 + q.edge2, p + q.edge2};
    out.mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    out.mesh.material_ids = {0, 0};
    Material m;
    m.name = "quad light " + q.pointer;
    m.type = MaterialType::Diffuse;
    m.kd = Vec3{0.0f};  // reflects nothing
    m.ke = q.radiance;
    m.emits_front_only = true;
    out.materials.push_back(m);
    return out;
}

}  // namespace sombra
