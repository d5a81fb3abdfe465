#!/usr/bin/env python3
"""Writes assets/cloth.png, the cloth's texture: a woven red-and-cream gingham.

Made procedurally (Python standard library only) so that anyone can change and regenerate it:
    python3 scripts/make_texture.py            # writes assets/cloth.png beside this script's repo

The pattern is meant to show the texture coordinates (u along ku, v along kv): 8 x 8 checks,
a gold hem along the border, and a darker blue corner patch at (u, v) = (0, 0) (particle
(0, 0), a pinned corner) so that the orientation of the grid can be read on screen.
"""

import math
import os
import struct
import zlib

SIZE = 256  # pixels per side
CHECKS = 8  # checks per side
THREAD = 4  # pixels per thread of the weave

CREAM = (238, 228, 206)
CRIMSON = (178, 42, 56)
HEM_GOLD = (214, 168, 62)
CORNER_BLUE = (40, 70, 140)


def mix(a, b, t):
    return tuple(x + (y - x) * t for x, y in zip(a, b))


def scale(color, factor):
    return tuple(min(255.0, max(0.0, c * factor)) for c in color)


def texel(x, y):
    check = SIZE // CHECKS
    # Gingham: warp threads (along v) are red in every other column of checks, weft threads
    # (along u) in every other row; where both are red the check is darkest.
    warp_red = (x // check) % 2 == 0
    weft_red = (y // check) % 2 == 0
    red_amount = 0.5 * warp_red + 0.5 * weft_red
    color = mix(CREAM, CRIMSON, red_amount)
    # Plain weave: threads pass over and under each other, so alternate thread crossings are
    # lit differently; a soft cosine keeps each thread rounded.
    over = ((x // THREAD) + (y // THREAD)) % 2 == 0
    along = (x % THREAD + 0.5) / THREAD if over else (y % THREAD + 0.5) / THREAD
    roundness = 0.90 + 0.10 * math.sin(math.pi * along)
    color = scale(color, roundness * (1.0 if over else 0.93))
    # Gold hem and the blue corner patch at (u, v) = (0, 0).
    hem = SIZE // 64
    if x < hem or y < hem or x >= SIZE - hem or y >= SIZE - hem:
        color = scale(HEM_GOLD, roundness)
    elif x < check // 2 and y < check // 2:
        color = scale(CORNER_BLUE, roundness)
    return tuple(int(round(c)) for c in color)


def write_png(path, width, height, rows):
    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    raw = b"".join(b"\x00" + bytes(row) for row in rows)  # filter type 0 on every row
    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)  # 8-bit RGB
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", header))
        f.write(chunk(b"IDAT", zlib.compress(raw, 9)))
        f.write(chunk(b"IEND", b""))


def main():
    # Image row 0 is the top; the renderer maps v = 0 to the first row loaded by stb_image,
    # so row y holds v = y / SIZE.
    rows = []
    for y in range(SIZE):
        row = []
        for x in range(SIZE):
            row.extend(texel(x, y))
        rows.append(row)
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    path = os.path.join(root, "assets", "cloth.png")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    write_png(path, SIZE, SIZE, rows)
    print("wrote", path)


if __name__ == "__main__":
    main()
