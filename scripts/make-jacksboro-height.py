#!/usr/bin/env python3
"""Writes assets/relief/jacksboro/jacksboro_height.png, the real terrain of the Baboud & Decoret
reproductions, from matplotlib's sample elevation grid (Debian package python-matplotlib-data).

The grid is 344 x 403 signed 16-bit elevations in metres (236-1076 m), 3 arc-seconds apart,
around the Jacksboro fault in Tennessee (84.41-84.08 W, 36.45-36.73 N). The 344 x 344 square at
its centre is written as a 16-bit grey PNG, elevation mapped linearly onto 0-65535 over the
crop's own range (ReliefLab configs read it with convention = "height"). Standard library only.

  scripts/make-jacksboro-height.py [path/to/jacksboro_fault_dem.npz]
"""
import ast
import os
import struct
import sys
import zipfile
import zlib

DEFAULT = "/usr/share/matplotlib/mpl-data/sample_data/jacksboro_fault_dem.npz"


def read_npy(archive, name):
    data = archive.read(name)
    if data[:6] != b"\x93NUMPY":
        sys.exit(f"{name}: not a .npy array")
    header_len = struct.unpack("<H", data[8:10])[0]
    header = ast.literal_eval(data[10 : 10 + header_len].decode("latin1"))
    return header, data[10 + header_len :]


def png_chunk(kind, payload):
    body = kind + payload
    return struct.pack(">I", len(payload)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)


def main():
    source = sys.argv[1] if len(sys.argv) > 1 else DEFAULT
    if not os.path.isfile(source):
        sys.exit(f"{source}: not found (apt-get install python-matplotlib-data, or name the file)")
    header, raw = read_npy(zipfile.ZipFile(source), "elevation.npy")
    if header["descr"] != "<i2" or header["fortran_order"] or len(header["shape"]) != 2:
        sys.exit(f"{source}: elevation.npy is {header}, expected 2-D '<i2' in C order")
    rows, cols = header["shape"]
    count = rows * cols
    elevation = struct.unpack(f"<{count}h", raw[: 2 * count])
    side = min(rows, cols)
    x0, y0 = (cols - side) // 2, (rows - side) // 2
    crop = [elevation[(y0 + y) * cols + x0 : (y0 + y) * cols + x0 + side] for y in range(side)]
    lo = min(min(r) for r in crop)
    hi = max(max(r) for r in crop)
    scanlines = b"".join(
        b"\x00" + struct.pack(f">{side}H", *(round((v - lo) * 65535 / (hi - lo)) for v in r))
        for r in crop
    )
    png = b"\x89PNG\r\n\x1a\n"
    png += png_chunk(b"IHDR", struct.pack(">IIBBBBB", side, side, 16, 0, 0, 0, 0))
    png += png_chunk(b"IDAT", zlib.compress(scanlines, 9))
    png += png_chunk(b"IEND", b"")
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "assets", "relief",
                       "jacksboro", "jacksboro_height.png")
    with open(out + ".tmp", "wb") as f:
        f.write(png)
    os.replace(out + ".tmp", out)
    print(f"{os.path.normpath(out)}: {side} x {side}, columns {x0}-{x0 + side - 1}, "
          f"elevation {lo}-{hi} m")


if __name__ == "__main__":
    main()
