#!/usr/bin/env python3
"""blind33 self-check.  Standard library + the black-box binary (only `damper predict --no-fit`).

Checks
  1. key.json: 30 trials, 6 none, 24 effects = 3 distinct shapes x 8 categories, 12 strong /
     12 weak, ratio and noise ranges, amplitudes inside their declared bounds.
  2. layout of every record equals the measured semi-active files (header keys/values/order,
     8 columns, 1024 Hz time base, 9-25 s, quantisation grids, travel and speed limits).
  3. the Python base model in gen.py equals the black box on every record.
  4. 'none' records: force column == quantised(black box + the trial's regenerated noise);
     residual statistics are white with the key's SD.
  5. effect records: force column == quantised(F_true + noise); the strength ratio
     RMS(F_true - black box)/SD over both records equals the key's ratio and its target, and
     a data-only estimate sqrt(mean((F - BB)^2)/SD^2 - 1) agrees.
Last line: VERIFY PASS or VERIFY FAIL.
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
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import gen  # noqa: E402

BIN = '/work/runs/binhead/hybridsim'
CONFIG = '/work/main/configs/brfd-semiactive.yaml'
MEASURED = os.path.join(gen.TEMPLATE_DIR, gen.TEMPLATE_FILES[0])

fails = []
notes = []


def check(cond, msg):
    if not cond:
        fails.append(msg)
    return cond


def black_box(path, tmp):
    out = os.path.join(tmp, os.path.basename(os.path.dirname(path)) + '_' +
                       os.path.basename(path)[:-5])
    r = subprocess.run([BIN, 'damper', 'predict', '--config', CONFIG, '--no-fit', '--test', path,
                        '--out', out, '--no-figure'], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError('black box failed on %s: %s' % (path, r.stderr[-500:]))
    csvs = [f for f in os.listdir(out) if f.endswith('.csv')]
    rows = list(csv.DictReader(open(os.path.join(out, csvs[0]))))
    return [float(row['predicted_force_kip']) for row in rows]


def grid_ok(vals, q, off, tol):
    return max(abs((a - off) / q - round((a - off) / q)) for a in vals) < tol


def main():
    t0 = time.time()
    key = json.load(open(os.path.join(ROOT, 'key.json')))
    meas = json.load(open(MEASURED))
    meas_keys = list(meas.keys())

    # ---------------------------------------------------------------- 1. key ------------
    tids = ['t%02d' % k for k in range(1, 31)]
    check(sorted(key.keys()) == tids, 'key has not exactly t01..t30')
    cats = {}
    nstrong = nweak = nnone = 0
    for tid in tids:
        e = key[tid]
        for fld in ('category', 'shape', 'strength', 'ratio', 'noise_kip', 'params'):
            check(fld in e, '%s: key field %s missing' % (tid, fld))
        check(0.02 <= e['noise_kip_exact'] <= 0.06, '%s: noise SD out of range' % tid)
        if e['category'] == 'none':
            nnone += 1
            check(e['ratio'] == 0.0, '%s: none trial with ratio' % tid)
            continue
        check(e['category'] in gen.CATEGORIES, '%s: unknown category' % tid)
        cats.setdefault(e['category'], []).append(e['shape'])
        if e['strength'] == 'strong':
            nstrong += 1
            check(8.5 <= e['ratio_target'] <= 11.5, '%s: strong target out of range' % tid)
        elif e['strength'] == 'weak':
            nweak += 1
            check(2.7 <= e['ratio_target'] <= 3.8, '%s: weak target out of range' % tid)
        else:
            check(False, '%s: bad strength' % tid)
        lo, hi = e['amplitude_bounds']
        amp = e['params'][e['amplitude_name']]
        check(lo <= amp <= hi, '%s: amplitude %g outside bounds' % (tid, amp))
    check(nnone == 6, 'need 6 none trials, got %d' % nnone)
    check(nstrong == 12 and nweak == 12, 'strong/weak = %d/%d' % (nstrong, nweak))
    check(sorted(cats.keys()) == sorted(gen.CATEGORIES), 'categories missing')
    for c, shs in cats.items():
        check(len(shs) == 3 and len(set(shs)) == 3, '%s: need 3 distinct shapes' % c)
    print('key: %d none, %d strong, %d weak, categories %s' % (
        nnone, nstrong, nweak, ' '.join('%s:%d' % (c, len(s)) for c, s in sorted(cats.items()))))

    # ---------------------------------------------------------------- records -----------
    tmp = tempfile.mkdtemp(prefix='blind33_verify_')
    worst_bb = 0.0
    total_s = []
    for tid in tids:
        e = key[tid]
        cat = e['category']
        sd = e['noise_kip_exact']
        tdir = os.path.join(ROOT, 'cases', tid)
        check(sorted(os.listdir(tdir)) == ['A.json', 'B.json'], '%s: files' % tid)
        ss_model = 0.0
        ss_data = 0.0
        ntot = 0
        for name in ('A', 'B'):
            path = os.path.join(tdir, name + '.json')
            meta = e['records'][name]
            rec, obj = gen.load_record(path, meta)
            d = obj['data']
            n = len(d)
            total_s.append((n - 1) * gen.DT)
            # ---- 2. layout
            check(list(obj.keys()) == meas_keys, '%s%s: header keys/order differ' % (tid, name))
            for k in meas_keys:
                if k != 'data':
                    check(obj[k] == meas[k] and type(obj[k]) == type(meas[k]),
                          '%s%s: header %s differs' % (tid, name, k))
            check(all(len(r) == 8 for r in d), '%s%s: not 8 columns' % (tid, name))
            check(type(d[0][0]) == type(meas['data'][0][0]) == int and d[0][0] == 0,
                  '%s%s: time[0]' % (tid, name))
            check(all(d[i][0] == i * gen.DT for i in range(1, n)), '%s%s: time base' % (tid, name))
            check(9 * 1024 + 1 <= n <= 25 * 1024 + 1, '%s%s: duration %.2f s' % (tid, name, (n - 1) * gen.DT))
            check(all(all(isinstance(a, (int, float)) and math.isfinite(a) for a in r) for r in d),
                  '%s%s: non-finite value' % (tid, name))
            x = [r[1] for r in d]
            check(max(abs(a) for a in x) <= 1.3, '%s%s: travel beyond 1.3 in' % (tid, name))
            vmax = max(abs(a) for a in rec.v)
            check(vmax <= 4.2, '%s%s: drum speed %.2f in/s' % (tid, name, vmax))
            F = [r[2] for r in d]
            check(grid_ok(F, gen.Q_F, 0.0, 1e-6), '%s%s: force not on the measured LSB grid' % (tid, name))
            check(grid_ok([r[6] for r in d], gen.Q_T1, gen.OFF_T1, 1e-6), '%s%s: act1 force grid' % (tid, name))
            check(grid_ok([r[7] for r in d], gen.Q_T2, gen.OFF_T2, 1e-6), '%s%s: act2 force grid' % (tid, name))
            tr1 = max(abs(r[4] - d[0][4]) for r in d)
            tr2 = max(abs(r[5] - d[0][5]) for r in d)
            check(tr1 <= 0.05 and tr2 <= 0.05, '%s%s: actuator travel %.4f/%.4f' % (tid, name, tr1, tr2))
            check(all(0.3 <= r[4] <= 1.2 and 0.3 <= r[5] <= 1.2 for r in d), '%s%s: actuator range' % (tid, name))
            check(meta['actuators_move'] == (max(tr1, tr2) > 0.005), '%s%s: actuator flag' % (tid, name))
            # velocity column carries the measured files' 1/125 quirk
            num = sum(rec.v[i] * d[i][3] for i in range(n))
            den = sum(d[i][3] ** 2 for i in range(n))
            check(100 < num / den < 150, '%s%s: velocity column scale %.1f' % (tid, name, num / den))
            # ---- 3. base model == black box
            bb = black_box(path, tmp)
            check(len(bb) == n, '%s%s: black box length' % (tid, name))
            base = rec.base()
            dev = max(abs(a - b) for a, b in zip(base, bb))
            worst_bb = max(worst_bb, dev)
            check(dev < 2e-5, '%s%s: Python base differs from black box by %.2e' % (tid, name, dev))
            # ---- 4./5. force column
            noise = gen.noise_array(meta['noise_seed'], n, sd)
            if cat == 'none':
                ref = bb
                tol = gen.Q_F / 2 + 2e-6
            else:
                amp = e['params'][e['amplitude_name']]
                ref = gen.true_force(rec, cat, e['shape'], amp, e['fixed'])
                tol = gen.Q_F / 2 + 1e-9
            errq = max(abs(F[i] - (ref[i] + noise[i])) for i in range(1, n))
            check(errq <= tol, '%s%s: force != Q(reference + noise) (%.2e)' % (tid, name, errq))
            check(F[0] == rec.f0, '%s%s: initial force' % (tid, name))
            if cat == 'none':
                res = [F[i] - bb[i] for i in range(1, n)]
                m = sum(res) / len(res)
                s = math.sqrt(sum((a - m) ** 2 for a in res) / len(res))
                r1 = sum((res[i] - m) * (res[i + 1] - m) for i in range(len(res) - 1)) / (s * s * len(res))
                check(abs(m) < 4 * sd / math.sqrt(len(res)) + 1e-4, '%s%s: residual mean %.4f' % (tid, name, m))
                check(abs(s / math.sqrt(sd * sd + gen.Q_F ** 2 / 12) - 1) < 0.03,
                      '%s%s: residual SD %.4f vs %.4f' % (tid, name, s, sd))
                check(abs(r1) < 0.04, '%s%s: residual lag-1 correlation %.3f' % (tid, name, r1))
            else:
                ss_model += sum((a - b) ** 2 for a, b in zip(ref, bb))
            ss_data += sum((F[i] - bb[i]) ** 2 for i in range(1, n))
            ntot += n
        if cat != 'none':
            r_model = math.sqrt(ss_model / ntot) / sd
            r_data = math.sqrt(max(0.0, ss_data / ntot / (sd * sd + gen.Q_F ** 2 / 12) - 1.0))
            ok1 = check(abs(r_model / e['ratio'] - 1) < 2e-3, '%s: ratio %.4f != key %.4f' % (tid, r_model, e['ratio']))
            ok2 = check(abs(r_model / e['ratio_target'] - 1) < 3e-3, '%s: ratio %.4f misses target %.4f' % (tid, r_model, e['ratio_target']))
            rng_ok = (8.5 <= r_model <= 11.5) if e['strength'] == 'strong' else (2.7 <= r_model <= 3.8)
            check(rng_ok, '%s: ratio %.3f outside its strength band' % (tid, r_model))
            ok3 = check(abs(r_data / r_model - 1) < 0.05, '%s: data-based ratio %.3f vs %.3f' % (tid, r_data, r_model))
            print('%s %-16s %-6s ratio(black box) %7.3f  target %7.3f  data-estimate %7.3f  %s' % (
                tid, cat, e['strength'], r_model, e['ratio_target'], r_data,
                'ok' if ok1 and ok2 and ok3 and rng_ok else 'BAD'))
        else:
            r_data = math.sqrt(max(0.0, ss_data / ntot / (sd * sd + gen.Q_F ** 2 / 12) - 1.0))
            print('%s %-16s %-6s ratio 0 (base + noise), data-estimate %.3f' % (tid, cat, '-', r_data))
    print('records: %d, %.1f-%.1f s; worst |Python base - black box| = %.2e kip' % (
        len(total_s), min(total_s), max(total_s), worst_bb))
    print('verify took %.1f s' % (time.time() - t0))
    for f in fails:
        print('FAIL:', f)
    print('VERIFY PASS' if not fails else 'VERIFY FAIL')


if __name__ == '__main__':
    main()
