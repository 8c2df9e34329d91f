// The loaded scene of spec §2: everything the renderer needs, in world space.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "core/vec3.h"
#include "scene/material.h"
#include "scene/mesh.h"

namespace sombra {

struct RenderSettings {
    int width = 640;
    int height = 480;
    int spp = 1;
    std::uint64_t seed = 0;
};

// The camera as written in the scene file (spec §3): exactly one form is set.
struct CameraBasis {
    Vec3 origin, left, up, forward;
};
struct CameraLookAt {
    Vec3 origin, look_at;
    Vec3 up{0, 1, 0};
    float fov_degrees = 45;
};
struct CameraSpec {
    std::optional<CameraBasis> basis;
    std::optional<CameraLookAt> look_at;
};

struct PointLight {
    Vec3 position;
    Vec3 intensity;  // radiant intensity, RGB (W/sr)
};

struct Scene {
    RenderSettings render;
    Vec3 background{0.0f};
    CameraSpec camera;
    std::vector<Material> materials;
    std::vector<PointLight> lights;
    TriangleMesh geometry;  // all objects, world space; material_ids index materials
};

}  // namespace sombra
