// A scene file's "render" section as RenderSettings (spec §2, §10): the
// integrator, max_depth and texture filter, and what content needs the path
// integrator.
#include <gtest/gtest.h>

#include <string>

#include "io/scene_json/scene_file.h"
#include "io/scene_json/scene_file_fixture.h"

namespace sombra {
namespace {

class SceneRenderSettings : public testing::SceneFileTest {};

TEST_F(SceneRenderSettings, RenderIntegratorAndMaxDepth) {
    const RenderSettings path = settings_of(scene(R"("render": {"integrator": "path", "max_depth": 1024})"));
    EXPECT_EQ(path.integrator, IntegratorKind::Path);
    EXPECT_EQ(path.max_depth, 1024);
    const RenderSettings direct = settings_of(scene(R"("render": {"integrator": "direct", "max_depth": 0})"));
    EXPECT_EQ(direct.integrator, IntegratorKind::Direct);
    EXPECT_EQ(direct.max_depth, 0);
    const RenderSettings defaults = settings_of(scene(""));
    EXPECT_EQ(defaults.integrator, IntegratorKind::Direct);
    EXPECT_EQ(defaults.max_depth, 8);
}

TEST_F(SceneRenderSettings, RenderTextureFilter) {
    EXPECT_EQ(settings_of(scene("")).texture_filter, TextureFilter::Bilinear);
    EXPECT_EQ(settings_of(scene(R"("render": {"texture_filter": "bilinear"})")).texture_filter,
              TextureFilter::Bilinear);
    EXPECT_EQ(settings_of(scene(R"("render": {"texture_filter": "mipmap"})")).texture_filter, TextureFilter::Mipmap);
}

TEST_F(SceneRenderSettings, WhatNeedsThePathIntegrator) {
    EXPECT_FALSE(needs_path_integrator(load(scene(""))));
    // Emission of version 1 does not.
    EXPECT_FALSE(
        needs_path_integrator(load(with_material(R"({"type": "diffuse", "kd": [0, 0, 0], "ke": [5, 5, 5]})"))));
    EXPECT_FALSE(
        needs_path_integrator(load(with_material(R"({"type": "conductor", "ks": [1, 1, 1], "roughness": 0.5})"))));
    EXPECT_TRUE(needs_path_integrator(load(with_material(R"({"type": "mirror", "kr": [1, 1, 1]})"))));
    EXPECT_TRUE(needs_path_integrator(load(with_material(R"({"type": "dielectric"})"))));
    EXPECT_TRUE(needs_path_integrator(load(with_environment(R"({"file": "sky.exr"})"))));
    // A mirror no triangle uses does not.
    EXPECT_FALSE(needs_path_integrator(load(scene(R"("materials": {"m": {"type": "mirror", "kr": [1, 1, 1]}})"))));
}

}  // namespace
}  // namespace sombra
