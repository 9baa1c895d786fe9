# Shared by the vesper-scene/1 -> Cycles 3.4 translation (vesper_to_cycles.py):
# the error type, coordinate conversion, key checks, transforms, mesh objects.
import math

import bpy
from mathutils import Matrix, Vector

# Vesper is Y-up, Blender Z-up, both right-handed: (x, y, z) -> (x, -z, y).
Y_UP_TO_Z_UP = Matrix(((1, 0, 0, 0), (0, 0, -1, 0), (0, 1, 0, 0), (0, 0, 0, 1)))


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


def new_material(name):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    return mat, nodes, nodes["Material Output"]
