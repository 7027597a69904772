#!/usr/bin/env python3
"""make_floor_map.py - writes the small floor plan of logs/maps/ (floor.pgm + floor.yaml, and the
same plan as floor.png + floor_png.yaml): a 20 m x 12 m building at 5 cm a cell, a corridor
along its middle, three rooms below it and two above, each reached through a 1 m doorway, and a
table in the first room. Pixels follow map_saver: 254 free, 0 occupied, 205 unknown (outside).

Usage: python3 logs/maps/make_floor_map.py   (writes next to this file; no dependency)
"""
import os
import struct
import zlib

RES = 0.05
W, H = 440, 280           # 22 m x 14 m image; the building is [1, 21] x [1, 13] m inside it
ORIGIN = (-11.0, -7.0, 0.0)
FREE, OCC, UNKNOWN = 254, 0, 205
WALL = 0.2                # m


def plan():
    img = [[UNKNOWN] * W for _ in range(H)]  # img[row][col], row 0 at the top

    def fill(x0, y0, x1, y1, v):
        """Fills the cells whose centres lie in [x0, x1] x [y0, y1] (m, image frame, y up)."""
        for j in range(H):
            y = (j + 0.5) * RES
            if not (y0 <= y <= y1):
                continue
            row = img[H - 1 - j]
            for i in range(W):
                x = (i + 0.5) * RES
                if x0 <= x <= x1:
                    row[i] = v

    fill(1.0, 1.0, 21.0, 13.0, OCC)                      # building with its outer walls
    fill(1.0 + WALL, 1.0 + WALL, 21.0 - WALL, 13.0 - WALL, FREE)
    for y in (6.0, 8.0):                                  # corridor walls y in [6, 8]
        fill(1.0, y - WALL / 2, 21.0, y + WALL / 2, OCC)
    for x in (8.0, 14.0):                                 # rooms below the corridor
        fill(x - WALL / 2, 1.0, x + WALL / 2, 6.0, OCC)
    fill(11.0 - WALL / 2, 8.0, 11.0 + WALL / 2, 13.0, OCC)  # two rooms above it
    for x0 in (4.0, 10.5, 17.0):                          # doorways, 1 m wide
        fill(x0, 6.0 - WALL, x0 + 1.0, 6.0 + WALL, FREE)
    for x0 in (5.0, 16.0):
        fill(x0, 8.0 - WALL, x0 + 1.0, 8.0 + WALL, FREE)
    fill(3.0, 2.5, 5.0, 3.5, OCC)                         # a table in the first room
    return img


def write_pgm(path, img):
    with open(path, 'wb') as f:
        f.write(b'P5\n# gmmrrt floor plan (logs/maps/make_floor_map.py)\n%d %d\n255\n' % (W, H))
        f.write(bytes(v for row in img for v in row))


def write_png(path, img):
    raw = b''.join(b'\x00' + bytes(row) for row in img)

    def chunk(kind, data):
        return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data) & 0xffffffff)

    with open(path, 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n')
        f.write(chunk(b'IHDR', struct.pack('>IIBBBBB', W, H, 8, 0, 0, 0, 0)))
        f.write(chunk(b'IDAT', zlib.compress(raw, 9)))
        f.write(chunk(b'IEND', b''))


def write_yaml(path, image):
    with open(path, 'w') as f:
        f.write('image: %s\nresolution: %.2f\norigin: [%.1f, %.1f, %.1f]\nnegate: 0\n'
                'occupied_thresh: 0.65\nfree_thresh: 0.196\n' % ((image, RES) + ORIGIN))


if __name__ == '__main__':
    here = os.path.dirname(os.path.abspath(__file__))
    img = plan()
    write_pgm(os.path.join(here, 'floor.pgm'), img)
    write_yaml(os.path.join(here, 'floor.yaml'), 'floor.pgm')
    write_png(os.path.join(here, 'floor.png'), img)
    write_yaml(os.path.join(here, 'floor_png.yaml'), 'floor.png')
