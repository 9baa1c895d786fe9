# Materials of a vesper-scene/1 file as Cycles 3.4 shader trees: diffuse and
# dielectric exactly, conductor and principled approximately (README.md).
import math

from cycles_common import SceneError, check_keys, new_material


def normal_incidence_reflectance(eta, k):
    # Conductor Fresnel at normal incidence: ((n-1)^2 + k^2) / ((n+1)^2 + k^2).
    return [((n - 1) ** 2 + kk ** 2) / ((n + 1) ** 2 + kk ** 2) for n, kk in zip(eta, k)]


def burley_albedo(roughness, cos_o, frostbite, n=24):
    """Directional albedo of the Burley diffuse lobe, white base colour.

    frostbite: Vesper's (renderer/bsdf/principled.h: bias 0.5 r, energy factor
    1 -> 1/1.51); else Cycles 3.4's Disney original (bias 0.5, no factor).
    """
    r, total = roughness, 0.0
    sin_o = math.sqrt(max(0.0, 1.0 - cos_o * cos_o))
    bias, factor = (0.5 * r, 1.0 + r * (1.0 / 1.51 - 1.0)) if frostbite else (0.5, 1.0)
    for a in range(n):
        for b in range(n):  # cosine-weighted directions: the estimator is f * pi
            u1, phi = (a + 0.5) / n, 2.0 * math.pi * (b + 0.5) / n
            cos_i = math.sqrt(1.0 - u1)
            cos_d2 = 0.5 * (sin_o * math.sqrt(u1) * math.cos(phi) + cos_o * cos_i + 1.0)
            fd90 = bias + 2.0 * r * cos_d2
            total += factor * (1 + (fd90 - 1) * (1 - cos_i) ** 5) * (1 + (fd90 - 1) * (1 - cos_o) ** 5)
    return total / (n * n)


# View cosines at which the albedo ratio is tabulated for the curve below.
RATIO_COSINES = (0.0, 0.05, 0.1, 0.2, 0.3, 0.45, 0.6, 0.8, 1.0)


def diffuse_energy_ratio(roughness, cos_o):
    """Vesper's over Cycles' Burley albedo for the view cosine cos_o."""
    cos_o = max(cos_o, 0.01)
    return burley_albedo(roughness, cos_o, True) / burley_albedo(roughness, cos_o, False)


def compensated_base_color(tree, base_color, roughness):
    """base_color * ratio(|Incoming . Normal|): a socket for the Base Color input.

    Matches Vesper's diffuse albedo for every view direction (a curve through
    the ratio at RATIO_COSINES), not only on average.
    """
    nodes, links = tree.nodes, tree.links
    geometry = nodes.new("ShaderNodeNewGeometry")
    cosine = nodes.new("ShaderNodeVectorMath")
    cosine.operation = "DOT_PRODUCT"
    links.new(geometry.outputs["Incoming"], cosine.inputs[0])
    links.new(geometry.outputs["Normal"], cosine.inputs[1])
    magnitude = nodes.new("ShaderNodeMath")
    magnitude.operation = "ABSOLUTE"
    links.new(cosine.outputs["Value"], magnitude.inputs[0])
    curve = nodes.new("ShaderNodeFloatCurve")
    points = curve.mapping.curves[0].points
    ratios = [diffuse_energy_ratio(roughness, c) for c in RATIO_COSINES]
    points[0].location, points[1].location = (0.0, ratios[0]), (1.0, ratios[-1])
    for c, r in zip(RATIO_COSINES[1:-1], ratios[1:-1]):
        points.new(c, r)
    for point in points:
        point.handle_type = "VECTOR"  # piecewise linear: no overshoot between samples
    curve.mapping.update()
    links.new(magnitude.outputs[0], curve.inputs["Value"])
    scaled = nodes.new("ShaderNodeVectorMath")
    scaled.operation = "SCALE"
    scaled.inputs[0].default_value = base_color
    links.new(curve.outputs["Value"], scaled.inputs["Scale"])
    return scaled.outputs["Vector"]


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
        # Approximate diffuse: Cycles' Burley lacks Vesper's Frostbite energy
        # renormalisation (Vesper's lobe reflects 66-95 % of Cycles'). A
        # dielectric's base colour only tints the diffuse lobe, so it is scaled
        # by the ratio of the two lobes' albedos for the view direction; a
        # metallic one is left as is.
        check_keys(m, ptr, {"type", "base_color", "metallic", "roughness"})
        base, metallic, roughness = m.get("base_color", [0.8] * 3), m.get("metallic", 0.0), m.get("roughness", 0.5)
        node = principled_node(nodes, base, metallic, roughness)
        if metallic == 0:
            links = mat.node_tree.links
            links.new(compensated_base_color(mat.node_tree, base, roughness), node.inputs["Base Color"])
    else:
        raise SceneError(f"{ptr}/type", f"material type '{kind}' is not translated")
    mat.node_tree.links.new(node.outputs[0], out.inputs["Surface"])
    return mat
