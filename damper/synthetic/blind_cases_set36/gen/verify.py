#!/usr/bin/env python3
"""blind36 self-check.  Python 3 standard library only (plus the black-box binary, run ONLY as
`hybridsim damper predict --no-fit`).  Last line: VERIFY PASS or VERIFY FAIL.

Checks
  1. key.json: 30 trials, 6 'none', 24 effects = 3 per category with 3 different shapes,
     12 strong (ratio in [8.5, 11.5]) + 12 weak ([2.7, 3.8]), noise SD in [0.02, 0.06] kip,
     strength parameter within [0, bound], ratio == target.
  2. layout of every record equals the measured semi-active files (same header keys in the same
     order and values, 8 numeric columns, time = i/1024, 9-25 s, |disp| <= 1.3 in, realistic speed,
     rests present, actuator positions near x', force / load-cell values on the measured grids,
     velocity column ~ d(disp)/dt / 125.4); actuator motion present in some but not all records.
  3. the black box (`damper predict --no-fit`) on every record reproduces our base-model replica.
  4. 'none' records: recorded force == quantise(black box + the stored noise) sample by sample
     (sample 0 = the held force the black box starts from), residual SD == noise SD.
  5. effect records: recorded force == quantise(truth(key params) + noise), the effect present in
     both records (RMS >= 1 noise SD in each); the strength ratio
     RMS over both records of (F_true - F_blackbox) / SD recomputed with the black box equals the
     key's ratio and lies in its band.
"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import model as M  # noqa: E402
import gen as G    # noqa: E402

ROOT = os.path.dirname(HERE)
BIN = '/work/runs/binhead/hybridsim'
CONFIG = '/work/main/configs/brfd-semiactive.yaml'
TEMPLATE = os.path.join(G.SRC_DIR, 'harmonic0.015forward.json')

fails = []
warns = []


def check(cond, msg):
    if not cond:
        fails.append(msg)
    return cond


def on_grid(vals, q, off=0.0, tol=2e-3):
    worst = 0.0
    for v in vals:
        r = (v - off) / q
        worst = max(worst, abs(r - round(r)))
    return worst <= tol, worst


def run_blackbox(path, outdir):
    r = subprocess.run([BIN, 'damper', 'predict', '--config', CONFIG, '--no-fit', '--test', path,
                        '--out', outdir, '--no-figure'], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError('black box failed on %s: %s' % (path, r.stderr[-500:]))
    stem = os.path.splitext(os.path.basename(path))[0]
    rows = list(csv.DictReader(open(os.path.join(outdir, stem + '_predict.csv'))))
    return [float(r['predicted_force_kip']) for r in rows]


def main():
    t0 = time.time()
    key = json.load(open(os.path.join(ROOT, 'key.json')))
    tmpl = json.load(open(TEMPLATE))
    tkeys = list(tmpl.keys())

    # ---------------- 1. key ----------------
    ids = ['t%02d' % i for i in range(1, 31)]
    check(sorted(key) == ids, 'key ids are not t01..t30')
    cats = {}
    nstrong = nweak = nnone = 0
    for tid in ids:
        e = key[tid]
        c = e['category']
        if c == 'none':
            nnone += 1
            check(e['ratio'] == 0.0, '%s none with nonzero ratio' % tid)
        else:
            check(c in M.SHAPES and e['shape'] in M.SHAPES[c], '%s unknown category/shape' % tid)
            cats.setdefault(c, []).append(e['shape'])
            if e['strength'] == 'strong':
                nstrong += 1
                check(8.5 <= e['ratio'] <= 11.5, '%s strong ratio %.3f out of band' % (tid, e['ratio']))
            else:
                nweak += 1
                check(e['strength'] == 'weak', '%s bad strength label' % tid)
                check(2.7 <= e['ratio'] <= 3.8, '%s weak ratio %.3f out of band' % (tid, e['ratio']))
            check(abs(e['ratio'] - e['target_ratio']) <= 0.01, '%s ratio misses target' % tid)
            pn = e['params']['_strength_param']
            pv = e['params'][pn]
            check(0.0 < pv <= e['params']['_strength_param_max'] + 1e-12,
                  '%s strength parameter %s=%g outside (0, %g]' % (tid, pn, pv, e['params']['_strength_param_max']))
        check(0.02 <= e['noise_kip'] <= 0.06, '%s noise SD out of range' % tid)
    check(nnone == 6, 'expected 6 none trials, got %d' % nnone)
    check(nstrong == 12 and nweak == 12, 'expected 12 strong + 12 weak, got %d + %d' % (nstrong, nweak))
    check(sorted(cats) == sorted(M.SHAPES), 'categories missing: %s' % sorted(set(M.SHAPES) - set(cats)))
    for c, shs in cats.items():
        check(len(shs) == 3 and len(set(shs)) == 3, 'category %s does not have 3 different shapes' % c)
    print('key: %d none, %d strong, %d weak, categories %s' % (nnone, nstrong, nweak,
                                                              {c: len(s) for c, s in sorted(cats.items())}))

    # ---------------- 2-5. records ----------------
    tmpdir = tempfile.mkdtemp(prefix='blind36_verify_')
    n_act = 0
    n_rec = 0
    worst_bb = 0.0
    summary = []
    for tid in ids:
        e = key[tid]
        c, sh = e['category'], e['shape']
        sd = e['noise_kip']
        fx = {k: v for k, v in e['params'].items() if not k.startswith('_')}
        p = 0.0
        if c != 'none':
            p = fx.pop(e['params']['_strength_param'])
        ss_bb = 0.0
        ss_sim = 0.0
        nn = 0
        resid_none = []
        for name in ('A', 'B'):
            path = os.path.join(ROOT, 'cases', tid, name + '.json')
            obj = json.load(open(path))
            n_rec += 1
            where = '%s/%s' % (tid, name)
            # ---- layout ----
            check(list(obj.keys()) == tkeys, '%s header keys/order differ from the measured files' % where)
            for k in tkeys:
                if k != 'data':
                    check(obj[k] == tmpl[k] and type(obj[k]) is type(tmpl[k]), '%s header %s differs' % (where, k))
            d = obj['data']
            n = len(d)
            check(all(len(r) == 8 for r in d), '%s rows are not 8 columns' % where)
            check(all(all(isinstance(q, (int, float)) and math.isfinite(q) for q in r) for r in d),
                  '%s non-numeric / non-finite values' % where)
            check(d[0][0] == 0 and all(d[i][0] == i * M.DT for i in range(n)), '%s time column not i/1024' % where)
            dur = (n - 1) * M.DT
            check(9.0 <= dur <= 25.0, '%s duration %.2f s' % (where, dur))
            rinfo = e['records'][name]
            check(rinfo['n_samples'] == n, '%s sample count differs from key' % where)
            x = [r[1] for r in d]
            F = [r[2] for r in d]
            vcol = [r[3] for r in d]
            a1 = [r[4] for r in d]
            a2 = [r[5] for r in d]
            f1 = [r[6] for r in d]
            f2 = [r[7] for r in d]
            check(max(abs(q) for q in x) <= 1.3, '%s drum travel beyond 1.3 in' % where)
            v = M.derive_velocity(x)
            vmax = max(abs(q) for q in v)
            check(0.4 <= vmax <= 3.8, '%s peak drum speed %.2f in/s unrealistic' % (where, vmax))
            # rests: runs of |v| < 0.06 in/s longer than 0.3 s
            runs = []
            k = 0
            while k < n:
                if abs(v[k]) < M.REST_V:
                    j = k
                    while j < n and abs(v[j]) < M.REST_V:
                        j += 1
                    if j - k > 0.3 * M.FS:
                        runs.append((j - k) / M.FS)
                    k = j
                else:
                    k += 1
            check(len(runs) >= 2, '%s fewer than two rests' % where)
            # strokes: reversals count
            tr = M.Rec(x, a1, a2, F[0])
            check(max(abs(q - a1[0]) for q in a1) <= 0.05 and max(abs(q - a2[0]) for q in a2) <= 0.05,
                  '%s actuator excursion beyond 0.05 in' % where)
            check(0.3 <= min(a1 + a2) and max(a1 + a2) <= 1.2, '%s actuator outside its range' % where)
            moved = max(abs(q - a1[0]) for q in a1) > 0.002 or max(abs(q - a2[0]) for q in a2) > 0.002
            n_act += moved
            if c in ('actuator_lag', 'pretension'):
                check(moved, '%s: %s trial without actuator motion' % (where, c))
            ok, w = on_grid(F, G.Q_F)
            check(ok, '%s force not on the measured grid (worst %.3g steps)' % (where, w))
            ok, w = on_grid(f1, G.Q_F1, G.OFF_F1)
            check(ok, '%s actuator-1 force not on grid (%.3g)' % (where, w))
            ok, w = on_grid(f2, G.Q_F2, G.OFF_F2)
            check(ok, '%s actuator-2 force not on grid (%.3g)' % (where, w))
            check(min(f1) > 0 and min(f2) > 0 and max(f1 + f2) < 5000, '%s actuator forces implausible' % where)
            sxy = sum(p_ * q for p_, q in zip(v, vcol))
            sxx = sum(p_ * p_ for p_ in v)
            k_ = sxx / sxy if sxy else 0
            check(115 < k_ < 135, '%s velocity column is not ~v/125.4 (got 1/%.1f)' % (where, k_))
            # ---- black box ----
            Fbb = run_blackbox(path, tmpdir)
            check(len(Fbb) == n, '%s black box returned %d rows' % (where, len(Fbb)))
            Fmine = tr.base()
            dmax = max(abs(p_ - q) for p_, q in zip(Fmine, Fbb))
            worst_bb = max(worst_bb, dmax)
            check(dmax < 2e-6, '%s black box differs from the replica by %.3g kip' % (where, dmax))
            check(abs(Fbb[0] - (F[0] + M.SIG2 * v[0])) < 2e-6, '%s black box does not start from sample 0' % where)
            # ---- noise ----
            nz = G.noise_seq(rinfo['noise_seed'], n, sd)
            if c == 'none':
                worst = max(abs(F[i] - (Fbb[i] + nz[i])) for i in range(1, n))
                exact = sum(1 for i in range(1, n) if F[i] == G.quantise_force([Fbb[i] + nz[i]])[0])
                check(worst <= G.Q_F / 2 + 2e-6, '%s none record != black box + noise (worst %.3g)' % (where, worst))
                check(exact >= 0.999 * (n - 1), '%s none record: only %d/%d samples exact' % (where, exact, n - 1))
                resid_none.extend(F[i] - Fbb[i] for i in range(1, n))
            # truth from the key parameters (independent re-simulation from the recorded columns)
            Ft = M.simulate(c, sh, p, tr, fx)
            Fq = G.quantise_force([a + b for a, b in zip(Ft, nz)])
            worst = max(abs(Fq[i] - F[i]) for i in range(1, n))
            check(worst < 1e-6, '%s record != quantise(truth(key) + noise) (worst %.3g)' % (where, worst))
            ss_rec = sum((Ft[i] - Fbb[i]) ** 2 for i in range(n))
            if c != 'none':
                check(math.sqrt(ss_rec / n) / sd >= 1.0,
                      '%s: the hidden effect is hardly present in this record (%.2f SD)' % (where, math.sqrt(ss_rec / n) / sd))
            ss_sim += ss_rec
            ss_bb += sum((F[i] - nz[i] - Fbb[i]) ** 2 for i in range(1, n))
            nn += n
        if c == 'none':
            m = sum(resid_none) / len(resid_none)
            s = math.sqrt(sum((q - m) ** 2 for q in resid_none) / len(resid_none))
            s_exp = math.sqrt(sd * sd + G.Q_F ** 2 / 12)
            check(abs(s / s_exp - 1) < 0.03, '%s none residual SD %.4f vs %.4f' % (tid, s, s_exp))
            check(abs(m) < 5 * sd / math.sqrt(len(resid_none)), '%s none residual mean %.4g' % (tid, m))
            summary.append('%s none             resid SD %.4f (noise %.4f)' % (tid, s, sd))
        else:
            r_sim = math.sqrt(ss_sim / nn) / sd
            r_bb = math.sqrt(ss_bb / nn) / sd
            check(abs(r_sim - e['ratio']) < 2e-3, '%s ratio (replica truth vs black box) %.4f != key %.4f' % (tid, r_sim, e['ratio']))
            check(abs(r_bb - e['ratio']) < 0.01 * e['ratio'] + 0.01,
                  '%s ratio from record-noise vs black box %.4f != key %.4f' % (tid, r_bb, e['ratio']))
            band = (8.5, 11.5) if e['strength'] == 'strong' else (2.7, 3.8)
            check(band[0] <= r_bb <= band[1], '%s black-box ratio %.3f out of band' % (tid, r_bb))
            summary.append('%s %-16s %-30s %-6s ratio key %.3f  bb(truth) %.3f  bb(record-noise) %.3f' % (
                tid, c, sh, e['strength'], e['ratio'], r_sim, r_bb))
        print(summary[-1])
        sys.stdout.flush()
    check(0 < n_act < n_rec, 'actuator motion should be present in some, not all, records (%d/%d)' % (n_act, n_rec))
    print('records: %d, with actuator motion: %d; worst |black box - replica| = %.2g kip' % (n_rec, n_act, worst_bb))
    print('checked in %.1f s' % (time.time() - t0))
    for w in warns:
        print('WARN', w)
    for f in fails:
        print('FAIL', f)
    print('VERIFY PASS' if not fails else 'VERIFY FAIL')


if __name__ == '__main__':
    main()
