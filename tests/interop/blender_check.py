# SPDX-License-Identifier: MIT
# Opens odeskin's outputs in Blender, headless, and checks that Blender plays them with odeskin's
# motion: the deformed vertices Blender evaluates are compared with `odeskin play --t` at the same
# times. Registered in CTest by tests/interop/CMakeLists.txt; run by hand as
#
#   blender -b --factory-startup --python tests/interop/blender_check.py -- CHECK \
#       --odeskin build/samples/odeskin --asset horse.odsk --out DIR
#
# CHECK is one of
#   compact  `odeskin export --interpolation linear` (or --interpolation cubic): skin, skeletal
#            animation and per-mode morph targets whose weights Blender imports as shape-key F-curves;
#   baked    `odeskin play --fps F -o OUT.glb` and `odeskin export --bake --fps F`: a morph target
#            per frame, STEP or LINEAR weights;
#   pc2, mdd `odeskin play --fps F -o OUT.pc2` (or OUT.mdd) on the mesh `play --t 0` writes,
#            through Blender's Mesh Cache modifier;
#   rig      `odeskin rig MESH -o OUT.tgf --gltf OUT.glb` (--mesh instead of --asset): an armature
#            whose bones start at the .tgf's joints, one vertex group per bone, and the mesh at rest;
#   ply      `odeskin compare ASSET --t T REFERENCE -o OUT.ply` (--reference): the heat map's errors
#            and colours recomputed here from odeskin play and the reference, and Blender's PLY
#            importer showing the same vertices and colours;
#   animated `odeskin rig MESH --gltf` (--mesh), animated in Blender (bones turned at 0.5 s and 1 s)
#            and exported with its skin and animation; `odeskin fit --times 0.5,1` reads it, `odeskin
#            export` writes it back, and Blender shows the example poses where its own file had them;
#   surface  `odeskin surface NETWORK -o OUT.glb --obj` (--network): the same vertices as the OBJ,
#            and the weld intact in Blender: only the rim edges the command reports have one face;
#   roundtrip  Blender makes a character from --poses OBJ files (shape keys, smooth shading, UVs, a
#            textured material) and exports it as glTF; `odeskin fit` reads it, `odeskin export
#            --materials` (and `play -o OUT.glb --materials`) write it back, and Blender imports
#            them: the same vertices, UVs and material, moving as `odeskin play` does.
#   obj_uv   Blender's textured character as in roundtrip, written by Blender's OBJ exporter as one
#            OBJ per pose (vt and vn on every corner); `odeskin fit` reads them, and Blender imports
#            `play --t 0`'s OBJ (the input's vertices in order, the same UVs corner by corner), plays
#            a PC2 cache on it, and imports `odeskin export`'s glTF (the same UVs, the same motion).
#   rig_gltf Blender's textured character as in roundtrip (--poses: the shape keys are example
#            poses, `--targets`); `odeskin rig CHARACTER.glb --gltf OUT.glb` rigs it, and Blender
#            imports an armature of the .tgf's bones over the same vertices, UVs and material.
# Exits 1 on any failure (a missing odeskin, an import error, a vertex off by more than the
# tolerance); nothing is skipped.
import argparse
import json
import math
import re
import subprocess
import sys
import tempfile
from pathlib import Path

import bmesh
import bpy
import mathutils
import numpy

sys.path.insert(0, str(Path(__file__).resolve().parent))  # Blender runs this file as a script
from blender_support import (CheckFailure, compare, evaluated_positions, failures, log, obj_positions,  # noqa: E402
                             odeskin, only_mesh, reset_scene, segment_seconds)

# Blender evaluates in float32; the compact export's keys and fit add up to about 5e-5 of the box
# between keys (odeskin export prints its bounds), and --quantize's rounding adds about 1e-4 more
# (2.5e-5 to a bake).
TOLERANCE = {"compact": 1e-4, "quantized": 2e-4, "baked": 1e-5, "baked_quantized": 5e-5, "pc2": 1e-6, "mdd": 1e-6, "rig": 1e-6, "ply": 1e-6, "surface": 1e-6,
             "roundtrip": 1e-4, "animated": 1e-4, "rig_gltf": 1e-6, "obj_uv": 1e-4}


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else []
    parser = argparse.ArgumentParser(prog="blender_check.py")
    parser.add_argument("check", choices=sorted(TOLERANCE))
    parser.add_argument("--odeskin", required=True)
    parser.add_argument("--asset", help="the fitted .odsk (compact, baked, pc2, mdd, ply)")
    parser.add_argument("--mesh", help="rig, animated: the OBJ mesh to rig")
    parser.add_argument("--reference", help="ply: the ground-truth OBJ the asset is compared with")
    parser.add_argument("--t", default="0.5", help="ply: the asset's time T")
    parser.add_argument("--poses", nargs="+", help="roundtrip, rig_gltf: OBJ files of one mesh, the first the base")
    parser.add_argument("--network", help="surface: a curve network (.json) for odeskin surface")
    parser.add_argument("--out", required=True)
    parser.add_argument("--times", default="0,0.37,0.51,1,1.52,1.99,2",
                        help="compact: key times T (odeskin play --t) to compare")
    parser.add_argument("--fps", type=int, default=24, help="baked, pc2 and mdd: frames per second")
    parser.add_argument("--interpolation", default="linear", choices=["linear", "cubic"],
                        help="compact: odeskin export --interpolation (Blender drops cubic tangents)")
    return parser.parse_args(argv)


def compare_with_play(options, asset, obj, t, frame, out):
    """Blender's `obj` at `frame` against `odeskin play ASSET --t T`, with the check's tolerance."""
    reference = out / f"{options.check}-t{t}.obj"
    odeskin(options, "play", str(asset), "--t", str(t), "-o", str(reference))
    compare(f"{options.check} t {t}", evaluated_positions(obj, frame), obj_positions(reference),
            TOLERANCE[options.check])


def check_compact(options, out):
    glb = out / f"{options.check}.glb"
    quantize = ["--quantize"] if options.check == "quantized" else []
    odeskin(options, "export", options.asset, "-o", str(glb), "--interpolation", options.interpolation, *quantize)
    seconds = segment_seconds(options, options.asset)
    # A scene at 100 fps puts T = 0.37 on a whole frame: Blender's sub-frames are not needed.
    fps = 100
    reset_scene(fps)
    bpy.ops.import_scene.gltf(filepath=str(glb))
    obj = only_mesh()
    if not any(m.type == "ARMATURE" for m in obj.modifiers):
        raise CheckFailure("the imported mesh has no armature modifier: the skin was lost")
    keys = obj.data.shape_keys
    if keys is None or len(keys.key_blocks) < 2:
        raise CheckFailure("the imported mesh has no shape keys: the morph targets were lost")
    curves = keys.animation_data.action.fcurves if keys.animation_data and keys.animation_data.action else []
    if len(curves) != len(keys.key_blocks) - 1:
        raise CheckFailure(f"{len(curves)} shape-key F-curves for {len(keys.key_blocks) - 1} shape keys")
    log(f"{glb.name}: {len(keys.key_blocks) - 1} shape keys, each with its F-curve")
    for t in (float(x) for x in options.times.split(",")):
        frame = t * seconds * fps
        if abs(frame - round(frame)) > 1e-6:
            raise CheckFailure(f"--times {t}: {t * seconds} s is not a whole frame at {fps} fps")
        compare_with_play(options, options.asset, obj, t, round(frame), out)


def frame_references(options, out, stem):
    odeskin(options, "play", options.asset, "--fps", str(options.fps), "-o", str(out / f"{stem}_%04d.obj"))
    return sorted(out.glob(f"{stem}_*.obj"))


def check_baked(options, out):
    # play's bake switches frames with STEP weights, export --bake cross-fades them with LINEAR ones;
    # at the frames themselves both are the frames.
    played, exported = out / "played.glb", out / "exported.glb"
    odeskin(options, "play", options.asset, "--fps", str(options.fps), "-o", str(played))
    quantize = ["--quantize"] if options.check == "baked_quantized" else []
    odeskin(options, "export", options.asset, "--bake", "--fps", str(options.fps), "-o", str(exported), *quantize)
    frames = frame_references(options, out, "baked")
    for glb in (played, exported):
        reset_scene(options.fps)
        bpy.ops.import_scene.gltf(filepath=str(glb))
        obj = only_mesh()
        for k, reference in enumerate(frames):
            tolerance = TOLERANCE[options.check if glb == exported else "baked"]
            compare(f"{glb.stem} frame {k}", evaluated_positions(obj, k), obj_positions(reference), tolerance)


def check_point_cache(options, out):
    kind = options.check  # "pc2" or "mdd", the file's extension and the modifier's format
    base, cache = out / "base.obj", out / f"cache.{kind}"
    odeskin(options, "play", options.asset, "--t", "0", "-o", str(base))
    odeskin(options, "play", options.asset, "--fps", str(options.fps), "-o", str(cache))
    frames = frame_references(options, out, kind)
    reset_scene(options.fps)
    bpy.ops.wm.obj_import(filepath=str(base))
    obj = only_mesh()
    modifier = obj.modifiers.new("odeskin", "MESH_CACHE")
    modifier.cache_format = kind.upper()
    modifier.filepath = str(cache)
    for k, reference in enumerate(frames):
        compare(f"{kind} frame {k}", evaluated_positions(obj, k), obj_positions(reference), TOLERANCE[kind])


def tgf_bones(path):
    """The joints (x, y, z) and bones (first joint, second joint) of a libigl .tgf, joints turned z-up."""
    joints, bones, in_edges = {}, [], False
    with open(path) as f:
        for line in f:
            fields = line.split()
            if not fields:
                continue
            if fields[0] == "#":
                in_edges = True
            elif in_edges:
                bones.append((int(fields[0]), int(fields[1])))
            else:
                x, y, z = (float(v) for v in fields[1:4])
                joints[int(fields[0])] = (x, -z, y)
    return joints, bones


def check_rig(options, out):
    tgf, glb = out / "rig.tgf", out / "rig.glb"
    odeskin(options, "rig", options.mesh, "-o", str(tgf), "--gltf", str(glb))
    joints, bones = tgf_bones(tgf)
    reset_scene(24)
    bpy.ops.import_scene.gltf(filepath=str(glb))
    armatures = [o for o in bpy.context.scene.objects if o.type == "ARMATURE"]
    if len(armatures) != 1:
        raise CheckFailure(f"expected one armature after import, found {len(armatures)}")
    armature = armatures[0]
    obj = only_mesh()
    if len(armature.data.bones) != len(bones):
        raise CheckFailure(f"Blender has {len(armature.data.bones)} bones, {tgf.name} {len(bones)}")
    if len(obj.vertex_groups) != len(bones):
        raise CheckFailure(f"{len(obj.vertex_groups)} vertex groups for {len(bones)} bones")
    reference = numpy.array([p for _, p in sorted(joints.items())])
    box = float((reference.max(axis=0) - reference.min(axis=0)).max())
    heads = numpy.array([tuple(armature.matrix_world @ b.head_local) for b in armature.data.bones])
    starts = numpy.array([joints[first] for first, _ in bones])
    # Bone names are not the .tgf's indices: every head must sit on a bone's first joint, and the
    # other way round.
    head_to_start = max(numpy.linalg.norm(starts - h, axis=1).min() for h in heads) / box
    start_to_head = max(numpy.linalg.norm(heads - p, axis=1).min() for p in starts) / box
    log(f"{glb.name}: {len(bones)} bones and vertex groups; bone heads within {max(head_to_start, start_to_head):.2e} "
        f"of the box of the .tgf's joints")
    if not max(head_to_start, start_to_head) <= TOLERANCE["rig"]:
        failures.append(f"a bone head is {max(head_to_start, start_to_head):.2e} of the box from its .tgf joint")
    compare("rig at rest", evaluated_positions(obj, 0), obj_positions(options.mesh), TOLERANCE["rig"])


def heat_colour(s):
    """engine/visual/render_shading.h's heatColour, written again: blue, cyan, green, yellow, red."""
    stops = numpy.array([(0.17, 0.30, 0.80), (0.16, 0.68, 0.90), (0.40, 0.80, 0.36), (0.98, 0.80, 0.18),
                         (0.86, 0.16, 0.13)])
    x = numpy.clip(s, 0.0, 1.0) * 4.0
    k = numpy.minimum(x.astype(int), 3)
    f = (x - k)[:, None]
    return (1.0 - f) * stops[k] + f * stops[k + 1]


def read_ply(path):
    """The vertex records odeskin's PLY writer makes: float x y z, uchar r g b, float quality."""
    data = path.read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode()
    if "binary_little_endian" not in header or "property float quality" not in header:
        raise CheckFailure(f"{path.name}: not the PLY layout expected:\n{header}")
    count = int(re.search(r"element vertex (\d+)", header).group(1))
    heat_max = float(re.search(r"colour = error / ([0-9.e+-]+) of the box", header).group(1))
    record = numpy.dtype([("p", "<f4", 3), ("rgb", "u1", 3), ("quality", "<f4")])
    return numpy.frombuffer(data, record, count, end), heat_max


def check_ply(options, out):
    ply, mesh, report = out / "error.ply", out / "mesh.obj", out / "error.json"
    odeskin(options, "compare", options.asset, options.reference, "--t", options.t, "-o", str(ply), "--json", str(report))
    odeskin(options, "play", options.asset, "--t", options.t, "-o", str(mesh))
    vertices, heat_max = read_ply(ply)
    played, truth = obj_positions(mesh), obj_positions(options.reference)
    box = float((truth.max(axis=0) - truth.min(axis=0)).max())
    errors = numpy.linalg.norm(played - truth, axis=1) / box
    figures = json.loads(report.read_text())
    log(f"{ply.name}: {len(vertices)} vertices, MVE {figures['max']['relative']:.4f} of the box at vertex "
        f"{figures['max']['vertex']}, colours up to {heat_max:.4f}")
    if len(vertices) != len(played):
        raise CheckFailure(f"{ply.name} has {len(vertices)} vertices, odeskin play {len(played)}")
    if abs(figures["max"]["relative"] - errors.max()) > 1e-6 or figures["max"]["vertex"] != int(errors.argmax()):
        failures.append(f"the report's MVE {figures['max']} is not {errors.max():.6f} at vertex {errors.argmax()}")
    if abs(figures["mean"] - errors.mean()) > 1e-6:
        failures.append(f"the report's mean {figures['mean']} is not {errors.mean():.6f}")
    if numpy.abs(vertices["quality"] - errors).max() > 1e-6:
        failures.append("the PLY's quality is not each vertex's error over the box")
    expected = numpy.rint(heat_colour(errors / heat_max) * 255.0)
    if numpy.abs(vertices["rgb"] - expected).max() > 1:
        failures.append("the PLY's colours are not the heat map of the errors")
    # The same file through Blender's PLY importer: vertices as written, and a corner colour attribute.
    reset_scene(24)
    bpy.ops.import_mesh.ply(filepath=str(ply))
    obj = only_mesh()
    shown = evaluated_positions(obj, 0)
    compare("ply in Blender", shown, vertices["p"].astype(float), TOLERANCE["ply"])
    colours = obj.data.color_attributes[0] if len(obj.data.color_attributes) else None
    if colours is None:
        raise CheckFailure(f"Blender read no colours from {ply.name}")
    loops = numpy.empty(len(obj.data.loops), dtype=int)
    obj.data.loops.foreach_get("vertex_index", loops)
    srgb = numpy.array([tuple(c.color_srgb)[:3] for c in colours.data])
    worst = float(numpy.abs(srgb * 255.0 - vertices["rgb"][loops]).max())
    log(f"ply colours in Blender ({colours.domain.lower()} domain): largest difference {worst:.2f} of 255")
    if worst > 1.0:
        failures.append(f"Blender shows colours up to {worst:.1f}/255 away from the file's")


def make_character(poses, glb):
    """A textured character with one shape key per further pose, exported by Blender's glTF exporter."""
    textured_character(poses)
    bpy.ops.export_scene.gltf(filepath=str(glb), export_format="GLB", export_morph=True)


def textured_character(poses):
    """The first pose with one shape key per further pose, smooth shading, UV islands and a textured material."""
    reset_scene(24)
    bpy.ops.wm.obj_import(filepath=poses[0])
    obj = only_mesh()
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    obj.shape_key_add(name="Basis")
    for pose in poses[1:]:
        key = obj.shape_key_add(name=Path(pose).stem)
        # The importer turned the object, not its vertices: shape keys take the OBJ's coordinates.
        with open(pose) as f:
            coords = [tuple(float(v) for v in line.split()[1:4]) for line in f if line.startswith("v ")]
        if len(coords) != len(key.data):
            raise CheckFailure(f"{pose} has {len(coords)} vertices, {poses[0]} {len(key.data)}")
        key.data.foreach_set("co", numpy.array(coords).ravel())
    bpy.ops.object.shade_smooth()
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.mesh.select_all(action="SELECT")
    bpy.ops.uv.smart_project(angle_limit=1.15)  # UV islands: seams that split glTF vertices
    bpy.ops.object.mode_set(mode="OBJECT")
    image = bpy.data.images.new("odeskin-grid", 64, 64)
    image.generated_type = "COLOR_GRID"
    image.pack()
    material = bpy.data.materials.new("odeskin-skin")
    material.use_nodes = True
    texture = material.node_tree.nodes.new("ShaderNodeTexImage")
    texture.image = image
    material.node_tree.links.new(texture.outputs["Color"], material.node_tree.nodes["Principled BSDF"].inputs["Base Color"])
    obj.data.materials.append(material)
    return obj


def loop_uvs(obj, name):
    """`obj`'s UVs per face corner, in its loop order."""
    if not obj.data.uv_layers:
        raise CheckFailure(f"{name}: the imported mesh has no UVs")
    uvs = numpy.empty(len(obj.data.loops) * 2)
    obj.data.uv_layers[0].data.foreach_get("uv", uvs)
    return uvs.reshape(-1, 2)


def render_vertex_map(path):
    """The vertex each `vt` of an OBJ belongs to, from its `f v/vt` corners (0-based)."""
    vertex_of = {}
    with open(path) as f:
        for line in f:
            if line.startswith("f "):
                for corner in line.split()[1:]:
                    v, t = (int(i) - 1 for i in corner.split("/")[:2])
                    if vertex_of.setdefault(t, v) != v:
                        raise CheckFailure(f"{path.name}: texture coordinate {t + 1} is on vertices {vertex_of[t] + 1} and {v + 1}")
    if sorted(vertex_of) != list(range(len(vertex_of))):
        raise CheckFailure(f"{path.name}: some texture coordinates are on no face")
    return numpy.array([vertex_of[t] for t in range(len(vertex_of))])


def check_obj_uv(options, out):
    character = textured_character(options.poses)
    keys = character.data.shape_keys.key_blocks
    exported = []
    for k in range(len(options.poses)):
        for i in range(1, len(keys)):
            keys[i].value = 1.0 if i == k else 0.0
        bpy.context.view_layer.update()
        exported.append(out / f"pose-{k}.obj")
        bpy.ops.wm.obj_export(filepath=str(exported[-1]), export_selected_objects=True, export_uv=True,
                              export_normals=True, export_materials=False, apply_modifiers=True)
    moved = float(numpy.abs(obj_positions(exported[1]) - obj_positions(exported[0])).max())
    log(f"Blender's OBJ files: pose 1 moves up to {moved:.3g} from pose 0")
    if moved == 0.0:
        raise CheckFailure("Blender wrote every pose alike: the shape keys were not applied")
    asset, base, glb, cache = out / "character.odsk", out / "base.obj", out / "exported.glb", out / "cache.pc2"
    odeskin(options, "fit", *(str(p) for p in exported), "-o", str(asset))
    odeskin(options, "play", str(asset), "--t", "0", "-o", str(base))
    odeskin(options, "export", str(asset), "--interpolation", "linear", "-o", str(glb))

    reset_scene(24)
    bpy.ops.wm.obj_import(filepath=str(exported[0]))
    source = only_mesh()
    source_vertices, source_uvs = len(source.data.vertices), loop_uvs(source, exported[0].name)
    for written in (base, glb):
        reset_scene(100)
        if written == base:
            bpy.ops.wm.obj_import(filepath=str(written))
        else:
            bpy.ops.import_scene.gltf(filepath=str(written))
        obj = only_mesh()
        uvs = loop_uvs(obj, written.name)
        log(f"{written.name}: {len(obj.data.vertices)} vertices (the input {source_vertices}), {len(uvs)} face corners")
        if written == base and len(obj.data.vertices) != source_vertices:
            failures.append(f"{written.name}: {len(obj.data.vertices)} vertices, the input {source_vertices}")
        compare_uvs(written.name, uvs, source_uvs, "the input")
    # The glTF holds render vertices (split at the UV seams), play's OBJ the input's vertices: the
    # OBJ's corners `v/vt` say which vertex each render vertex (each `vt`) is.
    vertex_of_render = render_vertex_map(base)
    if len(vertex_of_render) != len(obj.data.vertices):
        raise CheckFailure(f"{base.name} names {len(vertex_of_render)} texture coordinates, {glb.name} has "
                           f"{len(obj.data.vertices)} vertices")
    seconds = segment_seconds(options, asset)
    for t in (0.0, 0.37, 1.0, float(len(options.poses) - 1)):
        reference = out / f"obj_uv-t{t}.obj"
        odeskin(options, "play", str(asset), "--t", str(t), "-o", str(reference))
        compare(f"obj_uv t {t}", evaluated_positions(obj, round(t * seconds * 100)),
                obj_positions(reference)[vertex_of_render], TOLERANCE["obj_uv"])

    # The point cache animates the OBJ `play --t 0` wrote, which is the input's mesh.
    fps = 4
    odeskin(options, "play", str(asset), "--fps", str(fps), "-o", str(cache))
    odeskin(options, "play", str(asset), "--fps", str(fps), "-o", str(out / "frame_%04d.obj"))
    reset_scene(fps)
    bpy.ops.wm.obj_import(filepath=str(base))
    obj = only_mesh()
    modifier = obj.modifiers.new("odeskin", "MESH_CACHE")
    modifier.cache_format = "PC2"
    modifier.filepath = str(cache)
    for k, reference in enumerate(sorted(out.glob("frame_*.obj"))):
        compare(f"pc2 frame {k}", evaluated_positions(obj, k), obj_positions(reference), TOLERANCE["pc2"])


def imported_look(glb, fps):
    """Blender's reading of a glTF: the mesh object, its UVs per face corner and its material's image."""
    reset_scene(fps)
    bpy.ops.import_scene.gltf(filepath=str(glb))
    obj = only_mesh()
    uvs = loop_uvs(obj, glb.name)
    materials = [m for m in obj.data.materials if m is not None]
    images = [n.image for m in materials if m.node_tree for n in m.node_tree.nodes if n.type == "TEX_IMAGE" and n.image]
    if len(materials) != 1 or len(images) != 1:
        raise CheckFailure(f"{glb.name}: {len(materials)} materials with {len(images)} images, expected one of each")
    return obj, uvs, materials[0].name, tuple(images[0].size)


def check_roundtrip(options, out):
    source, asset, glb = out / "character.glb", out / "character.odsk", out / "exported.glb"
    make_character(options.poses, source)
    odeskin(options, "fit", str(source), "--targets", ",".join(str(k) for k in range(len(options.poses) - 1)),
            "-o", str(asset))
    odeskin(options, "export", str(asset), "--materials", str(source), "--interpolation", "linear", "-o", str(glb))
    # The baked form dresses itself the same way (play -o .glb --materials).
    baked = out / "baked.glb"
    odeskin(options, "play", str(asset), "--fps", "4", "--materials", str(source), "-o", str(baked))
    look = imported_look(source, 100)
    for written in (baked, glb):  # the compact export last: its motion is checked below
        obj = check_same_look(written, look)
    seconds = segment_seconds(options, asset)
    for t in (0.0, 0.37, 1.0, 1.52, float(len(options.poses) - 1)):
        compare_with_play(options, asset, obj, t, round(t * seconds * 100), out)


def check_same_look(written, source_look):
    """`written` imported shows the source's material, image and UVs, corner by corner; returns its mesh object."""
    _, source_uvs, source_material, source_image = source_look
    obj, uvs, material, image = imported_look(written, 100)
    log(f"{written.name}: {len(obj.data.vertices)} vertices, {len(uvs)} face corners, material '{material}' "
        f"with a {image[0]}x{image[1]} image")
    if (material, image) != (source_material, source_image):
        failures.append(f"{written.name}: material '{material}' {image} is not the source's "
                        f"'{source_material}' {source_image}")
    compare_uvs(written.name, uvs, source_uvs, "the source")
    return obj


def compare_uvs(name, uvs, reference, reference_name):
    """UVs per face corner against `reference`'s, corner by corner, to float32's 1e-6."""
    if uvs.shape != reference.shape:
        raise CheckFailure(f"{name}: {len(uvs)} face corners with UVs, {reference_name} {len(reference)}")
    uv_error = float(numpy.abs(uvs - reference).max())
    log(f"{name} UVs: largest difference {uv_error:.2e} from {reference_name}'s, corner by corner")
    if uv_error > 1e-6:
        failures.append(f"{name}: UVs differ from {reference_name}'s by {uv_error:.2e}")


def check_rig_gltf(options, out):
    source, tgf, rigged = out / "character.glb", out / "rig.tgf", out / "rigged.glb"
    make_character(options.poses, source)
    targets = ",".join(str(k) for k in range(len(options.poses) - 1))
    odeskin(options, "rig", str(source), "--targets", targets, "-o", str(tgf), "--gltf", str(rigged))
    # Blender places the mesh by its node's transform, which odeskin must apply to an unskinned mesh.
    with open(source, "rb") as f:
        glb = f.read()
    chunk = int.from_bytes(glb[12:16], "little")
    node = next(n for n in json.loads(glb[20 : 20 + chunk])["nodes"] if "mesh" in n)
    log(f"{source.name}: the mesh node's transform {({k: v for k, v in node.items() if k in ('matrix', 'translation', 'rotation', 'scale')})}")
    look = imported_look(source, 100)
    rest = evaluated_positions(look[0], 0)  # before the next import empties the scene
    obj = check_same_look(rigged, look)
    _, bones = tgf_bones(tgf)
    armatures = [o for o in bpy.context.scene.objects if o.type == "ARMATURE"]
    if len(armatures) != 1 or len(armatures[0].data.bones) != len(bones):
        raise CheckFailure(f"{rigged.name}: {len(armatures)} armatures, expected one with the {len(bones)} bones of {tgf.name}")
    if len(obj.vertex_groups) != len(bones) or not any(m.type == "ARMATURE" for m in obj.modifiers):
        raise CheckFailure(f"{rigged.name}: {len(obj.vertex_groups)} vertex groups for {len(bones)} bones, or no armature modifier")
    log(f"{rigged.name}: an armature of {len(bones)} bones, one vertex group each")
    compare("rig_gltf at rest against the source", evaluated_positions(obj, 0), rest, TOLERANCE["rig_gltf"])


def animate_rig(rig_glb, animated_glb):
    """Blender's keyframes on odeskin's rig: the last four bones turned 35 degrees at frame 12 and
    -30 degrees about another axis at frame 24 (24 fps), exported with the skin and animation."""
    reset_scene(24)
    bpy.ops.import_scene.gltf(filepath=str(rig_glb))
    armature = next(o for o in bpy.context.scene.objects if o.type == "ARMATURE")
    bones = list(armature.pose.bones)
    turned = bones[-4:]
    for frame, axis, degrees in ((0, (1, 0, 0), 0.0), (12, (1, 0, 0), 35.0), (24, (0, 0, 1), -30.0)):
        for bone in bones:
            bone.rotation_mode = "QUATERNION"
            bone.rotation_quaternion = (1.0, 0.0, 0.0, 0.0)
        for bone in turned:
            bone.rotation_quaternion = mathutils.Quaternion(axis, math.radians(degrees))
        for bone in bones:
            bone.keyframe_insert("rotation_quaternion", frame=frame)
    bpy.context.scene.frame_start, bpy.context.scene.frame_end = 0, 24
    bpy.ops.export_scene.gltf(filepath=str(animated_glb), export_format="GLB", export_animations=True)
    return [b.name for b in turned]


def check_animated(options, out):
    rig, animated, asset, glb = out / "rig.glb", out / "animated.glb", out / "animated.odsk", out / "exported.glb"
    odeskin(options, "rig", options.mesh, "-o", str(out / "rig.tgf"), "--gltf", str(rig))
    turned = animate_rig(rig, animated)
    log(f"{animated.name}: Blender turned {', '.join(turned)} at 0.5 s and 1 s")
    reset_scene(24)
    bpy.ops.import_scene.gltf(filepath=str(animated))
    source = only_mesh()
    shown = {t: evaluated_positions(source, frame) for t, frame in ((0, 0), (1, 12), (2, 24))}
    box = float((shown[0].max(axis=0) - shown[0].min(axis=0)).max())
    for t in (1, 2):  # a test of poses that do not move would prove nothing
        moved = float(numpy.linalg.norm(shown[t] - shown[t - 1], axis=1).max()) / box
        log(f"Blender's pose {t} moves vertices up to {moved:.3f} of the box from pose {t - 1}")
        if moved < 0.01:
            raise CheckFailure(f"Blender's animation barely moves between poses {t - 1} and {t} ({moved:.2e} of the box)")
    # The bind pose, then the animation at 0.5 s and 1 s: keys t = 0, 1, 2 of 1 s segments.
    odeskin(options, "fit", str(animated), "--times", "0.5,1", "-o", str(asset))
    odeskin(options, "export", str(asset), "--interpolation", "linear", "-o", str(glb))
    reset_scene(24)
    bpy.ops.import_scene.gltf(filepath=str(glb))
    exported = only_mesh()
    for t, pose in shown.items():
        compare(f"example pose t {t} against Blender's own file", evaluated_positions(exported, 24 * t), pose,
                TOLERANCE["animated"])
    for t in (0.5, 1.5):
        compare_with_play(options, asset, exported, t, round(24 * t), out)


def check_surface(options, out):
    glb = out / "surface.glb"
    done = subprocess.run([options.odeskin, "surface", options.network, "-o", str(glb), "--obj"], capture_output=True,
                          text=True)
    # "welded; 256 rim edges, ..." or "welded; closed (no rim), ..."
    rims = re.search(r"welded; (?:(\d+) rim edges|closed \(no rim\))", done.stdout)
    if done.returncode != 0 or not rims:
        raise CheckFailure(f"odeskin surface {options.network} exited {done.returncode}, or printed no weld line: "
                           f"{done.stderr.strip() or done.stdout.strip()}")
    rim_edges = int(rims.group(1) or 0)
    reset_scene(24)
    bpy.ops.import_scene.gltf(filepath=str(glb))
    obj = only_mesh()
    compare("surface", evaluated_positions(obj, 0), obj_positions(glb.with_suffix(".obj")), TOLERANCE["surface"])
    mesh = bmesh.new()
    mesh.from_mesh(obj.data)
    boundary = sum(1 for e in mesh.edges if len(e.link_faces) == 1)
    non_manifold = sum(1 for e in mesh.edges if len(e.link_faces) > 2)
    mesh.free()
    log(f"{glb.name}: {boundary} edges with one face (odeskin reports {rim_edges} rim edges), "
        f"{non_manifold} with more than two")
    if boundary != rim_edges or non_manifold:
        failures.append(f"Blender sees {boundary} open and {non_manifold} non-manifold edges, odeskin {rim_edges} rim edges")


def main():
    options = parse_args()
    out = Path(options.out)
    out.mkdir(parents=True, exist_ok=True)
    log(f"Blender {bpy.app.version_string}, check {options.check}, input {options.mesh or options.asset or options.network or options.poses}")
    needs = {"rig": "mesh", "animated": "mesh", "roundtrip": "poses", "rig_gltf": "poses", "obj_uv": "poses",
             "surface": "network"}.get(options.check, "asset")
    given = [name for name in ("mesh", "poses", "asset", "network") if getattr(options, name) is not None]
    if given != [needs] or (options.check in ("roundtrip", "rig_gltf", "obj_uv") and len(options.poses) < 2):
        log(f"FAILED: the {options.check} check takes --{needs}" + (" with two or more poses" if needs == "poses" else ""))
        sys.exit(1)
    if (options.check == "ply") != (options.reference is not None):
        log("FAILED: give --reference for the ply check, and only for it")
        sys.exit(1)
    try:
        with tempfile.TemporaryDirectory(dir=out) as scratch:
            checks = {"compact": check_compact, "quantized": check_compact, "baked": check_baked,
                      "baked_quantized": check_baked, "pc2": check_point_cache,
                      "mdd": check_point_cache, "rig": check_rig, "ply": check_ply, "roundtrip": check_roundtrip,
                      "rig_gltf": check_rig_gltf, "surface": check_surface, "animated": check_animated,
                      "obj_uv": check_obj_uv}
            checks[options.check](options, Path(scratch))
        if failures:
            raise CheckFailure(f"{len(failures)} comparison(s) over the tolerance; first: {failures[0]}")
    except CheckFailure as failure:
        log(f"FAILED: {failure}")
        sys.exit(1)
    except Exception as error:  # an importer's own exception is a failure too, not a crash of the test
        log(f"FAILED: {type(error).__name__}: {error}")
        sys.exit(1)
    log("passed")


main()
