# Lights of a vesper-scene/1 file in Cycles 3.4 units (PEERS.md): quad lights
# as one-sided emissive meshes, point/spot (with radius), sun, constant sky.
import math

import bpy

from cycles_common import SceneError, add_mesh_object, check_keys, new_material, quad_positions, rgb_strength, to_blender


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
