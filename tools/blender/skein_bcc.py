"""Blender add-on: import skein's yarn (.bcc) as exact curves (issue 25, part 4).

skein's yarn is uniform Catmull-Rom curves through its control points (docs/FORMATS.md, ".bcc"); an open yarn's
end segments repeat their end point as the missing neighbour. Each segment p1..p2 with neighbours p0, p3 is the
cubic Bezier with handles p1 + (p2 - p0) / 6 and p2 - (p3 - p1) / 6, so the curves Blender draws are skein's
curves exactly. Each yarn becomes one Bezier spline of a curve object whose bevel depth is the yarn radius from
the file's header, in metres (Blender's unit) unless told otherwise.

Install: Edit > Preferences > Add-ons > Install..., pick this file, enable "Import: skein yarn". Then
File > Import > skein yarn (.bcc). Headless: blender -b --python tools/blender/skein_bcc.py -- yarn.bcc [out.blend]
"""
import struct
import sys

bl_info = {
    "name": "skein yarn (.bcc)",
    "author": "skein",
    "version": (1, 0, 0),
    "blender": (3, 4, 0),
    "location": "File > Import > skein yarn (.bcc)",
    "description": "Imports skein's Catmull-Rom yarn curves as exact Bezier curves with the yarn's radius",
    "category": "Import-Export",
}


def read_bcc(path):
    """(radius in mm, curves): curves as (closed, [(x, y, z), ...]). Raises ValueError naming what is wrong."""
    with open(path, "rb") as f:
        data = f.read()
    if len(data) < 64 or data[:3] != b"BCC" or data[3] != 0x44:
        raise ValueError(f"{path}: not a .bcc file of 4-byte numbers")
    if data[4:6] != b"C0" or data[6] != 3:
        raise ValueError(f"{path}: not 3-D Catmull-Rom curves")
    count = struct.unpack_from("<Q", data, 8)[0]
    text = data[24:64].split(b"\0")[0].decode(errors="replace")
    radius = float(text.split("radius ")[1].split()[0]) if "radius " in text else 0.5
    curves, at = [], 64
    for c in range(count):
        if at + 4 > len(data):
            raise ValueError(f"{path}: curve {c} is cut off at byte {at}")
        n = struct.unpack_from("<i", data, at)[0]
        closed, n = n < 0, abs(n)
        if at + 4 + 12 * n > len(data):
            raise ValueError(f"{path}: curve {c} is cut off at byte {at}")
        curves.append((closed, list(struct.iter_unpack("<3f", data[at + 4:at + 4 + 12 * n]))))
        at += 4 + 12 * n
    return radius, curves


def bezier_handles(points, closed):
    """Per control point (left handle, right handle) of the Catmull-Rom curve through `points`."""
    n = len(points)
    def at(i):
        if closed:
            return points[i % n]
        return points[min(max(i, 0), n - 1)]  # an open yarn repeats its end points
    handles = []
    for i in range(n):
        prev, here, nxt = at(i - 1), at(i), at(i + 1)
        tangent = [(nxt[k] - prev[k]) / 6 for k in range(3)]
        handles.append((tuple(here[k] - tangent[k] for k in range(3)), tuple(here[k] + tangent[k] for k in range(3))))
    return handles


def import_bcc(path, scale=0.001, name=None):
    """Adds one curve object holding every yarn of `path`; coordinates times `scale` (mm to m by default)."""
    import bpy
    radius, curves = read_bcc(path)
    data = bpy.data.curves.new(name or "skein yarn", type="CURVE")
    data.dimensions = "3D"
    data.bevel_depth = radius * scale
    data.bevel_resolution = 2
    data.resolution_u = 4
    for closed, points in curves:
        if len(points) < 2:
            continue
        spline = data.splines.new("BEZIER")
        spline.bezier_points.add(len(points) - 1)
        for point, p, (left, right) in zip(spline.bezier_points, points, bezier_handles(points, closed)):
            point.co = tuple(x * scale for x in p)
            point.handle_left_type = point.handle_right_type = "FREE"
            point.handle_left = tuple(x * scale for x in left)
            point.handle_right = tuple(x * scale for x in right)
        spline.use_cyclic_u = closed
    obj = bpy.data.objects.new(name or "skein yarn", data)
    bpy.context.scene.collection.objects.link(obj)
    return obj


try:  # the add-on's operator and menu entry, when run inside Blender
    import bpy
    from bpy_extras.io_utils import ImportHelper

    class ImportSkeinBcc(bpy.types.Operator, ImportHelper):
        """Import skein yarn curves (.bcc)"""
        bl_idname = "import_curve.skein_bcc"
        bl_label = "Import skein yarn"
        filename_ext = ".bcc"
        filter_glob: bpy.props.StringProperty(default="*.bcc", options={"HIDDEN"})
        scale: bpy.props.FloatProperty(name="Scale", description="Metres per file unit (skein writes millimetres)", default=0.001)

        def execute(self, context):
            try:
                import_bcc(self.filepath, self.scale)
            except (OSError, ValueError) as error:
                self.report({"ERROR"}, str(error))
                return {"CANCELLED"}
            return {"FINISHED"}

    def menu_entry(self, context):
        self.layout.operator(ImportSkeinBcc.bl_idname, text="skein yarn (.bcc)")

    def register():
        bpy.utils.register_class(ImportSkeinBcc)
        bpy.types.TOPBAR_MT_file_import.append(menu_entry)

    def unregister():
        bpy.types.TOPBAR_MT_file_import.remove(menu_entry)
        bpy.utils.unregister_class(ImportSkeinBcc)
except ImportError:  # outside Blender: read_bcc and bezier_handles still work
    pass


if __name__ == "__main__" and "--" in sys.argv:
    args = sys.argv[sys.argv.index("--") + 1:]
    import bpy
    bpy.ops.wm.read_factory_settings(use_empty=True)
    import_bcc(args[0])
    if len(args) > 1:
        bpy.ops.wm.save_as_mainfile(filepath=args[1])
