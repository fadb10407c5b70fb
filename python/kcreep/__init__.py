"""kcreep: Kalker's creep coefficients of any contact patch.

    import kcreep
    r = kcreep.solve_ellipse(2.0, 1.0, nu=0.25, g=82000.0, mx=80, my=40, scheme="backward")
    r.f        # 3 x 3 creep-force matrix, (Fx, Fy, Mz) = -f (xi, eta, phi)
    r.c        # C11, C22, C23
    r.verdict  # 'ok' or what is wrong
    t = kcreep.wheel_rail("S1002.prw", "UIC60.prr", [0, 4, 8], g=82000.0, nu=0.28, vertical_force=80e3)
    t["y_rail"], t["c11"]   # the contact table (as &wheel_rail), numpy arrays by column
    ct = kcreep.ContactTable("S1002.prw", "UIC60.prr", [0, 1, 2], g=82000.0, nu=0.28, vertical_force=80e3)
    ct.at(0.5), ct.forces(0.5, 0.3, [[1e-3, 0, 0]])   # patches and forces between rows (docs/mbs.md)

The solver is the shared library libkcreep: inside the package when it was
installed with `pip install ./python` (which builds it), else the source
tree's `build/`, or where KCREEP_LIBRARY says;
`kcreep.table` reads kcreep's table files and `kcreep.contact_inp` the gap
values of CONTACT's input files; both need nothing but Python.
"""
from . import table  # noqa: F401  (standard library only)

__all__ = ["solve_ellipse", "solve_mask", "wheel_rail", "WHEEL_RAIL_COLUMNS", "wheelset", "WHEELSET_COLUMNS", "Solver", "Result", "KcreepError",
           "version", "table", "ContactTable"]


def __getattr__(name):
    # the bindings load numpy and the shared library only when first used
    if name in ("solve_ellipse", "solve_mask", "wheel_rail", "WHEEL_RAIL_COLUMNS", "wheelset", "WHEELSET_COLUMNS",
                "Solver", "Result", "KcreepError",
                "version"):
        from . import library
        return getattr(library, name)
    if name == "ContactTable":
        from .contact_table import ContactTable
        return ContactTable
    raise AttributeError(name)
