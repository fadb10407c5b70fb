"""Row-by-row comparison of two kcreep tables (coefficients, not times)."""
import math

FORCE = ["f11", "f12", "f13", "f21", "f22", "f23", "f31", "f32", "f33"]
EXACT = ["mx", "my", "n"]
RELATIVE = ["alpha", "nu", "g", "c", "c11", "c22", "c23", "klt11", "klt22", "klt23", "rcond"]


def nan(x):
    return isinstance(x, float) and math.isnan(x)


def row_difference(a, b):
    """(worst difference, column): the fij relative to the largest |fij| of the row
    (the zero entries of a symmetric patch are round-off, ~1e-17), the others
    relative to themselves; berr only has to be at round-off level in both
    (it is the round-off). NaN must match NaN; a mismatch counts as inf."""
    worst, where = 0.0, ""
    if a["verdict"] != b["verdict"]:
        return math.inf, "verdict"
    scale = max([abs(a[c]) for c in FORCE if not nan(a[c])] + [1e-300])
    for c in EXACT + FORCE + RELATIVE + ["berr"]:
        x, y = a[c], b[c]
        if nan(x) or nan(y):
            d = 0.0 if nan(x) and nan(y) else math.inf
        elif c in EXACT:
            d = 0.0 if x == y else math.inf
        elif c in FORCE:
            d = abs(x - y) / scale
        elif c == "berr":
            d = 0.0 if max(x, y) <= 1e-13 else abs(x - y) / max(abs(x), abs(y))
        else:
            d = abs(x - y) / max(abs(x), abs(y), 1e-300)
        if d > worst:
            worst, where = d, c
    return worst, where
