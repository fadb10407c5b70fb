"""FASTSIM's flexibility rules against the exact rolling solver, on a small subset of the study
scripts/fastsim_vs_exact.py (docs/fastsim.md, "Against the exact solver"): three of its 110 generated patches, made
by the same generator with the same seed (ellipse00: a/b = 0.2, Hertz; two_lobed0: make_shapes'
two_lobed stretched, parabolic strip pressure; paraboloid0: a gap of curvature ratio 0.2 through
the normal problem), at 12 of its 77 creepages (the same definition: level s of the linear theory,
|(f11 xi, f22 eta, f22 c phi)| / (mu Fn)): the combined directions (1,1,0), (0,1,-1), (1,0,1),
(1,1,1), (-1,2,-1) at s = 1.2 and 4, pure xi and pure spin at s = 1.2.
Error of a point |F - F_exact| / (mu Fn), F = (Fx, Fy); per patch its largest over the 12 points.
Measured by the study (% of mu Fn, aligned / separate / weighted, exact L):
  ellipse00 4.92 / 17.12 / 17.20, two_lobed0 4.03 / 14.91 / 22.02, paraboloid0 4.53 / 12.43 / 18.85.
Checks (limits: the measured numbers with a margin of 0.5 % of mu Fn for the aligned rule's error
and 1 % for its advantage):
  - the aligned rule (the default) on every patch: largest error below measured + 0.5;
  - its advantage: separate's and weighted's largest error exceed aligned's by the measured
    difference less 1 (at least 6.9 % of mu Fn on each patch);
  - on the pure points the three rules give the same forces (1e-12 mu Fn);
  - the summary of the run with both groups (rule 'aligned') prints FASTSIM's largest distance from
    the exact forces per flexibility source, the number the study computes from the tables (to its
    3 printed decimals): how far FASTSIM is from exact on the user's own patch.
About 10 s on one core.
usage: test_fastsim_exact.py KCREEP SOURCE_DIR"""
import importlib.util
import os
import random
import re
import sys
import types

import kctest as kc

folder = kc.setup()
root = os.path.abspath(sys.argv[2])
sys.path.insert(0, os.path.join(root, 'python'))
spec = importlib.util.spec_from_file_location('fastsim_vs_exact', os.path.join(root, 'scripts', 'fastsim_vs_exact.py'))
study = importlib.util.module_from_spec(spec)
spec.loader.exec_module(study)

MEASURED = {'ellipse00': (4.92, 17.12, 17.20), 'two_lobed0': (4.03, 14.91, 22.02), 'paraboloid0': (4.53, 12.43, 18.85)}
d = {v: k for k, v in enumerate(study.DIRECTIONS)}
SUBSET = {(d[(1, 0, 0)], 1.2), (d[(0, 0, 1)], 1.2)} | {(d[c], s) for c in [(1, 1, 0), (0, 1, -1), (1, 0, 1),
                                                                         (1, 1, 1), (-1, 2, -1)] for s in (1.2, 4.0)}
args = types.SimpleNamespace(kcreep=kc.KCREEP, lock='none', reuse=False)
patches = {p[1]: p for p in study.generate_patches(random.Random(30))}
for name, (m_al, m_sep, m_wt) in MEASURED.items():
    res = study.run_patch(args, folder, patches[name], SUBSET)
    kc.check(len(res['points']) == 12, f'{name}: {len(res["points"])} creepages')
    err = study.point_errors(res)
    worst = {rule: 100 * max(err[(rule, 'exact')]) for rule in study.RULES}
    print(f'{name}: largest error, exact L: ' + ', '.join(f'{r} {w:.2f} %' for r, w in worst.items()))
    kc.check(worst['aligned'] < m_al + 0.5, f'{name}: aligned {worst["aligned"]:.2f} % < {m_al + 0.5:.2f} % of mu Fn')
    for rule, m in (('separate', m_sep), ('weighted', m_wt)):
        kc.check(worst[rule] - worst['aligned'] > m - m_al - 1,
                 f'{name}: {rule} {worst[rule]:.2f} % exceeds aligned by more than {m - m_al - 1:.2f} %')
    pure = [q for q, p in enumerate(res['points']) if sum(1 for v in study.DIRECTIONS[p[1]] if v) == 1]
    same = max(abs(res['fast'][(r, 'exact', q)][k] - res['fast'][('aligned', 'exact', q)][k]) / (study.MU * row[6])
               for q in pure for r in study.RULES for k in (0, 1) for row in [res['roll'][q]])
    kc.check(len(pure) == 2 and same < 1e-12, f'{name}: pure creepages, the three rules alike ({same:.1e} mu Fn)')
    # the summary (the run with &rolling carries rule RULES[0], aligned) against the study's own numbers
    rule = study.RULES[0]
    for line in res['summary']:
        m = re.search(r'FASTSIM \((\w+), L of ([\w-]+)\) against exact: largest \|F - F_exact\| =\s+([0-9.]+) %', line)
        kc.check(m is not None and m.group(1) == rule, f'{name}: summary line {line!r}')
        if m:
            mine = 100 * max(err[(rule, m.group(2))])
            kc.check(abs(float(m.group(3)) - mine) <= 6e-4, f'{name}: summary, L of {m.group(2)}: {m.group(3)} % '
                     f'= {mine:.4f} % from the tables')
    kc.check(len(res['summary']) == 3, f'{name}: summary lines for the three sources')
    # the fast force model's line beside them (patches up to 4000 cells): within the issue's
    # 2 % of mu Fn (measured 0.06-0.25 % on these three patches)
    m = re.search(r'fast model against exact: largest \|F - F_exact\| =\s+([0-9.]+) %', ' '.join(res['fast_model']))
    kc.check(m is not None and float(m.group(1)) < 2, f'{name}: fast model against exact {res["fast_model"]}')
kc.finish()
