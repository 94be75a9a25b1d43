#!/usr/bin/env python3
"""blind30 self-check.  Python 3 standard library only.

Checks
  1. set composition: 30 trials, 6 'none', 3 trials per category with 3 different shapes, 24 distinct
     shapes, 12 strong / 12 weak, noise SD in [0.02, 0.06] kip, amplitudes inside their bounds;
  2. layout of every record equals the measured semi-active files (same header keys in the same
     order, dt, sampling freq, units, 8 numeric columns, time = i/1024), duration 9..25 s,
     |drum travel| <= 1.3 in, peak drum speed, actuator travel, force on the measured quantisation grid;
  3. the black box (`hybridsim damper predict --no-fit`) on every record: our replica of the base
     model equals it (max |diff| < 1e-6 kip);
  4. 'none' records: F = quantise(F_blackbox + noise) sample by sample (noise regenerated from the
     stored seed), residual SD within 6 % of noise_kip;
  5. effect records: F = quantise(F_true + noise); ratio = RMS over both records of
     (F_true - F_blackbox) / noise_kip equals key ratio and its target, inside the strong/weak band.
Last line: VERIFY PASS or VERIFY FAIL.
"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import gen  # noqa: E402

ROOT = gen.ROOT
BIN = '/work/runs/binhead/hybridsim'
CONFIG = '/work/main/configs/brfd-semiactive.yaml'
MEASURED = os.path.join(gen.DATA_DIR, gen.SOURCE_FILES[0])

fails = []
notes = []


def check(cond, msg):
    if not cond:
        fails.append(msg)
    return cond


def blackbox(path, tmp):
    out = os.path.join(tmp, os.path.basename(os.path.dirname(path)) + os.path.basename(path)[:-5])
    r = subprocess.run([BIN, 'damper', 'predict', '--config', CONFIG, '--no-fit', '--test', path,
                        '--out', out, '--no-figure'], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError('black box failed on %s: %s' % (path, r.stderr[-500:]))
    csvs = [f for f in os.listdir(out) if f.endswith('_predict.csv')]
    with open(os.path.join(out, csvs[0])) as fh:
        return [float(row['predicted_force_kip']) for row in csv.DictReader(fh)]


def on_grid(v, q, off=0.0, tol=1e-6):
    k = (v - off) / q
    return abs(k - round(k)) < tol * max(1.0, abs(k))


def main():
    with open(MEASURED) as fh:
        ref = json.load(fh)
    ref_keys = list(ref.keys())
    with open(os.path.join(ROOT, 'key.json')) as fh:
        key = json.load(fh)

    # ---------------------------------------------------------------- 1. composition
    trials = ['t%02d' % i for i in range(1, 31)]
    check(sorted(key) == trials, 'key must hold t01..t30')
    cats = [key[t]['category'] for t in trials]
    check(cats.count('none') == 6, '6 none trials')
    for c in gen.CATEGORIES:
        sh = [key[t]['shape'] for t in trials if key[t]['category'] == c]
        check(len(sh) == 3 and len(set(sh)) == 3, 'category %s: 3 trials with 3 different shapes' % c)
        for s in sh:
            check(gen.SHAPES[s]['cat'] == c, 'shape %s belongs to %s' % (s, c))
    eff = [t for t in trials if key[t]['category'] != 'none']
    check(len(set(key[t]['shape'] for t in eff)) == 24, '24 distinct shapes')
    st = [key[t]['strength'] for t in eff]
    check(st.count('strong') == 12 and st.count('weak') == 12, '12 strong / 12 weak')
    for t in trials:
        k = key[t]
        check(0.02 <= k['noise_sd_exact'] <= 0.06, '%s noise SD in [0.02, 0.06]' % t)
        if k['category'] != 'none':
            check(0.0 < k['amp'] <= k['amp_bounds'][1], '%s amplitude inside bounds' % t)
            lo, hi = (8.5, 11.5) if k['strength'] == 'strong' else (2.7, 3.8)
            check(lo <= k['ratio_target'] <= hi, '%s target inside the %s band' % (t, k['strength']))

    # ---------------------------------------------------------------- 2-5 per record
    tmp = tempfile.mkdtemp(prefix='blind30verify_')
    worst_replica = 0.0
    ratio_rows = []
    for t in trials:
        k = key[t]
        sigma = k['noise_sd_exact']
        shape = k['shape']
        sp = {kk: vv for kk, vv in k['params'].items() if kk != k.get('amp_name')}
        amp = k.get('amp', 0.0)
        dsum = 0.0
        dn = 0
        for R in ('A', 'B'):
            path = os.path.join(ROOT, 'cases', t, R + '.json')
            with open(path) as fh:
                d = json.load(fh)
            tag = '%s/%s' % (t, R)
            # --- layout
            check(list(d.keys()) == ref_keys, tag + ' header keys/order as measured')
            for kk in ref_keys:
                if kk != 'data':
                    check(d[kk] == ref[kk], tag + ' header %s equals measured' % kk)
            D = d['data']
            n = len(D)
            check(all(len(r) == 8 for r in D), tag + ' 8 columns')
            check(all(isinstance(v, (int, float)) and math.isfinite(v) for r in D[::97] for v in r),
                  tag + ' numeric finite values')
            check(all(abs(D[i][0] - i * gen.DT) < 1e-12 for i in range(n)), tag + ' time = i/1024')
            dur = (n - 1) * gen.DT
            check(9.0 <= dur <= 25.0, tag + ' duration %.3f s in [9, 25]' % dur)
            x = [r[1] for r in D]
            F = [r[2] for r in D]
            a1 = [r[4] for r in D]
            a2 = [r[5] for r in D]
            check(max(abs(v) for v in x) <= 1.3, tag + ' |x| <= 1.3 in')
            v = gen.derive_velocity(x)
            check(max(abs(vv) for vv in v) <= 4.0, tag + ' peak drum speed <= 4 in/s')
            check(max(abs(a - a1[0]) for a in a1) <= 0.06 and max(abs(a - a2[0]) for a in a2) <= 0.06,
                  tag + ' actuator travel <= 0.06 in')
            check(all(on_grid(f, gen.Q_FORCE) for f in F), tag + ' force on the measured quantisation grid')
            # --- black box vs replica
            Fbb = blackbox(path, tmp)
            check(len(Fbb) == n, tag + ' black box length')
            meta = k['records'][R]
            rest = [False] * n
            for i0, i1 in meta['rest_samples']:
                for i in range(i0, i1):
                    rest[i] = True
            rec = dict(x=x, a1=a1, a2=a2, F0=F[0], rest=rest)
            gen.prep(rec)
            Frep = gen.base_force(rec)
            err = max(abs(p - q) for p, q in zip(Frep, Fbb))
            worst_replica = max(worst_replica, err)
            check(err < 1e-6, tag + ' replica base == black box (max diff %.2e)' % err)
            # --- truth and noise
            if shape == 'none':
                Ft = Fbb                       # 'none': the black box itself
            else:
                Ft = gen.simulate_shape(rec, shape, sp, amp)
            nz = gen.noise_sequence(n, sigma, meta['noise_seed'])
            mism = 0
            for i in range(1, n):
                q = round((Ft[i] + nz[i]) / gen.Q_FORCE) * gen.Q_FORCE
                if abs(q - F[i]) > 1.01 * gen.Q_FORCE:
                    mism += 1
            check(mism == 0, tag + ' F = quantise(F_true + noise) (%d mismatches)' % mism)
            res = [F[i] - Ft[i] for i in range(1, n)]
            mu = sum(res) / len(res)
            sd = math.sqrt(sum((r - mu) ** 2 for r in res) / len(res))
            check(abs(sd / sigma - 1.0) < 0.06 and abs(mu) < 0.1 * sigma,
                  tag + ' residual SD %.4f vs noise %.4f, mean %.4f' % (sd, sigma, mu))
            for p, q in zip(Ft, Fbb):
                dsum += (p - q) ** 2
            dn += n
        ratio = math.sqrt(dsum / dn) / sigma
        ratio_rows.append((t, k['category'], shape, k['strength'], ratio, k.get('ratio_target')))
        if shape == 'none':
            check(ratio < 1e-4, '%s none: F_true == black box (ratio %.2e)' % (t, ratio))
        else:
            lo, hi = (8.5, 11.5) if k['strength'] == 'strong' else (2.7, 3.8)
            check(abs(ratio - k['ratio_target']) <= 0.01 * k['ratio_target'],
                  '%s ratio %.3f vs target %.3f' % (t, ratio, k['ratio_target']))
            check(abs(ratio - k['ratio']) <= 0.002 * k['ratio'] + 1e-3, '%s ratio equals key ratio' % t)
            check(lo <= ratio <= hi, '%s ratio %.3f inside the %s band' % (t, ratio, k['strength']))
        print('%s %-16s %-20s %-6s ratio(black box base) %7.3f  target %s' % (
            t, k['category'], shape, k['strength'] or '-', ratio,
            '%.3f' % k['ratio_target'] if k.get('ratio_target') else '-'), flush=True)
    print('worst |replica - black box| = %.2e kip' % worst_replica)
    if fails:
        for f in fails[:50]:
            print('FAIL:', f)
        print('%d failed checks' % len(fails))
        print('VERIFY FAIL')
        return 1
    print('all checks passed')
    print('VERIFY PASS')
    return 0


if __name__ == '__main__':
    sys.exit(main())
