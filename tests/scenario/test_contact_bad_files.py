"""The CONTACT reader on broken files made here from the real samples
(truncated, corrupted numbers, wrong case number, missing or mismatched
element file): one clear error line, exit status 2, nothing written (an
existing table stays as it was, no new file appears).
usage: test_contact_bad_files.py KCREEP SAMPLES_DIR"""
import os
import shutil
import subprocess
import sys
import kctest as kc

root = kc.setup()
samples = os.path.abspath(sys.argv[2])
if not os.path.isdir(samples):
    sys.exit(f"FAIL: the CONTACT samples folder {samples} is missing (CI clones shared/ beside the repository)")


def sample(name):
    with open(os.path.join(samples, name)) as f:
        return f.read()


def lines_cut(text, n):
    return "".join(text.splitlines(keepends=True)[:n])


circle, kidney = sample("circle_r5_nu25.out"), sample("kidney_nu25.out")
kmat = sample("kidney_nu25.0001.mat")
kmat_lines = kmat.splitlines(keepends=True)
first_element = next(i for i, l in enumerate(kmat_lines) if "IGS" in l) + 1
cmat = {k: sample(f"circle_r5_nu25.000{k}.mat") for k in (1, 2, 3)}
emat = sample("ellipse_a6_b4_nu28.0001.mat")


def corrupt_element(i, text):
    lines = kmat_lines[:]
    lines[first_element + i] = text + "\n"
    return "".join(lines)


def nml(case=1, extra=""):
    return f"&patch shape='contact', contact_file='c.out', contact_case={case} /\n{extra}"


circle_mats = {"c.0001.mat": cmat[1], "c.0002.mat": cmat[2], "c.0003.mat": cmat[3]}
cases = [
    # name, namelist, files, expected fragment of the message
    ("truncated_out", nml(1), {"c.out": lines_cut(circle, 40), **circle_mats}, "block missing or cut short"),
    ("truncated_stats", nml(1), {"c.out": lines_cut(circle, 63), **circle_mats}, "CONTACT STATISTICS"),
    ("truncated_case3", nml(3), {"c.out": lines_cut(circle, 230), **circle_mats}, "case 3"),
    ("corrupt_force", nml(1), {"c.out": circle.replace("-8418.", "-84x8."), **circle_mats}, "'-84x8.'"),
    ("corrupt_creepage", nml(1), {"c.out": circle.replace("1.000E-03", "1.0#0E-03", 1), **circle_mats},
     "'1.0#0E-03'"),
    ("corrupt_ncon", nml(1), {"c.out": circle.replace("1089    697    697", "1089    69?    697", 1), **circle_mats},
     "'69?'"),
    ("wrong_case", nml(4), {"c.out": circle, **circle_mats}, "no case 4 (the file has 3 case(s))"),
    ("case_zero", nml(0), {"c.out": circle, **circle_mats}, "contact_case = 0"),
    ("missing_mat_nonhertzian", nml(1), {"c.out": kidney}, "does not exist"),
    ("missing_map_rows", nml(3), {"c.out": lines_cut(circle, 270)}, "incomplete"),
    ("truncated_mat", nml(1), {"c.out": kidney, "c.0001.mat": "".join(kmat_lines[:first_element + 300])}, "NCON = 708"),
    ("truncated_mat_header", nml(1), {"c.out": kidney, "c.0001.mat": "".join(kmat_lines[:7])}, "MX MY XL YL DX DY"),
    ("corrupt_mat_igs", nml(1), {"c.out": kidney, "c.0001.mat": corrupt_element(5, "  300   x  0.1")}, "I, IGS"),
    ("mat_igs_range", nml(1), {"c.out": kidney, "c.0001.mat": corrupt_element(5, "  300   7  0.1")}, "IGS = 7"),
    ("mat_element_range", nml(1), {"c.out": kidney, "c.0001.mat": corrupt_element(5, " 99999   1  0.1")},
     "I = 99999"),
    ("mat_of_other_run", nml(1), {"c.out": circle, "c.0001.mat": emat}, "element file of another run"),
    ("not_contact_output", nml(1), {"c.out": sample("circle_r5_nu25.inp")}, "no \"Case\" header"),
    ("no_file", "&patch shape='contact', contact_file='nothere.out' /\n", {}, "cannot open"),
    ("no_file_name", "&patch shape='contact' /\n", {}, "needs contact_file"),
    ("material_given", nml(1, "&material g = 1 /\n"), {"c.out": circle, **circle_mats}, "not allowed"),
    ("mask_given", "&patch shape='contact', contact_file='c.out', mx=5 /\n", {"c.out": circle, **circle_mats},
     "takes its grid and mask from contact_file"),
]
for name, text, files, fragment in cases:
    folder = os.path.join(root, name)
    os.mkdir(folder)
    with open(os.path.join(folder, "case.tab"), "w") as f:
        f.write("previous table\n")
    before = set(os.listdir(folder)) | set(files) | {"case.nml"}
    code, out, err, _ = kc.run(text, folder, "case", expect_ok=False, files=files)
    lines = err.strip().splitlines()
    kc.check(code == 2, f"{name}: exit status {code} (want 2)")
    kc.check(len(lines) == 1 and lines[0].startswith("kcreep: error: ") and fragment in lines[0],
             f"{name}: one error line containing {fragment!r}: {err.strip()!r}")
    with open(os.path.join(folder, "case.tab")) as f:
        kc.check(f.read() == "previous table\n", f"{name}: the existing table is untouched")
    kc.check(set(os.listdir(folder)) == before, f"{name}: no file written ({sorted(set(os.listdir(folder)) - before)})")

# the good path for contrast: the same folder layout works
folder = os.path.join(root, "good")
os.mkdir(folder)
code, out, err, table = kc.run(nml(1), folder, "case", files={"c.out": circle, **circle_mats})
kc.check(code == 0 and table is not None and "agrees with CONTACT" in out, "good copy of circle_r5_nu25 case 1 runs")
# Hertzian .out without element file: the printed map covers the whole grid and is used
folder = os.path.join(root, "map_only")
os.mkdir(folder)
code, out, err, table = kc.run(nml(2), folder, "case", files={"c.out": circle})
kc.check(code == 0 and "mask from the out map" in out and "agrees with CONTACT" in out,
         "Hertzian .out without .mat: mask from the printed map, still agrees")

# Memory in proportion to the file, not to its lines times a fixed width: the
# reader kept every line padded to 8192 characters, so a .mat of 17,424
# elements (132 x 132) took 143 MB and reading cost more than the solve
# (issue 45). The circle's .mat with 20,000 blank lines after its elements
# (valid: blank lines are skipped): peak RSS measured 16 MB now, 179 MB with
# the padded lines; 60 MB leaves room for another libc or libgfortran.
folder = os.path.join(root, "blank_lines")
os.mkdir(folder)
for name, content in {"c.out": circle, "c.0001.mat": cmat[1] + "\n" * 20000}.items():
    with open(os.path.join(folder, name), "w") as f:
        f.write(content)
with open(os.path.join(folder, "case.nml"), "w") as f:
    f.write(nml(1))
proc = subprocess.Popen([kc.KCREEP, "case.nml"], cwd=folder, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                        text=True)
out, err = proc.stdout.read(), proc.stderr.read()
_, code, usage = os.wait4(proc.pid, 0)
proc.returncode = os.waitstatus_to_exitcode(code)
peak_mb = usage.ru_maxrss / 1024
kc.check(proc.returncode == 0 and "agrees with CONTACT" in out, f"blank_lines: the padded .mat still reads and "
         f"agrees ({err.strip()[:200]})")
kc.check(peak_mb < 60, f"blank_lines: peak memory {peak_mb:.0f} MB < 60 MB for a 1 MB element file")
kc.finish()
