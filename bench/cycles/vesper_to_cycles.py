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
import traceback

import bpy
from mathutils import Matrix, Vector

# The translation's modules live beside this script (the bench's cache key
# hashes every .py here); no __pycache__ in the source tree.
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cycles_common import Y_UP_TO_Z_UP, SceneError, check_keys, reject_keyframes  # noqa: E402
from cycles_lights import add_lights  # noqa: E402
from cycles_materials import translate_material  # noqa: E402
from cycles_media import add_media  # noqa: E402
from cycles_shapes import add_shapes  # noqa: E402


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


def translate_and_render():
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


def main():
    try:
        translate_and_render()
    except Exception:  # a bug, or Blender failing: never exit 0 without the outputs
        traceback.print_exc()
        sys.exit(1)


if __name__ == "__main__":
    main()
