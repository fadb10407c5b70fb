"""ctypes bindings of kcreep's C API (include/kcreep.h), with numpy arrays.

Errors of the library become KcreepError carrying kcreep's one-line message.
"""
import ctypes
import os

import numpy as np

_HERE = os.path.dirname(os.path.abspath(__file__))
_NAME = "libkcreep.so"


class KcreepError(RuntimeError):
    """A kcreep call failed; .code is the status, str() the message."""

    def __init__(self, code, message):
        super().__init__(message)
        self.code = code


def _candidates():
    env = os.environ.get("KCREEP_LIBRARY")
    if env:
        return [env]
    return [
        os.path.join(_HERE, _NAME),                                   # bundled beside the package
        os.path.join(_HERE, "..", "..", "build", _NAME),              # the source tree's build/
        os.path.join(_HERE, "..", "..", "..", "..", "lib", _NAME),    # <prefix>/lib/pythonX/site-packages
        _NAME,                                                        # the loader's search path
    ]


def _load():
    tried = []
    for path in _candidates():
        try:
            return ctypes.CDLL(path)
        except OSError as e:
            tried.append(f"{path} ({e})")
    raise OSError("kcreep: libkcreep.so not found; build it (scripts/setup.sh) or set KCREEP_LIBRARY. Tried: "
                  + "; ".join(tried))


_lib = _load()
_h = ctypes.c_void_p
_d = ctypes.c_double
_i = ctypes.c_int
_p = ctypes.c_void_p
_signatures = {
    "kcreep_version": ([], _i),
    "kcreep_new": ([], _h),
    "kcreep_delete": ([ctypes.POINTER(_h)], None),
    "kcreep_get_message": ([_h, ctypes.c_char_p, _i], _i),
    "kcreep_set_material": ([_h, _d, _d], _i),
    "kcreep_set_scheme": ([_h, ctypes.c_char_p, _d, _d], _i),
    "kcreep_set_solver": ([_h, ctypes.c_char_p, _d], _i),
    "kcreep_set_extrapolation": ([_h, _i, _i], _i),
    "kcreep_set_threads": ([_h, _i], _i),
    "kcreep_get_threads": ([_h, ctypes.POINTER(_i)], _i),
    "kcreep_set_ellipse": ([_h, _d, _d, _i, _i], _i),
    "kcreep_set_mask": ([_h, _i, _i, _p, _d, _d, _d, _d], _i),
    "kcreep_solve": ([_h], _i),
    "kcreep_solve_mask": ([_h, _i, _i, _p, _d, _d, _d, _d], _i),
    "kcreep_get_matrix": ([_h, _p], _i),
    "kcreep_get_normalised": ([_h, _p], _i),
    "kcreep_get_error_estimate": ([_h, _p, _p], _i),
    "kcreep_get_fastsim": ([_h, _p], _i),
    "kcreep_get_verdict": ([_h, ctypes.POINTER(_i), ctypes.c_char_p, _i], _i),
    "kcreep_get_warning": ([_h, _i, ctypes.c_char_p, _i], _i),
    "kcreep_get_cells": ([_h, ctypes.POINTER(_i), ctypes.POINTER(_i), ctypes.POINTER(_i)], _i),
    "kcreep_get_tractions": ([_h, _i, _p, _p, _p], _i),
    "kcreep_get_reuse_count": ([_h, ctypes.POINTER(_i)], _i),
    "kcreep_get_results": ([_h, _i, _p], _i),
    "kcreep_set_error_control": ([_h, _d, _i, _i], _i),
    "kcreep_set_cell_budget": ([_h, _d], _i),
    "kcreep_get_relative_error": ([_h, _p], _i),
    "kcreep_set_bodies": ([_h, _d, _d, _d, _d], _i),
    "kcreep_set_spin_centre": ([_h, _d, _d], _i),
    "kcreep_set_gap": ([_h, _i, _i, _p, _d, _d, _d, _d, _d, _d], _i),
    "kcreep_get_normal": ([_h, ctypes.POINTER(_d), ctypes.POINTER(_d), ctypes.POINTER(_d), ctypes.POINTER(_i),
                           ctypes.POINTER(_i)], _i),
    "kcreep_fastsim": ([_h, _d, _i, _p, _p, ctypes.c_char_p, _p, _p], _i),
    "kcreep_rolling": ([_h, _d, _i, _p, _p, _p, _p], _i),
    "kcreep_fast_forces": ([_h, _d, _i, _p, _p, _p], _i),
    "kcreep_coarsen_patch": ([_h, _i], _i),
    "kcreep_get_diagnostics": ([_h, ctypes.POINTER(_i), ctypes.POINTER(_d), ctypes.POINTER(_d), ctypes.POINTER(_d)], _i),
    "kcreep_set_profiles": ([_h, ctypes.c_char_p, ctypes.c_char_p, _i, _i, _d], _i),
    "kcreep_set_track": ([_h, ctypes.c_char_p, _d, _d, _d, _d, _d, _d], _i),
    "kcreep_wheel_rail": ([_h, _i, _p, _d, _d, _d, ctypes.POINTER(_i)], _i),
    "kcreep_get_wheel_rail": ([_h, _i, _p], _i),
    "kcreep_take_wheel_rail_row": ([_h, _h, _i], _i),
    "kcreep_wheel_rail_at": ([_h, _d, _i, _p, _p, _p, ctypes.POINTER(_i)], _i),
    "kcreep_wheel_rail_forces": ([_h, _d, _d, _i, _i, _p, _i, _p], _i),
    "kcreep_set_left_profiles": ([_h, ctypes.c_char_p, ctypes.c_char_p], _i),
    "kcreep_wheelset": ([_h, _i, _p, _d, _d, ctypes.POINTER(_i)], _i),
    "kcreep_get_wheelset": ([_h, _i, _p], _i),
}
#: the columns of the wheel-rail contact table (KCREEP_WHEEL_RAIL_COLUMN_NAMES of kcreep.h)
WHEEL_RAIL_COLUMNS = ("shift yaw patch fn delta y_rail y_wheel r_wheel area length width c11 c22 c23 c33 "
                      "err11 err22 err23 verdict l1 l2 l3 spin kind turn").split()
#: the columns of the wheelset table (KCREEP_WHEELSET_COLUMN_NAMES of kcreep.h)
WHEELSET_COLUMNS = "shift r_right r_left delta_r delta_right delta_left roll z lambda_eq".split()
for _name, (_args, _res) in _signatures.items():
    _f = getattr(_lib, _name)
    _f.argtypes = _args
    _f.restype = _res


def version():
    """kcreep's version as 'major.minor.patch'."""
    v = _lib.kcreep_version()
    return f"{v // 10000}.{v // 100 % 100}.{v % 100}"


class Result:
    """One solve: f (3 x 3), c (C11, C22, C23), fastsim (L1, L2, L3), verdict,
    verdict_flags, warnings, n (cells), err (estimated relative errors of c,
    NaN when there is none), ext and ext_error (NaN unless extrapolated), iterations, residual, rcond, seconds, threads (diagnostics) and, with tractions=True, traction (n x 2 x 3: px, py per load
    case xi, eta, phi) with the cells' grid indices ix, iy (1-based)."""

    def __repr__(self):
        return f"Result(c={self.c.tolist()}, verdict={self.verdict!r}, n={self.n})"


def _creep_arrays(creepages, pressure):
    """FASTSIM's and exact rolling's arguments as the C API takes them: the
    creepages n x 3 (xi, eta, phi), n, room for the forces and adhesion, and
    the pressure (None: the normal problem's)."""
    creep = np.ascontiguousarray(np.atleast_2d(creepages), dtype=np.float64)
    if creep.ndim != 2 or creep.shape[1] != 3:
        raise KcreepError(2, "creepages must be n x 3 (xi, eta, phi)")
    n = creep.shape[0]
    pressure = None if pressure is None else np.ascontiguousarray(pressure, dtype=np.float64)
    return creep, n, np.empty((n, 3)), np.empty(n), pressure


class Solver:
    """A handle of the C API: settings, geometry, and repeated solves that
    reuse the operator table when grid, scheme and material stay the same.
    method: "auto", "dense", "iterative", or "table" (ellipses with 0.1 <= a/b
    <= 10 from kcreep's refined table in microseconds, err the stated
    uncertainty, no tractions). cell_budget: the most patch cells of a level
    kcreep chooses under error control (0: the defaults, a run-time budget;
    raise it for reference work, e.g. target_error=1e-4). threads: 0
    automatic (the CPUs this process may use that are free when a stage
    starts, where the work pays), else exactly this many; solvers on several
    threads, one each, run at once."""

    def __init__(self, *, nu=0.25, g=1.0, scheme="backward", alpha=0.5, spin_shift=0.0,
                 method="auto", tolerance=0.0, extrapolate_levels=0, refine_ratio=2,
                 target_error=1e-3, refine_grid=True, estimate_error=True, cell_budget=0.0, spin_centre=(0.0, 0.0),
                 bodies=None, threads=0):
        self._handle = _h(_lib.kcreep_new())
        self._check(_lib.kcreep_set_threads(self._handle, int(threads)))
        self._check(_lib.kcreep_set_spin_centre(self._handle, float(spin_centre[0]), float(spin_centre[1])))
        self._check(_lib.kcreep_set_error_control(self._handle, target_error, int(bool(refine_grid)),
                                                  int(bool(estimate_error))))
        self._check(_lib.kcreep_set_cell_budget(self._handle, float(cell_budget)))
        self._check(_lib.kcreep_set_material(self._handle, g, nu))
        self._check(_lib.kcreep_set_scheme(self._handle, scheme.encode(), alpha, spin_shift))
        self._check(_lib.kcreep_set_solver(self._handle, method.encode(), tolerance))
        self._check(_lib.kcreep_set_extrapolation(self._handle, extrapolate_levels, refine_ratio))
        if bodies is not None:   # (e1, nu1, e2, nu2) instead of g, nu
            self._check(_lib.kcreep_set_bodies(self._handle, *map(float, bodies)))

    def __del__(self):
        if getattr(self, "_handle", None) is not None and _lib is not None:
            _lib.kcreep_delete(ctypes.byref(self._handle))
            self._handle = None

    def _check(self, code):
        if code != 0:
            buffer = ctypes.create_string_buffer(1024)
            _lib.kcreep_get_message(self._handle, buffer, len(buffer))
            raise KcreepError(code, buffer.value.decode(errors="replace") or f"kcreep status {code}")

    def set_material(self, *, g, nu):
        self._check(_lib.kcreep_set_material(self._handle, g, nu))

    def solve_ellipse(self, semi_a, semi_b, mx=None, my=None, tractions=False):
        """mx, my None: kcreep chooses the grids (or answers from its refined
        table) as the program does; given: that grid, solved as given and judged."""
        if (mx is None) != (my is None):
            raise KcreepError(2, "solve_ellipse: give both mx and my, or neither (kcreep chooses the grids)")
        self._check(_lib.kcreep_set_ellipse(self._handle, semi_a, semi_b, int(mx or 0), int(my or 0)))
        self._check(_lib.kcreep_solve(self._handle))
        return self._result(tractions)

    def solve_mask(self, inside, dx, dy, x0=0.0, y0=0.0, tractions=False):
        cells = np.ascontiguousarray(np.asarray(inside) != 0, dtype=np.intc)
        if cells.ndim != 2:
            raise KcreepError(2, f"inside must be a 2-D array (rows in increasing y), got {cells.ndim}-D")
        my, mx = cells.shape
        self._check(_lib.kcreep_solve_mask(self._handle, mx, my, cells.ctypes.data, dx, dy, x0, y0))
        return self._result(tractions)

    def solve_gap(self, gap, dx, dy, x0=0.0, y0=0.0, *, approach=0.0, normal_force=0.0, tractions=False):
        """The normal problem on the undeformed distance gap (2-D array, rows in
        increasing y), with approach or normal_force prescribed, then the
        coefficients of the contact area found. The Result also has fn,
        approach, pmax and normal_iterations."""
        h = np.ascontiguousarray(gap, dtype=np.float64)
        if h.ndim != 2:
            raise KcreepError(2, f"gap must be a 2-D array (rows in increasing y), got {h.ndim}-D")
        my, mx = h.shape
        self._check(_lib.kcreep_set_gap(self._handle, mx, my, h.ctypes.data, dx, dy, x0, y0, approach, normal_force))
        self._check(_lib.kcreep_solve(self._handle))
        r = self._result(tractions)
        fn, app, pmax, cells, iterations = _d(), _d(), _d(), _i(), _i()
        self._check(_lib.kcreep_get_normal(self._handle, ctypes.byref(fn), ctypes.byref(app), ctypes.byref(pmax),
                                           ctypes.byref(cells), ctypes.byref(iterations)))
        r.fn, r.approach, r.pmax, r.normal_iterations = fn.value, app.value, pmax.value, iterations.value
        return r

    def fastsim(self, mu, creepages, pressure=None, rule="aligned"):
        """FASTSIM with friction mu on the last solved patch for creepages (n x 3:
        xi, eta, phi), the patch's exact L1 L2 L3, flexibility rule "aligned",
        "separate" or "weighted" (docs/fastsim.md); pressure on the patch's grid
        (2-D, rows in increasing y) or None for the normal problem's. Returns
        (forces n x 3: Fx, Fy, Mz; adhesion n: fraction of the area adhering)."""
        creep, n, forces, adhesion, p = _creep_arrays(creepages, pressure)
        self._check(_lib.kcreep_fastsim(self._handle, mu, n, creep.ctypes.data, None if p is None else p.ctypes.data,
                                        rule.encode(), forces.ctypes.data, adhesion.ctypes.data))
        return forces, adhesion

    def wheel_rail(self, wheel_file, rail_file, shifts, *, vertical_force=0.0, approach=0.0, yaw=0.0,
                   side="right", gauge_width=1435.0, gauge_height=14.0, rail_cant=0.0, flange_back_distance=1360.0,
                   flange_back_position=-70.0, nominal_radius=460.0, wheel_mirror=False, rail_mirror=False,
                   smoothing=-1.0):
        """The contact table of a wheel on a rail over the lateral shifts (mm), as
        the program's &wheel_rail (docs/wheel_rail.md): exactly one of
        vertical_force (N) and approach (mm) > 0; smoothing (mm^4) negative:
        automatic, as the program's default; this Solver's material,
        solver settings and target_error (0: the program's default, 1e-3).
        Returns a dict of numpy arrays, one per column of WHEEL_RAIL_COLUMNS (one
        entry per shift and patch; 'patch' integers, 'verdict' the verdict bits,
        'kind' the words 'tread' or 'flange')."""
        s = np.ascontiguousarray(np.atleast_1d(shifts), dtype=np.float64)
        self._check(_lib.kcreep_set_profiles(self._handle, os.fsencode(wheel_file), os.fsencode(rail_file),
                                             int(bool(wheel_mirror)), int(bool(rail_mirror)), float(smoothing)))
        self._check(_lib.kcreep_set_track(self._handle, side.encode(), gauge_width, gauge_height, rail_cant,
                                          flange_back_distance, flange_back_position, nominal_radius))
        rows = _i()
        self._check(_lib.kcreep_wheel_rail(self._handle, s.size, s.ctypes.data, yaw, vertical_force, approach,
                                           ctypes.byref(rows)))
        n = len(WHEEL_RAIL_COLUMNS)
        values = np.empty(rows.value * n)
        self._check(_lib.kcreep_get_wheel_rail(self._handle, values.size, values.ctypes.data))
        values = values.reshape(rows.value, n)
        table = {name: values[:, k].copy() for k, name in enumerate(WHEEL_RAIL_COLUMNS)}
        table["patch"] = table["patch"].astype(int)
        table["verdict"] = table["verdict"].astype(int)
        table["kind"] = np.where(table["kind"] > 0.5, "flange", "tread")
        return table

    def wheelset(self, wheel_file, rail_file, shifts, *, vertical_force, yaw=0.0, left_wheel_file=None,
                 left_rail_file=None, gauge_width=1435.0, gauge_height=14.0, rail_cant=0.0,
                 flange_back_distance=1360.0, flange_back_position=-70.0, nominal_radius=460.0, wheel_mirror=False,
                 rail_mirror=False, smoothing=0.0):
        """The wheelset table over the lateral shifts (mm), as the program's
        &wheel_rail wheelset = .true. (docs/wheel_rail.md, Wheelset): each wheel
        carrying vertical_force (N), the left wheel the right one mirrored or on
        left_wheel_file / left_rail_file. Returns a dict of numpy arrays, one per
        column of WHEELSET_COLUMNS (one entry per shift)."""
        s = np.ascontiguousarray(np.atleast_1d(shifts), dtype=np.float64)
        self._check(_lib.kcreep_set_profiles(self._handle, os.fsencode(wheel_file), os.fsencode(rail_file),
                                             int(bool(wheel_mirror)), int(bool(rail_mirror)), float(smoothing)))
        self._check(_lib.kcreep_set_track(self._handle, b"right", gauge_width, gauge_height, rail_cant,
                                          flange_back_distance, flange_back_position, nominal_radius))
        self._check(_lib.kcreep_set_left_profiles(self._handle, None if left_wheel_file is None else
                                                  os.fsencode(left_wheel_file), None if left_rail_file is None else
                                                  os.fsencode(left_rail_file)))
        rows = _i()
        self._check(_lib.kcreep_wheelset(self._handle, s.size, s.ctypes.data, yaw, vertical_force,
                                         ctypes.byref(rows)))
        n = len(WHEELSET_COLUMNS)
        values = np.empty(rows.value * n)
        self._check(_lib.kcreep_get_wheelset(self._handle, values.size, values.ctypes.data))
        values = values.reshape(rows.value, n)
        return {name: values[:, k].copy() for k, name in enumerate(WHEELSET_COLUMNS)}

    def take_wheel_rail_row(self, source, row):
        """Row `row` (0-based) of the Solver source's last wheel_rail table
        becomes this Solver's solved patch (grid, pressure, coefficients), so
        fastsim and rolling run on it (kcreep_take_wheel_rail_row)."""
        self._check(_lib.kcreep_take_wheel_rail_row(self._handle, source._handle, int(row)))

    def rolling(self, mu, creepages, pressure=None):
        """Exact steady rolling with friction mu on the last solved patch
        (docs/rolling.md) for creepages (n x 3: xi, eta, phi); pressure on the
        patch's grid (2-D, rows in increasing y) or None for the normal
        problem's. Returns (forces n x 3: Fx, Fy, Mz; adhesion n: fraction of
        the patch cells adhering)."""
        creep, n, forces, adhesion, p = _creep_arrays(creepages, pressure)
        self._check(_lib.kcreep_rolling(self._handle, mu, n, creep.ctypes.data, None if p is None else p.ctypes.data,
                                        forces.ctypes.data, adhesion.ctypes.data))
        return forces, adhesion

    def fast_forces(self, mu, creepages, pressure=None):
        """The fast force model of the last solved patch (docs/rolling.md): the
        forces of rolling (n x 3: Fx, Fy, Mz, its conventions) interpolated in a
        table of exact solutions, built on the first call for a pressure and
        kept until the next solve; microseconds per point."""
        creep, n, forces, _, p = _creep_arrays(creepages, pressure)
        self._check(_lib.kcreep_fast_forces(self._handle, mu, n, creep.ctypes.data,
                                            None if p is None else p.ctypes.data, forces.ctypes.data))
        return forces

    def coarsen_patch(self, max_cells):
        """The solved patch and the normal problem's pressure coarsened by
        square blocks of cells to at most max_cells cells, for fastsim,
        rolling and fast_forces (kcreep_coarsen_patch); the coefficients stay
        the solved ones."""
        self._check(_lib.kcreep_coarsen_patch(self._handle, int(max_cells)))

    @property
    def reuse_count(self):
        count = _i()
        self._check(_lib.kcreep_get_reuse_count(self._handle, ctypes.byref(count)))
        return count.value

    def _result(self, tractions):
        # one call for all numbers (each ctypes call costs microseconds in a loop)
        r = Result()
        v = np.empty(33)
        self._check(_lib.kcreep_get_results(self._handle, 33, v.ctypes.data))
        r.f = v[0:9].reshape(3, 3)
        r.c, r.fastsim, r.err = v[9:12], v[12:15], v[15:18]
        r.ext, r.ext_error = v[18:21], v[21:24]
        r.iterations, r.residual, r.rcond, r.seconds = int(v[24]), v[25], v[26], v[27]
        r.n, r.mx, r.my, r.verdict_flags = int(v[28]), int(v[29]), int(v[30]), int(v[31])
        threads = _i()
        self._check(_lib.kcreep_get_threads(self._handle, ctypes.byref(threads)))
        r.threads = threads.value
        if r.verdict_flags == 0 and v[32] == 0:
            r.verdict, r.warnings = "ok", []
        else:
            flags = _i()
            buffer = ctypes.create_string_buffer(8192)
            self._check(_lib.kcreep_get_verdict(self._handle, ctypes.byref(flags), buffer, len(buffer)))
            # the verdict words (comma-separated, no "; ") lead the joined string;
            # the warnings are fetched one by one, whatever they contain
            r.verdict = buffer.value.decode(errors="replace").split("; ")[0]
            r.warnings = []
            for k in range(int(v[32])):
                self._check(_lib.kcreep_get_warning(self._handle, k, buffer, len(buffer)))
                r.warnings.append(buffer.value.decode(errors="replace"))
        if tractions:
            t = np.empty(6 * r.n)
            r.ix, r.iy = np.empty(r.n, dtype=np.intc), np.empty(r.n, dtype=np.intc)
            self._check(_lib.kcreep_get_tractions(self._handle, t.size, t.ctypes.data, r.ix.ctypes.data,
                                                  r.iy.ctypes.data))
            r.traction = t.reshape(3, 2, r.n).transpose(2, 1, 0)
        return r


def solve_ellipse(semi_a, semi_b, *, nu=0.25, g=1.0, mx=None, my=None, scheme="backward", alpha=0.5,
                  method="auto", target_error=1e-3, cell_budget=0.0, tractions=False):
    """Coefficients of the ellipse with semi-axes semi_a (along x, rolling) and
    semi_b: without mx, my as the program's default run (kcreep chooses the
    grids, or answers from its refined table, within target_error); with
    them that grid as given, with its estimated error and verdict."""
    return Solver(nu=nu, g=g, scheme=scheme, alpha=alpha, method=method, target_error=target_error,
                  cell_budget=cell_budget).solve_ellipse(semi_a, semi_b, mx, my, tractions)


def solve_mask(inside, dx, dy, *, x0=0.0, y0=0.0, nu=0.25, g=1.0, scheme="backward", alpha=0.5,
               method="auto", target_error=1e-3, refine_grid=True, cell_budget=0.0, tractions=False):
    """Coefficients of the patch inside (2-D boolean array, rows in increasing y)
    with cell sizes dx, dy and the centre (x0, y0) of cell [0, 0]: as the
    program's default run, every cell split until the estimates meet
    target_error (refine_grid=False: the grid as given, judged)."""
    return Solver(nu=nu, g=g, scheme=scheme, alpha=alpha, method=method, target_error=target_error,
                  refine_grid=refine_grid, cell_budget=cell_budget).solve_mask(inside, dx, dy, x0, y0, tractions)


def wheel_rail(wheel_file, rail_file, shifts, *, g, nu, target_error=1e-3, threads=0, **placement):
    """The contact table of a wheel on a rail (Solver.wheel_rail) with material
    g, nu at target_error (the program's default 1e-3): a dict of numpy arrays
    by column. placement: vertical_force or approach, and the other keywords of
    Solver.wheel_rail (yaw, side, gauge_width, ...)."""
    return Solver(g=g, nu=nu, target_error=target_error, refine_grid=True, threads=threads).wheel_rail(
        wheel_file, rail_file, shifts, **placement)


def wheelset(wheel_file, rail_file, shifts, *, g, nu, vertical_force, threads=0, **placement):
    """The wheelset table (Solver.wheelset) with material g, nu: a dict of numpy
    arrays by column (WHEELSET_COLUMNS). placement: yaw, left_wheel_file,
    left_rail_file and the track keywords of Solver.wheelset."""
    return Solver(g=g, nu=nu, refine_grid=True, threads=threads).wheelset(
        wheel_file, rail_file, shifts, vertical_force=vertical_force, **placement)
