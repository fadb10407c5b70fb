"""Every bad input ends in one clear line on stderr, a non-zero exit
status, and no output: an existing table of the same name is left as it
was and no temporary file is left behind."""
import os
import subprocess
import kctest as kc

folder = kc.setup()
good_patch = "semi_a=1, semi_b=1, mx=8, my=8"
mask_ok = "3 2 0.1 0.1 0 0\n###\n.#.\n"
cases = [
    # (name, namelist text, extra files, fragment expected in the message)
    ("unknown_variable", "&patch foo = 1 /\n", {}, "&patch"),
    ("unknown_group", "&solverr alpha = 0.5 /\n", {}, "unknown namelist group &solverr"),
    ("wrong_type", "&patch mx = 'abc' /\n", {}, "&patch"),
    ("unterminated", "&patch mx = 10\n", {}, "&patch"),
    ("nu_high", kc.namelist(good_patch, "nu=0.6"), {}, "nu = 0.6"),
    ("nu_negative", kc.namelist(good_patch, "nu=-0.1"), {}, "nu = -0.1"),
    ("nu_nan", kc.namelist(good_patch, "nu=NaN"), {}, "nu = NaN"),
    ("g_zero", kc.namelist(good_patch, "g=0"), {}, "g = 0"),
    ("g_negative", kc.namelist(good_patch, "g=-5"), {}, "g = -5"),
    ("g_infinite", kc.namelist(good_patch, "g=Inf"), {}, "g = Inf"),
    ("alpha_one", kc.namelist(good_patch, "", "alpha=1"), {}, "alpha = 1"),
    ("alpha_low", kc.namelist(good_patch, "", "alpha=-1.5"), {}, "alpha = -1.5"),
    ("scheme", kc.namelist(good_patch, "", "scheme='forward'"), {}, "scheme = 'forward'"),
    ("load_cases", kc.namelist(good_patch, "", "load_cases='xi zeta'"), {}, "unknown case 'zeta'"),
    ("load_cases_empty", kc.namelist(good_patch, "", "load_cases=' '"), {}, "load_cases is empty"),
    ("shape", kc.namelist("shape='circle'"), {}, "shape = 'circle'"),
    ("semi_a", kc.namelist("semi_a=0"), {}, "semi_a = 0"),
    ("semi_b", kc.namelist("semi_b=-2"), {}, "semi_b = -2"),
    ("mx_negative", kc.namelist("mx=-3"), {}, "mx = -3"),
    ("ellipse_with_mask", kc.namelist("mask_rows='##'"), {}, "takes no mask_file or mask_rows"),
    ("rows_unequal", kc.namelist("shape='mask', mask_rows='###','##', dx=1, dy=1"), {}, "mask row 2 has 2 cells"),
    ("rows_vs_my", kc.namelist("shape='mask', mask_rows='##','##', my=3, dx=1, dy=1"), {}, "my = 3 but mask_rows has 2 rows"),
    ("rows_vs_mx", kc.namelist("shape='mask', mask_rows='##','##', mx=3, dx=1, dy=1"), {}, "mx = 3 but mask row 1 has 2"),
    ("empty_patch", kc.namelist("shape='mask', mask_rows='...','000', dx=1, dy=1"), {}, "the patch is empty"),
    ("bad_character", kc.namelist("shape='mask', mask_rows='#x#', dx=1, dy=1"), {}, "character 'x'"),
    ("inline_dx", kc.namelist("shape='mask', mask_rows='##'"), {}, "dx = 0"),
    ("inline_dy_negative", kc.namelist("shape='mask', mask_rows='##', dx=1, dy=-1"), {}, "dy = -1"),
    ("mask_both", kc.namelist("shape='mask', mask_rows='##', mask_file='m.mask', dx=1, dy=1"),
     {"m.mask": mask_ok}, "not both"),
    ("mask_none", kc.namelist("shape='mask'"), {}, "needs mask_file or mask_rows"),
    ("mask_file_missing", kc.namelist("shape='mask', mask_file='nowhere.mask'"), {}, "mask_file 'nowhere.mask': cannot open"),
    ("mask_header", kc.namelist("shape='mask', mask_file='h.mask'"), {"h.mask": "3 2 0.1\n###\n"}, "header"),
    ("mask_header_dx", kc.namelist("shape='mask', mask_file='d.mask'"), {"d.mask": "3 2 0 0.1 0 0\n###\n###\n"}, "dx, dy"),
    ("mask_file_rows", kc.namelist("shape='mask', mask_file='r.mask'"), {"r.mask": "3 3 0.1 0.1 0 0\n###\n###\n"},
     "only      2 mask rows"),
    ("mask_file_row_length", kc.namelist("shape='mask', mask_file='l.mask'"), {"l.mask": "3 2 0.1 0.1 0 0\n###\n####\n"},
     "mask row 2 has 4 cells"),
    ("mask_file_character", kc.namelist("shape='mask', mask_file='c.mask'"), {"c.mask": "3 2 0.1 0.1 0 0\n###\n#o#\n"},
     "character 'o'"),
    ("mask_file_mx", kc.namelist("shape='mask', mask_file='m.mask', mx=5"), {"m.mask": mask_ok}, "mx = 5 but mask_file"),
    ("table_folder", kc.namelist(good_patch, "", "", "table_file='no/such/folder/x.tab'"), {}, "table_file"),
    ("traction_folder", kc.namelist(good_patch, "", "", "traction_file='no/such/t.txt'"), {}, "traction_file"),
    ("method", kc.namelist(good_patch, "", "method='fast'"), {}, "method = 'fast'"),
    ("tolerance", kc.namelist(good_patch, "", "tolerance=0"), {}, "tolerance = 0"),
    ("max_iterations", kc.namelist(good_patch, "", "max_iterations=0"), {}, "max_iterations = 0"),
    ("cell_budget", kc.namelist("", "", "target_error=1e-3, scheme='backward', cell_budget=500"), {},
     "cell_budget = 500.000 (allowed"),
    ("cell_budget_given_grid", kc.namelist(good_patch, "", "cell_budget=5000"), {}, "this case has none"),
    ("restart", kc.namelist(good_patch, "", "restart=0"), {}, "restart = 0"),
    ("preconditioner", kc.namelist(good_patch, "", "preconditioner='ilu'"), {}, "preconditioner = 'ilu'"),
    ("preconditioner_dense", kc.namelist(good_patch, "", "method='dense', preconditioner='strip'"), {},
     "preconditioner = 'strip' is the iterative"),
    ("too_large", kc.namelist("semi_a=1, semi_b=1, mx=2000, my=2000", "", "method='dense'"), {}, "GiB"),
]
for name, text, files, fragment in cases:
    table = os.path.join(folder, name + ".tab")
    with open(table, "w") as f:
        f.write("keep me\n")
    code, out, err, _ = kc.run(text, folder, name, expect_ok=False, files=files)
    lines = err.strip().splitlines()
    kc.check(code != 0, f"{name}: exit status {code}")
    kc.check(len(lines) == 1 and lines[0].startswith("kcreep: error: "), f"{name}: one error line: {err.strip()!r}")
    kc.check(fragment in err, f"{name}: message names the problem ({fragment!r})")
    kc.check(open(table).read() == "keep me\n", f"{name}: existing table untouched")
    leftovers = [f for f in os.listdir(folder) if "kcreep-tmp" in f]
    kc.check(not leftovers, f"{name}: no temporary file left ({leftovers})")

# the input file itself missing or unreadable
proc = subprocess.run([kc.KCREEP, "does-not-exist.nml"], cwd=folder, capture_output=True, text=True)
kc.check(proc.returncode == 2 and "does-not-exist.nml" in proc.stderr and len(proc.stderr.strip().splitlines()) == 1,
         f"missing input file: {proc.stderr.strip()!r}")
proc = subprocess.run([kc.KCREEP], cwd=folder, capture_output=True, text=True)
kc.check(proc.returncode == 2 and "usage" in proc.stderr, "no argument: usage line")
kc.finish()
