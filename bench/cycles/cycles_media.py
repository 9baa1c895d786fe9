# Media of a vesper-scene/1 file as Cycles 3.4 volumes: homogeneous fog in a
# box (or the world volume when unbounded), OpenVDB grids as Volume objects.
import os

import bpy
from mathutils import Matrix, Vector

from cycles_common import Y_UP_TO_Z_UP, SceneError, add_mesh_object, check_keys, new_material, vesper_transform

FOG_INSET = 1e-4  # a fog box flush with walls must not share their faces


def volume_shader(tree, output_socket, medium, density=None):
    """Volume Scatter (sigma_s = C * D) + Volume Absorption (sigma_a = (1 - C) * D), PEERS.md.

    density: a socket multiplying both densities (a VDB grid), or None (homogeneous).
    """
    nodes, links = tree.nodes, tree.links
    shaders = []
    sigma_s, sigma_a = medium.get("sigma_s", [1, 1, 1]), medium.get("sigma_a", [0, 0, 0])
    for kind, sigma in (("scatter", sigma_s), ("absorption", sigma_a)):
        peak = max(sigma)
        if peak <= 0:
            continue
        if kind == "scatter":
            node = nodes.new("ShaderNodeVolumeScatter")
            node.inputs["Anisotropy"].default_value = medium.get("g", 0.0)
            color = [c / peak for c in sigma]
        else:
            node = nodes.new("ShaderNodeVolumeAbsorption")
            color = [1.0 - c / peak for c in sigma]
        node.inputs["Color"].default_value = (*color, 1.0)
        node.inputs["Density"].default_value = peak
        if density is not None:
            scaled = nodes.new("ShaderNodeMath")
            scaled.operation = "MULTIPLY"
            scaled.inputs[1].default_value = peak
            links.new(density, scaled.inputs[0])
            links.new(scaled.outputs[0], node.inputs["Density"])
        shaders.append(node.outputs[0])
    while len(shaders) > 1:
        add = nodes.new("ShaderNodeAddShader")
        links.new(shaders.pop(), add.inputs[1])
        links.new(shaders.pop(), add.inputs[0])
        shaders.append(add.outputs[0])
    if shaders:
        links.new(shaders[0], output_socket)


def add_fog_box(name, medium):
    mat, nodes, out = new_material(name)
    mat.cycles.homogeneous_volume = True  # analytic distance sampling
    volume_shader(mat.node_tree, out.inputs["Volume"], medium)
    lo = [c + FOG_INSET for c in medium["bounds"]["min"]]
    hi = [c - FOG_INSET for c in medium["bounds"]["max"]]
    corners = [(x, y, z) for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    add_mesh_object(name, corners, faces, mat)  # no surface shader: the box is only a volume


def add_vdb(name, medium, ptr, scene_dir):
    path = os.path.abspath(os.path.join(scene_dir, medium["file"]))
    if "#" in os.path.basename(medium["file"]):
        raise SceneError(f"{ptr}/file", "per-frame file sequences are not translated")
    if not os.path.isfile(path):
        raise SceneError(f"{ptr}/file", f"VDB file not found: '{path}'")
    volume = bpy.data.volumes.new(name)
    volume.filepath = path
    volume.grids.load()
    grid_name = medium.get("grid", "density")
    grid = volume.grids.get(grid_name)
    if grid is None:
        raise SceneError(f"{ptr}/grid", f"no grid '{grid_name}' in '{path}'")
    volume.render.space = "WORLD"  # else density is integrated over object-space length
    volume.render.precision = "FULL"
    mat, nodes, out = new_material(name)
    attribute = nodes.new("ShaderNodeAttribute")
    attribute.attribute_name = grid_name
    scaled = nodes.new("ShaderNodeMath")
    scaled.operation = "MULTIPLY"
    scaled.inputs[1].default_value = medium.get("density_scale", 1.0)
    mat.node_tree.links.new(attribute.outputs["Fac"], scaled.inputs[0])
    volume_shader(mat.node_tree, out.inputs["Volume"], medium, scaled.outputs[0])
    volume.materials.append(mat)
    obj = bpy.data.objects.new(name, volume)
    # Cycles samples voxel values at cell centres, OpenVDB (and Vesper) at
    # integer index coordinates: shift by -0.5 voxel in the grid's own axes.
    half_voxel = grid.matrix_object.to_3x3() @ Vector((-0.5, -0.5, -0.5))
    transform = vesper_transform(medium.get("transform"), f"{ptr}/transform")
    obj.matrix_world = Y_UP_TO_Z_UP @ transform @ Matrix.Translation(half_voxel)
    bpy.context.scene.collection.objects.link(obj)


def add_media(doc, scene_dir, world):
    unbounded = []
    for name, medium in sorted(doc.get("media", {}).items()):
        ptr = f"/media/{name}"
        kind = medium.get("type")
        if kind == "homogeneous":
            check_keys(medium, ptr, {"type", "sigma_a", "sigma_s", "g", "bounds"})
            if "bounds" in medium:
                add_fog_box(f"fog_{name}", medium)
            else:
                unbounded.append(medium)
        elif kind == "vdb":
            check_keys(medium, ptr, {"type", "file", "grid", "density_scale", "sigma_a", "sigma_s", "g",
                                     "transform"})
            add_vdb(f"vdb_{name}", medium, ptr, scene_dir)
        else:
            raise SceneError(f"{ptr}/type", f"medium type '{kind}' is not translated")
    if len(unbounded) > 1:
        raise SceneError("/media", "more than one unbounded medium is not translated")
    if unbounded:  # fills everything: Cycles' world volume
        out = world.node_tree.nodes["World Output"]
        volume_shader(world.node_tree, out.inputs["Volume"], unbounded[0])
