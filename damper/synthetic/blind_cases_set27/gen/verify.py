#!/usr/bin/env python3
"""Verify the blind set in /work/blind27: layout, quantisation, durations, final rest,
actuator-motion timing, trial balance, ratios (recomputed against the BLACK-BOX base prediction)
and that the 'none' trials are exactly the black-box base model plus noise.
Last line: VERIFY PASS or VERIFY FAIL."""
import csv, json, math, os, subprocess, sys, tempfile, struct

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import gen  # noqa: E402

BB = '/work/runs/binhead/hybridsim'
CONFIG = '/work/runs/brfd-semiactive.yaml'
fails = []


def check(cond, msg):
    if not cond:
        fails.append(msg)
        print('FAIL', msg)
    return cond


def f32ok(x):
    return struct.unpack('f', struct.pack('f', x))[0] == x


def on_grid(x, q, off=0.0, tol=1e-3):
    k = (x - off) / q
    return abs(k - round(k)) < tol


def blackbox(path, outdir):
    r = subprocess.run([BB, 'damper', 'predict', '--no-fit', '--config', CONFIG, '--test', path,
                        '--out', outdir, '--no-figure'], capture_output=True, text=True)
    if r.returncode != 0:
        return None, r.stderr
    name = os.path.splitext(os.path.basename(path))[0]
    rows = list(csv.DictReader(open(os.path.join(outdir, name + '_predict.csv'))))
    return [float(r['predicted_force_kip']) for r in rows], r.stdout


def main():
    ref_path = os.path.join(gen.DATA, gen.FILES[1])
    ref = json.load(open(ref_path))
    ref_keys = list(ref.keys())
    key = json.load(open(os.path.join(ROOT, 'key.json')))
    trials = gen.plan()
    check(sorted(key) == ['t%02d' % k for k in range(1, 31)], 'key has t01..t30')
    check(sorted(os.listdir(os.path.join(ROOT, 'cases'))) == ['t%02d' % k for k in range(1, 31)],
          'cases/t01..t30 present')
    # balance
    cats = {}
    for t, e in key.items():
        cats.setdefault(e['category'], []).append(e['shape'])
    for c in gen.CATEGORIES:
        check(len(cats.get(c, [])) == 3 and len(set(cats[c])) == 3, 'category %s has 3 distinct shapes' % c)
    check(len(cats.get('none', [])) == 6, '6 none trials')
    nweak = sum(1 for e in key.values() if e['strength'] == 'weak')
    nstrong = sum(1 for e in key.values() if e['strength'] == 'strong')
    check(nweak == 12 and nstrong == 12, '12 weak + 12 strong (got %d + %d)' % (nweak, nstrong))
    early_count = 0
    (q1, o1), (q2, o2) = gen.library()['grids']['f1'], gen.library()['grids']['f2']
    tmp = tempfile.mkdtemp(prefix='verify27_')
    for t in sorted(key):
        e = key[t]; spec = trials[t]
        check(spec['category'] == e['category'] and spec['shape'] == e['shape'], '%s plan matches key' % t)
        check(0.02 <= e['noise_kip'] <= 0.06, '%s noise in [0.02, 0.06]' % t)
        noise, recs = gen.make_trial_records(t, spec)
        check(abs(noise - e['noise_kip']) < 1e-12, '%s noise regenerates' % t)
        Ft_all, bb_all, res_all = [], [], []
        for ri, (r, R) in enumerate(zip('AB', recs)):
            path = os.path.join(ROOT, 'cases', t, r + '.json')
            txt = open(path).read()
            obj = json.loads(txt)
            check(list(obj.keys()) == ref_keys, '%s/%s header keys/order' % (t, r))
            for k in ref_keys[1:]:
                check(obj[k] == ref[k] and type(obj[k]) == type(ref[k]), '%s/%s header %s' % (t, r, k))
            d = obj['data']
            n = len(d)
            dur = (n - 1) * gen.DT
            check(6.5 <= dur <= 25.0, '%s/%s duration %.2f s in [6.5, 25]' % (t, r, dur))
            ok = True
            for i, row in enumerate(d):
                if len(row) != 8 or row[0] != i * gen.DT:
                    ok = False; break
                for u in row:
                    if isinstance(u, float) and u.is_integer():
                        ok = False
            check(ok, '%s/%s rows: 8 columns, uniform time, integral values written as ints' % (t, r))
            x = [row[1] for row in d]; F = [row[2] for row in d]
            a1 = [row[4] for row in d]; a2 = [row[5] for row in d]
            check(all(f32ok(u) and on_grid(u, gen.QX, gen.OX, 0.02) for u in x), '%s/%s displacement quantised' % (t, r))
            check(all(on_grid(u, gen.QF, 0.0, 1e-6) for u in F), '%s/%s force quantised' % (t, r))
            check(all(f32ok(u) for u in a1 + a2), '%s/%s actuator positions float32' % (t, r))
            check(all(on_grid(row[6], q1, o1, 1e-6) and on_grid(row[7], q2, o2, 1e-6) for row in d),
                  '%s/%s actuator forces quantised' % (t, r))
            # determinism: regenerated record equals the file
            check(x == R['x'] and a1 == R['a1'] and a2 == R['a2'], '%s/%s regenerates identically' % (t, r))
            # final rest >= 1.5 s
            m = int(1.5 / gen.DT)
            tail = x[-m:]
            v = gen.smooth_velocity(x)
            check(max(tail) - min(tail) <= 5 * gen.QX and max(abs(u) for u in v[-m:-8]) < 0.02,
                  '%s/%s final rest >= 1.5 s' % (t, r))
            # actuator motion timing
            fm = gen.first_motion_time(a1, a2)
            early = fm is not None and fm < 1.0
            early_count += early
            check(early == spec['early'][ri], '%s/%s early-motion flag (first motion %s)' % (t, r, fm))
            if e['category'] in gen.NEEDS_MOTION:
                check(fm is not None, '%s/%s has actuator motion' % (t, r))
            # black box
            bb, msg = blackbox(path, tmp)
            if not check(bb is not None and len(bb) == n, '%s/%s black box accepts the record' % (t, r)):
                continue
            amp = e['params']['amplitude']
            Ft = R['Fbase'] if e['shape'] == 'none' else gen.true_sim(R, e['shape'], amp, e['params'], R['F0'])
            # my base replica equals the black box
            check(max(abs(a - b) for a, b in zip(R['Fbase'], bb)) < 2e-5, '%s/%s base replica == black box' % (t, r))
            if e['shape'] == 'none':
                bad = [i for i in range(n) if abs(F[i] - gen.qf(bb[i] + R['noise'][i])) > 1.5 * gen.QF]
                check(not bad, '%s/%s none == black-box base + noise (quantised); bad rows %s' % (t, r, bad[:5]))
                check(abs(F[0] - bb[0]) < 1e-6, '%s/%s none: row 0 equals the black-box start' % (t, r))
            Ft_all.append(Ft); bb_all.append(bb)
            res_all.extend(F[i] - Ft[i] for i in range(1, n))
        if len(Ft_all) == 2:
            ratio = gen.rms_ratio(Ft_all, bb_all, e['noise_kip'])
            check(abs(ratio - e['ratio']) < 0.01 * max(e['ratio'], 1) + 0.01, '%s ratio %.3f vs key %.3f' % (t, ratio, e['ratio']))
            if e['strength'] == 'weak':
                check(2.7 <= ratio <= 3.8, '%s weak ratio %.3f in [2.7, 3.8]' % (t, ratio))
            elif e['strength'] == 'strong':
                check(8.5 <= ratio <= 11.5, '%s strong ratio %.3f in [8.5, 11.5]' % (t, ratio))
            else:
                check(ratio < 1e-3, '%s none ratio %.2g ~ 0' % (t, ratio))
            rn = math.sqrt(sum(u * u for u in res_all) / len(res_all)) / e['noise_kip']
            mn = sum(res_all) / len(res_all) / e['noise_kip']
            check(0.93 < rn < 1.07 and abs(mn) < 0.05, '%s residual (measured - true) rms/noise %.3f mean %.3f' % (t, rn, mn))
            print('%s %-7s ratio %.3f  residual/noise %.3f' % (t, e['strength'], ratio, rn), flush=True)
    check(15 <= early_count <= 25, 'about 1/3 of the 60 records move actuators within 1 s (%d)' % early_count)
    print('records with actuator motion in the first second: %d of 60' % early_count)
    print('failures: %d' % len(fails))
    print('VERIFY PASS' if not fails else 'VERIFY FAIL')


if __name__ == '__main__':
    main()
