#!/usr/bin/env python3
"""Writes terrain.png, the height image of terrain.xml (standard library only).

64 x 64 grey pixels; at 0.05 m per pixel the terrain is 3.2 m square. A flat
floor (grey 0) of radius 1 m around the centre, where the snake starts,
rising into bumpy hills towards the edges (grey 255 = Scene height).
"""
import math
import struct
import zlib

SIZE = 64
METERS_PER_PIXEL = 0.05


def height(col, row):
    # Pixel centre in metres from the image centre (+y up the image).
    x = (col + 0.5 - SIZE / 2) * METERS_PER_PIXEL
    y = (SIZE / 2 - row - 0.5) * METERS_PER_PIXEL
    r = math.hypot(x, y)
    t = min(max((r - 1.0) / 0.5, 0.0), 1.0)
    ramp = t * t * (3 - 2 * t)  # smoothstep
    return ramp * (0.6 + 0.4 * math.sin(4 * x) * math.cos(4 * y))


def main():
    rows = []
    for row in range(SIZE):
        values = [round(255 * height(col, row)) for col in range(SIZE)]
        rows.append(b"\x00" + bytes(values))  # filter type 0 per row
    raw = b"".join(rows)

    def chunk(kind, data):
        body = kind + data
        return (struct.pack(">I", len(data)) + body +
                struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF))

    png = b"\x89PNG\r\n\x1a\n"
    png += chunk(b"IHDR", struct.pack(">IIBBBBB", SIZE, SIZE, 8, 0, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9))
    png += chunk(b"IEND", b"")
    with open("terrain.png", "wb") as f:
        f.write(png)


if __name__ == "__main__":
    main()
