"""sombra's participating media (spec §26) as Cycles volume shaders.

Imported by tools/cycles/sombra_scene.py inside Blender. A homogeneous
medium is a Volume Scatter (σ_s, HG g) plus a Volume Absorption (σ_a) plus
a Volume Emission: each node's coefficient is density × colour (scatter,
emission) or density × (1 − colour) (absorption), so the colours and
densities below give sombra's coefficients exactly. A grid medium is an
OpenVDB Volume object whose "density" attribute scales σ_a and σ_s, as
sombra's d(x). Cycles 3.4 samples heterogeneous volumes by ray marching
(biased, step rate 1: a voxel), homogeneous ones analytically; each
renderer is measured against its own reference, so that difference counts
only as noise, not as an error.
"""
import os

import bpy


def _colour_and_density(rgb, absorbing=False):
    """(colour, density) whose node coefficient is `rgb` per channel."""
    density = max(max(rgb), 1e-12)
    if absorbing:
        return tuple(1.0 - c / density for c in rgb) + (1.0,), density
    return tuple(c / density for c in rgb) + (1.0,), density


def volume_shader(nodes, links, medium, density_socket=None):
    """The output socket of a volume shader with `medium`'s coefficients,
    each multiplied by `density_socket` (a grid's attribute) when given."""
    scale = medium.get("scale", 1.0)
    sigma_a = [scale * c for c in medium.get("sigma_a", [0, 0, 0])]
    sigma_s = [scale * c for c in medium.get("sigma_s", [0, 0, 0])]
    shaders = []

    def scaled(density):
        if density_socket is None:
            return None
        product = nodes.new("ShaderNodeMath")
        product.operation = "MULTIPLY"
        product.inputs[1].default_value = density
        links.new(density_socket, product.inputs[0])
        return product.outputs[0]

    if max(sigma_s) > 0:
        scatter = nodes.new("ShaderNodeVolumeScatter")
        colour, density = _colour_and_density(sigma_s)
        scatter.inputs["Color"].default_value = colour
        scatter.inputs["Density"].default_value = density
        scatter.inputs["Anisotropy"].default_value = medium.get("g", 0.0)
        if density_socket is not None:
            links.new(scaled(density), scatter.inputs["Density"])
        shaders.append(scatter.outputs[0])
    if max(sigma_a) > 0:
        absorb = nodes.new("ShaderNodeVolumeAbsorption")
        colour, density = _colour_and_density(sigma_a, absorbing=True)
        absorb.inputs["Color"].default_value = colour
        absorb.inputs["Density"].default_value = density
        if density_socket is not None:
            links.new(scaled(density), absorb.inputs["Density"])
        shaders.append(absorb.outputs[0])
    emission = medium.get("emission", [0, 0, 0])
    if max(emission) > 0:
        # Cycles' volume emission is radiance per unit length, as sombra's (not × σ_a).
        emit = nodes.new("ShaderNodeEmission")
        emit.inputs["Color"].default_value = tuple(emission) + (1.0,)
        emit.inputs["Strength"].default_value = 1.0
        shaders.append(emit.outputs[0])
    if not shaders:
        return None
    out = shaders[0]
    for other in shaders[1:]:
        add = nodes.new("ShaderNodeAddShader")
        links.new(out, add.inputs[0])
        links.new(other, add.inputs[1])
        out = add.outputs[0]
    return out


def fill_world(world, medium):
    """The render's medium: a world volume fills the space outside objects."""
    nodes, links = world.node_tree.nodes, world.node_tree.links
    out = next(n for n in nodes if n.type == "OUTPUT_WORLD")
    shader = volume_shader(nodes, links, medium)
    if shader is not None:
        links.new(shader, out.inputs["Volume"])


def interior_material(name, medium, surface=None):
    """A material bounding `medium`: `surface` (a material to copy) around
    it, or none at all for sombra's "interface" (a volume-only object)."""
    mat = surface.copy() if surface is not None else bpy.data.materials.new(name)
    mat.name = name
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    if surface is None:
        nodes.clear()
        nodes.new("ShaderNodeOutputMaterial")
    out = next(n for n in nodes if n.type == "OUTPUT_MATERIAL")
    shader = volume_shader(nodes, links, medium)
    if shader is not None:
        links.new(shader, out.inputs["Volume"])
    return mat


def import_grid(path, grid, matrix, medium, to_blender):
    """A grid medium: the VDB file as a Volume object, placed by its grid's
    transform (Blender applies it), then the sombra object's `matrix`."""
    before = set(bpy.data.objects)
    bpy.ops.object.volume_import(filepath=path, align="WORLD", location=(0, 0, 0))
    objects = [o for o in bpy.data.objects if o not in before]
    mat = bpy.data.materials.new("grid-" + os.path.basename(path))
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    attribute = nodes.new("ShaderNodeAttribute")
    attribute.attribute_name = grid
    shader = volume_shader(nodes, links, medium, attribute.outputs["Fac"])
    links.new(shader, out.inputs["Volume"])
    for obj in objects:
        # The grid's own coordinates are sombra's (y up): only the axes turn.
        obj.matrix_world = to_blender @ matrix
        obj.data.materials.clear()
        obj.data.materials.append(mat)
    return objects
