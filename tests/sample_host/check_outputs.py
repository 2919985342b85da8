#!/usr/bin/env python3
"""Checks what the sample programs write, run by ctest:

  check_outputs.py host HOST_EXE OUT_DIR [SCENE]
                                             runs the headless host on SCENE (default: the
                                             bundled default scene) for 7 frames with exports
                                             (meshes, poses, .vti volumes) and snapshots every
                                             3 frames, checks every file against what the
                                             scene holds
  check_outputs.py viewer VIEWER_EXE PNG     runs the viewer for a few frames (the caller
                                             provides the display, e.g. xvfb-run), checks the
                                             screenshot is not blank
"""
import csv
import json
import os
import re
import math
import shutil
import struct
import subprocess
import sys
import xml.etree.ElementTree as ET

from PIL import Image


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def check_not_blank(path, min_foreground=0.05):
    """A picture of the scene, not a cleared buffer: enough pixels differ from the background
    (the most common colour), and they are not all one colour."""
    if not os.path.isfile(path):
        fail("%s was not written" % path)
    img = Image.open(path).convert("RGB")
    pixels = list(img.getdata())
    background = max(set(pixels), key=pixels.count)
    foreground = sum(1 for p in pixels if sum(abs(a - b) for a, b in zip(p, background)) > 30)
    fraction = foreground / len(pixels)
    distinct = len(set(pixels))
    print("%s: %dx%d, %.1f%% off the background, %d colours" % (path, img.width, img.height, 100 * fraction, distinct))
    if fraction < min_foreground:
        fail("%s is nearly blank (%.2f%% foreground)" % (path, 100 * fraction))
    if distinct < 50:
        fail("%s has only %d colours: no shading, nothing drawn?" % (path, distinct))


def read_ply(path):
    """Vertex positions of an ASCII PLY file, and the face count; checks normals are there."""
    with open(path) as f:
        header = []
        for line in f:
            header.append(line.strip())
            if line.strip() == "end_header":
                break
        if header[0] != "ply" or "format ascii 1.0" not in header:
            fail("%s: not an ASCII PLY file" % path)
        counts = {h.split()[1]: int(h.split()[2]) for h in header if h.startswith("element")}
        props = [h.split()[-1] for h in header if h.startswith("property") and "list" not in h]
        if props[:6] != ["x", "y", "z", "nx", "ny", "nz"]:
            fail("%s: expected x y z nx ny nz vertex properties, got %s" % (path, props))
        rows = [next(f).split() for _ in range(counts["vertex"])]
        faces = [next(f).split() for _ in range(counts["face"])]
    if not rows or not faces or any(face[0] != "3" for face in faces):
        fail("%s: expected a triangle mesh, got %d vertices, %d faces" % (path, len(rows), len(faces)))
    if any(int(i) >= len(rows) for face in faces for i in face[1:]):
        fail("%s: face index out of range" % path)
    return [tuple(float(v) for v in r[:3]) for r in rows], len(faces)


DEFAULT_SCENE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "sample_host", "scenes",
                             "default.json")


def read_scene(path):
    """The scene as JSON; scene files may hold // and /* */ comments (outside strings)."""
    with open(path) as f:
        text = f.read()
    pattern = r'("(?:\\.|[^"\\])*")|//[^\n]*|/\*.*?\*/'
    return json.loads(re.sub(pattern, lambda m: m.group(1) or "", text, flags=re.S))


def labels(scene, kind, key):
    """The host's labels for a kind of actor: its scene name, or KIND + its place. (The test
    scenes' names are already file- and CSV-safe and unique; vp_actor_labels_test covers the
    rest of the rules.)"""
    return [a.get("name") or "%s%d" % (kind, k) for k, a in enumerate(scene.get(key, []))]


def check_fluid_stats(rows):
    """A scene with fluids reports their phases: time in advection every frame, and a pressure
    solve that iterated (a warm-started solve of a fluid at rest may need no iteration in some
    frames, so not necessarily in every one)."""
    for row in rows:
        if float(row["fluid_ms"]) <= 0 or float(row["fluid_advect_ms"]) <= 0:
            fail("stats.csv frame %s: no fluid phases (fluid_ms %s, fluid_advect_ms %s)"
                 % (row["frame"], row["fluid_ms"], row["fluid_advect_ms"]))
    if not any(int(row["fluid_pressure_iters"]) > 0 for row in rows):
        fail("stats.csv: the fluids' pressure solve never iterated")


FRAME_PLAN_COLUMNS = ("interval", "progress", "slices", "residual")


def check_actor_columns(rows, header, deformables, fluids):
    """Every actor has its own columns, named by its label, and no column is there twice;
    without a budget every actor steps every frame, so a fluid's simulated time is the frame's
    dt (1/60 s, the host's default) and every interval 1; the frame plan's progress is a
    fraction, its slices a count, its residual not negative."""
    if len(set(header)) != len(header):
        fail("stats.csv repeats columns: %s" % sorted(c for c in set(header) if header.count(c) > 1))
    actors = deformables + fluids
    names = ["%s_ms" % a for a in actors] + ["%s_sim_dt" % f for f in fluids]
    names += ["%s_%s" % (a, c) for a in actors for c in FRAME_PLAN_COLUMNS]
    missing = [n for n in names if n not in rows[0]]
    if missing:
        fail("stats.csv lacks the per-actor columns %s (has %s)" % (missing, header))
    for row in rows:
        if any(float(row["%s_ms" % d]) <= 0 for d in deformables):
            fail("stats.csv frame %s: a deformable took no time" % row["frame"])
        if any(abs(float(row["%s_sim_dt" % f]) - 1 / 60) > 1e-5 for f in fluids) \
                or row["fluid_interval"] != "1":
            fail("stats.csv frame %s: unbudgeted fluids did not step every frame" % row["frame"])
        for a in actors:
            interval, progress = row[a + "_interval"], float(row[a + "_progress"])
            slices, residual = row[a + "_slices"], float(row[a + "_residual"])
            if interval != "1" or not 0 <= progress <= 1 or not slices.isdigit() or not residual >= 0:
                fail("stats.csv frame %s: %s has interval %s, progress %s, slices %s, residual %s (unbudgeted: "
                     "interval 1, progress in [0, 1], a count of slices, a residual >= 0)"
                     % (row["frame"], a, interval, progress, slices, residual))


def check_summary(stdout, frames, deformables, fluids):
    """The summary line: no frame over an unlimited budget, every actor at interval 1 all run
    long, and the deformables' residual percentiles when there are deformables."""
    lines = [l for l in stdout.splitlines() if l.startswith("summary: %d frames" % frames)]
    if len(lines) != 1:
        fail("expected one summary line for %d frames in the host's output" % frames)
    summary = lines[0]
    intervals = "".join(" %s 1-1" % a for a in deformables + fluids)
    expected = ["over 1.1x budget 0 (0.0%)"] + ([", intervals" + intervals] if intervals else [])
    missing = [e for e in expected if e not in summary]
    residuals = re.search(r"deformable residual p50 (\S+) p95 (\S+)$", summary)
    if missing or bool(residuals) != bool(deformables):
        fail("summary line %r lacks %s%s" % (summary, missing, " or the residual percentiles" if deformables else ""))
    if residuals and not 0 <= float(residuals.group(1)) <= float(residuals.group(2)):
        fail("summary line %r: residual p50 above p95 or negative" % summary)


def check_liquid_meshes(out, fluid, names):
    """A liquid's surface in every exported frame: a real triangle mesh with normals (read_ply
    checks both) in world space, so inside the fluid's domain box."""
    h = fluid.get("cellSize", 1.0 / 32)
    lo = fluid.get("origin", [0, 0, 0])
    hi = [lo[a] + h * fluid.get("resolution", [32, 32, 32])[a] for a in range(3)]
    for name in names:
        vertices, faces = read_ply(os.path.join(out, "meshes", name))
        if faces < 10:
            fail("%s: a liquid surface of only %d triangles" % (name, faces))
        outside = [v for v in vertices if any(v[a] < lo[a] - h or v[a] > hi[a] + h for a in range(3))]
        if outside:
            fail("%s: %d vertices outside the domain %s..%s, e.g. %s" % (name, len(outside), lo, hi, outside[0]))


def check_poses(out, scene, colliders, frames):
    """poses.csv: a row per exported frame, seven columns per collider named by its label; a
    static collider stays where the scene put it (position; rotation given or identity)."""
    with open(os.path.join(out, "poses.csv")) as f:
        reader = csv.reader(f)
        header = next(reader)
        rows = list(reader)
    expected = ["frame", "time_s"] + ["%s_%s" % (c, a) for c in colliders
                                      for a in ("px", "py", "pz", "qx", "qy", "qz", "qw")]
    if header != expected:
        fail("poses.csv header %s, expected %s" % (header, expected))
    if [int(r[0]) for r in rows] != list(frames):
        fail("poses.csv holds frames %s, expected %s" % ([r[0] for r in rows], list(frames)))
    for row in rows:
        if abs(float(row[1]) - (int(row[0]) + 1) / 60) > 1e-5:
            fail("poses.csv frame %s: time %s, expected (frame + 1) / 60" % (row[0], row[1]))
        for k, c in enumerate(scene.get("colliders", [])):
            if c.get("bodyType", "static") != "static" or "rotation" in c or "axisAngle" in c:
                continue
            pose = [float(v) for v in row[2 + 7 * k:9 + 7 * k]]
            want = list(c.get("position", [0, 0, 0])) + [0, 0, 0, 1]
            if any(abs(a - b) > 1e-5 for a, b in zip(pose, want)):
                fail("poses.csv frame %s: static %s at %s, the scene puts it at %s" % (row[0], colliders[k], pose, want))


def read_vti(path):
    """A .vti as the host writes it: the XML before the raw appended data (parsed, so it is
    well-formed), and each CellData array by name, read at its offset (UInt64 byte count, then
    little-endian Float32 values)."""
    with open(path, "rb") as f:
        data = f.read()
    marker = b'<AppendedData encoding="raw">'
    at = data.find(marker)
    if at < 0:
        fail("%s: no raw appended data" % path)
    root = ET.fromstring(data[:at].decode("ascii") + "</VTKFile>")
    if root.get("type") != "ImageData" or root.get("header_type") != "UInt64" \
            or root.get("byte_order") != "LittleEndian":
        fail("%s: VTKFile attributes %s" % (path, root.attrib))
    start = data.index(b"_", at) + 1
    arrays = {}
    for a in root.iter("DataArray"):
        offset = start + int(a.get("offset"))
        (size,) = struct.unpack_from("<Q", data, offset)
        arrays[a.get("Name")] = struct.unpack_from("<%df" % (size // 4), data, offset + 8)
    if root.find("ImageData/Piece/CellData") is None or len(arrays) != len(list(root.iter("DataArray"))):
        fail("%s: expected the arrays as CellData" % path)
    return root.find("ImageData"), arrays


def check_volumes(out, fluids, names, frames):
    """volumes/LABEL_fNNNNN.vti for every fluid and exported frame: the image is the fluid's
    domain in cells, smoke has density (not negative, some where the emitter is) and
    temperature, a liquid a level set whose inside holds about the scene's initial liquid on
    the first frame (boxes; what the colliders in it displace is within the tolerance)."""
    for fluid, name in zip(fluids, names):
        h = fluid.get("cellSize", 1.0 / 32)
        n = fluid.get("resolution", [32, 32, 32])
        origin = fluid.get("origin", [0, 0, 0])
        liquid = fluid.get("kind", "smoke") == "liquid"
        for frame in frames:
            path = os.path.join(out, "volumes", "%s_f%05d.vti" % (name, frame))
            image, arrays = read_vti(path)
            extent = [int(v) for v in image.get("WholeExtent").split()]
            if extent != [0, n[0], 0, n[1], 0, n[2]]:
                fail("%s: WholeExtent %s for a grid of %s cells" % (path, extent, n))
            if any(abs(float(v) - o) > 1e-6 for v, o in zip(image.get("Origin").split(), origin)) \
                    or any(abs(float(v) - h) > 1e-7 for v in image.get("Spacing").split()):
                fail("%s: Origin %s Spacing %s, the scene has %s and %s" % (path, image.get("Origin"),
                                                                         image.get("Spacing"), origin, h))
            expected = ["level_set"] if liquid else ["density", "temperature"]
            if sorted(arrays) != sorted(expected) or any(len(v) != n[0] * n[1] * n[2] for v in arrays.values()):
                fail("%s: arrays %s of %s values, expected %s of %d" % (
                    path, sorted(arrays), [len(v) for v in arrays.values()], expected, n[0] * n[1] * n[2]))
            if any(not math.isfinite(x) for v in arrays.values() for x in v):
                fail("%s: values that are not finite" % path)
            if liquid and frame == frames[0]:
                inside = sum(h ** 3 for phi in arrays["level_set"] if phi < 0)
                initial = sum(8 * r["halfExtents"][0] * r["halfExtents"][1] * r["halfExtents"][2]
                              for r in fluid.get("initialLiquid", []) if r.get("type") == "box")
                if abs(inside - initial) > 0.25 * initial:
                    fail("%s: %.4f m^3 inside the level set, the scene starts with %.4f" % (path, inside, initial))
            elif not liquid and (min(arrays["density"]) < 0 or max(arrays["density"]) <= 0):
                fail("%s: smoke density in [%g, %g]" % (path, min(arrays["density"]), max(arrays["density"])))
        print("%s: %d frames of %s, %s" % (name, len(frames), "x".join(map(str, n)), ", ".join(expected)))


def check_host(exe, out, scene_path=DEFAULT_SCENE):
    shutil.rmtree(out, ignore_errors=True)
    scene = read_scene(scene_path)
    colliders = labels(scene, "collider", "colliders")
    deformables = labels(scene, "deformable", "deformables")
    fluids = scene.get("fluids", [])
    fluid_names = labels(scene, "fluid", "fluids")
    liquids = [k for k, f in enumerate(fluids) if f.get("kind", "smoke") == "liquid"]
    # No frame budget: the motion checked below must not depend on the machine's speed (under
    # ASan on a loaded machine the budget can be spent before the solver runs at all).
    r = subprocess.run([exe, "--scene", scene_path, "--frames", "7", "--budget", "0", "--export-every", "3",
                        "--export-volumes", "vti", "--snapshot-every", "3", "--quiet", "--out", out],
                       capture_output=True, text=True, timeout=300)
    print(r.stdout + r.stderr)
    if r.returncode != 0:
        fail("host exited with %d" % r.returncode)
    with open(os.path.join(out, "stats.csv")) as f:
        header = f.readline().strip().split(",")
        f.seek(0)
        rows = list(csv.DictReader(f))
    if len(rows) != 7:
        fail("stats.csv has %d rows, expected 7" % len(rows))
    # Frames 0, 3, 6 (every 3rd, and the last) for every deformable and every liquid (smoke has
    # no surface to export), each collider's mesh once.
    frames = (0, 3, 6)
    liquid_files = ["%s_f%05d.ply" % (fluid_names[k], f) for k in liquids for f in frames]
    expected = ["%s_f%05d.ply" % (d, f) for d in deformables for f in frames] + liquid_files
    expected += ["%s.ply" % c for c in colliders]
    meshes = sorted(os.listdir(os.path.join(out, "meshes")))
    if meshes != sorted(expected):
        fail("meshes/ holds %s, expected %s" % (meshes, expected))
    if deformables:
        first, nf0 = read_ply(os.path.join(out, "meshes", "%s_f00000.ply" % deformables[0]))
        last, nf6 = read_ply(os.path.join(out, "meshes", "%s_f00006.ply" % deformables[0]))
        if len(first) != len(last) or nf0 != nf6:
            fail("the render mesh changed its size between frames")
        moved = max(abs(a[1] - b[1]) for a, b in zip(first, last))
        if moved < 1e-3:
            fail("the exported jelly did not move between frames 0 and 6 (max dy %g)" % moved)
    for k in liquids:
        check_liquid_meshes(out, fluids[k], [n for n in liquid_files if n.startswith(fluid_names[k] + "_f")])
    for c in colliders:
        read_ply(os.path.join(out, "meshes", c + ".ply"))
    check_poses(out, scene, colliders, frames)
    volumes = sorted(os.listdir(os.path.join(out, "volumes")))
    if volumes != sorted("%s_f%05d.vti" % (n, f) for n in fluid_names for f in frames):
        fail("volumes/ holds %s" % volumes)
    check_volumes(out, fluids, fluid_names, frames)
    if fluids:
        check_fluid_stats(rows)
    check_actor_columns(rows, header, deformables, fluid_names)
    check_summary(r.stdout, 7, deformables, fluid_names)
    shots = sorted(os.listdir(os.path.join(out, "snapshots")))
    if shots != ["frame_00000.png", "frame_00003.png", "frame_00006.png"]:
        fail("snapshots/ holds %s" % shots)
    for s in shots:
        check_not_blank(os.path.join(out, "snapshots", s))
    svg = ET.parse(os.path.join(out, "frame_times.svg")).getroot()
    lines = {e.get("id"): e for e in svg.iter() if e.tag.endswith("polyline")}
    if sorted(lines) != ["budget", "over_budget", "step_time"] or \
            any(len(e.get("points").split()) != 7 for e in lines.values()):
        fail("frame_times.svg: expected budget, over-budget and step-time lines of 7 points each, got %s" % sorted(lines))
    print("host outputs OK")


def check_viewer(exe, png):
    if os.path.exists(png):
        os.unlink(png)
    r = subprocess.run([exe, "--frames", "20", "--size", "640x400", "--screenshot", png],
                       capture_output=True, text=True, timeout=300)
    print(r.stdout + r.stderr)
    if r.returncode != 0:
        fail("viewer exited with %d" % r.returncode)
    check_not_blank(png)
    print("viewer screenshot OK")


if __name__ == "__main__":
    if sys.argv[1:2] == ["host"] and len(sys.argv) in (4, 5):
        check_host(*sys.argv[2:])
    elif sys.argv[1:2] == ["viewer"] and len(sys.argv) == 4:
        check_viewer(sys.argv[2], sys.argv[3])
    else:
        print(__doc__)
        sys.exit(2)
