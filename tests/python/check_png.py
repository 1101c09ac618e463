#!/usr/bin/python3
"""Checks snapshot pictures with PIL (a decoder the engine has no part in).

  check_png.py size <png> <width> <height>
      the file decodes as an RGB image of that size
  check_png.py bed <png> <width> <height> <top> <centres> <bottom> <left> <right> <bg r,g,b>
      a bed seen from the side, coloured "none" (the grain colour is reddish brown: r > g > b):
      every pixel in the rows above `top` (the bed's highest point) is the background; every pixel
      in rows centres..bottom and columns left..right (inside the outermost sphere centres) is grain
      coloured, never the background
  check_png.py height <png> <width> <height> <centres> <bottom> <left> <right>
      the same bed coloured by height: the viridis map runs from blue-violet at the bottom to
      green-yellow at the top, so red + green grows with height and blue dominates low down
  check_png.py pixels <png> <width> <height> <x>,<y>,<bg|grain|mesh> ...
      the background colour (white), a grain colour (r > g > b), a mesh colour (grey-blue: r < g < b),
      or the colour map's low end (violet: b > r > g) or high end (yellow: r > b and g > b)
Rows and columns are pixel indices, fractional ones rounded inwards by a pixel.
"""
import math
import sys

from PIL import Image

failures = []


def fail(msg):
    failures.append(msg)
    print("FAIL:", msg)


def load(path, w, h):
    img = Image.open(path)
    img.load()
    if img.size != (w, h) or img.mode != "RGB":
        fail(f"{path}: {img.size} {img.mode}, expected ({w}, {h}) RGB")
    return img.convert("RGB")


def main(args):
    mode, path, w, h = args[0], args[1], int(args[2]), int(args[3])
    img = load(path, w, h)
    px = img.load()
    if mode == "size":
        return
    if mode == "bed":
        top, centres, bottom, left, right = map(float, args[4:9])
        bg = tuple(int(c) for c in args[9].split(","))
        above = [(x, y) for y in range(0, math.floor(top) - 1) for x in range(w) if px[x, y] != bg]
        if above:
            fail(f"{len(above)} pixels above the bed's top (row {top:.1f}) are not the background, e.g. {above[:3]}")
        inside = [(x, y) for y in range(math.ceil(centres) + 1, math.floor(bottom))
                  for x in range(math.ceil(left) + 1, math.floor(right))]
        if len(inside) < 100:
            fail(f"only {len(inside)} pixels inside the bed to check")
        bad = [(x, y, px[x, y]) for x, y in inside if px[x, y] == bg or not px[x, y][0] > px[x, y][1] > px[x, y][2]]
        if bad:
            fail(f"{len(bad)} of {len(inside)} pixels inside the bed are not grain coloured, e.g. {bad[:3]}")
        print(f"bed: {len(inside)} grain pixels below row {centres:.1f}, background above row {top:.1f}")
    elif mode == "pixels":
        for spec in args[4:]:
            x, y, kind = spec.split(",")
            c = px[int(x), int(y)]
            ok = {"bg": c == (255, 255, 255), "grain": c != (255, 255, 255) and c[0] > c[1] > c[2],
                  "mesh": c != (255, 255, 255) and c[0] < c[1] < c[2],
                  "low": c[2] > c[0] > c[1], "high": c[0] > c[2] + 60 and c[1] > c[2] + 60}[kind]
            if not ok:
                fail(f"pixel ({x}, {y}) is {c}, expected {kind}")
        print(f"pixels: {len(args) - 4} checked")
    elif mode == "height":
        centres, bottom, left, right = map(float, args[4:8])
        x0, x1 = math.ceil(left) + 1, math.floor(right)
        band = max(2, int((bottom - centres) / 6))

        def mean(y0):
            cols = [px[x, y] for y in range(y0, y0 + band) for x in range(x0, x1)]
            return [sum(c[k] for c in cols) / len(cols) for k in range(3)]

        hi, lo = mean(math.ceil(centres) + 1), mean(math.floor(bottom) - band)
        if not (hi[0] + hi[1] > lo[0] + lo[1] + 60 and lo[2] > lo[0]):
            fail(f"colour by height: top band {hi}, bottom band {lo}")
        print(f"height: top band {[round(c) for c in hi]}, bottom band {[round(c) for c in lo]}")


if __name__ == "__main__":
    main(sys.argv[1:])
    sys.exit(1 if failures else 0)
