#!/usr/bin/env python3
"""Write the mask files of the non-elliptic example patches in input/ (standard library only).
Lengths in mm, x along the rolling direction; cells of 0.2 mm.
  two_lobed       two overlapping ellipses along y (a two-point contact merging into one patch)
  crescent        a crescent bent toward -x, as on a worn flange
  twin            two separate patches (tread and flange)
  rectangle       8 mm (x) by 4 mm (y)
  superellipse    |x/4|^4 + |y/5|^4 <= 1
usage: scripts/make_shapes.py [FOLDER]   (default input/)
       scripts/make_shapes.py --help     this text
"""
import os
import sys
if any(a in ("-h", "--help") for a in sys.argv[1:]):
    print(__doc__.strip())
    sys.exit(0)

H = 0.2


def inside(shape, x, y):
    x, y = round(x, 9), round(y, 9)      # no decision on a rounding error of the grid
    if shape == 'two_lobed':
        return ((x / 3.0) ** 2 + ((y - 2.6) / 3.0) ** 2 <= 1) or ((x / 3.6) ** 2 + ((y + 2.6) / 3.4) ** 2 <= 1)
    if shape == 'crescent':
        d = ((x - 9.0) ** 2 + y ** 2) ** 0.5
        return 8.0 <= d <= 11.0 and abs(y) <= 6.5 and x < 9.0
    if shape == 'twin':
        return ((x / 4.0) ** 2 + ((y + 3.5) / 3.0) ** 2 <= 1) or ((x / 2.5) ** 2 + ((y - 4.0) / 1.6) ** 2 <= 1)
    if shape == 'rectangle':
        return abs(x) <= 4.0 and abs(y) <= 2.0
    if shape == 'superellipse':
        return abs(x / 4.0) ** 4 + abs(y / 5.0) ** 4 <= 1
    raise ValueError(shape)


def write(folder, shape):
    # bounding box of the shape on a fine sample, then the grid with one empty cell around
    # cell centres at odd multiples of H/2: the grid is symmetric about x = 0 and y = 0
    xs = [(i + 0.5) * H for i in range(-80, 80)]
    cells = [(x, y) for x in xs for y in xs if inside(shape, x, y)]
    x_lo = min(c[0] for c in cells) - H; x_hi = max(c[0] for c in cells) + H
    y_lo = min(c[1] for c in cells) - H; y_hi = max(c[1] for c in cells) + H
    mx = int(round((x_hi - x_lo) / H)) + 1
    my = int(round((y_hi - y_lo) / H)) + 1
    rows = []
    for iy in range(my):
        y = y_lo + iy * H
        rows.append(''.join('#' if inside(shape, x_lo + ix * H, y) else '.' for ix in range(mx)))
    with open(os.path.join(folder, f'{shape}.mask'), 'w') as f:
        f.write(f'{mx} {my} {H} {H} {round(x_lo, 9):.6g} {round(y_lo, 9):.6g}\n')
        f.write('\n'.join(rows) + '\n')
    return mx, my, sum(r.count('#') for r in rows)


if __name__ == '__main__':
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), '..', 'input')
    for s in ('two_lobed', 'crescent', 'twin', 'rectangle', 'superellipse'):
        print(s, *write(folder, s))
