#!/usr/bin/python3
"""A wheelset that hunts: S1002 wheels on UIC60 rails, forces from a kcreep.ContactTable.

One rigid wheelset on straight track, lateral (ky) and yaw (kpsi) springs to
a frame moving at speed V (no damping), states y, psi, their rates. Each wheel's
patches come from one contact table of the right side (S1002 / UIC60 at 70 kN,
the program's benchmark pair): the right wheel at wheelset shift y reads the
table at y, the left wheel (the right one mirrored) at -y, its lateral
quantities mirrored back. Prints

    kinematic wavelength at amplitude A mm: L m (Klingel: K m)
    critical speed: V km/h (fast model), V2 km/h (FASTSIM), V3 km/h (linear Kalker)

(--check: the rows' force models on their normal grids coarsened to at most
350 cells, ContactTable's force_cells, so that each row's fast model builds
in about a second on one thread) and draws the motion and the limit cycle
(wheelset_hunting.png).
docs/mbs.md says what the model leaves out.

    /usr/bin/python3 examples/wheelset_hunting.py [--check] [--png FILE]
"""
import argparse
import os
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "python"))
import kcreep  # noqa: E402

PROFILES = os.path.join(HERE, "..", "..", "shared", "profiles")
WHEEL, RAIL = os.path.join(PROFILES, "MBench_S1002_v3.prw"), os.path.join(PROFILES, "MBench_UIC60_v3.prr")
G, NU, LOAD, MU = 82000.0, 0.28, 70e3, 0.3      # N/mm^2, -, N per wheel, friction
MASS, INERTIA = 1500.0, 800.0                   # kg, kg m^2 (yaw)
KY, KPSI = 1.0e6, 4.0e6                         # N/m, N m/rad: the springs to the frame
FLANGE_BACK_DISTANCE, FLANGE_BACK_POSITION = 1360.0, -70.0   # mm, the table's placement (defaults)


class Wheelset:
    """The wheelset's equations of motion with one of the table's force models:
    'fast' (ContactTable.forces), 'fastsim', 'linear' (Kalker's linear theory)."""

    def __init__(self, table, model, speed, springs=True, klingel=False):
        self.table, self.model, self.v = table, model, speed
        # klingel: Klingel's assumptions, no lateral component of the normal
        # forces (gravitational stiffness) and no geometric spin
        self.klingel = klingel
        self.ky, self.kpsi = (KY, KPSI) if springs else (0.0, 0.0)
        centre = table.at(0.0)
        weight = sum(p["fn"] for p in centre)
        self.r0 = sum(p["fn"] * p["r_wheel"] for p in centre) / weight / 1000   # m
        # the contact point's distance from the track centre at shift 0: the
        # wheel profile's origin (flange-back placement) plus y_wheel
        self.e = (FLANGE_BACK_DISTANCE / 2 - FLANGE_BACK_POSITION +
                  sum(p["fn"] * p["y_wheel"] for p in centre) / weight) / 1000   # m

    def patches(self, y):
        """A right wheel's patches at wheelset shift y (m): the table at y mm
        (the solver may try a state past the table's edge before the run's
        out-of-range event stops it: the edge row there)."""
        shift = min(max(1000 * y, self.table.shifts[0]), self.table.shifts[-1])
        return shift, self.table.at(shift)

    def wheel(self, shift, patches, r_ref, psi, dy, dpsi):
        """A right wheel's lateral force and yaw moment about the wheelset
        centre (N, N m) at yaw psi (track frame: x ahead, y to the right
        wheel's field side, z down), the axle turning at V / r_ref.
        Creepages of the wheel against the rail in each patch's plane (tilted
        by delta about x): xi = 1 - r / r_ref - e dpsi / V, eta = (dy / V -
        psi) cos(delta), phi = -sin(delta) / r + dpsi cos(delta) / V (kcreep's
        table spin, sin(delta) / r, is the rail's against the wheel); the
        forces of these creepages are the wheel's (F(-c) = -F(c))."""
        creep = []
        for p in patches:
            d, r = p["delta"], p["r_wheel"]
            spin = 0.0 if self.klingel else -np.sin(d) / r
            creep.append(np.array([[1 - r / 1000 / r_ref - self.e * dpsi / self.v, (dy / self.v - psi) * np.cos(d),
                                    spin + dpsi * np.cos(d) / self.v / 1000]]))
        if self.model == "fast":
            forces = self.table.forces(shift, MU, creep)
        elif self.model == "fastsim":
            forces = self.table.fastsim_forces(shift, MU, creep)
        else:
            forces = self.table.linear_forces(shift, creep)
        lateral = moment = 0.0
        for p, f in zip(patches, forces):
            fx, fy, mz = f[0]
            d = p["delta"]
            lateral += fy * np.cos(d) - (0.0 if self.klingel else p["fn"] * np.sin(d))
            moment += -self.e * fx + mz * np.cos(d) / 1000
        return lateral, moment

    def rhs(self, t, s):
        y, psi, dy, dpsi = s
        right, left = self.patches(y), self.patches(-y)       # the left wheel: mirrored, at -y
        # the axle turns freely (no torque): at V / r_ref, r_ref the mean rolling radius
        r_ref = sum(p["fn"] * p["r_wheel"] for p in right[1] + left[1]) / \
            sum(p["fn"] for p in right[1] + left[1]) / 1000
        lat_r, mom_r = self.wheel(*right, r_ref, psi, dy, dpsi)
        lat_l, mom_l = self.wheel(*left, r_ref, -psi, -dy, -dpsi)
        fy = lat_r - lat_l - self.ky * y
        mz = mom_r - mom_l - self.kpsi * psi
        return [dy, dpsi, fy / MASS, mz / INERTIA]

    def run(self, y0, distance, limit_mm):
        """The motion from a lateral offset y0 (m) over distance (m); stops
        when |y| reaches limit_mm (the table's range)."""
        def out_of_range(t, s):
            return limit_mm / 1000 - abs(s[0])
        out_of_range.terminal = True
        return solve_ivp(self.rhs, (0, distance / self.v), [y0, 0, 0, 0], method="LSODA", rtol=1e-5,
                         atol=[1e-8, 1e-8, 1e-6, 1e-6], events=out_of_range, max_step=0.05)


def crossings(x, y):
    """The x of the upward zero crossings of y(x) (linear between samples)."""
    k = np.flatnonzero((y[:-1] < 0) & (y[1:] >= 0))
    return x[k] - y[k] * (x[k + 1] - x[k]) / (y[k + 1] - y[k])


def decays(ws, disturbance, distance, limit):
    """Whether a lateral disturbance (m) decays: the largest |y| over the last
    third of the run is below the disturbance (and the run stayed in range)."""
    sol = ws.run(disturbance, distance, limit)
    if sol.status == 1:
        return False, sol
    x = ws.v * sol.t
    last = x > x[-1] * 2 / 3
    return np.max(np.abs(sol.y[0][last])) < disturbance, sol


def critical_speed(table, model, lo, hi, steps, disturbance, distance, limit):
    """Bisection on V (m/s) between lo and hi: the speed where the disturbance
    stops decaying; None when it decays at hi or grows at lo."""
    if not decays(Wheelset(table, model, lo), disturbance, distance, limit)[0]:
        return None
    if decays(Wheelset(table, model, hi), disturbance, distance, limit)[0]:
        return None
    for _ in range(steps):
        mid = 0.5 * (lo + hi)
        if decays(Wheelset(table, model, mid), disturbance, distance, limit)[0]:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true", help="the quick version (under a minute, one thread)")
    ap.add_argument("--png", default="wheelset_hunting.png", help="the figure (default %(default)s)")
    ap.add_argument("--amplitude", type=float, default=3.0, help="mm, a table shift (default %(default)s)")
    a = ap.parse_args()
    t0 = time.time()
    step = 1.0 if a.check else 0.5
    shifts = np.arange(-9.0, 9.0 + step / 2, step)
    limit = 8.5   # mm: a run ends here (the table's range +-9 mm)
    if not (np.any(np.isclose(shifts, a.amplitude)) and 0 < a.amplitude <= limit):
        print(f"wheelset_hunting: --amplitude = {a.amplitude:g} mm (allowed: a table shift, 0 to {limit:g} mm in "
              f"{step:g} mm steps)", file=sys.stderr)
        sys.exit(2)
    # the table once: coarse shift step, target 1e-2, at most ~1000 cells a level
    table = kcreep.ContactTable(WHEEL, RAIL, shifts, g=G, nu=NU, vertical_force=LOAD, target_error=1e-2,
                                cell_budget=1000.0, threads=1,
                                # --check: the force models on at most 350 cells a row (the rows' normal
                                # grids have 1,600-4,000: a fast model there costs 2-9 s a row)
                                force_cells=350 if a.check else 0)
    grids = f"at most {table.force_cells} cells a row" if table.force_cells else "the rows' normal grids"
    flagged = [f"{table.shifts[i]:g}..{table.shifts[i + 1]:g}" for i, f in enumerate(table.flags) if f]
    print(f"contact table: {shifts.size} shifts {shifts[0]:g} to {shifts[-1]:g} mm, {table.table['shift'].size} rows, "
          f"fast model: {table.fast_model} on {grids}; intervals flagged (> 1 % interpolation error): "
          f"{', '.join(flagged) or 'none'}")

    # kinematic wavelength: free wheelset (no springs), small speed
    amp = a.amplitude
    ws_table = kcreep.wheelset(WHEEL, RAIL, table.shifts[(table.shifts >= 0) & (table.shifts <= amp + 1e-9)], g=G,
                               nu=NU, vertical_force=LOAD, threads=1, smoothing=-1.0)
    lambda_eq = ws_table["lambda_eq"][-1]
    # Klingel's assumptions: creep forces only (no gravitational stiffness, no
    # geometric spin); then the same with them (the full model)
    lengths = {}
    for klingel in (True, False):
        slow = Wheelset(table, "fast", 5.0, springs=False, klingel=klingel)
        run = slow.run(amp / 1000, (2.2 if a.check else 3.2) * 2 * np.pi * np.sqrt(slow.r0 * slow.e / lambda_eq), limit)
        up = crossings(slow.v * run.t, run.y[0])
        lengths[klingel] = (np.mean(np.diff(up)) if up.size > 1 else float("nan"), run)
    klingel_length = 2 * np.pi * np.sqrt(slow.r0 * slow.e / lambda_eq)
    wavelength, sol = lengths[True]
    x = slow.v * sol.t
    print(f"kinematic wavelength at amplitude {amp:g} mm: {wavelength:.2f} m (Klingel: {klingel_length:.2f} m)")
    print(f"  (free wheelset at {slow.v:g} m/s, creep forces only; with gravitational stiffness and spin: "
          f"{lengths[False][0]:.2f} m; r0 = {1000 * slow.r0:.1f} mm, e = {1000 * slow.e:.1f} mm, lambda_eq = "
          f"{lambda_eq:.4f} from kcreep.wheelset at the table's shifts)")

    # critical speeds: bisection on the decay of a lateral disturbance
    disturbance = 2e-3
    distance, steps = (60.0, 4) if a.check else (150.0, 7)
    lo, hi = 10.0, 120.0
    speeds = {}
    for model in ("fast", "fastsim", "linear"):
        speeds[model] = critical_speed(table, model, lo, hi, steps, disturbance, distance, limit)

    def kmh(v):
        return "n/a" if v is None else f"{3.6 * v:.0f}"
    print(f"critical speed: {kmh(speeds['fast'])} km/h (fast model), {kmh(speeds['fastsim'])} km/h (FASTSIM), "
          f"{kmh(speeds['linear'])} km/h (linear Kalker)")
    print(f"  (disturbance {1000 * disturbance:g} mm, decay over the last third of {distance:g} m, "
          f"bisection {3.6 * lo:g} to {3.6 * hi:g} km/h in {steps} steps: +-{3.6 * (hi - lo) / 2 ** (steps + 1):.0f} km/h)")

    # the motion and the limit cycle above the critical speed
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    v_cycle = 1.2 * (speeds["fast"] or hi)
    cycle = Wheelset(table, "fast", v_cycle).run(disturbance, 2 * distance, limit)
    fig, ax = plt.subplots(1, 3, figsize=(13, 3.6))
    ax[0].plot(x, 1000 * sol.y[0])
    ax[0].set(xlabel="distance (m)", ylabel="y (mm)", title=f"free wheelset, {slow.v:g} m/s")
    xc = v_cycle * cycle.t
    ax[1].plot(xc, 1000 * cycle.y[0])
    ax[1].set(xlabel="distance (m)", ylabel="y (mm)", title=f"{3.6 * v_cycle:.0f} km/h")
    tail = xc > xc[-1] / 2
    ax[2].plot(1000 * cycle.y[0][tail], 1000 * cycle.y[2][tail])
    ax[2].set(xlabel="y (mm)", ylabel="dy/dt (mm/s)", title="limit cycle (second half)")
    fig.tight_layout()
    fig.savefig(a.png, dpi=90)
    print(f"figure: {a.png}; {time.time() - t0:.1f} s")


if __name__ == "__main__":
    main()
