// Scene files' "instances" (spec §23): what a list becomes in the scene
// model (one stored mesh, one Instance an entry, the object's transform
// applied first), the single-entry case flattened, and hostile lists as
// one error naming where and what.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "io/scene_json/scene_file.h"
#include "io/scene_json/scene_file_fixture.h"
#include "scene/scene_builder.h"

namespace sombra {
namespace {

class SceneInstances : public testing::SceneFileTest {};

TEST_F(SceneInstances, AListStoresTheMeshOnceAndPlacesEachEntryAfterTheObjectsTransform) {
    const Scene s = load(with_objects(R"({"file": "tri.obj"},
        {"file": "tri.obj", "transform": [{"scale": 2}],
         "instances": [[], [{"translate": [10, 0, 0]}], [{"scale": [-1, 1, 1]}]]})"));
    ASSERT_EQ(s.instanced_meshes.size(), 1u);
    ASSERT_EQ(s.instances.size(), 3u);
    EXPECT_EQ(s.geometry.triangle_count(), 1u) << "the first object alone is in the world geometry";
    EXPECT_EQ(s.instanced_meshes[0].positions[0], (Vec3{1, 0, 0})) << "the mesh keeps its own coordinates";
    EXPECT_EQ(stored_triangle_count(s), 2u);
    EXPECT_EQ(drawn_triangle_count(s), 4u);
    ASSERT_EQ(s.objects.size(), 2u);
    EXPECT_EQ(s.objects[1].name, "/objects/1");
    EXPECT_EQ(s.objects[1].first_instance, 0u);
    EXPECT_EQ(s.objects[1].instance_count, 3u);
    // Scale 2 first, then the instance's translation: (1, 0, 0) → (12, 0, 0).
    EXPECT_EQ(transform_point(s.instances[1].object_to_world, {1, 0, 0}), (Vec3{12, 0, 0}));
    EXPECT_EQ(transform_point(s.instances[1].world_to_object, {12, 0, 0}), (Vec3{1, 0, 0}));
    EXPECT_FALSE(s.instances[0].mirrored);
    EXPECT_TRUE(s.instances[2].mirrored);
    for (const Instance& i : s.instances) {
        EXPECT_EQ(i.mesh, 0u);
        EXPECT_EQ(i.object, 1u);
    }
}

TEST_F(SceneInstances, OneEntryIsAFlattenedCopy) {
    const Scene s = load(with_objects(
        R"({"file": "tri.obj", "transform": [{"scale": 2}], "instances": [[{"translate": [10, 0, 0]}]]})"));
    EXPECT_TRUE(s.instances.empty());
    ASSERT_EQ(s.geometry.triangle_count(), 1u);
    EXPECT_EQ(s.geometry.positions[0], (Vec3{12, 0, 0}));
    EXPECT_EQ(drawn_triangle_count(s), 1u);
}

TEST_F(SceneInstances, HostileListsNameWhereAndWhat) {
    expect_errors({
        {with_objects(R"({"file": "tri.obj", "instances": {}})"), ": /objects/0/instances: expected an array"},
        {with_objects(R"({"file": "tri.obj", "instances": []})"),
         ": /objects/0/instances: expected at least one instance (each a transform list)"},
        {with_objects(R"({"file": "tri.obj", "instances": [[], 3]})"), ": /objects/0/instances/1: expected an array"},
        {with_objects(R"({"file": "tri.obj", "instances": [[], [{"scale": 0}]]})"),
         ": /objects/0/instances/1/0/scale: scale must be non-zero (it would flatten the object)"},
        {with_objects(R"({"file": "tri.obj", "instances": [[], [{"scale": 1e39}]]})"),
         ": /objects/0/instances/1/0/scale: number out of range"},
        // Each list alone is fine; together they scale x by 1e-50: not invertible in float.
        {with_objects(
             R"({"file": "tri.obj", "transform": [{"scale": [1e-20, 1, 1]}], "instances": [[], [{"scale": [1e-30, 1, 1]}]]})"),
         ": /objects/0/instances/1: the object's transform and this instance together are not invertible"},
        {with_objects(
             R"({"file": "tri.obj", "transform": [{"scale": [1e20, 1, 1]}], "instances": [[], [{"scale": [1e20, 1, 1]}]]})"),
         ": /objects/0/instances/1: a transformed vertex is not finite"},
    });
}

}  // namespace
}  // namespace sombra
