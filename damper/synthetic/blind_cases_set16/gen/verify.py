#!/usr/bin/env python3
"""Checks for blind test set 16 (stdlib only).

 1. the generator's base model equals `hybridsim damper predict --no-fit` (predicted force, derived
    drum velocity and Eq. 4 kinetic friction columns) to CSV precision on the six measured
    semi-active tests and on all 60 records;
 2. every effect model reduces to the base model at p = 0;
 3. each trial's strength ratio (RMS over both records of (F_effect - F_base) / noise sd),
    recomputed from key.json, lies in its band (weak 2.7-3.8, strong 8.5-11.5, none 0);
 4. the residual (record force - noise-free model force) has the key's noise sd and zero mean;
 5. every record is 6-25 s long, starts with >= 0.3 s and ends with >= 1.5 s of rest;
 6. file format (keys, columns, dt) as the measured files; plan (8 x 3 shapes, 12/12/6, noise range,
    ~1/3 of the records with actuators moving within the first second).
Last line: a one-line summary.
"""
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import gen  # noqa: E402

ROOT = gen.ROOT
BIN = os.environ.get('HYBRIDSIM', '/work/runs/binhead/hybridsim')
CONFIG = os.environ.get('BRFD_CONFIG', '/work/runs/brfd-semiactive.yaml')
REL_TOL = 5.0000001e-8     # %.8g in the CSV: half a unit of the 8th significant digit

failures = []


def fail(msg):
    failures.append(msg)
    print('FAIL: ' + msg)


def predict(path, tmp):
    out = os.path.join(tmp, 'o')
    if os.path.isdir(out):
        shutil.rmtree(out)
    subprocess.run([BIN, 'damper', 'predict', '--no-fit', '--config', CONFIG, '--test', path,
                    '--out', out, '--no-figure'], check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    stem = os.path.splitext(os.path.basename(path))[0]
    with open(os.path.join(out, stem + '_predict.csv')) as fh:
        rows = list(csv.reader(fh))
    hdr = rows[0]
    cols = {h: i for i, h in enumerate(hdr)}
    body = rows[1:]
    return {h: [float(r[cols[h]]) for r in body] for h in
            ('predicted_force_kip', 'drum_vel_in_per_s', 'kinetic_friction_kip')}


def worst_rel(mine, ref):
    w = 0.0
    for a, b in zip(mine, ref):
        e = abs(a - b) - 1e-12
        if e > 0:
            r = e / abs(b) if b != 0 else float('inf')
            w = max(w, r)
    return w


def check_base(path, tmp, label):
    R, F = gen.base_from_file(path)
    P = predict(path, tmp)
    if len(P['predicted_force_kip']) != R['n']:
        fail('%s: predict returned %d rows for %d samples' % (label, len(P['predicted_force_kip']), R['n']))
        return 1.0
    w = max(worst_rel(F, P['predicted_force_kip']), worst_rel(R['v'], P['drum_vel_in_per_s']),
            worst_rel(R['fc'], P['kinetic_friction_kip']))
    if w > REL_TOL:
        fail('%s: base model differs from predict --no-fit (worst relative %.3g)' % (label, w))
    return w


def load_record(path):
    d = json.load(open(path))
    return d


def main():
    tmp = tempfile.mkdtemp(prefix='blind16_verify_')
    try:
        run(tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def run(tmp):
    key = json.load(open(os.path.join(ROOT, 'key.json')))
    # ---------------------------------------------------------------- 1a. measured tests
    wm = 0.0
    ref_keys = None
    for fn in gen.SRC_FILES:
        p = os.path.join(gen.SRC_DIR, fn)
        wm = max(wm, check_base(p, tmp, fn))
        if ref_keys is None:
            ref_keys = list(json.load(open(p)).keys())
    print('base vs predict --no-fit on the 6 measured tests: worst relative difference %.3g' % wm)
    # ---------------------------------------------------------------- plan
    tids = sorted(key)
    if tids != ['t%02d' % i for i in range(1, 31)]:
        fail('key.json does not hold t01..t30')
    cats = {}
    nweak = nstrong = nnone = 0
    for t in tids:
        k = key[t]
        if k['category'] == 'none':
            nnone += 1
        else:
            cats.setdefault(k['category'], set()).add(k['shape'])
            nweak += k['strength'] == 'weak'
            nstrong += k['strength'] == 'strong'
        if not (0.02 <= k['noise_kip'] <= 0.06):
            fail('%s: noise %.4f outside 0.02-0.06' % (t, k['noise_kip']))
    if len(cats) != 8 or any(len(s) != 3 for s in cats.values()):
        fail('effect plan is not 8 categories x 3 distinct shapes: %s' % {c: sorted(s) for c, s in cats.items()})
    if (nweak, nstrong, nnone) != (12, 12, 6):
        fail('strengths weak/strong/none = %d/%d/%d' % (nweak, nstrong, nnone))
    # ---------------------------------------------------------------- 2. reduction at p = 0
    first = key['t01']
    recs0 = []
    for nm in ('A', 'B'):
        d = load_record(os.path.join(ROOT, 'cases', 't01', nm + '.json'))['data']
        recs0.append(gen.prepare([r[1] for r in d], [r[4] for r in d], [r[5] for r in d], d[0][2]))
    bases0 = [gen.sim_base(R) for R in recs0]
    wred = 0.0
    for c, lst in gen.CATALOGUE.items():
        for shape, pmax, smp in lst:
            prm = None
            for t in tids:
                if key[t]['shape'] == shape:
                    prm = key[t]['params']
            for R, b in zip(recs0, bases0):
                e = gen.sim_effect(R, shape, 0.0, prm)
                wred = max(wred, max(abs(x - y) for x, y in zip(e, b)))
    if wred > 1e-9:
        fail('an effect model does not reduce to the base at p = 0 (max %.3g kip)' % wred)
    print('effect models at p = 0 vs base: max difference %.3g kip' % wred)
    # ---------------------------------------------------------------- per trial
    wrec = 0.0
    n_early = 0
    durs = []
    sd_ratios = []
    for t in tids:
        k = key[t]
        Rs, bases, recs = [], [], []
        for nm in ('A', 'B'):
            path = os.path.join(ROOT, 'cases', t, nm + '.json')
            doc = load_record(path)
            if list(doc.keys()) != ref_keys or doc['dt'] != gen.DT or doc['sampling freq'] != 1024:
                fail('%s/%s: keys or header differ from the measured files' % (t, nm))
            d = doc['data']
            if any(len(r) != 8 for r in d):
                fail('%s/%s: rows without 8 columns' % (t, nm))
            if not all(math.isfinite(q) for r in d for q in r):
                fail('%s/%s: non-finite values' % (t, nm))
            if any(abs(d[j][0] - j * gen.DT) > 1e-12 for j in range(len(d))):
                fail('%s/%s: time column not uniform 1024 Hz' % (t, nm))
            wrec = max(wrec, check_base(path, tmp, '%s/%s' % (t, nm)))
            R, F = gen.base_from_file(path)
            Rs.append(R)
            bases.append(F)
            recs.append(d)
            # durations and rests
            T = d[-1][0]
            durs.append(T)
            if not (6.0 <= T <= 25.0):
                fail('%s/%s: duration %.3f s' % (t, nm, T))
            nrest = int(math.ceil(1.5 / gen.DT))
            for lab, sl in (('final', slice(len(d) - nrest, len(d))), ('initial', slice(0, int(0.3 / gen.DT)))):
                xs = [r[1] for r in d[sl]]
                a1 = [r[4] for r in d[sl]]
                a2 = [r[5] for r in d[sl]]
                vv = R['v'][sl][8:-8]      # the one-sided end samples of the derivative excluded
                if (max(xs) - min(xs) > 1e-3 or max(abs(q) for q in vv) > 0.05 or
                        max(a1) - min(a1) > 1e-4 or max(a2) - min(a2) > 1e-4):
                    fail('%s/%s: no %s rest' % (t, nm, lab))
            mv = [r[0] for r in d if abs(r[4] - d[0][4]) > 0.002 or abs(r[5] - d[0][5]) > 0.002]
            if mv and mv[0] < 1.0:
                n_early += 1
        # effect force, ratio, residual noise
        ss, nn = 0.0, 0
        rs, rn, rm = 0.0, 0, 0.0
        for R, b, d in zip(Rs, bases, recs):
            e = gen.sim_effect(R, k['shape'], k['p'], k['params'])
            for x, y in zip(e, b):
                ss += (x - y) ** 2
            nn += len(b)
            for j in range(1, len(d)):
                q = d[j][2] - e[j]
                rs += q * q
                rm += q
                rn += 1
        ratio = math.sqrt(ss / nn) / k['noise_kip']
        band = {'weak': gen.WEAK_BAND, 'strong': gen.STRONG_BAND, 'none': (0.0, 0.0)}[k['strength']]
        if not (band[0] <= ratio <= band[1]):
            fail('%s: ratio %.4f outside %s band %s' % (t, ratio, k['strength'], band))
        if abs(ratio - k['ratio']) > 1e-6 * max(1.0, ratio):
            fail('%s: ratio %.6f differs from key %.6f' % (t, ratio, k['ratio']))
        sdr = math.sqrt(rs / rn) / k['noise_kip']
        mean = rm / rn
        sd_ratios.append(sdr)
        if abs(sdr - 1.0) > 0.03 or abs(mean) > 5.0 * k['noise_kip'] / math.sqrt(rn):
            fail('%s: residual sd/noise %.4f, mean %.4g kip' % (t, sdr, mean))
        print('%s ratio %7.3f (%s)  residual sd / noise %.4f  durations %.1f, %.1f s' % (
            t, ratio, k['strength'], sdr, recs[0][-1][0], recs[1][-1][0]))
    print('base vs predict --no-fit on the 60 records: worst relative difference %.3g' % wrec)
    if not (15 <= n_early <= 25):
        fail('%d of 60 records move the actuators within the first second (want ~20)' % n_early)
    print('records with actuators moving in the first second: %d / 60' % n_early)
    if failures:
        print('VERIFY FAIL: %d problem(s); first: %s' % (len(failures), failures[0]))
        sys.exit(1)
    print('VERIFY PASS: base == predict --no-fit to CSV precision (6 measured: %.2g, 60 records: %.2g rel); '
          '30 trials (24 effect = 8x3, 12 weak/12 strong, 6 none) ratios in band; residual sd/noise %.3f-%.3f; '
          'records %.1f-%.1f s with >=1.5 s final rest; %d/60 early-actuator records'
          % (wm, wrec, min(sd_ratios), max(sd_ratios), min(durs), max(durs), n_early))


if __name__ == '__main__':
    main()
