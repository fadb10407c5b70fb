"""kcreep.ContactTable: a wheel/rail contact table held for a time loop.

    t = kcreep.ContactTable("S1002.prw", "UIC60.prr", np.arange(-6, 10.5, 0.5), g=82000.0, nu=0.28,
                            vertical_force=70e3)
    t.at(2.3)                                   # one dict per patch, keyed by the table's columns
    t.forces(2.3, 0.3, [[1e-3, 0, 0]])          # list of n x 3 arrays (Fx, Fy, Mz), same order
    t.forces(2.3, 0.3, [[1e-3, 0, 0]], exact=True)
    t.flags                                     # per interval of shifts: why it is not interpolable

Each row's patch and pressure are kept on a Solver of their own
(kcreep_take_wheel_rail_row), so FASTSIM, exact rolling and the fast force
model run on that row's patch without solving it again. Between two rows a
patch's columns and forces are the linear interpolation of the two rows'
(continuous in the shift; the pairing and weights are the C API's
kcreep_wheel_rail_at); docs/mbs.md says what is interpolated and how
intervals are flagged.
"""
import bisect
import ctypes

import numpy as np

from .library import KcreepError, Solver, WHEEL_RAIL_COLUMNS, _lib

#: the default bound on the estimated interpolation error between two rows:
#: the fast force model's target, 1 % of mu Fn (issue 48), applied to Fn,
#: Fn sin(delta) (relative to the shift's total Fn) and to C11, C22, C23
#: (relative to their own size)
FLAG_TOLERANCE = 0.01

#: the default force_cells: the most cells of a row's patch for its force models. On S1002 /
#: UIC60 at the default target (0, 5, 7, 8 mm) the rows' normal grids have 7,010-43,928 cells:
#: an exact point 0.03-1.2 s, a fast model 11 s (0 mm) to a minute (8 mm) and more. On at most
#: 4000 cells (1,572-3,547 at 0, 7, 8 mm) the exact forces stay within 0.32-0.44 % of mu Fn of
#: the rows' own (95th percentile of 300 random creepages; largest 0.67-1.74 %) and a fast
#: model builds in 4.7-7.4 s on one thread (lab/fast_model_levels.py --s1002 --default 4000
#: 0 7 8).
FORCE_CELLS = 4000


def fast_forces(solver, mu, creepages):
    """The fast force model on a row's patch and pressure: the library's
    Solver.fast_forces when it has one (issue 48's model held to rolling),
    else FASTSIM (Solver.fastsim, rule 'aligned'). Forces n x 3 (Fx, Fy, Mz)."""
    if hasattr(solver, "fast_forces"):
        return solver.fast_forces(mu, creepages)
    return solver.fastsim(mu, creepages)[0]


class ContactTable:
    """The contact table of a wheel on a rail over `shifts` (mm), every row's
    patch, pressure and force model held for repeated use. g, nu, the table's
    target_error (the program's default 1e-3), threads and **placement as
    kcreep.wheel_rail (vertical_force or approach, yaw, side, gauge_width, ...).
    tolerance: the bound of the interpolation check (FLAG_TOLERANCE).
    fast_model: what forces(exact=False) uses, 'fast_forces' (the library's
    fast model, the default) or 'fastsim'. force_cells: the most cells of a
    row's patch for the force models (fast model, FASTSIM, exact rolling):
    the row's normal grid coarsened by square blocks (Solver.coarsen_patch;
    FORCE_CELLS, 4000, by default); 0: the rows' own grids."""

    def __init__(self, wheel_file, rail_file, shifts, *, g, nu, target_error=1e-3, threads=0,
                 cell_budget=0.0, tolerance=FLAG_TOLERANCE, fast_model=None, force_cells=FORCE_CELLS,
                 **placement):
        shifts = np.unique(np.asarray(shifts, dtype=np.float64))
        if shifts.size < 2:
            raise KcreepError(2, f"ContactTable: shifts = {shifts.tolist()} (allowed: at least 2 distinct values)")
        self._source = Solver(g=g, nu=nu, target_error=target_error, threads=threads, cell_budget=cell_budget)
        self.table = self._source.wheel_rail(wheel_file, rail_file, shifts, **placement)
        self.columns = list(WHEEL_RAIL_COLUMNS)
        self.shifts = shifts
        self.tolerance = tolerance
        n_rows = self.table["shift"].size
        # numbers for the C calls: kind as the C API gives it (0 tread, 1 flange)
        self._values = np.column_stack([(self.table[c] == "flange").astype(np.float64) if c == "kind"
                                        else self.table[c].astype(np.float64) for c in self.columns])
        self._solvers = [None] * n_rows
        self._g, self._nu, self._threads = g, nu, threads
        if force_cells and force_cells < 16:
            raise KcreepError(2, f"ContactTable: force_cells = {force_cells} (allowed: 0, the rows' own grids, or 16 "
                                 "or more)")
        self.force_cells = int(force_cells)
        self._rows_at = [np.flatnonzero(self.table["shift"] == s).tolist() for s in shifts]
        # room for kcreep_wheel_rail_at: every patch of two neighbouring rows
        self._capacity = 2 * max(len(r) for r in self._rows_at)
        self._buffer = np.empty((self._capacity, len(self.columns)))
        self._rows = np.empty((self._capacity, 2), dtype=np.intc)
        self._weights = np.empty((self._capacity, 2))
        self._tracks = self._match()
        self.flags = self._check_intervals()
        #: which fast model forces(exact=False) uses: 'fast_forces' or 'fastsim'
        # (the fast model's build costs seconds a row: 5-8 s on S1002 rows of at most 4000 cells, one thread)
        self.fast_model = fast_model or ("fast_forces" if hasattr(Solver, "fast_forces") else "fastsim")
        if self.fast_model not in ("fast_forces", "fastsim"):
            raise KcreepError(2, f"ContactTable: fast_model = {fast_model!r} (allowed: 'fast_forces', 'fastsim')")

    # -- patches across rows -------------------------------------------------------------------
    def _match(self):
        """Tracks: one dict {shift index: row} per patch followed across the
        shifts, from the C API's pairing of neighbouring rows
        (kcreep_wheel_rail_at at each interval's middle)."""
        track_of, tracks = {}, []
        for i in range(self.shifts.size - 1):
            _, rows, _ = self._at(0.5 * (self.shifts[i] + self.shifts[i + 1]))
            for a, b in rows:
                if a >= 0 and a not in track_of:
                    track_of[a] = len(tracks)
                    tracks.append({i: a})
                if b >= 0:
                    t = track_of[a] if a >= 0 else len(tracks)
                    if t == len(tracks):
                        tracks.append({})
                    tracks[t][i + 1] = b
                    track_of[b] = t
        return tracks

    def _check_intervals(self):
        """Per interval [shifts[i], shifts[i+1]] the reasons it is not
        interpolable within the tolerance ([] when it is): a patch that
        appears or vanishes, or a quantity whose linear interpolation error,
        estimated as h^2 / 8 times its second divided difference at either end
        of the interval (for C11, C22, C23 less the rows' own errNN), exceeds
        the tolerance."""
        col = {c: k for k, c in enumerate(self.columns)}
        v, s = self._values, self.shifts
        total = np.array([v[rows, col["fn"]].sum() for rows in self._rows_at])

        def quantities(r, i):
            fn, delta = v[r, col["fn"]], v[r, col["delta"]]
            return {"fn": fn / total[i], "fn_lateral": fn * np.sin(delta) / total[i],
                    "c11": v[r, col["c11"]], "c22": v[r, col["c22"]], "c23": v[r, col["c23"]]}

        flags = [[] for _ in range(s.size - 1)]
        for t, track in enumerate(self._tracks):
            for i in range(s.size - 1):
                if (i in track) != (i + 1 in track):
                    flags[i].append(f"patch {t + 1} {'appears' if i + 1 in track else 'vanishes'}")
                if not (i in track and i + 1 in track):
                    continue
                h = s[i + 1] - s[i]
                worst = {}
                for j in (i, i + 1):     # second divided differences centred at each end
                    if not all(k in track for k in (j - 1, j, j + 1)):
                        continue
                    q = [quantities(track[k], k) for k in (j - 1, j, j + 1)]
                    for name in q[0]:
                        d2 = 2 * ((q[2][name] - q[1][name]) / (s[j + 1] - s[j]) - (q[1][name] - q[0][name]) /
                                  (s[j] - s[j - 1])) / (s[j + 1] - s[j - 1])
                        scale = 1.0 if name.startswith("fn") else max(abs(q[1][name]), 1e-300)
                        # a C's own estimated error (errNN) is noise in its second
                        # difference that no step removes: the bound is above it
                        own = 0.0 if name.startswith("fn") else \
                            max(abs(v[track[k], col["err" + name[1:]]]) for k in (j - 1, j, j + 1))
                        e = h * h / 8 * abs(d2) / scale - (own if np.isfinite(own) else 0.0)
                        worst[name] = max(worst.get(name, 0.0), e)
                for name, e in worst.items():
                    if e > self.tolerance:
                        flags[i].append(f"patch {t + 1} {name} {100 * e:.2g} %")
        return flags

    def flagged(self, shift):
        """The flags of the interval holding shift ([] if interpolable there)."""
        i, _ = self._interval(shift)
        return self.flags[i]

    # -- interpolation -------------------------------------------------------------------------
    def _interval(self, shift):
        s = self.shifts
        if not (s[0] <= shift <= s[-1]):
            raise KcreepError(2, f"ContactTable: shift = {shift} (allowed: {s[0]} to {s[-1]} mm, the table's range)")
        return min(max(bisect.bisect_right(s, shift) - 1, 0), s.size - 2)

    def _at(self, shift):
        """kcreep_wheel_rail_at: the patches' values (patches x columns), rows
        (patches x 2, -1 none) and weights (patches x 2)."""
        self._interval(shift)
        n = ctypes.c_int()
        self._source._check(_lib.kcreep_wheel_rail_at(self._source._handle, float(shift), self._capacity,
                                                      self._buffer.ctypes.data, self._rows.ctypes.data,
                                                      self._weights.ctypes.data, ctypes.byref(n)))
        k = n.value
        return self._buffer[:k].copy(), self._rows[:k].copy(), self._weights[:k].copy()

    def _terms(self, shift):
        """Per patch at shift (at()'s order) its (row, weight) terms."""
        _, rows, weights = self._at(shift)
        return [[(int(r), float(w)) for r, w in zip(rr, ww) if r >= 0] for rr, ww in zip(rows, weights)]

    def at(self, shift):
        """Every patch at shift (mm): one dict per patch keyed by the table's
        columns, interpolated linearly between the neighbouring rows
        (kcreep_wheel_rail_at: at a row exactly that row's values; 'shift' the
        given shift, 'patch' and 'verdict' the nearer row's; a patch present
        at one end only keeps that row's values with fn scaled by its weight)."""
        values, _, _ = self._at(shift)
        out = []
        for v in values:
            d = dict(zip(self.columns, v.tolist()))
            for name in ("patch", "verdict"):
                if name in d:
                    d[name] = int(d[name])
            if "kind" in d:   # the word, as in the table (paired rows have the same kind)
                d["kind"] = "flange" if d["kind"] >= 0.5 else "tread"
            out.append(d)
        return out

    def solver(self, row):
        """The Solver holding row's patch and pressure (made on first use)."""
        if self._solvers[row] is None:
            s = Solver(g=self._g, nu=self._nu, threads=self._threads)
            s.take_wheel_rail_row(self._source, row)
            if self.force_cells:
                s.coarsen_patch(self.force_cells)
            self._solvers[row] = s
        return self._solvers[row]

    def forces(self, shift, mu, creepages, exact=False):
        """The forces of every patch at shift (the order of at()): a list of
        n x 3 arrays (Fx, Fy, Mz; the conventions of Solver.rolling) for
        creepages n x 3 (xi, eta, phi), the same for every patch, or a list
        with one n x 3 array per patch. Each row's forces on its own patch and
        pressure, interpolated as at(): exact=False the fast model
        (fast_forces), exact=True exact rolling (Solver.rolling)."""
        if exact:
            return self._combine(shift, creepages, lambda r, c: self.solver(r).rolling(mu, c)[0])
        if self.fast_model == "fastsim":
            return self.fastsim_forces(shift, mu, creepages)
        return self._combine(shift, creepages, lambda r, c: fast_forces(self.solver(r), mu, c))

    def fastsim_forces(self, shift, mu, creepages):
        """As forces(), with FASTSIM (Solver.fastsim, rule 'aligned') on each row."""
        return self._combine(shift, creepages, lambda r, c: self.solver(r).fastsim(mu, c)[0])

    def linear_forces(self, shift, creepages):
        """As forces(), with Kalker's linear theory: -f (xi, eta, phi), each
        row's full creep-force matrix f (Result.f)."""
        return self._combine(shift, creepages, lambda r, c: -c @ self.matrix(r).T)

    def _combine(self, shift, creepages, evaluate):
        terms = self._terms(shift)
        per_patch = isinstance(creepages, (list, tuple)) and len(creepages) == len(terms) and \
            np.ndim(creepages[0]) == 2
        out = []
        for k, patch in enumerate(terms):
            creep = np.atleast_2d(np.asarray(creepages[k] if per_patch else creepages, dtype=np.float64))
            out.append(np.asarray(sum(wt * evaluate(r, creep) for r, wt in patch)))
        return out

    def matrix(self, row):
        """Row's 3 x 3 creep-force matrix f, (Fx, Fy, Mz) = -f (xi, eta, phi)."""
        s = self.solver(row)
        if not hasattr(s, "_f"):
            s._f = s._result(False).f
        return s._f
