# Shapes of a vesper-scene/1 file as Cycles objects: quads and meshes (OBJ,
# PLY or inline, transformed per docs/scene-format.md "Transforms"), spheres
# (exact point-cloud spheres; finely tessellated ones for glass).
import os
import struct

import bmesh
import bpy
from mathutils import Vector

from cycles_common import SceneError, add_mesh_object, check_keys, quad_positions, to_blender, vesper_transform


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


# Segments of the tessellated sphere used for glass: its silhouette is within
# (pi / 256)^2 / 2 = 7.5e-5 of the radius, and smooth shading restores the normals.
GLASS_SPHERE_SEGMENTS = 256


def add_point_sphere(name, center, radius, material):
    # A one-point point cloud renders as an exact sphere in Cycles 3.4, but a
    # ray leaving its surface skips the point itself: refracted rays never meet
    # the far side (glass came out ~10 % bright, bench/cycles/README.md).
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


def add_mesh_sphere(name, center, radius, material):
    mesh = bpy.data.meshes.new(name)
    bm = bmesh.new()
    bmesh.ops.create_uvsphere(bm, u_segments=GLASS_SPHERE_SEGMENTS, v_segments=GLASS_SPHERE_SEGMENTS // 2,
                              radius=radius)
    bm.to_mesh(mesh)
    bm.free()
    mesh.polygons.foreach_set("use_smooth", [True] * len(mesh.polygons))
    mesh.materials.append(material)
    obj = bpy.data.objects.new(name, mesh)
    obj.location = to_blender(center)
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
            transmissive = doc["materials"][s["material"]].get("type") == "dielectric"
            add_sphere = add_mesh_sphere if transmissive else add_point_sphere
            add_sphere(f"sphere{i}", s["center"], s["radius"], material)
        elif kind == "mesh":
            check_keys(s, ptr, {"type", "file", "positions", "indices", "transform", "material", "name"})
            if "file" in s:
                path = os.path.join(scene_dir, s["file"])
                if "#" in os.path.basename(s["file"]):
                    raise SceneError(f"{ptr}/file", "per-frame file sequences are not translated")
                reader = read_ply if path.lower().endswith(".ply") else read_obj
                try:
                    positions, tris = reader(path)
                except (OSError, ValueError, KeyError, IndexError, struct.error) as e:
                    raise SceneError(f"{ptr}/file", f"cannot read mesh file '{path}': {e}") from e
            else:
                p, idx = s["positions"], s["indices"]
                positions = [p[k:k + 3] for k in range(0, len(p), 3)]
                tris = [tuple(idx[k:k + 3]) for k in range(0, len(idx), 3)]
            m = vesper_transform(s.get("transform"), f"{ptr}/transform")
            add_mesh_object(f"mesh{i}", [m @ Vector(p) for p in positions], tris, material)
        else:
            raise SceneError(f"{ptr}/type", f"shape type '{kind}' is not translated")
