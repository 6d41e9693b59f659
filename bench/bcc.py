"""Reads Cem Yuksel's .bcc curve files for the bench scripts (docs/FORMATS.md): the yarn radius from skein's header
text and each curve's control points."""
import struct
import sys


def read_curves(path):
    """(radius, curves): the radius from the header (0 when it names none), curves as lists of (x, y, z)."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:3] != b"BCC" or len(data) < 64:
        sys.exit(f"{path}: not a .bcc file")
    info = data[24:64].split(b"\0")[0].decode(errors="replace")
    radius = float(info.split("radius ")[1].split()[0]) if "radius " in info else 0.0
    count, at, curves = struct.unpack_from("<Q", data, 8)[0], 64, []
    for _ in range(count):
        n = abs(struct.unpack_from("<i", data, at)[0])
        curves.append(list(struct.iter_unpack("<3f", data[at + 4:at + 4 + 12 * n])))
        at += 4 + 12 * n
    return radius, curves


def rewrite_points(src, dst, move):
    """Copies the .bcc file src to dst with every control point p replaced by move(p) (header and curves kept)."""
    with open(src, "rb") as f:
        data = bytearray(f.read())
    if data[:3] != b"BCC" or len(data) < 64:
        sys.exit(f"{src}: not a .bcc file")
    count, at = struct.unpack_from("<Q", data, 8)[0], 64
    for _ in range(count):
        n = abs(struct.unpack_from("<i", data, at)[0])
        for k in range(n):
            struct.pack_into("<3f", data, at + 4 + 12 * k, *move(struct.unpack_from("<3f", data, at + 4 + 12 * k)))
        at += 4 + 12 * n
    with open(dst, "wb") as f:
        f.write(data)
