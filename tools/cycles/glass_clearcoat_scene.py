"""The gallery's glass-and-clearcoat scene, made in Blender (issue 24).

Run inside Blender (Debian's `blender` package, 3.4):

  blender -b --factory-startup --python tools/cycles/glass_clearcoat_scene.py -- OUTDIR [--spp N]

It builds the scene with Blender's own objects and Principled BSDFs — a
glass Suzanne (transmission with a thickness, so the exporter writes
KHR_materials_transmission, _volume and _ior), a frosted glass sphere
(the same at roughness 0.3), a red clear-coated sphere
(KHR_materials_clearcoat), a rough gold sphere, a floor, a sun — and
writes, into OUTDIR:
- scene.glb, exported by Blender's own glTF exporter (io_scene_gltf2) with
  its camera and light;
- scene.json, a sombra scene with that file as its one object, the same
  HDR sky (shared/envmaps/sunset.exr) and the camera's view;
- cycles.npy, Cycles' render (linear RGB, rows top to bottom) at N spp with
  the settings of tools/cycles/sombra_scene.py (no clamping, denoiser,
  light threshold or adaptive sampling; a one-pixel box filter).
tools/cycles/gallery.sh renders scene.json with sombra and puts the two side
by side.
"""
import argparse, json, math, os, sys

import bpy
import numpy as np
from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sombra_scene import set_world  # noqa: E402

WIDTH, HEIGHT, MAX_DEPTH = 640, 360, 16
SKY = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../../shared/envmaps/sunset.exr"))
SKY_ROTATE_Y = 120  # degrees, as sombra's environment `rotate_y`


def principled(name, **inputs):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    for key, value in inputs.items():
        bsdf.inputs[key].default_value = value
    return mat, bsdf


def glass_with_thickness(name, thickness, roughness):
    """Transmission 1 with the exporter's "glTF Material Output" group carrying
    a thickness, so the file says the mesh is a solid (KHR_materials_volume),
    as Cycles renders it."""
    mat, _ = principled(name, **{"Base Color": (0.92, 0.97, 1.0, 1), "Transmission": 1.0, "Roughness": roughness,
                                 "IOR": 1.45})
    group = bpy.data.node_groups.get("glTF Material Output")
    if group is None:
        group = bpy.data.node_groups.new("glTF Material Output", "ShaderNodeTree")
        group.inputs.new("NodeSocketFloat", "Thickness")
    node = mat.node_tree.nodes.new("ShaderNodeGroup")
    node.node_tree = group
    node.inputs["Thickness"].default_value = thickness
    return mat


def add(obj_op, material, location, **kwargs):
    obj_op(location=location, **kwargs)
    obj = bpy.context.active_object
    obj.data.materials.append(material)
    return obj


def build():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    floor, _ = principled("floor", **{"Base Color": (0.5, 0.48, 0.45, 1), "Roughness": 0.7})
    add(bpy.ops.mesh.primitive_plane_add, floor, (0, 0, 0), size=12)

    monkey = add(bpy.ops.mesh.primitive_monkey_add, glass_with_thickness("glass", 0.6, 0.0), (-0.55, 0.1, 0.62),
                 size=1.0)
    monkey.rotation_euler = (math.radians(-20), 0, math.radians(15))
    subdivision = monkey.modifiers.new("subdivision", "SUBSURF")
    subdivision.levels = subdivision.render_levels = 2
    bpy.ops.object.shade_smooth()

    paint, _ = principled("car paint", **{"Base Color": (0.6, 0.02, 0.03, 1), "Roughness": 0.45,
                                          "Clearcoat": 1.0, "Clearcoat Roughness": 0.03})
    add(bpy.ops.mesh.primitive_uv_sphere_add, paint, (1.95, 0.45, 0.45), radius=0.45, segments=64, ring_count=32)
    bpy.ops.object.shade_smooth()
    gold, _ = principled("rough gold", **{"Base Color": (1.0, 0.71, 0.29, 1), "Metallic": 1.0, "Roughness": 0.35})
    add(bpy.ops.mesh.primitive_uv_sphere_add, gold, (-1.95, 0.55, 0.45), radius=0.45, segments=64, ring_count=32)
    bpy.ops.object.shade_smooth()
    frosted = glass_with_thickness("frosted glass", 0.9, 0.3)
    add(bpy.ops.mesh.primitive_uv_sphere_add, frosted, (0.75, 0.2, 0.45), radius=0.45, segments=64, ring_count=32)
    bpy.ops.object.shade_smooth()

    sun = bpy.data.lights.new("sun", "SUN")
    sun.energy = 2.5  # W/m², exported as lux (×683)
    sun.angle = 0.0  # glTF's directional light is a delta light
    sun_object = bpy.data.objects.new("sun", sun)
    sun_object.rotation_euler = (math.radians(50), 0, math.radians(-35))
    scene.collection.objects.link(sun_object)

    camera = bpy.data.cameras.new("camera")
    camera.sensor_fit = "VERTICAL"
    camera.angle_y = math.radians(30)
    camera_object = bpy.data.objects.new("camera", camera)
    camera_object.location = (0.6, -5.2, 2.1)
    camera_object.rotation_euler = (Vector((0, 0, 0.45)) - camera_object.location).to_track_quat("-Z", "Y").to_euler()
    scene.collection.objects.link(camera_object)
    scene.camera = camera_object
    return scene, camera_object


def sombra_camera(camera_object):
    """The camera as sombra's look-at form, in glTF's y-up axes: (x, y, z) → (x, z, −y)."""
    m = camera_object.matrix_world
    to_y_up = lambda v: [v[0], v[2], -v[1]]  # noqa: E731
    origin = m.translation
    forward = -(m.to_3x3().col[2])
    up = m.to_3x3().col[1]
    return {"origin": to_y_up(origin), "look_at": to_y_up(origin + forward), "up": to_y_up(up),
            "fov": math.degrees(camera_object.data.angle_y)}


def main():
    argv = sys.argv[sys.argv.index("--") + 1:]
    p = argparse.ArgumentParser()
    p.add_argument("outdir")
    p.add_argument("--spp", type=int, default=1024)
    a = p.parse_args(argv)
    os.makedirs(a.outdir, exist_ok=True)
    scene, camera_object = build()
    environment = {"file": SKY, "rotate_y": SKY_ROTATE_Y, "clamp_negative": True}
    set_world(scene, {"environment": environment}, a.outdir)
    bpy.ops.export_scene.gltf(filepath=os.path.join(a.outdir, "scene.glb"), export_format="GLB",
                              export_cameras=True, export_lights=True, export_apply=True)
    json.dump({
        "render": {"width": WIDTH, "height": HEIGHT, "spp": a.spp, "integrator": "path", "max_depth": MAX_DEPTH},
        "environment": environment,
        "camera": sombra_camera(camera_object),
        "objects": [{"file": "scene.glb"}],
    }, open(os.path.join(a.outdir, "scene.json"), "w"), indent=2)

    c = scene.cycles
    scene.render.engine = "CYCLES"
    c.device, c.samples, c.seed = "CPU", a.spp, 0
    c.use_adaptive_sampling = c.use_denoising = False
    c.sample_clamp_direct = c.sample_clamp_indirect = c.light_sampling_threshold = c.blur_glossy = 0.0
    c.max_bounces = c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = MAX_DEPTH - 1
    c.volume_bounces = c.transparent_max_bounces = MAX_DEPTH - 1
    c.filter_type, c.filter_width = "BOX", 1.0
    scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = WIDTH, HEIGHT, 100
    scene.view_settings.view_transform, scene.view_settings.look = "Standard", "None"
    settings = scene.render.image_settings
    settings.file_format, settings.color_depth, settings.exr_codec = "OPEN_EXR", "32", "NONE"
    exr = os.path.join(os.path.abspath(a.outdir), "cycles.exr")
    scene.render.filepath = exr
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(exr)
    pixels = np.array(image.pixels[:], dtype=np.float32).reshape(HEIGHT, WIDTH, 4)[::-1, :, :3]
    np.save(os.path.join(a.outdir, "cycles.npy"), np.ascontiguousarray(pixels))


main()
