#!/usr/bin/env python3
"""Undeformed distance of a worn wheel on a rail, as a kcreep gap file.

Two simple profile functions (lengths in mm), y lateral, x rolling:
  rail head:   a crown arc of radius 300 mm,      r(y) = -y^2 / (2 * 300)
  worn wheel:  a hollow tread, two arcs (radii 200 and 260 mm) touching the
               contact plane at y = -5 and y = +7 mm (the worn middle is hollow):
               w(y) = min((y + 5)^2 / (2 * 200), (y - 7)^2 / (2 * 260))
  lateral gap: d(y) = w(y) - r(y), shifted so that its minimum is 0
  rolling:     the wheel radius 460 mm adds x^2 / (2 * 460)
so h(x, y) = d(y) - min d + x^2 / 920. d has two minima (one per arc) with a
ridge between them: at a small approach there are two separate patches
(two-point contact), at a larger one a single non-elliptic, two-lobed patch.

  scripts/wheel_rail_gap.py [OUT.gap]       (default input/wheel_rail.gap)
Grid: 0.2 mm cells, x in [-8, 8], y in [-11, 13] (the file's header).
Standard library only.

    scripts/wheel_rail_gap.py --help    this text
"""
import sys
if any(a in ("-h", "--help") for a in sys.argv[1:]):
    print(__doc__.strip())
    sys.exit(0)

R_RAIL, R1, Y1, R2, Y2, R_WHEEL = 300.0, 200.0, -5.0, 260.0, 7.0, 460.0
DX = DY = 0.2
MX, MY = 80, 120
X0, Y0 = -8.0 + DX / 2, -11.0 + DY / 2


def lateral(y):
    wheel = min((y - Y1) ** 2 / (2 * R1), (y - Y2) ** 2 / (2 * R2))
    rail = -y * y / (2 * R_RAIL)
    return wheel - rail


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "input/wheel_rail.gap"
    ys = [Y0 + j * DY for j in range(MY)]
    d = [lateral(y) for y in ys]
    dmin = min(lateral(Y1 + k * 1e-3) for k in range(-20000, 20001))   # fine search, below the grid's
    with open(out, "w") as f:
        f.write(f"{MX} {MY} {DX!r} {DY!r} {X0!r} {Y0!r}\n")
        f.write("% worn wheel on rail (scripts/wheel_rail_gap.py): h(x, y) in mm, rows in increasing y\n")
        for j in range(MY):
            row = [d[j] - dmin + (X0 + i * DX) ** 2 / (2 * R_WHEEL) for i in range(MX)]
            f.write(" ".join(f"{v:.10e}" for v in row) + "\n")
    print(f"wrote {out}: {MX} x {MY} cells of {DX} x {DY} mm")


if __name__ == "__main__":
    main()
