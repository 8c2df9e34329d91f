// MTL → materials (spec §5, §9): Kd, Ks/Ns (Phong when Ks > 0), Ke, clamping,
// and the default material for faces without a known one.
#include <gtest/gtest.h>

#include "io/mesh_file.h"
#include "io/obj/mtl_scan.h"
#include "io/polygon_test_files.h"

namespace sombra {
namespace {

using testing::shared_dir;
using testing::TempFolder;
namespace fs = std::filesystem;

const Material* find_material(const LoadedMesh& loaded, const std::string& name) {
    for (const Material& m : loaded.materials) {
        if (m.name == name) return &m;
    }
    return nullptr;
}

const Material& material_of(const LoadedMesh& loaded, std::size_t triangle) {
    return loaded.materials.at(loaded.mesh.material_ids.at(triangle));
}

Vec3 face_normal(const TriangleMesh& mesh, std::size_t t) {
    const Index3& c = mesh.triangles[t];
    return normalize(cross(mesh.positions[c[1]] - mesh.positions[c[0]], mesh.positions[c[2]] - mesh.positions[c[0]]));
}

TEST(ObjMaterials, CubeMapsDiffuseAndPhongPerFace) {
    SOMBRA_REQUIRE_SHARED("models");
    Diagnostics diag;
    const LoadedMesh cube = load_obj(shared_dir() / "models/cube.obj", diag);
    EXPECT_TRUE(diag.warnings.empty());
    ASSERT_EQ(cube.mesh.triangle_count(), 12u);

    const Material* red = find_material(cube, "red");
    const Material* white = find_material(cube, "white");
    const Material* blue = find_material(cube, "blue_glossy");
    ASSERT_TRUE(red && white && blue);
    EXPECT_EQ(red->type, MaterialType::Diffuse);
    EXPECT_EQ(red->kd, Vec3(0.7f, 0.1f, 0.1f));
    EXPECT_EQ(white->type, MaterialType::Diffuse);
    EXPECT_EQ(white->kd, Vec3(0.8f));
    EXPECT_EQ(blue->type, MaterialType::Phong);
    EXPECT_EQ(blue->kd, Vec3(0.1f, 0.2f, 0.6f));
    EXPECT_EQ(blue->ks, Vec3(0.3f));
    EXPECT_EQ(blue->shininess, 50.0f);
    EXPECT_EQ(blue->ke, Vec3(0.0f));

    // red on ±x, white on ±y, blue_glossy on ±z.
    for (std::size_t t = 0; t < 12; ++t) {
        const Vec3 n = abs(face_normal(cube.mesh, t));
        const std::string expected = n.x > 0.9f ? "red" : (n.y > 0.9f ? "white" : "blue_glossy");
        EXPECT_EQ(material_of(cube, t).name, expected) << "triangle " << t;
    }
}

TEST(ObjMaterials, CornellBoxLightEmits) {
    SOMBRA_REQUIRE_SHARED("models");
    Diagnostics diag;
    const LoadedMesh box = load_obj(shared_dir() / "models/CornellBox-Original.obj", diag);
    ASSERT_EQ(box.mesh.triangle_count(), 36u);
    EXPECT_EQ(box.mesh.positions.size(), 72u);
    const Material* light = find_material(box, "light");
    ASSERT_NE(light, nullptr);
    EXPECT_EQ(light->ke, Vec3(17, 12, 4));
    int emitting = 0;
    for (std::size_t t = 0; t < box.mesh.triangle_count(); ++t) {
        const Material& m = material_of(box, t);
        EXPECT_EQ(m.type, MaterialType::Diffuse) << m.name;  // all Ks are 0
        if (max_component(m.ke) > 0) {
            ++emitting;
            for (std::uint32_t v : box.mesh.triangles[t]) EXPECT_NEAR(box.mesh.positions[v].y, 1.98f, 1e-4f);
        }
    }
    EXPECT_EQ(emitting, 2);  // the light quad
}

TEST(ObjMaterials, OutOfRangeValuesAreClampedWithWarnings) {
    TempFolder tmp;
    tmp.write("odd.mtl",
              "newmtl odd\nKd 1.5 -0.2 0.5\nKs 2 0 0\nKe -1 5 100\nNs -3\n"
              "newmtl fine\nKd 0.2 0.3 0.4\n");
    const auto obj = tmp.write("odd.obj",
                               "mtllib odd.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                               "usemtl odd\nf 1 2 3\nusemtl fine\nf 1 3 2\n");
    Diagnostics diag;
    const LoadedMesh loaded = load_obj(obj, diag);
    const Material& odd = material_of(loaded, 0);
    EXPECT_EQ(odd.name, "odd");
    EXPECT_EQ(odd.kd, Vec3(1, 0, 0.5f));
    EXPECT_EQ(odd.type, MaterialType::Phong);
    EXPECT_EQ(odd.ks, Vec3(1, 0, 0));
    EXPECT_EQ(odd.shininess, 0.0f);
    EXPECT_EQ(odd.ke, Vec3(0, 5, 100));  // radiance: only the negative part goes
    int clamped = 0;
    for (const std::string& w : diag.warnings) {
        if (w.find("clamped") == std::string::npos) continue;
        ++clamped;
        EXPECT_NE(w.find("odd.mtl"), std::string::npos) << w;
        EXPECT_NE(w.find("'odd'"), std::string::npos) << w;
    }
    EXPECT_EQ(clamped, 4);  // Kd, Ks, Ke, Ns
    const Material& fine = material_of(loaded, 1);
    EXPECT_EQ(fine.type, MaterialType::Diffuse);
    EXPECT_EQ(fine.kd, Vec3(0.2f, 0.3f, 0.4f));
}

TEST(ObjMaterials, PhongThatReflectsMoreThanItReceivesWarns) {
    TempFolder tmp;
    tmp.write("e.mtl",
              "newmtl hot\nKd 0.8 0.2 0.2\nKs 0.5 0.5 0.5\nNs 10\nnewmtl ok\nKd 0.5 0.2 0.2\nKs 0.5 0.5 0.5\n");
    const auto obj =
        tmp.write("e.obj", "mtllib e.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl hot\nf 1 2 3\nusemtl ok\nf 1 3 2\n");
    Diagnostics diag;
    const LoadedMesh loaded = load_obj(obj, diag);
    ASSERT_EQ(diag.warnings.size(), 1u);
    EXPECT_NE(diag.warnings[0].find("'hot'"), std::string::npos) << diag.warnings[0];
    EXPECT_NE(diag.warnings[0].find("exceeds 1"), std::string::npos) << diag.warnings[0];
    EXPECT_EQ(material_of(loaded, 0).kd, Vec3(0.8f, 0.2f, 0.2f));  // warned, not changed
}

TEST(ObjMaterials, MissingMtlAndUnknownNamesGetTheDefault) {
    TempFolder tmp;
    tmp.write("known.mtl", "newmtl known\nKd 0.1 0.2 0.3\n");
    const auto obj = tmp.write("m.obj",
                               "mtllib absent.mtl\nmtllib known.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                               "f 1 2 3\nusemtl known\nf 1 3 2\nusemtl nowhere\nf 2 1 3\n");
    Diagnostics diag;
    const LoadedMesh loaded = load_obj(obj, diag);
    ASSERT_EQ(loaded.mesh.triangle_count(), 3u);
    const Material& none = material_of(loaded, 0);
    EXPECT_EQ(none.type, MaterialType::Diffuse);
    EXPECT_EQ(none.kd, Vec3(0.8f));
    EXPECT_EQ(material_of(loaded, 1).kd, Vec3(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(loaded.mesh.material_ids[2], loaded.mesh.material_ids[0]);  // the same default
    bool missing_file = false, unknown_name = false;
    for (const std::string& w : diag.warnings) {
        missing_file |= w.find("absent.mtl") != std::string::npos;
        unknown_name |= w.find("nowhere") != std::string::npos;
    }
    EXPECT_TRUE(missing_file);
    EXPECT_TRUE(unknown_name);
}

TEST(ObjMaterials, NoMtlAtAllGivesOneDefaultMaterial) {
    TempFolder tmp;
    Diagnostics diag;
    const LoadedMesh loaded = load_obj(tmp.write("plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), diag);
    ASSERT_EQ(loaded.materials.size(), 1u);
    EXPECT_EQ(loaded.materials[0].kd, default_material().kd);
    EXPECT_EQ(loaded.mesh.material_ids, std::vector<std::uint32_t>{0});
    EXPECT_TRUE(diag.warnings.empty());
}

// MTL version 2 (spec §11): illum 5 is a mirror with kr = Ks, illum 7 glass
// with ior = Ni (1.5 when missing or <= 1) and kt = Tf (1 when missing).
TEST(ObjMaterials, Illum5IsAMirrorAndIllum7Glass) {
    TempFolder folder;
    folder.write("m.mtl",
                 "newmtl mirror\nKs 0.9 0.8 0.7\nillum 5\n"
                 "newmtl glass\nNi 1.33\nTf 0.9 1 0.8\nillum 7\n"
                 "newmtl plain_glass\nillum 7\n"
                 "newmtl low_ni\nNi 0.9\nillum 7\nKe 1 2 3\n"
                 "newmtl phong\nKd 0.2 0.2 0.2\nKs 0.5 0.5 0.5\nillum 2\n");
    const fs::path obj = folder.write("m.obj",
                                      "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                      "usemtl mirror\nf 1 2 3\nusemtl glass\nf 1 2 3\nusemtl plain_glass\nf 1 2 3\n"
                                      "usemtl low_ni\nf 1 2 3\nusemtl phong\nf 1 2 3\n");
    Diagnostics diag;
    const LoadedMesh loaded = load_obj(obj, diag);
    EXPECT_TRUE(diag.warnings.empty()) << diag.warnings.front();
    ASSERT_EQ(loaded.mesh.triangle_count(), 5u);

    const Material& mirror = material_of(loaded, 0);
    EXPECT_EQ(mirror.type, MaterialType::Mirror);
    EXPECT_EQ(mirror.kr, (Vec3{0.9f, 0.8f, 0.7f}));

    const Material& glass = material_of(loaded, 1);
    EXPECT_EQ(glass.type, MaterialType::Dielectric);
    EXPECT_FLOAT_EQ(glass.ior, 1.33f);
    EXPECT_EQ(glass.kt, (Vec3{0.9f, 1.0f, 0.8f}));

    const Material& plain = material_of(loaded, 2);
    EXPECT_EQ(plain.type, MaterialType::Dielectric);
    EXPECT_EQ(plain.ior, 1.5f);
    EXPECT_EQ(plain.kt, Vec3{1.0f});

    const Material& low = material_of(loaded, 3);
    EXPECT_EQ(low.type, MaterialType::Dielectric);
    EXPECT_EQ(low.ior, 1.5f);
    EXPECT_EQ(low.ke, (Vec3{1, 2, 3}));

    EXPECT_EQ(material_of(loaded, 4).type, MaterialType::Phong);
}

// MTL's PBR extension (spec §11): Pr or Pm makes a pbr material with
// base_color = Kd, roughness = Pr, metallic = Pm (a missing one 0, as
// tinyobjloader gives it), ior = Ni when > 1; illum 5 and 7 still win.
TEST(ObjMaterials, PrAndPmMakeAPbrMaterial) {
    TempFolder folder;
    folder.write("m.mtl",
                 "newmtl plastic\nKd 0.8 0.1 0.1\nKs 0.5 0.5 0.5\nNi 1.45\nPr 0.3\nPm 0\n"
                 "newmtl rough_only\r\nKd 0.2 0.3 0.4\r\n  Pr\t0.6  \r\n"
                 "newmtl metal_only\nKd 0.9 0.8 0.5\nPm 1\n"
                 "newmtl smooth\nPr 0\nPm 0\n"
                 "newmtl mirror\nKs 1 1 1\nPm 1\nillum 5\n"
                 "newmtl out_of_range\nKd 0.5 0.5 0.5\nPr 1.5\nPm -2\n"
                 "newmtl phong\nKd 0.2 0.2 0.2\nKs 0.5 0.5 0.5\n# Pr 0.5\nPrx 0.5\nmap_Pr r.png\n");
    const fs::path obj =
        folder.write("m.obj",
                     "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                     "usemtl plastic\nf 1 2 3\nusemtl rough_only\nf 1 2 3\nusemtl metal_only\nf 1 2 3\n"
                     "usemtl smooth\nf 1 2 3\nusemtl mirror\nf 1 2 3\nusemtl out_of_range\nf 1 2 3\n"
                     "usemtl phong\nf 1 2 3\n");
    Diagnostics diag;
    const LoadedMesh loaded = load_obj(obj, diag);
    ASSERT_EQ(loaded.mesh.triangle_count(), 7u);

    const Material& plastic = material_of(loaded, 0);
    EXPECT_EQ(plastic.type, MaterialType::Pbr);
    EXPECT_EQ(plastic.base_color, (Vec3{0.8f, 0.1f, 0.1f}));
    EXPECT_EQ(plastic.roughness, 0.3f);
    EXPECT_EQ(plastic.metallic, 0.0f);
    EXPECT_FLOAT_EQ(plastic.ior, 1.45f);

    const Material& rough = material_of(loaded, 1);  // CRLF lines, blanks around
    EXPECT_EQ(rough.type, MaterialType::Pbr);
    EXPECT_EQ(rough.base_color, (Vec3{0.2f, 0.3f, 0.4f}));
    EXPECT_EQ(rough.roughness, 0.6f);
    EXPECT_EQ(rough.metallic, 0.0f);
    EXPECT_EQ(rough.ior, 1.5f);  // no Ni

    const Material& metal = material_of(loaded, 2);
    EXPECT_EQ(metal.type, MaterialType::Pbr);
    EXPECT_EQ(metal.metallic, 1.0f);
    EXPECT_EQ(metal.roughness, 0.0f);  // Pr missing: tinyobjloader's 0

    const Material& smooth = material_of(loaded, 3);  // stated, even as zeros
    EXPECT_EQ(smooth.type, MaterialType::Pbr);
    EXPECT_EQ(smooth.base_color, Vec3{0.0f});  // Kd missing: tinyobjloader's 0

    EXPECT_EQ(material_of(loaded, 4).type, MaterialType::Mirror);

    const Material& clamped = material_of(loaded, 5);
    EXPECT_EQ(clamped.type, MaterialType::Pbr);
    EXPECT_EQ(clamped.roughness, 1.0f);
    EXPECT_EQ(clamped.metallic, 0.0f);
    ASSERT_EQ(diag.warnings.size(), 2u);
    EXPECT_NE(diag.warnings[0].find("material 'out_of_range': Pr 1.5 clamped to [0, 1]"), std::string::npos)
        << diag.warnings[0];
    EXPECT_NE(diag.warnings[1].find("material 'out_of_range': Pm -2 clamped to [0, 1]"), std::string::npos)
        << diag.warnings[1];

    EXPECT_EQ(material_of(loaded, 6).type, MaterialType::Phong);  // a comment, Prx and map_Pr are not Pr
}

TEST(ObjMaterials, PbrKeyScanFollowsTinyobjloadersMaterialOrder) {
    // Keys before the first newmtl belong to no material; "newmtl" alone names
    // none (the blank after it is trimmed), so its keys go to the one before;
    // the last material is always added.
    const std::vector<MtlPbrKeys> keys =
        scan_mtl_pbr_keys("Pr 0.5\nnewmtl a\nPm 1\nnewmtl \nPr 1\nnewmtl b\rPr 0.1\rnewmtl c\n\tPm\t0.2");
    ASSERT_EQ(keys.size(), 3u);
    EXPECT_TRUE(keys[0].roughness && keys[0].metallic);
    EXPECT_TRUE(keys[1].roughness && !keys[1].metallic);
    EXPECT_TRUE(!keys[2].roughness && keys[2].metallic);
    EXPECT_EQ(scan_mtl_pbr_keys("").size(), 1u);
}

}  // namespace
}  // namespace sombra
