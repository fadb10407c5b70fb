"""The installed library: `cmake --install` into a scratch prefix, a C
program (tests/api) configured with find_package(kcreep) and built against
it, its error paths, and the same numbers from the command line, C and
Python for the same patches.

usage: test_install.py KCREEP BUILD_DIR SOURCE_DIR   (needs numpy: /usr/bin/python3)
"""
import os
import subprocess
import sys

import kctest as kc

folder = kc.setup()
build_dir, source_dir = os.path.abspath(sys.argv[2]), os.path.abspath(sys.argv[3])
prefix = os.path.join(folder, "prefix")
api_build = os.path.join(folder, "api-build")


def run(*cmd, **kw):
    proc = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if proc.returncode != 0:
        print(proc.stdout[-3000:], proc.stderr[-3000:])
    return proc


# installed in one place, used from another: the package is relocatable
installed = os.path.join(folder, "installed")
kc.check(run("cmake", "--install", build_dir, "--prefix", installed).returncode == 0, "cmake --install into a prefix")
for dirpath, _, names in os.walk(installed):
    for name in names:
        if name.endswith(".cmake"):
            text = open(os.path.join(dirpath, name)).read()
            kc.check(installed not in text and "/usr/" not in text and build_dir not in text,
                     f"{name}: no absolute paths (relocatable)")
os.rename(installed, prefix)
modules = sorted(n for _, _, names in os.walk(prefix) for n in names if n.endswith(".mod"))
kc.check(modules == ["kcreep.mod"], f"one Fortran module installed, the facade's ({len(modules)}: {modules[:3]})")
for path in ("include/kcreep.h", "include/kcreep/kcreep.mod", "lib/cmake/kcreep/kcreepConfig.cmake"):
    kc.check(os.path.exists(os.path.join(prefix, path)), f"installed {path}")
libdir = next(d for d in ("lib", "lib64", "lib/x86_64-linux-gnu") if os.path.exists(os.path.join(prefix, d, "libkcreep.so")))
library = os.path.join(prefix, libdir, "libkcreep.so")
kc.check(os.path.islink(library) and ".so.0" in os.readlink(library), "libkcreep.so -> SOVERSION 0")

configured = run("cmake", "-S", os.path.join(source_dir, "tests", "api"), "-B", api_build,
                 f"-DCMAKE_PREFIX_PATH={prefix}")
kc.check(configured.returncode == 0, "find_package(kcreep) from the installed prefix")
kc.check(run("cmake", "--build", api_build).returncode == 0, "C program built against kcreep::kcreep")
example = os.path.join(api_build, "api_example")
# the C program must run on the installed library, not the build tree's
env = dict(os.environ, LD_LIBRARY_PATH=os.path.join(prefix, libdir))


def c_values(mode):
    proc = run(example, mode, env=env)
    kc.check(proc.returncode == 0, f"api_example {mode} exits 0")
    values = {}
    for line in proc.stdout.splitlines():
        words = line.split()
        values[" ".join(words[:2])] = words[2:]
    return values


# a project that enables C only links the static library (the Fortran runtime
# and OpenMP come with the target)
static = run(os.path.join(api_build, "api_example_static"), "ellipse")
kc.check(static.returncode == 0 and "ellipse f" in static.stdout,
         "C-only project linked to kcreep::kcreep_static runs")
# a Fortran program needs kcreep.mod alone
with open(os.path.join(folder, "use_kcreep.f90"), "w") as f:
    f.write("program use_kcreep\n  use kcreep\n  implicit none\n  type(problem_t) :: p\n  type(result_t) :: r\n"
            "  type(status_t) :: s\n  p = default_problem()\n  call ellipse_patch(2d0, 1d0, 20, 20, p%patch, s)\n"
            "  call kcreep_solve(p, r, s)\n  print '(i0, es24.16)', s%code, r%f(1, 1)\nend program\n")
fortran = run("gfortran", "-I", os.path.join(prefix, "include", "kcreep"), os.path.join(folder, "use_kcreep.f90"),
              "-L", os.path.join(prefix, libdir), "-lkcreep", "-o", os.path.join(folder, "use_kcreep"))
kc.check(fortran.returncode == 0, "a Fortran program built with the installed kcreep.mod alone")
if fortran.returncode == 0:
    out = run(os.path.join(folder, "use_kcreep"), env=env).stdout.split()
    kc.check(len(out) == 2 and out[0] == "0" and float(out[1]) > 0, "and solves an ellipse")

ldd = run("ldd", example, env=env).stdout
kc.check(os.path.join(prefix, libdir) in ldd, "api_example loads the installed libkcreep")

errors = c_values("errors")
kc.check(errors.get("errors failures") == ["0"], "C API error paths: NULL handle, NULL arrays, bad values")
kc.check("nu" in " ".join(errors.get("errors nu", [])) and "0.5" in " ".join(errors.get("errors nu", [])),
         "the message names the variable and the allowed range")

# the same patches through the command line
# (the library's defaults: the backward scheme, the grid as given)
ellipse_row = kc.coefficients(kc.namelist(patch="semi_a = 2, semi_b = 1, mx = 40, my = 40",
                                          material="g = 82000, nu = 0.25", solver="scheme = 'backward'"),
                              folder, "ellipse")
rows = ["".join("1" if ((-1 + (ix + 0.5) / 20) ** 2 + (-1 + (iy + 0.5) / 20) ** 2) <= 1 else "0"
                for ix in range(40)) for iy in range(40)]
mask_row = kc.coefficients(kc.namelist(patch="shape = 'mask', dx = 0.05, dy = 0.05, x0 = -0.975, y0 = -0.975, "
                                             "mask_rows = " + ", ".join(f"'{r}'" for r in rows),
                                       material="g = 82000, nu = 0.25",
                                       # the library's defaults: target 1e-3, the cells split
                                       solver="scheme = 'backward', target_error = 1e-3"),
                           folder, "mask")
names = ["f11", "f12", "f13", "f21", "f22", "f23", "f31", "f32", "f33"]

# Python on the installed library (KCREEP_LIBRARY), numpy from Debian
py = f"""
import sys; sys.path.insert(0, {os.path.join(source_dir, 'python')!r})
import numpy as np, kcreep
e = kcreep.solve_ellipse(2.0, 1.0, nu=0.25, g=82000.0, mx=40, my=40)
y, x = np.mgrid[0:40, 0:40]
inside = ((-1 + (x + 0.5) / 20) ** 2 + (-1 + (y + 0.5) / 20) ** 2) <= 1
m = kcreep.solve_mask(inside, 0.05, 0.05, x0=-0.975, y0=-0.975, nu=0.25, g=82000.0)
print(' '.join(repr(v) for v in e.f.ravel()))
print(' '.join(repr(v) for v in m.f.ravel()))
"""
proc = run("/usr/bin/python3", "-c", py, env=dict(os.environ, KCREEP_LIBRARY=library))
kc.check(proc.returncode == 0, "Python on the installed library")
python_f = [list(map(float, line.split())) for line in proc.stdout.splitlines()[:2]] if proc.returncode == 0 else [[], []]

# The three ways run the same compiled code on the same grid: the numbers are
# the same to the last printed digit (the table prints 16 significant digits;
# 1e-14 relative leaves room only for the last digit's rounding).
for label, cli_row, c_key, py_f in (("ellipse", ellipse_row, "ellipse f", python_f[0]),
                                    ("mask", mask_row, "mask f", python_f[1])):
    c_f = list(map(float, c_values(label)[c_key]))
    cli_f = [cli_row[k] for k in names]
    scale = max(abs(v) for v in cli_f)
    kc.check(len(c_f) == 9 and max(abs(a - b) for a, b in zip(c_f, cli_f)) <= 1e-14 * scale,
             f"{label}: C API f == command line f")
    kc.check(len(py_f) == 9 and max(abs(a - b) for a, b in zip(py_f, cli_f)) <= 1e-14 * scale,
             f"{label}: Python f == command line f")

mask = c_values("mask")
kc.check(mask.get("mask reused") == ["1"], "second solve on the same grid reuses the operator table")
kc.finish()
