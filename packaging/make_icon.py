#!/usr/bin/env python3
"""Draws mrsim-studio's icon: a modular robot (pitch modules orange, yaw
blue, a green sensor module at the front, as the viewer colours them)
pushing a red ball. One list of shapes gives both the SVG (hicolor
scalable) and the PNGs (hicolor 48x48 and 128x128, for menus that do not
draw SVG), so the icon has one source and needs no image tool.

Usage: make_icon.py OUT_DIR   writes mrsim-studio.svg, mrsim-studio-48.png
                              and mrsim-studio-128.png
"""
import os
import struct
import sys
import zlib

# (kind, geometry, colour) in a 128 x 128 box; drawn in order.
SHAPES = [
    ("rrect", (4, 4, 124, 124, 22), (38, 50, 56)),     # background
    ("rrect", (12, 92, 116, 98, 3), (96, 110, 118)),   # ground
    ("rrect", (14, 66, 32, 90, 4), (240, 140, 40)),    # pitch module
    ("rrect", (34, 60, 52, 90, 4), (60, 120, 220)),    # yaw module
    ("rrect", (54, 66, 72, 90, 4), (240, 140, 40)),    # pitch module
    ("rrect", (74, 60, 90, 90, 4), (60, 180, 90)),     # sensor module
    ("circle", (33, 78, 4), (207, 216, 220)),          # hinges
    ("circle", (53, 78, 4), (207, 216, 220)),
    ("circle", (73, 78, 4), (207, 216, 220)),
    ("circle", (106, 80, 12), (220, 60, 60)),          # the ball
]


def inside(kind, g, x, y):
    if kind == "circle":
        cx, cy, r = g
        return (x - cx) ** 2 + (y - cy) ** 2 <= r * r
    x0, y0, x1, y1, r = g
    if not (x0 <= x <= x1 and y0 <= y <= y1):
        return False
    # Distance to the rectangle shrunk by r, within r: rounded corners.
    dx = max(x0 + r - x, 0, x - (x1 - r))
    dy = max(y0 + r - y, 0, y - (y1 - r))
    return dx * dx + dy * dy <= r * r


def png(size):
    """RGBA PNG bytes, 4x4 samples per pixel for smooth edges."""
    scale = 128.0 / size
    n = 4
    rows = []
    for py in range(size):
        row = bytearray([0])  # filter type: none
        for px in range(size):
            acc = [0.0, 0.0, 0.0, 0.0]
            for sy in range(n):
                for sx in range(n):
                    x = (px + (sx + 0.5) / n) * scale
                    y = (py + (sy + 0.5) / n) * scale
                    colour = None
                    for kind, g, c in SHAPES:
                        if inside(kind, g, x, y):
                            colour = c
                    if colour:
                        acc[0] += colour[0]
                        acc[1] += colour[1]
                        acc[2] += colour[2]
                        acc[3] += 255
            covered = acc[3] / 255
            if covered:
                row += bytes(round(acc[i] / covered) for i in range(3))
            else:
                row += b"\0\0\0"
            row.append(round(acc[3] / (n * n)))
        rows.append(bytes(row))

    def chunk(tag, data):
        return (struct.pack(">I", len(data)) + tag + data +
                struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF))
    header = struct.pack(">IIBBBBB", size, size, 8, 6, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) +
            chunk(b"IDAT", zlib.compress(b"".join(rows), 9)) +
            chunk(b"IEND", b""))


def svg():
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="128" '
           'height="128" viewBox="0 0 128 128">']
    for kind, g, c in SHAPES:
        fill = "#%02x%02x%02x" % c
        if kind == "circle":
            out.append('  <circle cx="%g" cy="%g" r="%g" fill="%s"/>'
                       % (g[0], g[1], g[2], fill))
        else:
            x0, y0, x1, y1, r = g
            out.append('  <rect x="%g" y="%g" width="%g" height="%g" '
                       'rx="%g" fill="%s"/>'
                       % (x0, y0, x1 - x0, y1 - y0, r, fill))
    out.append("</svg>")
    return "\n".join(out) + "\n"


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: make_icon.py OUT_DIR")
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "mrsim-studio.svg"), "w") as f:
        f.write(svg())
    for size in (48, 128):
        with open(os.path.join(out, "mrsim-studio-%d.png" % size), "wb") as f:
            f.write(png(size))


if __name__ == "__main__":
    main()
