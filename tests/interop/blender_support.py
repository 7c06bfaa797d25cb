# SPDX-License-Identifier: MIT
# What every check in blender_check.py shares: running odeskin, reading its OBJ files, resetting
# Blender's scene, evaluating a mesh at a frame, and comparing vertices with a tolerance.
import re
import subprocess

import bpy
import numpy

# Debian 12's Blender 3.4 glTF importer still uses numpy.bool, which Debian's numpy 1.24 removed:
# every glTF import fails with AttributeError without this alias (the importer means the builtin).
if "bool" not in numpy.__dict__:
    numpy.bool = bool


class CheckFailure(Exception):
    pass


def log(message):
    print(f"blender-check: {message}", flush=True)


def odeskin(options, *args):
    done = subprocess.run([options.odeskin, *args, "--quiet"], capture_output=True, text=True)
    if done.returncode != 0:
        raise CheckFailure(f"odeskin {' '.join(args)} exited {done.returncode}: {done.stderr.strip()}")


def segment_seconds(options, asset):
    done = subprocess.run([options.odeskin, "info", str(asset)], capture_output=True, text=True)
    # "key poses:      3 (2 segments, 2 s)"
    found = re.search(r"^key poses:\s+\d+ \((\d+) segments?, ([0-9.e+-]+) s\)", done.stdout, re.MULTILINE)
    if done.returncode != 0 or not found:
        raise CheckFailure(f"odeskin info {asset} did not give the segment length: {done.stderr.strip()}")
    return float(found.group(2)) / int(found.group(1))


def obj_positions(path):
    """Positions of an OBJ odeskin wrote, turned from glTF's y-up to Blender's z-up as its importers do."""
    points = []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                x, y, z = (float(v) for v in line.split()[1:4])
                points.append((x, -z, y))
    return numpy.array(points)


def reset_scene(fps):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.context.scene.render.fps = fps  # importers turn glTF seconds into frames at the scene's rate
    bpy.context.scene.render.fps_base = 1.0


def only_mesh():
    meshes = [o for o in bpy.context.scene.objects if o.type == "MESH"]
    if len(meshes) != 1:
        raise CheckFailure(f"expected one mesh object after import, found {len(meshes)}")
    return meshes[0]


def evaluated_positions(obj, frame):
    bpy.context.scene.frame_set(frame)
    evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
    mesh = evaluated.to_mesh()
    local = numpy.empty(len(mesh.vertices) * 3)
    mesh.vertices.foreach_get("co", local)
    evaluated.to_mesh_clear()
    matrix = numpy.array(obj.matrix_world)
    local = local.reshape(-1, 3)
    return local @ matrix[:3, :3].T + matrix[:3, 3]


failures = []  # every time is compared and printed before the check fails


def compare(label, shown, reference, tolerance):
    if shown.shape != reference.shape:
        raise CheckFailure(f"{label}: Blender has {len(shown)} vertices, odeskin's file {len(reference)}")
    box = float((reference.max(axis=0) - reference.min(axis=0)).max())
    distance = numpy.linalg.norm(shown - reference, axis=1)
    worst = int(distance.argmax())
    relative = float(distance[worst]) / box
    log(f"{label}: {len(shown)} vertices, largest difference {relative:.2e} of the box (vertex {worst})")
    if not relative <= tolerance:
        failures.append(f"{label}: vertex {worst} is {relative:.2e} of the box from odeskin's "
                        f"(tolerance {tolerance:.0e})")
