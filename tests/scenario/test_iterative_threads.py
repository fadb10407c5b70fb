"""The iterative (FFT/GMRES) solution does not depend on the number of
OpenMP threads: the coefficients and iteration counts of runs with
&solver threads = 1 and 2 are equal to all the digits the table holds.

Why exact: the FFT operator and the circulant preconditioner give each
thread whole transforms with the same single-threaded plan, the kernel
product and the running sums have no reductions, and GMRES's
orthogonalisation sums over fixed blocks of rows in a fixed order; so the
same operations run in the same order on any number of threads
(tests/unit/test_fft_operator.f90 checks the operator bit for bit). Not the
strip preconditioner: its row factors go through the threaded BLAS, whose
sums may depend on the threads."""
import kctest as kc

folder = kc.setup()
names = ["f11", "f12", "f13", "f21", "f22", "f23", "f31", "f32", "f33", "iterations", "berr"]

# an asymmetric, non-convex patch (from test_symmetry_scaling)
rows = ["..####......", ".#######....", "##########..", "###########.", "....########",
        ".....#######", "###..######.", "##########..", ".########...", "...####....."]
rows = [r.replace("#", "###").replace(".", "...") for r in rows for _ in (0, 1, 2)]
mask = "shape='mask', mask_rows=" + ", ".join(f"'{r}'" for r in rows) + \
       f", dx=0.05, dy=0.05, x0={-(len(rows[0]) - 1) * 0.025}, y0={-(len(rows) - 1) * 0.025}"
cases = {"circle 64 x 64, backward": ("semi_a=1, semi_b=1, mx=64, my=64", "scheme='backward'"),
         "ellipse a/b = 3, collocation": ("semi_a=1.5, semi_b=0.5, mx=75, my=25",
                                          f"{kc.scheme_setting('collocation', 0.5)}"),
         "asymmetric mask, backward": (mask, "scheme='backward'")}

for label, (patch, solver) in cases.items():
    result = {}
    for threads in ("1", "2"):
        text = kc.namelist(patch, "nu=0.3", f"{solver}, method='iterative', threads={threads}")
        result[threads] = kc.coefficients(text, folder, f"t{threads}")
    differ = [n for n in names if result["1"][n] != result["2"][n] and not
              (kc.isnan(result["1"][n]) and kc.isnan(result["2"][n]))]
    kc.check(not differ, f"{label}: 2 threads = 1 thread in {', '.join(names)} "
             f"({result['1']['iterations']:.0f} iterations)" + (f"; differ: {differ}" if differ else ""))
kc.finish()
