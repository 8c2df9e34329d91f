"""Build a sombra scene file in Blender and render it with Cycles (issue 21 §4).

Run inside Blender (Debian's `blender` package, 3.4):

  blender -b --factory-startup --python tools/cycles/sombra_scene.py -- \\
      SCENE.json --width W --height H --spp N --seed S --max-depth D --threads T \\
      --out OUT.npy [--blend OUT.blend]

It writes the image as a float32 numpy array (H, W, 3), rows top to bottom,
linear RGB, and OUT.json with the seconds the render operator took (scene
sync, BVH build and path tracing: Cycles' share of the process, as sombra's
`total_seconds` is its share) and the whole script's seconds.

The translation follows sombra's contract (shared/spec/scene-format.md) so
that both renderers converge to the same image, and turns off what would
make Cycles biased or differ from it: no clamping, no light threshold, no
denoiser, no adaptive sampling, a box pixel filter one pixel wide, the
Standard view transform. Cycles' bounces are max_depth − 1 (spec §10).
Supported: the look-at and basis cameras without lens, quad, point, spot
and emissive OBJ/MTL lights, media (tools/cycles/media.py: the render's
medium, homogeneous interiors, grid interiors of interface objects),
`background`, `environment` (equirect map,
scale, rotate_y, clamp_negative), and the materials diffuse, mirror,
dielectric (exact Fresnel, kt on transmission only) and conductor (GGX,
α = r², Schlick with ks). Anything else is refused with a message.
"""
import argparse, json, math, os, sys, time

import bpy
import numpy as np
from mathutils import Matrix, Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import media  # noqa: E402

# sombra is y-up; Blender is z-up. (x, y, z) → (x, −z, y), as the OBJ importer's
# default axes (forward −Z, up Y) do for the vertices.
TO_BLENDER = Matrix(((1, 0, 0, 0), (0, 0, -1, 0), (0, 1, 0, 0), (0, 0, 0, 1)))


def refuse(what):
    sys.stderr.write(f"sombra_scene.py: {what}\n")
    sys.exit(1)


def vec(v):
    return (TO_BLENDER.to_3x3() @ Vector(v))


def transform_matrix(steps):
    """The sombra transform list (applied in order) as a 4×4 in sombra axes."""
    m = Matrix.Identity(4)
    for step in steps or []:
        if "scale" in step:
            s = step["scale"]
            s = [s, s, s] if isinstance(s, (int, float)) else s
            t = Matrix.Diagonal((s[0], s[1], s[2], 1))
        elif "translate" in step:
            t = Matrix.Translation(step["translate"])
        elif "rotate" in step:
            r = step["rotate"]
            t = Matrix.Rotation(math.radians(r.get("degrees", r.get("angle", 0))), 4, Vector(r["axis"]))
        elif "matrix" in step:
            t = Matrix(step["matrix"])
        else:
            refuse(f"transform step {step} is not supported")
        m = t @ m
    return m


def node_material(name):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    return mat, nodes, links, out


def rgb(c, default=(1, 1, 1)):
    c = default if c is None else c
    c = [c, c, c] if isinstance(c, (int, float)) else c
    return (c[0], c[1], c[2], 1.0)


def emission_one_sided(nodes, links, radiance):
    """Emission toward the front (sombra's quad: black from behind)."""
    emit = nodes.new("ShaderNodeEmission")
    emit.inputs["Color"].default_value = rgb(radiance)
    emit.inputs["Strength"].default_value = 1.0
    black = nodes.new("ShaderNodeEmission")
    black.inputs["Strength"].default_value = 0.0
    geometry = nodes.new("ShaderNodeNewGeometry")
    mix = nodes.new("ShaderNodeMixShader")
    links.new(geometry.outputs["Backfacing"], mix.inputs["Fac"])
    links.new(emit.outputs[0], mix.inputs[1])
    links.new(black.outputs[0], mix.inputs[2])
    return mix.outputs[0]


def make_material(name, m):
    mat, nodes, links, out = node_material(name)
    kind = m.get("type", "diffuse")
    if kind == "diffuse":
        bsdf = nodes.new("ShaderNodeBsdfDiffuse")
        bsdf.inputs["Color"].default_value = rgb(m.get("kd"), (0.8, 0.8, 0.8))
        bsdf.inputs["Roughness"].default_value = 0.0
        shader = bsdf.outputs[0]
    elif kind == "mirror":
        bsdf = nodes.new("ShaderNodeBsdfGlossy")
        bsdf.distribution = "SHARP"
        bsdf.inputs["Color"].default_value = rgb(m.get("kr"))
        shader = bsdf.outputs[0]
    elif kind == "dielectric":
        # Exact dielectric Fresnel choosing between a white mirror and a
        # refraction tinted by kt: Cycles' Glass BSDF would tint both.
        ior = m.get("ior", 1.5)
        fresnel = nodes.new("ShaderNodeFresnel")
        fresnel.inputs["IOR"].default_value = ior
        refraction = nodes.new("ShaderNodeBsdfRefraction")
        refraction.distribution = "SHARP"
        refraction.inputs["IOR"].default_value = ior
        refraction.inputs["Color"].default_value = rgb(m.get("kt"))
        reflection = nodes.new("ShaderNodeBsdfGlossy")
        reflection.distribution = "SHARP"
        mix = nodes.new("ShaderNodeMixShader")
        links.new(fresnel.outputs[0], mix.inputs["Fac"])
        links.new(refraction.outputs[0], mix.inputs[1])
        links.new(reflection.outputs[0], mix.inputs[2])
        shader = mix.outputs[0]
    elif kind == "conductor":
        bsdf = nodes.new("ShaderNodeBsdfPrincipled")
        bsdf.distribution = "GGX"
        bsdf.inputs["Base Color"].default_value = rgb(m.get("ks"))
        bsdf.inputs["Metallic"].default_value = 1.0
        bsdf.inputs["Roughness"].default_value = m.get("roughness", 0.0)
        bsdf.inputs["Specular"].default_value = 0.0
        shader = bsdf.outputs[0]
    else:
        refuse(f"material {name}: type {kind} is not supported")
    ke = m.get("ke")
    if ke is not None and max(rgb(ke)[:3]) > 0:
        emit = nodes.new("ShaderNodeEmission")
        emit.inputs["Color"].default_value = rgb(ke)
        add = nodes.new("ShaderNodeAddShader")
        links.new(shader, add.inputs[0])
        links.new(emit.outputs[0], add.inputs[1])
        shader = add.outputs[0]
    links.new(shader, out.inputs["Surface"])
    return mat


def read_mtl(path):
    """name → {"type": "diffuse", "kd", "ke"} from an MTL file (Kd and Ke only)."""
    mats, current = {}, None
    for line in open(path):
        words = line.split()
        if not words:
            continue
        if words[0] == "newmtl":
            current = mats.setdefault(words[1], {"type": "diffuse"})
        elif current is not None and words[0] in ("Kd", "Ke"):
            current[words[0].lower()] = [float(x) for x in words[1:4]]
    return mats


def import_obj(path, matrix, material):
    before = set(bpy.data.objects)
    bpy.ops.wm.obj_import(filepath=path, forward_axis="NEGATIVE_Z", up_axis="Y")
    objects = [o for o in bpy.data.objects if o not in before]
    mtl = {}
    for line in open(path, errors="replace"):
        if line.startswith("mtllib"):
            mtl.update(read_mtl(os.path.join(os.path.dirname(path), line.split(None, 1)[1].strip())))
    for obj in objects:
        obj.matrix_world = TO_BLENDER @ matrix @ TO_BLENDER.inverted() @ obj.matrix_world
        if material is not None:
            obj.data.materials.clear()
            obj.data.materials.append(material)
        else:
            for slot in obj.material_slots:
                name = slot.material.name.split(".")[0] if slot.material else None
                if name not in mtl:
                    refuse(f"{path}: material {name} is not in its MTL")
                slot.material = make_material("mtl-" + name, mtl[name])


def add_quad(index, light):
    p, a, b = Vector(light["corner"]), Vector(light["edge1"]), Vector(light["edge2"])
    corners = [vec(p), vec(p + a), vec(p + a + b), vec(p + b)]
    mesh = bpy.data.meshes.new(f"quad-{index}")
    mesh.from_pydata(corners, [], [(0, 1, 2, 3)])
    mat, nodes, links, out = node_material(f"quad-{index}")
    links.new(emission_one_sided(nodes, links, light["radiance"]), out.inputs["Surface"])
    mesh.materials.append(mat)
    bpy.context.scene.collection.objects.link(bpy.data.objects.new(f"quad-{index}", mesh))


def add_point_or_spot(index, light):
    """A point or spot light of radius 0. Cycles' light of power P has
    radiant intensity P/(4π) W/sr; its spot is a cone of half-angle `outer`
    with a smoothstep blend (and a cosine: sombra's falloff s² is not
    matched exactly)."""
    kind = "POINT" if light["type"] == "point" else "SPOT"
    data = bpy.data.lights.new(f"light-{index}", kind)
    intensity = light["intensity"]
    intensity = [intensity] * 3 if isinstance(intensity, (int, float)) else intensity
    power = max(intensity)
    data.energy = 4 * math.pi * power
    data.color = [c / power for c in intensity] if power > 0 else (0, 0, 0)
    data.shadow_soft_size = 0.0
    obj = bpy.data.objects.new(f"light-{index}", data)
    obj.location = vec(light["position"])
    if kind == "SPOT":
        outer = math.radians(light.get("outer_angle", 45))
        inner = math.radians(light.get("inner_angle", 0))
        data.spot_size = 2 * outer
        data.spot_blend = (math.cos(inner) - math.cos(outer)) / (1 - math.cos(outer))
        # A spot shines down its −z.
        obj.rotation_mode = "QUATERNION"
        obj.rotation_quaternion = vec(light["direction"]).normalized().to_track_quat("-Z", "Y")
    bpy.context.scene.collection.objects.link(obj)


def set_world(scene, spec, base):
    world = bpy.data.worlds.new("world")
    scene.world = world
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    nodes.clear()
    out = nodes.new("ShaderNodeOutputWorld")
    background = nodes.new("ShaderNodeBackground")
    links.new(background.outputs[0], out.inputs["Surface"])
    if "environment" in spec:
        env = spec["environment"]
        image = bpy.data.images.load(os.path.normpath(os.path.join(base, env["file"])))
        image.colorspace_settings.name = "Non-Color"  # linear, as sombra reads it
        texture = nodes.new("ShaderNodeTexEnvironment")
        texture.image = image
        texture.interpolation = "Linear"
        coords = nodes.new("ShaderNodeTexCoord")
        mapping = nodes.new("ShaderNodeMapping")
        mapping.vector_type = "VECTOR"
        # Cycles reads its map at u = 0.5 − atan2(y, x)/2π: +x sees the centre
        # and u grows toward −y. sombra's centre is at −z (Blender's +y) and u
        # grows toward +x: a turn of −90° about z, and rotate_y's R_y(−θ) is
        # R_z(−θ) in Blender's axes.
        mapping.inputs["Rotation"].default_value = (0, 0, math.radians(-90 - env.get("rotate_y", 0)))
        links.new(coords.outputs["Generated"], mapping.inputs["Vector"])
        links.new(mapping.outputs[0], texture.inputs["Vector"])
        colour = texture.outputs["Color"]
        if env.get("clamp_negative", False):
            separate = nodes.new("ShaderNodeSeparateColor")
            combine = nodes.new("ShaderNodeCombineColor")
            links.new(colour, separate.inputs[0])
            for i in range(3):
                clamp = nodes.new("ShaderNodeMath")
                clamp.operation = "MAXIMUM"
                clamp.inputs[1].default_value = 0.0
                links.new(separate.outputs[i], clamp.inputs[0])
                links.new(clamp.outputs[0], combine.inputs[i])
            colour = combine.outputs[0]
        links.new(colour, background.inputs["Color"])
        background.inputs["Strength"].default_value = env.get("scale", 1.0)
    else:
        background.inputs["Color"].default_value = rgb(spec.get("background"), (0, 0, 0))
        background.inputs["Strength"].default_value = 1.0


def set_camera(scene, cam, width, height):
    o = Vector(cam["origin"])
    if "look_at" in cam:
        f = (Vector(cam["look_at"]) - o).normalized()
        up = Vector(cam.get("up", [0, 1, 0]))
        left = up.cross(f).normalized()
        u = f.cross(left).normalized()
        fov = math.radians(cam.get("fov", 45))
    else:
        f, left, u = Vector(cam["forward"]), Vector(cam["left"]), Vector(cam["up"])
        fov = 2 * math.atan(u.length / f.length)
        f, left, u = f.normalized(), left.normalized(), u.normalized()
    if cam.get("aperture_radius", 0) > 0:
        refuse("a thin-lens camera is not supported")
    data = bpy.data.cameras.new("camera")
    data.sensor_fit = "VERTICAL"
    data.angle_y = fov
    data.clip_start = 1e-4
    data.clip_end = 1e6
    obj = bpy.data.objects.new("camera", data)
    # Blender's camera looks down its −z with +y up and +x right (sombra's −left).
    rotation = Matrix((vec(-left), vec(u), vec(-f))).transposed()
    obj.matrix_world = Matrix.Translation(vec(o)) @ rotation.to_4x4()
    scene.collection.objects.link(obj)
    scene.camera = obj


def main():
    argv = sys.argv[sys.argv.index("--") + 1:]
    p = argparse.ArgumentParser()
    p.add_argument("scene")
    p.add_argument("--width", type=int, required=True)
    p.add_argument("--height", type=int, required=True)
    p.add_argument("--spp", type=int, required=True)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--max-depth", type=int, default=8)
    p.add_argument("--threads", type=int, default=0)
    p.add_argument("--out", required=True)
    p.add_argument("--blend")
    a = p.parse_args(argv)
    start = time.perf_counter()
    spec = json.load(open(a.scene))
    base = os.path.dirname(os.path.abspath(a.scene))

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = a.spp
    c.seed = a.seed
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.light_sampling_threshold = 0.0
    c.blur_glossy = 0.0
    c.caustics_reflective = True
    c.caustics_refractive = True
    bounces = max(a.max_depth - 1, 0)
    c.max_bounces = bounces
    c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = bounces
    c.transparent_max_bounces = bounces
    # sombra counts medium events against max_volume_depth only; Cycles
    # counts them against max_bounces as well.
    c.volume_bounces = spec.get("render", {}).get("max_volume_depth", 256)
    c.filter_type = "BOX"
    c.filter_width = 1.0
    scene.render.resolution_x, scene.render.resolution_y = a.width, a.height
    scene.render.resolution_percentage = 100
    if a.threads > 0:
        scene.render.threads_mode = "FIXED"
        scene.render.threads = a.threads
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.image_settings.exr_codec = "NONE"

    materials = {name: make_material(name, m) for name, m in spec.get("materials", {}).items()}
    for index, obj in enumerate(spec.get("objects", [])):
        if "file" not in obj or not obj["file"].endswith(".obj"):
            refuse(f"object {obj} is not an OBJ file")
        if "instances" in obj:
            refuse("instances are not supported")
        path = os.path.normpath(os.path.join(base, obj["file"]))
        matrix = transform_matrix(obj.get("transform"))
        name = obj.get("material")
        surface = None if name in (None, "interface") else materials[name]
        if "interior" in obj:
            medium = spec["media"][obj["interior"]]
            if medium.get("type") == "grid":
                if name != "interface":
                    refuse("a grid medium is supported inside an interface only")
                media.import_grid(os.path.normpath(os.path.join(base, medium["file"])),
                                  medium.get("grid", "density"), matrix, medium, TO_BLENDER)
                continue
            surface = media.interior_material(f"interior-{index}", medium, surface)
        elif name == "interface":
            continue  # crossed unchanged: nothing to draw
        import_obj(path, matrix, surface)
    for i, light in enumerate(spec.get("lights", [])):
        if light["type"] == "quad":
            add_quad(i, light)
        elif light["type"] in ("point", "spot"):
            add_point_or_spot(i, light)
        else:
            refuse(f"light type {light['type']} is not supported")
    set_world(scene, spec, base)
    if "medium" in spec.get("render", {}):
        media.fill_world(scene.world, spec["media"][spec["render"]["medium"]])
    if "medium" in spec["camera"]:
        refuse("a camera medium is not supported")
    set_camera(scene, spec["camera"], a.width, a.height)
    if a.blend:
        bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(a.blend))

    exr = os.path.splitext(a.out)[0] + ".exr"
    scene.render.filepath = exr
    render_start = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    render_seconds = time.perf_counter() - render_start
    image = bpy.data.images.load(exr)
    pixels = np.array(image.pixels[:], dtype=np.float32).reshape(a.height, a.width, 4)[::-1, :, :3]
    np.save(a.out, np.ascontiguousarray(pixels))
    json.dump({"render_seconds": render_seconds, "script_seconds": time.perf_counter() - start},
              open(os.path.splitext(a.out)[0] + ".json", "w"))


if __name__ == "__main__":
    main()
