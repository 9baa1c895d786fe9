# Builds the Blender Cycles 3.4 equivalent of a vesper-scene/1 file from
# scratch and renders it (bench/cycles/README.md: what translates exactly,
# what approximately, what is refused). Run it with
#   blender -b --factory-startup --python bench/cycles/vesper_to_cycles.py -- \
#     --scene S.json --spp N --seed K --threads T --width W --height H \
#     --out OUT.exr --stats OUT.json
# Writes OUT.exr (scene-linear float RGBA) and OUT.json (render_seconds of
# bpy.ops.render.render() only, blender_version, samples). Anything it cannot
# translate exits with status 2 and "<scene>: <JSON pointer>: <why>": never a
# silently different scene. Units follow PEERS.md (as measured on Cycles 3.4).
import argparse
import json
import math
import os
import struct
import sys
import time

import bpy
from mathutils import Matrix, Vector

# Vesper is Y-up, Blender Z-up, both right-handed: (x, y, z) -> (x, -z, y).
Y_UP_TO_Z_UP = Matrix(((1, 0, 0, 0), (0, 0, -1, 0), (0, 1, 0, 0), (0, 0, 0, 1)))
FOG_INSET = 1e-4  # a fog box flush with walls must not share their faces


class SceneError(Exception):
    def __init__(self, pointer, message):
        super().__init__(message)
        self.pointer = pointer


def to_blender(v):
    return Vector((v[0], -v[2], v[1]))


def check_keys(obj, pointer, allowed):
    if not isinstance(obj, dict):
        raise SceneError(pointer, "expected an object")
    for key in obj:
        if key not in allowed:
            raise SceneError(f"{pointer}/{key}", f"key '{key}' is not translated to Cycles "
                             f"(translated here: {', '.join(sorted(allowed))})")


def reject_keyframes(value, pointer):
    # Keyed values change over frames; the bench renders one still frame.
    if isinstance(value, dict):
        if "keys" in value:
            raise SceneError(pointer, "keyframed values are not translated to Cycles")
        for key, child in value.items():
            reject_keyframes(child, f"{pointer}/{key}")
    elif isinstance(value, list):
        for i, child in enumerate(value):
            reject_keyframes(child, f"{pointer}/{i}")


def rgb_strength(rgb):
    """(colour with max 1, strength): Blender colours are meant to stay in [0, 1]."""
    peak = max(rgb)
    if peak <= 0:
        return (0.0, 0.0, 0.0), 0.0
    return tuple(c / peak for c in rgb), peak


# ---------------------------------------------------------------- transforms
def vesper_transform(spec, pointer):
    """The docs' "Transforms": scale, then rotate, then translate; or a row-major matrix."""
    if spec is None:
        return Matrix.Identity(4)
    check_keys(spec, pointer, {"translate", "rotate", "scale", "matrix"})
    if "matrix" in spec:
        m = spec["matrix"]
        return Matrix([m[0:4], m[4:8], m[8:12], m[12:16]])
    scale = spec.get("scale", 1.0)
    s = [scale] * 3 if isinstance(scale, (int, float)) else scale
    result = Matrix.Diagonal((s[0], s[1], s[2], 1.0))
    if "rotate" in spec:
        check_keys(spec["rotate"], f"{pointer}/rotate", {"axis", "angle"})
        rot = spec["rotate"]
        result = Matrix.Rotation(math.radians(rot["angle"]), 4, Vector(rot["axis"]).normalized()) @ result
    return Matrix.Translation(Vector(spec.get("translate", [0, 0, 0]))) @ result


# -------------------------------------------------------------------- meshes
def read_obj(path):
    positions, triangles = [], []
    with open(path, encoding="utf-8", errors="replace") as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                positions.append(tuple(float(x) for x in parts[1:4]))
            elif parts[0] == "f":
                idx = []
                for p in parts[1:]:
                    i = int(p.split("/")[0])
                    idx.append(i - 1 if i > 0 else len(positions) + i)
                triangles += [(idx[0], idx[k], idx[k + 1]) for k in range(1, len(idx) - 1)]
    return positions, triangles


PLY_TYPES = {"char": "b", "int8": "b", "uchar": "B", "uint8": "B", "short": "h", "int16": "h",
             "ushort": "H", "uint16": "H", "int": "i", "int32": "i", "uint": "I", "uint32": "I",
             "float": "f", "float32": "f", "double": "d", "float64": "d"}


def read_ply(path):
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header") + len(b"end_header")
    end = data.index(b"\n", end) + 1
    fmt, elements = None, []
    for line in data[:end].decode("ascii", "replace").splitlines():
        p = line.split()
        if p and p[0] == "format":
            fmt = p[1]
        elif p and p[0] == "element":
            elements.append((p[1], int(p[2]), []))
        elif p and p[0] == "property":
            elements[-1][2].append(p[1:])
    body, tokens = data[end:], None
    if fmt == "ascii":
        tokens = iter(body.split())
    order = {"binary_little_endian": "<", "binary_big_endian": ">"}.get(fmt, "<")
    offset, positions, triangles = 0, [], []

    def read(kind):
        nonlocal offset
        if tokens is not None:
            return float(next(tokens)) if PLY_TYPES[kind] in "fd" else int(next(tokens))
        code = order + PLY_TYPES[kind]
        value = struct.unpack_from(code, body, offset)[0]
        offset += struct.calcsize(code)
        return value

    for name, count, props in elements:
        for _ in range(count):
            values = {}
            for prop in props:
                if prop[0] == "list":
                    values[prop[3]] = [read(prop[2]) for _ in range(read(prop[1]))]
                else:
                    values[prop[1]] = read(prop[0])
            if name == "vertex":
                positions.append((values["x"], values["y"], values["z"]))
            elif name == "face":
                idx = values.get("vertex_indices", values.get("vertex_index", []))
                triangles += [(idx[0], idx[k], idx[k + 1]) for k in range(1, len(idx) - 1)]
    return positions, triangles


def add_mesh_object(name, positions, faces, material):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([to_blender(p) for p in positions], [], faces)
    mesh.validate()
    mesh.materials.append(material)  # flat shading: Vesper uses geometric normals
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def quad_positions(s):
    c, e1, e2 = Vector(s["corner"]), Vector(s["edge1"]), Vector(s["edge2"])
    return [c, c + e1, c + e1 + e2, c + e2]  # counter-clockwise about cross(e1, e2)


def add_sphere(name, center, radius, material):
    # A one-point point cloud renders as an exact sphere in Cycles 3.4.
    tree = bpy.data.node_groups.new(name, "GeometryNodeTree")
    tree.outputs.new("NodeSocketGeometry", "Geometry")
    points = tree.nodes.new("GeometryNodePoints")
    points.inputs["Count"].default_value = 1
    points.inputs["Position"].default_value = to_blender(center)
    points.inputs["Radius"].default_value = radius
    set_mat = tree.nodes.new("GeometryNodeSetMaterial")
    set_mat.inputs["Material"].default_value = material
    out = tree.nodes.new("NodeGroupOutput")
    tree.links.new(points.outputs["Geometry"], set_mat.inputs["Geometry"])
    tree.links.new(set_mat.outputs["Geometry"], out.inputs["Geometry"])
    obj = bpy.data.objects.new(name, bpy.data.meshes.new(name))
    obj.modifiers.new("sphere", "NODES").node_group = tree
    bpy.context.scene.collection.objects.link(obj)


def add_shapes(doc, materials, scene_dir):
    for i, s in enumerate(doc["shapes"]):
        ptr = f"/shapes/{i}"
        kind = s.get("type")
        material = materials[s["material"]]
        if kind == "quad":
            check_keys(s, ptr, {"type", "corner", "edge1", "edge2", "material", "name"})
            add_mesh_object(f"quad{i}", quad_positions(s), [(0, 1, 2, 3)], material)
        elif kind == "sphere":
            check_keys(s, ptr, {"type", "center", "radius", "material", "name"})
            add_sphere(f"sphere{i}", s["center"], s["radius"], material)
        elif kind == "mesh":
            check_keys(s, ptr, {"type", "file", "positions", "indices", "transform", "material", "name"})
            if "file" in s:
                path = os.path.join(scene_dir, s["file"])
                if "#" in os.path.basename(s["file"]):
                    raise SceneError(f"{ptr}/file", "per-frame file sequences are not translated")
                reader = read_ply if path.lower().endswith(".ply") else read_obj
                positions, tris = reader(path)
            else:
                p, idx = s["positions"], s["indices"]
                positions = [p[k:k + 3] for k in range(0, len(p), 3)]
                tris = [tuple(idx[k:k + 3]) for k in range(0, len(idx), 3)]
            m = vesper_transform(s.get("transform"), f"{ptr}/transform")
            add_mesh_object(f"mesh{i}", [m @ Vector(p) for p in positions], tris, material)
        else:
            raise SceneError(f"{ptr}/type", f"shape type '{kind}' is not translated")


# ----------------------------------------------------------------- materials
def new_material(name):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    return mat, nodes, nodes["Material Output"]


def normal_incidence_reflectance(eta, k):
    # Conductor Fresnel at normal incidence: ((n-1)^2 + k^2) / ((n+1)^2 + k^2).
    return [((n - 1) ** 2 + kk ** 2) / ((n + 1) ** 2 + kk ** 2) for n, kk in zip(eta, k)]


def principled_node(nodes, base_color, metallic, roughness):
    node = nodes.new("ShaderNodeBsdfPrincipled")
    node.distribution = "GGX"  # single scattering, as Vesper
    node.inputs["Base Color"].default_value = (*base_color, 1.0)
    node.inputs["Metallic"].default_value = metallic
    node.inputs["Roughness"].default_value = roughness
    node.inputs["Specular"].default_value = 0.5  # F0 = 0.08 * 0.5 = 0.04, as Vesper
    node.inputs["Specular Tint"].default_value = 0.0
    node.inputs["Sheen Tint"].default_value = 0.0
    return node


def translate_material(name, m, ptr):
    kind = m.get("type")
    mat, nodes, out = new_material(name)
    if kind == "diffuse":
        check_keys(m, ptr, {"type", "albedo"})
        node = nodes.new("ShaderNodeBsdfDiffuse")  # roughness 0: Lambert
        node.inputs["Color"].default_value = (*m.get("albedo", [0.8] * 3), 1.0)
        node.inputs["Roughness"].default_value = 0.0
    elif kind == "dielectric":
        check_keys(m, ptr, {"type", "ior", "roughness"})
        node = nodes.new("ShaderNodeBsdfGlass")
        roughness = m.get("roughness", 0.0)
        node.distribution = "SHARP" if roughness == 0 else "GGX"
        node.inputs["Roughness"].default_value = roughness  # Cycles squares it, as Vesper
        node.inputs["IOR"].default_value = m.get("ior", 1.5)
        node.inputs["Color"].default_value = (1, 1, 1, 1)
    elif kind == "conductor":
        # Approximate: Cycles 3.4 has no complex-IOR Fresnel; Principled metallic
        # uses Schlick from the normal-incidence reflectance of eta, k.
        check_keys(m, ptr, {"type", "eta", "k", "roughness"})
        f0 = normal_incidence_reflectance(m.get("eta", [0.2, 0.92, 1.1]), m.get("k", [3.9, 2.45, 2.14]))
        node = principled_node(nodes, f0, 1.0, m.get("roughness", 0.0))
    elif kind == "principled":
        # Approximate diffuse: Cycles' Burley lacks Vesper's Frostbite renormalisation.
        check_keys(m, ptr, {"type", "base_color", "metallic", "roughness"})
        node = principled_node(nodes, m.get("base_color", [0.8] * 3), m.get("metallic", 0.0),
                               m.get("roughness", 0.5))
    else:
        raise SceneError(f"{ptr}/type", f"material type '{kind}' is not translated")
    mat.node_tree.links.new(node.outputs[0], out.inputs["Surface"])
    return mat


# -------------------------------------------------------------------- lights
def one_sided_emission(name, radiance):
    # Emission only on the front face (Vesper quad lights are one-sided); the
    # back is black and opaque, like Vesper's.
    mat, nodes, out = new_material(name)
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Color"].default_value = (*radiance, 1.0)
    geometry = nodes.new("ShaderNodeNewGeometry")
    front = nodes.new("ShaderNodeMath")
    front.operation = "SUBTRACT"
    front.inputs[0].default_value = 1.0
    links = mat.node_tree.links
    links.new(geometry.outputs["Backfacing"], front.inputs[1])
    links.new(front.outputs[0], emission.inputs["Strength"])
    links.new(emission.outputs[0], out.inputs["Surface"])
    return mat


def point_toward(obj, direction_yup):
    # Blender lights shine along their local -Z: turn it to `direction_yup`.
    obj.rotation_euler = to_blender(direction_yup).to_track_quat("-Z", "Y").to_euler()


def add_light_object(name, kind, position=None):
    light = bpy.data.lights.new(name, kind)
    obj = bpy.data.objects.new(name, light)
    if position is not None:
        obj.location = to_blender(position)
    bpy.context.scene.collection.objects.link(obj)
    return light, obj


def cancel_spot_cosine(light, axis_yup):
    # Cycles 3.4 spot lights carry an extra cos(theta) (PEERS.md); a strength
    # of 1 / |Incoming . axis| in the light's shader cancels it (measured
    # against the analytic irradiance under a 60-degree spot: bench/cycles/README.md).
    light.use_nodes = True
    nodes, links = light.node_tree.nodes, light.node_tree.links
    geometry = nodes.new("ShaderNodeNewGeometry")
    cosine = nodes.new("ShaderNodeVectorMath")
    cosine.operation = "DOT_PRODUCT"
    links.new(geometry.outputs["Incoming"], cosine.inputs[0])
    cosine.inputs[1].default_value = to_blender(axis_yup).normalized()
    magnitude = nodes.new("ShaderNodeMath")
    magnitude.operation = "ABSOLUTE"
    links.new(cosine.outputs["Value"], magnitude.inputs[0])
    inverse = nodes.new("ShaderNodeMath")
    inverse.operation = "DIVIDE"
    inverse.inputs[0].default_value = 1.0
    links.new(magnitude.outputs[0], inverse.inputs[1])
    links.new(inverse.outputs[0], nodes["Emission"].inputs["Strength"])


def add_point_or_spot(i, lt, ptr):
    color, peak = rgb_strength(lt["intensity"])
    light, obj = add_light_object(f"light{i}", lt["type"].upper(), lt["position"])
    light.color = color
    light.energy = 4.0 * math.pi * peak  # Cycles: I = P / (4 pi)
    light.shadow_soft_size = lt.get("radius", 0.0)
    obj.visible_camera = False  # Vesper's sphere lights are not seen by the camera
    if lt["type"] == "spot":
        cone, falloff = lt["cone_angle"], lt.get("falloff_start", lt["cone_angle"])
        if cone > 90:
            raise SceneError(f"{ptr}/cone_angle", "a cone wider than 90 degrees has no Cycles spot")
        light.spot_size = math.radians(2.0 * cone)  # Cycles: the full cone
        cos_a, cos_f = math.cos(math.radians(cone)), math.cos(math.radians(falloff))
        light.spot_blend = (cos_f - cos_a) / (1.0 - cos_a)
        point_toward(obj, lt["direction"])
        cancel_spot_cosine(light, lt["direction"])


def add_lights(doc, world_nodes):
    for i, lt in enumerate(doc.get("lights", [])):
        ptr = f"/lights/{i}"
        kind = lt.get("type")
        if kind == "quad":
            check_keys(lt, ptr, {"type", "corner", "edge1", "edge2", "radiance", "group"})
            mat = one_sided_emission(f"quadlight{i}", lt["radiance"])
            add_mesh_object(f"quadlight{i}", quad_positions(lt), [(0, 1, 2, 3)], mat)
        elif kind in ("point", "spot"):
            allowed = {"type", "position", "intensity", "radius", "group"}
            if kind == "spot":
                allowed |= {"direction", "cone_angle", "falloff_start"}
            check_keys(lt, ptr, allowed)
            add_point_or_spot(i, lt, ptr)
        elif kind == "sun":
            check_keys(lt, ptr, {"type", "direction", "irradiance", "angle", "group"})
            color, peak = rgb_strength(lt["irradiance"])
            light, obj = add_light_object(f"sun{i}", "SUN")
            light.color, light.energy = color, peak  # Cycles: sun strength = irradiance
            light.angle = math.radians(lt.get("angle", 0.53))  # angular diameter
            point_toward(obj, [-c for c in lt["direction"]])  # direction points at the sun
        elif kind == "environment":
            check_keys(lt, ptr, {"type", "radiance", "file", "scale", "rotation", "group"})
            if "file" in lt:
                raise SceneError(f"{ptr}/file", "environment images are not translated to Cycles "
                                 "(only a constant radiance)")
            world_nodes["Background"].inputs["Color"].default_value = (*lt["radiance"], 1.0)
            world_nodes["Background"].inputs["Strength"].default_value = 1.0
        else:
            raise SceneError(f"{ptr}/type", f"light type '{kind}' is not translated")


# --------------------------------------------------------------------- media
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


# -------------------------------------------------------- camera and settings
def add_camera(cam, width, height):
    check_keys(cam, "/camera", {"type", "from", "to", "up", "fov", "aperture", "focus_distance"})
    eye, target, up = Vector(cam["from"]), Vector(cam["to"]), Vector(cam["up"])
    forward = (target - eye).normalized()
    right = forward.cross(up).normalized()
    true_up = right.cross(forward)
    m = Matrix.Identity(4)
    for row in range(3):  # columns: right, up, -forward, eye (Blender cameras look down -Z)
        m[row][0], m[row][1], m[row][2], m[row][3] = right[row], true_up[row], -forward[row], eye[row]
    data = bpy.data.cameras.new("camera")
    data.sensor_fit = "VERTICAL" if width >= height else "HORIZONTAL"
    data.angle = math.radians(cam["fov"])  # across the shorter axis, as Vesper
    data.clip_start, data.clip_end = 1e-6, 1e12
    aperture = cam.get("aperture", 0.0)
    if aperture > 0:
        data.dof.use_dof = True
        data.dof.focus_distance = cam.get("focus_distance", (target - eye).length)
        # Cycles: aperture radius = 0.5 * lens_mm * 1e-3 / fstop (scene unit scale 1).
        data.dof.aperture_fstop = data.lens * 1e-3 / aperture
    obj = bpy.data.objects.new("camera", data)
    obj.matrix_world = Y_UP_TO_Z_UP @ m
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.scene.camera = obj


def check_settings(doc):
    check_keys(doc, "", {"format", "camera", "film", "render", "materials", "shapes", "lights", "media",
                         "layers"})
    if doc.get("format") != "vesper-scene/1":
        raise SceneError("/format", "expected \"vesper-scene/1\"")
    # Render settings the bench replaces (spp, seed) or that only add outputs
    # (aovs; layers never change the beauty) are ignored; the others change the image.
    check_keys(doc["render"], "/render", {"spp", "max_depth", "seed", "aovs"})
    check_keys(doc["film"], "/film", {"width", "height", "filter", "pixel_type", "compression"})
    if doc["camera"].get("type") != "perspective":
        raise SceneError("/camera/type", "only perspective cameras are translated")


def configure_render(scene, args, max_depth):
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = args.spp
    c.seed, c.use_animated_seed = args.seed % (2**31), False
    c.use_adaptive_sampling = False
    c.use_denoising = False
    scene.view_layers[0].cycles.use_denoising = False
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    c.light_sampling_threshold = 0.0
    c.blur_glossy = 0.0
    c.caustics_reflective = c.caustics_refractive = True
    # Cycles' bounce 0 is direct light only, Vesper's max_depth 1 (PEERS.md).
    bounces = max(0, max_depth - 1)
    c.max_bounces = c.diffuse_bounces = c.glossy_bounces = bounces
    c.transmission_bounces = c.volume_bounces = bounces
    c.transparent_max_bounces = 1024  # Vesper has no transparency; nothing to limit
    c.min_light_bounces = c.min_transparent_bounces = 0
    c.pixel_filter_type, c.filter_width = "BOX", 1.0
    r = scene.render
    r.resolution_x, r.resolution_y, r.resolution_percentage = args.width, args.height, 100
    r.pixel_aspect_x = r.pixel_aspect_y = 1.0
    r.threads_mode, r.threads = "FIXED", args.threads
    r.film_transparent = False
    r.image_settings.file_format = "OPEN_EXR"
    r.image_settings.color_depth = "32"
    r.image_settings.color_mode = "RGBA"
    r.image_settings.exr_codec = "ZIP"
    scene.view_settings.view_transform, scene.view_settings.look = "Standard", "None"
    scene.view_settings.exposure, scene.view_settings.gamma = 0.0, 1.0


def black_world():
    world = bpy.data.worlds.new("world")
    world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (0, 0, 0, 1)
    background.inputs["Strength"].default_value = 0.0
    bpy.context.scene.world = world
    return world


def build_scene(doc, scene_path, args):
    reject_keyframes(doc, "")
    check_settings(doc)
    scene_dir = os.path.dirname(os.path.abspath(scene_path))
    materials = {}
    for name, m in doc["materials"].items():
        materials[name] = translate_material(name, m, f"/materials/{name}")
    for i, s in enumerate(doc["shapes"]):
        if s.get("material") not in materials:
            raise SceneError(f"/shapes/{i}/material", f"unknown material {s.get('material')!r}")
    world = black_world()
    add_shapes(doc, materials, scene_dir)
    add_lights(doc, world.node_tree.nodes)
    add_media(doc, scene_dir, world)
    add_camera(doc["camera"], args.width, args.height)
    configure_render(bpy.context.scene, args, doc["render"].get("max_depth", 8))


def write_atomically(path, write):
    tmp = f"{path}.tmp{os.getpid()}{os.path.splitext(path)[1]}"
    try:
        write(tmp)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="vesper_to_cycles.py")
    for flag in ("--scene", "--out", "--stats"):
        p.add_argument(flag, required=True)
    for flag in ("--spp", "--threads"):
        p.add_argument(flag, type=int, required=True)
    p.add_argument("--width", type=int, help="default: the scene's film.width")
    p.add_argument("--height", type=int, help="default: the scene's film.height")
    p.add_argument("--seed", type=int, default=0)
    args = p.parse_args(argv)
    if min(args.spp, args.threads, args.width or 1, args.height or 1) < 1:
        p.error("--spp, --threads, --width and --height must be at least 1")
    return args


def main():
    args = parse_args()
    try:
        with open(args.scene, encoding="utf-8") as f:
            doc = json.load(f)
        args.width = args.width or doc["film"]["width"]
        args.height = args.height or doc["film"]["height"]
        bpy.ops.wm.read_factory_settings(use_empty=True)
        build_scene(doc, args.scene, args)
    except SceneError as e:
        print(f"{args.scene}: {e.pointer or '/'}: {e} (Cycles translation)", file=sys.stderr)
        sys.exit(2)
    except (OSError, ValueError, KeyError, IndexError, TypeError, struct.error) as e:
        print(f"{args.scene}: cannot translate to Cycles: {type(e).__name__}: {e}", file=sys.stderr)
        sys.exit(2)
    start = time.perf_counter()
    bpy.ops.render.render()
    seconds = time.perf_counter() - start
    result = bpy.data.images["Render Result"]
    write_atomically(args.out, lambda tmp: result.save_render(tmp))
    stats = {"render_seconds": seconds, "blender_version": bpy.app.version_string, "samples": args.spp,
             "threads": args.threads, "width": args.width, "height": args.height, "seed": args.seed}

    def dump(tmp):
        with open(tmp, "w", encoding="utf-8") as f:
            json.dump(stats, f, indent=2)

    write_atomically(args.stats, dump)


if __name__ == "__main__":
    main()
