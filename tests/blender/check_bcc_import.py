"""Run by Blender (label `blender`): blender -b --python tests/blender/check_bcc_import.py -- YARN.bcc OUT.png

Imports YARN.bcc with tools/blender/skein_bcc.py and checks that Blender's Bezier curves are skein's Catmull-Rom
curves (every segment's midpoint (-p0 + 9 p1 + 9 p2 - p3) / 16 on Blender's curve), that the bevel is the yarn
radius, and that a Workbench render of it is not blank. Exits 1 with the reason on a failure."""
import os
import sys

import bpy
from mathutils import Vector
from mathutils.geometry import interpolate_bezier

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "tools", "blender"))
import skein_bcc  # noqa: E402

bcc, png = sys.argv[sys.argv.index("--") + 1:][:2]


def fail(reason):
    print("FAIL:", reason)
    sys.exit(1)


bpy.ops.wm.read_factory_settings(use_empty=True)
radius, curves = skein_bcc.read_bcc(bcc)
obj = skein_bcc.import_bcc(bcc)
splines = obj.data.splines
if len(splines) != len(curves):
    fail(f"{len(splines)} splines for {len(curves)} curves")
if abs(obj.data.bevel_depth - radius * 0.001) > 1e-9:
    fail(f"bevel {obj.data.bevel_depth} m for a radius of {radius} mm")
worst, segments = 0.0, 0
for spline, (closed, points) in zip(splines, curves):
    n = len(points)
    if len(spline.bezier_points) != n or spline.use_cyclic_u != closed:
        fail(f"a spline of {len(spline.bezier_points)} points (cyclic {spline.use_cyclic_u}) for {n} (closed {closed})")
    at = (lambda i: Vector(points[i % n]) * 0.001) if closed else (lambda i: Vector(points[min(max(i, 0), n - 1)]) * 0.001)
    for i in range(n if closed else n - 1):
        a, b = spline.bezier_points[i], spline.bezier_points[(i + 1) % n]
        middle = interpolate_bezier(a.co, a.handle_right, b.handle_left, b.co, 3)[1]
        expected = (-at(i - 1) + 9 * at(i) + 9 * at(i + 1) - at(i + 2)) / 16
        worst = max(worst, (middle - expected).length)
        segments += 1
if worst > 1e-7:  # 0.1 micrometre: float precision of millimetres read in metres
    fail(f"a segment's midpoint is {worst * 1e3:.3g} mm off skein's curve")

# A picture: the Workbench engine, a camera framing the yarn from the front.
scene = bpy.context.scene
scene.render.engine = "BLENDER_WORKBENCH"
scene.render.resolution_x, scene.render.resolution_y = 480, 360
scene.render.filepath = png
lo = Vector([min(v[k] for _, pts in curves for v in pts) for k in range(3)]) * 0.001
hi = Vector([max(v[k] for _, pts in curves for v in pts) for k in range(3)]) * 0.001
centre, size = (lo + hi) / 2, max((hi - lo).length, 1e-3)
camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
scene.collection.objects.link(camera)
camera.location = centre + Vector((0, 0, 1.6 * size))
scene.camera = camera
bpy.ops.render.render(write_still=True)
image = bpy.data.images.load(png)
pixels = list(image.pixels)
background = pixels[0:3]
covered = sum(1 for k in range(0, len(pixels), 4) if sum(abs(pixels[k + c] - background[c]) for c in range(3)) > 0.1)
share = covered / (len(pixels) // 4)
if share < 0.05:
    fail(f"the render is blank ({share:.3f} of the pixels differ from the corner)")
print(f"OK: {len(curves)} curves, {segments} segments, worst midpoint {worst * 1e3:.2g} mm, render covers {share:.2f}")
