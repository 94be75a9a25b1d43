#!/usr/bin/env python3
"""Checks of blind test set 21.  Last line: VERIFY PASS or VERIFY FAIL.

  python3 verify.py [--skip-determinism] [--skip-blackbox]

1. layout of the 60 records against the measured semi-active files (keys, columns, dt,
   time column, quantisation, velocity quirk, durations, final rest, early actuation share);
2. key.json: 30 trials, 6 none, 8 categories x 3 distinct shapes, 12 weak / 12 strong;
3. truth recomputed from the files + key: noise SD (force - truth) and the ratio
   RMS(F_true - F_base)/SD over both records, against key and target ranges;
4. the reproduced base model against the black box
   `hybridsim damper predict --no-fit` on all 60 records (max |diff| < 1e-6 kip);
5. determinism: gen.py rerun into a temporary folder, all files byte-identical.
"""
import hashlib
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import gen  # noqa: E402

BLACKBOX = '/work/runs/binhead/hybridsim'
CONFIG = '/work/runs/brfd-semiactive.yaml'

fails = []
notes = []


def check(cond, msg):
    if not cond:
        fails.append(msg)
    return cond


def sha(path):
    h = hashlib.sha256()
    with open(path, 'rb') as fh:
        h.update(fh.read())
    return h.hexdigest()


def on_grid(v, q, off, tol):
    k = (v - off) / q
    return abs(k - round(k)) * q <= tol


def main():
    args = sys.argv[1:]
    with open(os.path.join(ROOT, 'key.json')) as fh:
        key = json.load(fh)
    # ---------------- key structure ----------------
    tids = ['t%02d' % i for i in range(1, 31)]
    check(sorted(key) == tids, 'key trials are not t01..t30')
    cats = {}
    nstrong = nweak = nnone = 0
    for t in tids:
        v = key[t]
        for f in ('category', 'shape', 'strength', 'p', 'p_meaning', 'noise_kip', 'ratio', 'target_ratio',
                  'params', 'records'):
            check(f in v, '%s: key lacks %s' % (t, f))
        if v['category'] == 'none':
            nnone += 1
            check(v['strength'] == 'none', '%s none with strength' % t)
            continue
        cats.setdefault(v['category'], []).append(v['shape'])
        nstrong += v['strength'] == 'strong'
        nweak += v['strength'] == 'weak'
        check(v['shape'] in gen.SHAPES.get(v['category'], {}), '%s unknown shape' % t)
    check(nnone == 6, 'none trials: %d' % nnone)
    check(len(cats) == 8 and all(len(s) == 3 and len(set(s)) == 3 for s in cats.values()),
          'categories x shapes not 8 x 3 distinct: %s' % cats)
    check(nstrong == 12 and nweak == 12, 'strong %d weak %d' % (nstrong, nweak))
    notes.append('key: 30 trials, %d none, %d categories x 3 shapes, %d strong / %d weak'
                 % (nnone, len(cats), nstrong, nweak))

    # reference layout from a measured file
    with open(os.path.join(gen.SRC_DIR, gen.SRC_FILES[0])) as fh:
        ref = json.load(fh)
    ref_keys = list(ref.keys())
    ref_hdr = {k: ref[k] for k in ref_keys if k != 'data'}

    early = 0
    nrec = 0
    max_bb = 0.0
    bb_done = 0
    tmpd = tempfile.mkdtemp(prefix='v21bb_')
    for t in tids:
        v = key[t]
        cat, shape = v['category'], v['shape']
        sd = v['noise_kip']
        check(0.02 <= sd <= 0.06, '%s noise sd %.4f out of range' % (t, sd))
        num = 0.0
        ntot = 0
        res_all = []
        for name in ('A', 'B'):
            path = os.path.join(ROOT, 'cases', t, name + '.json')
            if not check(os.path.exists(path), '%s missing' % path):
                continue
            nrec += 1
            with open(path) as fh:
                txt = fh.read()
            d = json.loads(txt)
            check(list(d.keys()) == ref_keys, '%s %s: keys %s' % (t, name, list(d.keys())))
            for k in ref_hdr:
                check(d.get(k) == ref_hdr[k], '%s %s: header %s' % (t, name, k))
            check(txt.startswith('{"data": [[0, '), '%s %s: data does not start like the measured files' % (t, name))
            rows = d['data']
            n = len(rows)
            dur = (n - 1) * gen.DT
            check(6.5 <= dur <= 25.0 + 1e-9, '%s %s: duration %.3f' % (t, name, dur))
            bad = 0
            for i, r in enumerate(rows):
                if len(r) != 8 or any((not isinstance(a, (int, float))) or a != a or abs(a) == float('inf') for a in r):
                    bad += 1
                    continue
                if r[0] != i * gen.DT:
                    bad += 1
                if not on_grid(r[2], gen.Q_F, 0.0, 1e-6 * max(1.0, abs(r[2]))):
                    bad += 1
                if not on_grid(r[1], gen.Q_X, gen.OFF_X, 2e-7):
                    bad += 1
                if gen.f32(r[4]) != r[4] or gen.f32(r[5]) != r[5] or gen.f32(r[3]) != r[3]:
                    bad += 1
            check(bad == 0, '%s %s: %d malformed / off-grid rows' % (t, name, bad))
            rec, F, _ = gen.rec_from_file(path)
            # velocity column quirk (~1/125 of dx/dt)
            sv = sum(abs(a) for a in rec.V)
            sc = sum(abs(r[3]) for r in rows)
            check(100 < sv / max(sc, 1e-12) < 150, '%s %s: velocity column factor %.1f' % (t, name, sv / max(sc, 1e-12)))
            # final rest: >= 1.5 s, drum still
            m = int(1.5 * gen.FS_HZ)
            tail = rec.x[-m:]
            check(max(tail) - min(tail) <= 4 * gen.Q_X + 1e-9, '%s %s: drum moves in the last 1.5 s' % (t, name))
            check(max(abs(a) for a in rec.V[-m:]) < 0.1, '%s %s: velocity in final rest' % (t, name))
            fm = next((i for i in range(rec.n) if abs(rec.u1[i]) > 0.002 or abs(rec.u2[i]) > 0.002), None)
            if fm is not None and fm * gen.DT < 1.0:
                early += 1
            # truth, base, noise
            fb = gen.base_force(rec)
            if cat != 'none':
                prm = dict(v['params'])
                ft = gen.truth_force(cat, shape, v['p'], rec, prm)
            else:
                ft = fb
            num += sum((a - b) ** 2 for a, b in zip(ft, fb))
            ntot += rec.n
            res = [F[i] - ft[i] for i in range(1, rec.n)]
            res_all.extend(res)
            # black box
            if '--skip-blackbox' not in args:
                od = os.path.join(tmpd, t + name)
                os.makedirs(od, exist_ok=True)
                cp = subprocess.run(['nice', '-n', '10', BLACKBOX, 'damper', 'predict', '--no-fit', '--config', CONFIG,
                                     '--test', path, '--out', od, '--no-figure'],
                                    stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
                if not check(cp.returncode == 0, '%s %s: black box failed: %s' % (t, name, cp.stdout[-300:])):
                    continue
                csvp = os.path.join(od, name + '_predict.csv')
                with open(csvp) as fh:
                    hdr = fh.readline().strip().split(',')
                    ip = hdr.index('predicted_force_kip')
                    pred = [float(line.split(',')[ip]) for line in fh if line.strip()]
                check(len(pred) == rec.n, '%s %s: black box length %d vs %d' % (t, name, len(pred), rec.n))
                dmax = max(abs(a - b) for a, b in zip(pred, fb))
                max_bb = max(max_bb, dmax)
                check(dmax < 1e-6, '%s %s: base vs black box max |diff| %.3g kip' % (t, name, dmax))
                check('quirk' in cp.stdout, '%s %s: black box did not treat the velocity column as the quirk' % (t, name))
                bb_done += 1
        if ntot == 0:
            continue
        ratio = math.sqrt(num / ntot) / sd
        mu = sum(res_all) / len(res_all)
        s = math.sqrt(sum((a - mu) ** 2 for a in res_all) / (len(res_all) - 1))
        k4 = sum((a - mu) ** 4 for a in res_all) / len(res_all) / s ** 4
        check(abs(s / sd - 1) < 0.03, '%s: residual SD %.5f vs noise %.5f' % (t, s, sd))
        check(abs(mu) < 4 * sd / math.sqrt(len(res_all)) + 1e-4, '%s: residual mean %.5f' % (t, mu))
        check(abs(k4 - 3) < 0.3, '%s: residual kurtosis %.2f' % (t, k4))
        check(abs(ratio - v['ratio']) <= 1e-6 * max(1.0, ratio), '%s: ratio %.6f vs key %.6f' % (t, ratio, v['ratio']))
        if cat == 'none':
            check(ratio == 0.0, '%s: none trial ratio %.3g' % (t, ratio))
        else:
            check(abs(ratio / v['target_ratio'] - 1) < 0.01, '%s: ratio %.3f vs target %.3f' % (t, ratio, v['target_ratio']))
            lo, hi = (2.7, 3.8) if v['strength'] == 'weak' else (8.5, 11.5)
            check(lo <= v['target_ratio'] <= hi, '%s: target %.3f outside %s' % (t, v['target_ratio'], (lo, hi)))
            check(lo * 0.99 <= ratio <= hi * 1.01, '%s: ratio %.3f outside %s' % (t, ratio, (lo, hi)))
        print('%s ok-so-far  noise %.4f  resid SD %.4f  ratio %.3f' % (t, sd, s, ratio), flush=True)
    shutil.rmtree(tmpd, ignore_errors=True)
    check(nrec == 60, 'records: %d' % nrec)
    check(15 <= early <= 25, 'records with actuator motion in the first second: %d of 60' % early)
    notes.append('records: %d, with actuator motion in the first second: %d' % (nrec, early))
    if '--skip-blackbox' not in args:
        check(bb_done == 60, 'black box compared on %d records' % bb_done)
        notes.append('black box vs reproduced base: %d records, max |diff| %.3g kip' % (bb_done, max_bb))

    # ---------------- determinism ----------------
    if '--skip-determinism' not in args:
        td = tempfile.mkdtemp(prefix='v21det_')
        cp = subprocess.run(['nice', '-n', '10', sys.executable, os.path.join(HERE, 'gen.py'), '--out', td],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
        check(cp.returncode == 0, 'gen.py rerun failed: %s' % cp.stdout[-500:])
        same = 0
        for t in tids:
            for name in ('A', 'B'):
                a = os.path.join(ROOT, 'cases', t, name + '.json')
                b = os.path.join(td, 'cases', t, name + '.json')
                if os.path.exists(b) and sha(a) == sha(b):
                    same += 1
        kb = os.path.join(td, 'key.json')
        check(os.path.exists(kb) and sha(kb) == sha(os.path.join(ROOT, 'key.json')), 'key.json not reproduced')
        check(same == 60, 'determinism: %d of 60 records identical' % same)
        notes.append('determinism: %d of 60 records and key.json byte-identical on rerun' % same)
        shutil.rmtree(td, ignore_errors=True)

    for nline in notes:
        print(nline)
    for f in fails:
        print('FAIL:', f)
    print('VERIFY PASS' if not fails else 'VERIFY FAIL')


if __name__ == '__main__':
    main()
