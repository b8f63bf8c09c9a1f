"""Blender reads Sinew's render surface and point cache (run inside Blender, headless):

    blender -b --factory-startup --python-exit-code 1 --python tests/blender/check_pc2.py -- \
        OUT_DIR [--prefix embedded_surface] [--frames 0,1,2]

Imports OUT_DIR/<prefix>_rest.obj with Blender's own OBJ importer (no axis change), adds a Mesh
Cache modifier reading OUT_DIR/<prefix>.pc2, and for each Sinew frame F reads the evaluated
vertex positions at the cache sample of F and compares them with OUT_DIR/<prefix>_FFFF.obj
(the vertices its faces use, in file order, which is the order Blender's importer keeps).
Raises (exit code 1 with --python-exit-code 1) on any mismatch; prints "check_pc2: ok".
"""
import argparse
import struct
import sys

import bpy


def obj_used_positions(path):
    """Positions of the vertices the faces use, in file order (what Blender's importer builds)."""
    positions, used = [], set()
    with open(path, encoding="utf-8") as f:
        for line in f:
            t = line.split()
            if not t:
                continue
            if t[0] == "v":
                positions.append(tuple(float(c) for c in t[1:4]))
            elif t[0] == "f":
                for corner in t[1:]:
                    i = int(corner.split("/")[0])
                    used.add(i - 1 if i > 0 else len(positions) + i)
    return [positions[i] for i in sorted(used)]


def pc2_header(path):
    with open(path, "rb") as f:
        magic, version, points, start, rate, samples = struct.unpack("<12siiffi", f.read(32))
    if magic != b"POINTCACHE2\0" or version != 1:
        raise RuntimeError(f"{path}: not a PC2 version 1 file")
    return points, start, rate, samples


def max_difference(a, b):
    return max(abs(p - q) for u, v in zip(a, b) for p, q in zip(u, v))


def main(argv):
    parser = argparse.ArgumentParser(prog="check_pc2.py")
    parser.add_argument("out_dir")
    parser.add_argument("--prefix", default="embedded_surface")
    parser.add_argument("--frames", default="0,1", help="Sinew frames to compare (multiples of output.every)")
    args = parser.parse_args(argv)
    base = f"{args.out_dir}/{args.prefix}"
    points, start, rate, samples = pc2_header(base + ".pc2")

    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.wm.obj_import(filepath=base + "_rest.obj", forward_axis="Y", up_axis="Z")
    meshes = [o for o in bpy.context.scene.objects if o.type == "MESH"]
    if len(meshes) != 1:
        raise RuntimeError(f"the rest OBJ imported as {len(meshes)} objects, expected 1")
    obj = meshes[0]
    rest = [tuple(v.co) for v in obj.data.vertices]
    if len(rest) != points:
        raise RuntimeError(f"Blender built {len(rest)} vertices, the cache has {points} points")
    expected_rest = obj_used_positions(base + "_rest.obj")
    scale = max(max(abs(c) for c in p) for p in expected_rest) or 1.0
    tolerance = 1e-5 * scale  # float32 in the cache and in Blender's mesh
    d = max_difference(rest, expected_rest)
    if d > tolerance:
        raise RuntimeError(f"rest OBJ vertices differ in Blender by {d}")

    cache = obj.modifiers.new("sinew", "MESH_CACHE")
    cache.cache_format = "PC2"
    cache.filepath = base + ".pc2"
    cache.time_mode = "FRAME"   # scene frame -> sample index: (frame - frame_start) * frame_scale
    cache.frame_start = 1.0     # Blender frame 1 plays Sinew's first sample (frame 0)
    cache.frame_scale = 1.0
    cache.interpolation = "NONE"
    cache.deform_mode = "OVERWRITE"
    scene = bpy.context.scene
    report = []
    for frame in (int(f) for f in args.frames.split(",")):
        sample = (frame - start) / rate
        if sample != int(sample) or not 0 <= sample < samples:
            raise RuntimeError(f"Sinew frame {frame} is not a sample of the cache (start {start}, rate {rate}, {samples} samples)")
        scene.frame_set(1 + int(sample))
        evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
        got = [tuple(v.co) for v in evaluated.data.vertices]
        expected = obj_used_positions(f"{base}_{frame:04d}.obj")
        if len(got) != len(expected):
            raise RuntimeError(f"frame {frame}: Blender has {len(got)} vertices, Sinew's OBJ {len(expected)}")
        d = max_difference(got, expected)
        moved = max_difference(expected, expected_rest)
        report.append(f"frame {frame}: max |Blender - Sinew| = {d:.2e} (moved {moved:.3g} from rest)")
        if d > tolerance:
            raise RuntimeError(f"frame {frame}: Blender's Mesh Cache positions differ from Sinew's by {d:.3e} (> {tolerance:.1e})")
    for line in report:
        print("check_pc2:", line)
    print(f"check_pc2: ok ({points} points, {samples} samples)")


main(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])
