#!/usr/bin/env python3
"""FASTSIM against CONTACT with friction (partial slip), on CONTACT's own grid and pressure.

For every case of every CONTACT `.out` given (its `.NNNN.mat` element files beside it):
  - the patch and pressure: cells with IGS >= 1 and their PN, from the `.mat`;
  - CONTACT's forces: sums of PX, PY (and x PY - y PX, spin part at the cell centre)
    over the `.mat` (six digits instead of the `.out`'s four);
  - the creepages: from the `.inp` beside the `.out` when there is one (the exact inputs),
    else from the `.out` (four digits);
  - the exact coefficients: kcreep on the patch (shape = 'contact', CONTACT's scheme);
  - FASTSIM (kcreep_fastsim_curve) with the patch's own L1 L2 L3 ('exact') and with those of
    the two equivalent ellipses ('box', 'moments'), flexibility rules 'weighted', 'separate' and
    'aligned' (and the variants separate-l1, separate-m of the -phi y term).
Prints per case the force errors |F_fastsim - F_contact| / (mu Fn) in %, per patch the
largest error over the pure and the combined cases, and writes every number to a CSV
(--csv). Standard library only.

  scripts/compare_contact_slip.py [--kcreep build/kcreep] [--curve build/kcreep_fastsim_curve]
                                  [--csv out.csv] FILE.out ...
Exit status 0, or 2 when a file cannot be read.
"""
import argparse
import math
import os
import re
import subprocess
import sys
import tempfile

SOURCES = ('exact', 'box', 'moments')
RULES = ('weighted', 'separate', 'separate-l1', 'separate-m', 'aligned')


def fail(msg):
    print('compare_contact_slip: error: ' + msg, file=sys.stderr)
    sys.exit(2)


def read_mat(path):
    """Grid, mu and the element rows (I, IGS, MU, PN, PX, PY) of a CONTACT element file."""
    try:
        lines = open(path).read().splitlines()
    except OSError as e:
        fail(f'{path}: {e.strerror}')
    grid = None
    cols = None
    rows = []
    for k, line in enumerate(lines):
        if line.startswith('%'):
            words = line[1:].split()
            if words[:6] == ['MX', 'MY', 'XL', 'YL', 'DX', 'DY']:
                v = lines[k + 1].split()
                grid = dict(mx=int(v[0]), my=int(v[1]), xl=float(v[2]), yl=float(v[3]),
                            dx=float(v[4]), dy=float(v[5]))
            elif words[:2] == ['I', 'IGS']:
                cols = words
            continue
        if cols is not None and line.strip():
            v = line.split()
            if len(v) >= len(cols):
                rows.append({c: float(x) for c, x in zip(cols, v)})
    if grid is None or not rows:
        fail(f'{path}: no grid block (MX MY XL YL DX DY) or no element rows (I IGS ... PN PX PY)')
    return grid, rows


def out_cases(path):
    """[(case number, (cksi, ceta, cphi), fn, nslip)] from the `.out`."""
    try:
        text = open(path).read().splitlines()
    except OSError as e:
        fail(f'{path}: {e.strerror}')
    cases = []
    case = 0
    creep = None
    fn = None
    for k, line in enumerate(text):
        m = re.search(r'\bCASE\s+(\d+)', line)
        if m and 'CASE' in line.upper() and line.strip().upper().startswith('CASE'):
            case = int(m.group(1))
        if 'CKSI' in line and 'CETA' in line and 'CPHI' in line and 'CHI' in line:
            heads = line.split()
            vals = text[k + 1].split()
            d = dict(zip(heads, vals))
            creep = (float(d['CKSI']), float(d['CETA']), float(d['CPHI']))
        if line.split()[:2] == ['FN', 'FX']:
            fn = float(text[k + 1].split()[0])
        if 'NSLIP' in line and 'NCON' in line:
            heads = line.split()
            vals = text[k + 1].split()
            nslip = int(dict(zip(heads, vals))['NSLIP'])
            cases.append([case or len(cases) + 1, creep, fn, nslip])
    return cases


def inp_creepages(path):
    """The exact (cksi, ceta, cphi) of each case from a CONTACT input file, or None."""
    if not os.path.exists(path):
        return None
    out = []
    for line in open(path):
        if 'CKSI' in line and 'FN' in line:
            v = line.split()
            out.append((float(v[1]), float(v[2]), float(v[3])))
    return out or None


def kcreep_coefficients(kcreep, out_path, case, tmp):
    nml = os.path.join(tmp, 'patch.nml')
    tab = os.path.join(tmp, 'patch.tab')
    with open(nml, 'w') as f:
        f.write(f"&patch shape = 'contact', contact_file = '{os.path.abspath(out_path)}', contact_case = {case} /\n"
                f"&output table_file = '{tab}' /\n")
    r = subprocess.run([kcreep, nml], capture_output=True, text=True)
    if r.returncode != 0:
        fail(f'kcreep on {out_path} case {case}: {r.stderr.strip()}')
    lines = [l for l in open(tab) if l.strip()]
    head = [l for l in lines if l.startswith('#')][-1][1:].split()
    row = dict(zip(head, lines[-1].split()))
    return {k: float(row[k]) for k in ('f11', 'f22', 'f23', 'f33', 'nu', 'g', 'c11', 'c22', 'c23', 'L1', 'L2', 'L3')}


def dense_curves(a, patch, pfile, cfile, mu, coef, fn, rows):
    """FASTSIM on 40 log-spaced creepages over the range of each pure series of CONTACT's cases."""
    creeps = []
    for comp, fkey in ((0, 'f11'), (1, 'f22'), (2, 'f23')):
        vals = [(r['xi'], r['eta'], r['phi'])[comp] for r in rows if r['kind'] == 'pure'
                and (r['xi'], r['eta'], r['phi'])[comp] != 0]
        if not vals:
            continue
        lo, hi = min(vals) / 2, max(vals) * 2
        for k in range(40):
            c = [0.0, 0.0, 0.0]
            c[comp] = lo * (hi / lo) ** (k / 39)
            creeps.append((comp, c, c[comp] * coef[fkey] / (mu * fn)))
    with open(cfile, 'w') as f:
        for _, c, _ in creeps:
            f.write('%r %r %r\n' % tuple(c))
    r = subprocess.run([a.curve, pfile, cfile, repr(mu), repr(coef['nu']), repr(coef['g']),
                        repr(coef['f11']), repr(coef['f22']), repr(coef['f23']), repr(coef['f33'])],
                       capture_output=True, text=True)
    if r.returncode != 0:
        fail(f'kcreep_fastsim_curve (curves of {patch}): {r.stderr.strip()}')
    out = []
    lines = [l.split() for l in r.stdout.splitlines() if not l.startswith('#')]
    per = len(lines) // len(creeps)
    for k, (comp, c, norm) in enumerate(creeps):
        for v in lines[k * per:(k + 1) * per]:
            out.append((patch, 'xi eta phi'.split()[comp], c[comp], norm, v[0], v[1],
                        float(v[5]) / (mu * fn), float(v[6]) / (mu * fn)))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--kcreep', default=os.environ.get('KCREEP', 'build/kcreep'))
    ap.add_argument('--curve', default=os.environ.get('KCREEP_FASTSIM_CURVE', 'build/kcreep_fastsim_curve'))
    ap.add_argument('--csv', default='')
    ap.add_argument('--curves', default='', help='CSV of dense pure-creepage curves (for the figure)')
    ap.add_argument('--quiet', action='store_true', help='only the per-patch summary')
    ap.add_argument('outs', nargs='+')
    a = ap.parse_args()

    csv_rows = []
    curve_rows = []
    summary = []
    for out_path in a.outs:
        base = out_path[:-4] if out_path.endswith('.out') else out_path
        patch = os.path.basename(base)
        cases = out_cases(out_path)
        exact_creep = inp_creepages(base + '.inp')
        if exact_creep is not None and len(exact_creep) != len(cases):
            exact_creep = None
        cache = {}
        with tempfile.TemporaryDirectory() as tmp:
            for idx, (case, creep, fn_out, nslip) in enumerate(cases):
                if exact_creep is not None:
                    creep = exact_creep[idx]
                mat = f'{base}.{case:04d}.mat'
                grid, rows = read_mat(mat)
                dx, dy = grid['dx'], grid['dy']
                mx, my = grid['mx'], grid['my']
                x0, y0 = grid['xl'] + dx / 2, grid['yl'] + dy / 2
                pn = [[0.0] * mx for _ in range(my)]
                fx = fy = mz = fn = 0.0
                mu = None
                key = []
                for r in rows:
                    if r['IGS'] < 1:
                        continue
                    i = int(r['I']) - 1
                    ix, iy = i % mx, i // mx
                    x, y = x0 + ix * dx, y0 + iy * dy
                    pn[iy][ix] = r['PN']
                    key.append(i)
                    fx += r['PX']; fy += r['PY']; mz += x * r['PY'] - y * r['PX']; fn += r['PN']
                    mu = r['MU']
                da = dx * dy
                fx, fy, mz, fn = fx * da, fy * da, mz * da, fn * da
                key = tuple(key)
                if key not in cache:
                    cache[key] = kcreep_coefficients(a.kcreep, out_path, case, tmp)
                coef = cache[key]
                pfile = os.path.join(tmp, 'p.txt')
                with open(pfile, 'w') as f:
                    f.write(f'{mx} {my} {dx!r} {dy!r} {x0!r} {y0!r}\n')
                    for row in pn:
                        f.write(' '.join(repr(v) for v in row) + '\n')
                cfile = os.path.join(tmp, 'c.txt')
                with open(cfile, 'w') as f:
                    f.write('%r %r %r\n' % creep)
                r = subprocess.run([a.curve, pfile, cfile, repr(mu), repr(coef['nu']), repr(coef['g']),
                                    repr(coef['f11']), repr(coef['f22']), repr(coef['f23']), repr(coef['f33'])],
                                   capture_output=True, text=True)
                if r.returncode != 0:
                    fail(f'kcreep_fastsim_curve on {mat}: {r.stderr.strip()}')
                res = {}
                for line in r.stdout.splitlines():
                    if line.startswith('#'):
                        continue
                    v = line.split()
                    res[(v[0], v[1])] = [float(x) for x in v[5:10]]
                mufn = mu * fn
                kind = 'pure' if sum(1 for c in creep if c != 0) == 1 else 'combined'
                row = dict(patch=patch, case=case, kind=kind, xi=creep[0], eta=creep[1], phi=creep[2], mu=mu, fn=fn,
                           nslip=nslip, contact_fx=fx / mufn, contact_fy=fy / mufn, contact_mz=mz)
                for (src, rule), v in res.items():
                    row[f'{src}_{rule}_fx'] = v[0] / mufn
                    row[f'{src}_{rule}_fy'] = v[1] / mufn
                    row[f'{src}_{rule}_mz'] = v[2]
                    row[f'{src}_{rule}_adh'] = v[4]
                    row[f'{src}_{rule}_err'] = 100 * math.hypot(v[0] - fx, v[1] - fy) / mufn
                csv_rows.append(row)
                if not a.quiet:
                    errs = ' '.join(f"{row[f'{s}_{q}_err']:6.2f}" for s in SOURCES for q in RULES
                                    if f'{s}_{q}_err' in row)
                    print(f'{patch:22s} {case:3d} {kind:8s} xi {creep[0]: .3e} eta {creep[1]: .3e} phi {creep[2]: .3e} '
                          f'CONTACT F/(mu Fn) ({fx / mufn: .4f},{fy / mufn: .4f})  err % [exact w s s1 sm a, box w s s1 a, moments w s s1 a] {errs}')
            if a.curves:
                curve_rows.extend(dense_curves(a, patch, pfile, cfile, mu, coef, fn,
                                               [r for r in csv_rows if r['patch'] == patch]))
        mine = [r for r in csv_rows if r['patch'] == patch]
        for src in SOURCES:
            for rule in RULES:
                for kind in ('pure', 'combined'):
                    errs = [r[f'{src}_{rule}_err'] for r in mine if r['kind'] == kind and f'{src}_{rule}_err' in r]
                    if errs:
                        summary.append((patch, src, rule, kind, max(errs), sum(errs) / len(errs), len(errs)))

    print('# largest (mean) |F_fastsim - F_contact| / (mu Fn) in %, per patch, flexibility source and rule')
    print('# patch source rule kind max mean cases')
    for s in summary:
        print(f'{s[0]:22s} {s[1]:8s} {s[2]:9s} {s[3]:9s} {s[4]:7.2f} {s[5]:7.2f} {s[6]:3d}')
    if a.curves and curve_rows:
        with open(a.curves, 'w') as f:
            f.write('patch,component,creepage,normalised,source,rule,fx_mufn,fy_mufn\n')
            for r in curve_rows:
                f.write(','.join(str(v) for v in r) + '\n')
    if a.csv:
        keys = list(csv_rows[0].keys())
        with open(a.csv, 'w') as f:
            f.write(','.join(keys) + '\n')
            for r in csv_rows:
                f.write(','.join(str(r.get(k, '')) for k in keys) + '\n')


if __name__ == '__main__':
    main()
