// Scene files that must not load, by key across every section of the spec:
// each is one error naming where (file:line:col or the JSON path) and what.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "io/scene_json/scene_file.h"
#include "io/scene_json/scene_file_fixture.h"

namespace sombra {
namespace {

class SceneFileErrors : public testing::SceneFileTest {};

struct BadScene {
    const char* label;
    std::string text;
    std::string where;  // after "scene path"; a JSON pointer is preceded by ": "
    std::string message_part;
};

TEST_F(SceneFileErrors, BadScenesNameWhereAndWhat) {
    const std::string kd_ok = R"("kd": [0.5, 0.5, 0.5])";
    const std::vector<BadScene> cases = {
        {"malformed", "{\n  \"render\": {\"width\": 10,}\n}", ":2:26", "unexpected '}'"},
        {"number overflow", "{\n\"render\": {\"seed\": 1e999}}", ":2:20", "number overflow"},
        {"not an object", "[1, 2]", "", "expected an object"},
        {"duplicate key", scene(R"("render": {"width": 10, "width": 20})"), ": /render/width", "duplicate key 'width'"},
        {"unknown top key", scene(R"("rendr": {})"), ": /rendr", "unknown key 'rendr'"},
        {"unknown nested key", scene(R"("render": {"widht": 10})"), ": /render/widht", "unknown key 'widht'"},
        {"width as string", scene(R"("render": {"width": "640"})"), ": /render/width", "expected an integer"},
        {"fractional spp", scene(R"("render": {"spp": 1.5})"), ": /render/spp", "expected an integer"},
        {"short background", scene(R"("background": [1, 2])"), ": /background", "expected an array of 3 numbers"},
        {"background of strings", scene(R"("background": ["a", 0, 0])"), ": /background",
         "expected an array of 3 numbers"},
        {"number beyond float", scene(R"("background": [1e39, 0, 0])"), ": /background/0", "number out of range"},
        {"negative background", scene(R"("background": [-1, 0, 0])"), ": /background", "non-negative"},
        {"spp 0", scene(R"("render": {"spp": 0})"), ": /render/spp", "between 1 and 65536"},
        {"width 0", scene(R"("render": {"width": 0})"), ": /render/width", "between 1 and 32768"},
        {"width 100000", scene(R"("render": {"width": 100000})"), ": /render/width", "between 1 and 32768"},
        {"too many pixels", scene(R"("render": {"width": 32768, "height": 32768})"), ": /render", "exceeds the limit"},
        {"negative seed", scene(R"("render": {"seed": -1})"), ": /render/seed", "non-negative"},
        {"missing objects", std::string("{") + kCamera + "}", ": /objects", "missing required key 'objects'"},
        {"empty objects", scene("", "[]"), ": /objects", "at least one object"},
        {"objects not array", scene("", R"({"file": "tri.obj"})"), ": /objects", "expected an array"},
        {"missing camera", R"({"objects": [{"file": "tri.obj"}]})", ": /camera", "missing required key 'camera'"},
        {"both camera forms",
         with_camera(
             R"({"origin": [0,0,0], "look_at": [0,0,-1], "left": [1,0,0], "up": [0,1,0], "forward": [0,0,-1]})"),
         ": /camera", "mixes"},
        {"no camera form", with_camera(R"({"origin": [0,0,0], "up": [0,1,0]})"), ": /camera", "needs"},
        {"basis missing forward", with_camera(R"({"origin": [0,0,0], "left": [1,0,0], "up": [0,1,0]})"),
         ": /camera/forward", "missing required key 'forward'"},
        {"basis not perpendicular",
         with_camera(R"({"origin": [0,0,0], "left": [1,0,0], "up": [0.05,1,0], "forward": [0,0,-1]})"), ": /camera",
         "'left' and 'up' are not perpendicular (angle 87.1°)"},
        {"basis zero vector", with_camera(R"({"origin": [0,0,0], "left": [1,0,0], "up": [0,1,0], "forward": [0,0,0]})"),
         ": /camera/forward", "is zero"},
        {"up parallel", with_camera(R"({"origin": [0,0,0], "look_at": [0,5,0]})"), ": /camera/up", "parallel"},
        {"look_at at origin", with_camera(R"({"origin": [1,2,3], "look_at": [1,2,3]})"), ": /camera/look_at",
         "same point"},
        {"fov 0", with_camera(R"({"origin": [0,0,5], "look_at": [0,0,0], "fov": 0})"), ": /camera/fov",
         "strictly between 0 and 180"},
        {"fov 180", with_camera(R"({"origin": [0,0,5], "look_at": [0,0,0], "fov": 180})"), ": /camera/fov",
         "strictly between 0 and 180"},
        {"unknown material", with_objects(R"({"file": "tri.obj", "material": "foo"})"), ": /objects/0/material",
         "unknown material 'foo'"},
        {"unknown material type", with_objects(R"({"file": "tri.obj"})", R"({"m": {"type": "glass", "kd": [0,0,0]}})"),
         ": /materials/m/type", "unknown material type 'glass'"},
        {"material without type", with_objects(R"({"file": "tri.obj"})", R"({"m": {"kd": [0,0,0]}})"),
         ": /materials/m/type", "missing required key 'type'"},
        {"kd out of range",
         with_objects(R"({"file": "tri.obj"})", R"({"m": {"type": "diffuse", "kd": [0.5, 1.2, 0]}})"),
         ": /materials/m/kd", "kd components must lie in [0, 1]"},
        {"ks below 0",
         with_objects(R"({"file": "tri.obj"})",
                      R"({"m": {"type": "phong", )" + kd_ok + R"(, "ks": [-0.1, 0, 0], "shininess": 1}})"),
         ": /materials/m/ks", "ks components must lie in [0, 1]"},
        {"negative shininess",
         with_objects(R"({"file": "tri.obj"})",
                      R"({"m": {"type": "phong", )" + kd_ok + R"(, "ks": [0.1, 0.1, 0.1], "shininess": -2}})"),
         ": /materials/m/shininess", "non-negative"},
        {"phong without ks", with_objects(R"({"file": "tri.obj"})", R"({"m": {"type": "phong", )" + kd_ok + "}}"),
         ": /materials/m/ks", "missing required key 'ks'"},
        {"diffuse with shininess",
         with_objects(R"({"file": "tri.obj"})", R"({"m": {"type": "diffuse", )" + kd_ok + R"(, "shininess": 3}})"),
         ": /materials/m/shininess", "only to phong"},
        {"unknown light type", scene(R"("lights": [{"type": "area", "position": [0,0,0], "intensity": [1,1,1]}])"),
         ": /lights/0/type", "unknown light type 'area'"},
        {"negative intensity", scene(R"("lights": [{"position": [0,0,0], "intensity": [1,-1,1]}])"),
         ": /lights/0/intensity", "non-negative"},
        {"light without position", scene(R"("lights": [{"type": "point", "intensity": [1,1,1]}])"),
         ": /lights/0/position", "missing required key 'position'"},
        {"missing mesh file", with_objects(R"({"file": "models/x.obj"})"), ": /objects/0/file",
         "cannot open 'models/x.obj': no such file"},
        {"mesh path a folder", with_objects(R"({"file": "models"})"), ": /objects/0/file", "folder"},
        {"mesh path the scene", with_objects(R"({"file": "scene.json"})"), ": /objects/0/file", "scene file itself"},
        {"object unknown key", with_objects(R"({"file": "tri.obj", "transfrom": []})"), ": /objects/0/transfrom",
         "unknown key 'transfrom'"},
        {"matrix last row",
         with_objects(R"({"file": "tri.obj", "transform": [{"matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,1,1]}]})"),
         ": /objects/0/transform/0/matrix", "last row must be [0, 0, 0, 1]"},
        {"matrix of 12", with_objects(R"({"file": "tri.obj", "transform": [{"matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0]}]})"),
         ": /objects/0/transform/0/matrix", "16 numbers"},
        {"singular matrix",
         with_objects(R"({"file": "tri.obj", "transform": [{"matrix": [1,2,3,0, 4,5,6,0, 5,7,9,0, 0,0,0,1]}]})"),
         ": /objects/0/transform/0/matrix", "not invertible"},
        {"scale 0", with_objects(R"({"file": "tri.obj", "transform": [{"translate": [1,2,3]}, {"scale": 0}]})"),
         ": /objects/0/transform/1/scale", "non-zero"},
        {"scale with a zero axis", with_objects(R"({"file": "tri.obj", "transform": [{"scale": [1, 0, 1]}]})"),
         ": /objects/0/transform/0/scale", "non-zero"},
        {"two ops in one step",
         with_objects(R"({"file": "tri.obj", "transform": [{"scale": 2, "translate": [1,1,1]}]})"),
         ": /objects/0/transform/0", "exactly one key"},
        {"unknown op", with_objects(R"({"file": "tri.obj", "transform": [{"shear": 2}]})"),
         ": /objects/0/transform/0/shear", "unknown transform step 'shear'"},
        {"zero rotation axis",
         with_objects(R"({"file": "tri.obj", "transform": [{"rotate": {"axis": [0,0,0], "degrees": 5}}]})"),
         ": /objects/0/transform/0/rotate/axis", "axis is zero"},
        {"overflowing transform",
         with_objects(R"({"file": "tri.obj", "transform": [{"scale": 1e30}, {"scale": 1e30}]})"),
         ": /objects/0/transform", "overflows"},
    };
    for (const BadScene& c : cases) {
        SCOPED_TRACE(c.label);
        try {
            load(c.text);
            ADD_FAILURE() << "no error for: " << c.text;
        } catch (const Error& e) {
            EXPECT_EQ(e.where(), scene_path.string() + c.where);
            EXPECT_NE(e.message().find(c.message_part), std::string::npos) << e.message();
            EXPECT_EQ(e.message().find('\n'), std::string::npos);
        }
    }
}

TEST_F(SceneFileErrors, BadRenderMaterialLightAndEnvironmentValuesNameWhereAndWhat) {
    expect_errors({
        {scene(R"("render": {"max_depth": 1025})"), ": /render/max_depth: must be between 0 and 1024"},
        {scene(R"("render": {"max_depth": -1})"), ": /render/max_depth: must be between 0 and 1024"},
        {scene(R"("render": {"max_depth": 2.5})"), ": /render/max_depth: expected an integer"},
        {scene(R"("render": {"integrator": "bdpt"})"),
         ": /render/integrator: unknown integrator 'bdpt' (expected 'direct' or 'path')"},
        {scene(R"("render": {"integrator": 1})"), ": /render/integrator: expected a string"},
        {scene(R"("render": {"texture_filter": "trilinear"})"),
         ": /render/texture_filter: unknown texture filter 'trilinear' (expected 'bilinear' or 'mipmap')"},
        {scene(R"("render": {"texture_filter": true})"), ": /render/texture_filter: expected a string"},
        {with_material(R"({"type": "dielectric", "ior": 1})"), ": /materials/m/ior: ior must be greater than 1"},
        {with_material(R"({"type": "dielectric", "ior": 0.5})"), ": /materials/m/ior: ior must be greater than 1"},
        {with_material(R"({"type": "dielectric", "ior": "NaN"})"), ": /materials/m/ior: expected a number"},
        {with_material(R"({"type": "dielectric", "ior": 1e39})"), ": /materials/m/ior: number out of range"},
        {with_material(R"({"type": "dielectric", "kt": [1.1, 1, 1]})"),
         ": /materials/m/kt: kt components must lie in [0, 1]"},
        {with_material(R"({"type": "conductor", "ks": [1, 1, 1], "roughness": -0.1})"),
         ": /materials/m/roughness: roughness must lie in [0, 1]"},
        {with_material(R"({"type": "conductor", "ks": [1, 1, 1], "roughness": 1.5})"),
         ": /materials/m/roughness: roughness must lie in [0, 1]"},
        {with_material(R"({"type": "conductor", "ks": [1, 1, 1]})"),
         ": /materials/m/roughness: missing required key 'roughness'"},
        {with_material(R"({"type": "mirror", "kr": [1.5, 0, 0]})"),
         ": /materials/m/kr: kr components must lie in [0, 1]"},
        {with_material(R"({"type": "mirror"})"), ": /materials/m/kr: missing required key 'kr'"},
        {with_material(R"({"type": "mirror", "kr": [1, 1, 1], "kd": [1, 1, 1]})"),
         ": /materials/m/kd: 'kd' applies only to diffuse and phong materials, not mirror"},
        {with_material(R"({"type": "mirror", "kr": [1, 1, 1], "shine": 1})"),
         ": /materials/m/shine: unknown key 'shine'"},
        {with_material(R"({"type": "pbr", "base_color": [1, 1, 1]})"),
         ": /materials/m/metallic: missing required key 'metallic'"},
        {with_material(R"({"type": "pbr", "metallic": 0, "roughness": 0.5})"),
         ": /materials/m/base_color: missing required key 'base_color'"},
        {with_material(R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": 0})"),
         ": /materials/m/roughness: missing required key 'roughness'"},
        {with_material(R"({"type": "pbr", "base_color": [1, 1.2, 1], "metallic": 0, "roughness": 0.5})"),
         ": /materials/m/base_color: base_color components must lie in [0, 1]"},
        {with_material(R"({"type": "pbr", "base_color": [1, 1], "metallic": 0, "roughness": 0.5})"),
         ": /materials/m/base_color: "},
        {with_material(R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": 1.01, "roughness": 0.5})"),
         ": /materials/m/metallic: metallic must lie in [0, 1]"},
        {with_material(R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": -0.5, "roughness": 0.5})"),
         ": /materials/m/metallic: metallic must lie in [0, 1]"},
        {with_material(R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": "1", "roughness": 0.5})"),
         ": /materials/m/metallic: expected a number"},
        {with_material(R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": 0, "roughness": 2})"),
         ": /materials/m/roughness: roughness must lie in [0, 1]"},
        {with_material(R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": 0, "roughness": 0.5, "ior": 1})"),
         ": /materials/m/ior: ior must be greater than 1"},
        {with_material(R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": 0, "roughness": 0.5, "ior": 1e39})"),
         ": /materials/m/ior: number out of range"},
        {with_material(R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": 0, "roughness": 0.5, "kd": [1, 1, 1]})"),
         ": /materials/m/kd: 'kd' applies only to diffuse and phong materials, not pbr"},
        {with_material(
             R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": 0, "roughness": 0.5, "emissive": [1, 1, 1]})"),
         ": /materials/m/emissive: unknown key 'emissive'"},
        {with_material(R"({"type": "conductor", "ks": [1, 1, 1], "roughness": 0.5, "metallic": 1})"),
         ": /materials/m/metallic: 'metallic' applies only to pbr materials, not conductor"},
        {with_material(R"({"type": "dielectric", "roughness": 0.5, "metallic": 0})"),
         ": /materials/m/metallic: 'metallic' applies only to pbr materials, not dielectric"},
        {with_material(R"({"type": "dielectric", "roughness": 1.5})"),
         ": /materials/m/roughness: roughness must lie in [0, 1]"},
        {scene(R"("materials": {"interface": {"type": "diffuse", "kd": [1, 1, 1]}})"),
         ": /materials/interface: 'interface' is reserved: it names the boundary rays cross unchanged (spec §26)"},
        {with_material(R"({"type": "metal"})"),
         ": /materials/m/type: unknown material type 'metal' (expected 'diffuse', 'phong', 'mirror', 'dielectric', "
         "'conductor' or 'pbr')"},
        {with_light(
             R"({"type": "quad", "corner": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [2, 0, 0], "radiance": [1, 1, 1]})"),
         ": /lights/0: quad light edges 'edge1' and 'edge2' are parallel"},
        {with_light(
             R"({"type": "quad", "corner": [0, 0, 0], "edge1": [0, 0, 0], "edge2": [0, 1, 0], "radiance": [1, 1, 1]})"),
         ": /lights/0/edge1: quad light edge 'edge1' is zero"},
        {with_light(
             R"({"type": "quad", "corner": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [0, 1, 0], "radiance": [1, -1, 1]})"),
         ": /lights/0/radiance: colour components must be non-negative"},
        {with_light(R"({"type": "quad", "corner": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [0, 1, 0]})"),
         ": /lights/0/radiance: missing required key 'radiance'"},
        {with_light(
             R"({"type": "quad", "corner": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [0, 1, 0], "radiance": [1, 1, 1], "position": [0, 0, 0]})"),
         ": /lights/0/position: unknown key 'position'"},
        {with_light(R"({"type": "area", "position": [0, 0, 0]})"), ": /lights/0/type: unknown light type 'area'"},
        {with_environment(R"({"file": "sky.exr"})", R"(, "background": [0, 0, 0])"),
         ": /environment: give either 'background' or 'environment', not both"},
        {with_environment(R"({"file": "nothing.exr"})"),
         ": /environment/file: cannot open 'nothing.exr': no such file"},
        {with_environment(R"({"file": "sky.exr", "scale": -1})"), ": /environment/scale: scale must be non-negative"},
        {with_environment(R"({"file": "sky.exr", "scale": "NaN"})"), ": /environment/scale: expected a number"},
        {with_environment(R"({"file": "sky.exr", "rotate_y": 1e39})"), ": /environment/rotate_y: number out of range"},
        {with_environment(R"({"file": "sky.exr", "clamp_negative": 1})"),
         ": /environment/clamp_negative: expected true or false"},
        {with_environment(R"({"file": "sky.exr", "exposure": 1})"), ": /environment/exposure: unknown key 'exposure'"},
    });
}

TEST_F(SceneFileErrors, BadSpotDirectionalAndLensValuesNameWhereAndWhat) {
    const std::string spot = R"("type": "spot", "position": [0, 0, 0], "intensity": [1, 1, 1])";
    const std::string sun = R"("type": "directional")";
    expect_errors({
        {with_light("{" + spot + R"(, "direction": [0, 0, 0]})"), ": /lights/0/direction: direction is zero"},
        {with_light("{" + spot + "}"), ": /lights/0/direction: missing required key 'direction'"},
        {with_light("{" + spot + R"(, "direction": [0, 0, "x"]})"),
         ": /lights/0/direction: expected an array of 3 numbers"},
        {with_light("{" + spot + R"(, "direction": [0, 0, -1], "outer_angle": 0})"),
         ": /lights/0/outer_angle: a spot light's outer_angle must be greater than 0 degrees"},
        {with_light("{" + spot + R"(, "direction": [0, 0, -1], "outer_angle": 91})"),
         ": /lights/0/outer_angle: angle 91 is outside (0, 90] degrees"},
        {with_light("{" + spot + R"(, "direction": [0, 0, -1], "outer_angle": -5})"),
         ": /lights/0/outer_angle: angle -5 is outside (0, 90] degrees"},
        {with_light("{" + spot + R"(, "direction": [0, 0, -1], "inner_angle": -1})"),
         ": /lights/0/inner_angle: angle -1 is outside [0, 90] degrees"},
        {with_light("{" + spot + R"(, "direction": [0, 0, -1], "outer_angle": 30, "inner_angle": 40})"),
         ": /lights/0/inner_angle: inner_angle 40 is larger than outer_angle 30"},
        {with_light("{" + spot + R"(, "direction": [0, 0, -1], "outer_angle": 1e39})"),
         ": /lights/0/outer_angle: number out of range"},
        {with_light("{" + spot + R"(, "direction": [0, 0, -1], "cone": 3})"), ": /lights/0/cone: unknown key 'cone'"},
        {with_light(R"({"type": "spot", "position": [0, 0, 0], "direction": [0, 0, -1], "intensity": [1, -1, 1]})"),
         ": /lights/0/intensity: colour components must be non-negative"},
        {with_light("{" + sun + R"(, "direction": [0, 0, 0], "irradiance": [1, 1, 1]})"),
         ": /lights/0/direction: direction is zero"},
        {with_light("{" + sun + R"(, "direction": [0, 0, -1], "irradiance": [1, 1, -1]})"),
         ": /lights/0/irradiance: colour components must be non-negative"},
        {with_light("{" + sun + R"(, "direction": [0, 0, -1]})"),
         ": /lights/0/irradiance: missing required key 'irradiance'"},
        {with_light("{" + sun + R"(, "direction": [0, 0, -1], "intensity": [1, 1, 1]})"),
         ": /lights/0/intensity: unknown key 'intensity'"},
        {with_light("{" + sun + R"(, "direction": [0, 0, -1], "irradiance": [1, 1, 1], "position": [0, 0, 0]})"),
         ": /lights/0/position: unknown key 'position'"},
        {with_camera(R"({"origin": [0, 0, 5], "look_at": [0, 0, 0], "aperture_radius": -0.1})"),
         ": /camera/aperture_radius: aperture_radius must be >= 0"},
        {with_camera(R"({"origin": [0, 0, 5], "look_at": [0, 0, 0], "aperture_radius": "wide"})"),
         ": /camera/aperture_radius: expected a number"},
        {with_camera(R"({"origin": [0, 0, 5], "look_at": [0, 0, 0], "focus_distance": 0})"),
         ": /camera/focus_distance: focus_distance must be > 0"},
        {with_camera(R"({"origin": [0, 0, 5], "look_at": [0, 0, 0], "focus_distance": -2})"),
         ": /camera/focus_distance: focus_distance must be > 0"},
        {with_camera(R"({"origin": [0, 0, 5], "left": [-1, 0, 0], "up": [0, 1, 0], "forward": [0, 0, -1],
            "aperture_radius": 0.1})"),
         ": /camera: a basis-form camera with 'aperture_radius' > 0 needs 'focus_distance'"},
    });
}

TEST_F(SceneFileErrors, MalformedJsonMessageDropsParserPrefix) {
    try {
        load("{\"objects\" 1}");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.where(), scene_path.string() + ":1:12");
        EXPECT_EQ(e.message(), "syntax error while parsing object separator - unexpected number literal; expected ':'");
    }
}

TEST_F(SceneFileErrors, MissingSceneFileIsAnError) {
    EXPECT_THROW(load_scene_file(dir / "nope.json", diag), Error);
    EXPECT_THROW(load_scene_file(dir / "models", diag), Error);
}

}  // namespace
}  // namespace sombra
