#!/usr/bin/env python3
"""Checks of blind test set 19.  Last line: VERIFY PASS or VERIFY FAIL.

    nice -n 10 python3 /work/blind19/gen/verify.py [--root /work/blind19] [--no-blackbox] [--no-regen]

Checks: key layout and trial mix; record format, length, rests, actuator timing, force
quantisation; the stored force = model truth + white noise of the stated SD; the achieved
ratio; sha256 of every record; the base model of gen.py against the black box
`hybridsim damper predict --no-fit` (if present); determinism (re-generates three trials).
"""
import sys, os, json, math, hashlib, subprocess, csv, glob, shutil

HERE = os.path.dirname(os.path.abspath(__file__))
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


def main():
    a = sys.argv[1:]
    root = a[a.index('--root') + 1] if '--root' in a else '/work/blind19'
    use_bb = '--no-blackbox' not in a and os.path.exists(BLACKBOX)
    regen = '--no-regen' not in a
    key = json.load(open(os.path.join(root, 'key.json')))
    tids = ['t%02d' % k for k in range(1, 31)]
    check(sorted(key) == tids, 'key must hold exactly t01..t30')
    # ------------------------------------------------------------ trial mix
    cats = {}
    nweak = nstrong = nnone = 0
    for t in tids:
        e = key[t]
        for f in ('category', 'shape', 'strength', 'p', 'noise_kip', 'ratio', 'params'):
            check(f in e, '%s: field %s missing' % (t, f))
        check(0.02 <= e['noise_kip'] <= 0.06, '%s: noise SD %.4f out of [0.02, 0.06]' % (t, e['noise_kip']))
        if e['category'] == 'none':
            nnone += 1
            check(e['strength'] == 'none' and e['p'] == 0 and e['ratio'] == 0, '%s: none trial not clean' % t)
            continue
        check(e['category'] in gen.CATEGORIES, '%s: unknown category' % t)
        cats.setdefault(e['category'], []).append(e)
        if e['strength'] == 'weak':
            nweak += 1
            check(2.7 <= e['target_ratio'] <= 3.8, '%s: weak target %.3f' % (t, e['target_ratio']))
        elif e['strength'] == 'strong':
            nstrong += 1
            check(8.5 <= e['target_ratio'] <= 11.5, '%s: strong target %.3f' % (t, e['target_ratio']))
        else:
            check(False, '%s: bad strength' % t)
        check(abs(e['ratio'] - e['target_ratio']) <= 0.01 * e['target_ratio'],
              '%s: ratio %.3f vs target %.3f' % (t, e['ratio'], e['target_ratio']))
        check(e['p'] > 0, '%s: p must be > 0' % t)
    check(nnone == 6, 'need 6 none trials, have %d' % nnone)
    check(nweak == 12 and nstrong == 12, 'need 12 weak + 12 strong, have %d + %d' % (nweak, nstrong))
    check(len(cats) == 8, 'need 8 categories, have %d' % len(cats))
    for c, L in cats.items():
        check(len(L) == 3, '%s: %d trials' % (c, len(L)))
        check(len(set(e['shape'] for e in L)) == 3, '%s: shapes not distinct' % c)
        st = set(e['strength'] for e in L)
        check(st == {'weak', 'strong'}, '%s: strengths not mixed (%s)' % (c, st))
    # ------------------------------------------------------------ records
    n_early = 0; durs = []
    bb_worst = 0.0
    for t in tids:
        e = key[t]
        shape = e['shape'] if e['shape'] != 'none' else 'base'
        num = 0.0; cnt = 0
        for lab in 'AB':
            path = os.path.join(root, 'cases', t, lab + '.json')
            if not check(os.path.exists(path), '%s: missing' % path):
                continue
            raw = open(path, 'rb').read()
            if 'records' in e:
                check(hashlib.sha256(raw).hexdigest() == e['records'][lab]['sha256'], '%s %s: sha256 differs' % (t, lab))
            doc = json.loads(raw)
            for k in ('data', 'dt', 'sampling freq', 'displacement units', 'time units', 'friction force units',
                      'actuator force units'):
                check(k in doc, '%s %s: key %s missing' % (t, lab, k))
            check(doc['dt'] == gen.DT and doc['sampling freq'] == 1024, '%s %s: dt / rate' % (t, lab))
            d = doc['data']; n = len(d)
            check(all(len(r) == 8 for r in d), '%s %s: rows must have 8 columns' % (t, lab))
            check(all(abs(r[0] - i * gen.DT) < 1e-9 for i, r in enumerate(d)), '%s %s: time column' % (t, lab))
            T = (n - 1) * gen.DT; durs.append(T)
            check(6.5 <= T <= 25.0, '%s %s: duration %.2f s' % (t, lab, T))
            x = [r[1] for r in d]; F = [r[2] for r in d]; x1 = [r[4] for r in d]; x2 = [r[5] for r in d]
            # final rest
            j = n - 1
            while j > 0 and x[j - 1] == x[-1] and x1[j - 1] == x1[-1] and x2[j - 1] == x2[-1]:
                j -= 1
            check((n - j) * gen.DT >= 1.5, '%s %s: final rest %.2f s' % (t, lab, (n - j) * gen.DT))
            # first actuator motion and passive stretch
            fa = next((i for i in range(n) if abs(x1[i] - x1[0]) > 0.002 or abs(x2[i] - x2[0]) > 0.002), None)
            check(fa is not None, '%s %s: actuators never move' % (t, lab))
            v = gen.velocity(x)
            if fa is not None:
                if fa * gen.DT < 1.0:
                    n_early += 1
                else:
                    # drum reversals before the first actuator motion (>= 4, i.e. >= 2 cycles)
                    s = 0; nrev = 0
                    for i in range(fa):
                        if v[i] > 0.1 and s <= 0:
                            nrev += (s < 0); s = 1
                        elif v[i] < -0.1 and s >= 0:
                            nrev += (s > 0); s = -1
                    check(nrev >= 4, '%s %s: passive stretch has only %d reversals' % (t, lab, nrev))
                    check(fa * gen.DT >= 4.0, '%s %s: passive stretch %.2f s' % (t, lab, fa * gen.DT))
            # velocity column = smoothed derivative / 125.4 (measured-file quirk)
            check(max(abs(r[3] * gen.VEL_QUIRK - vi) for r, vi in zip(d, v)) < 1e-4, '%s %s: velocity column' % (t, lab))
            # force quantisation
            check(max(abs(f / gen.Q_F - round(f / gen.Q_F)) for f in F) < 1e-3, '%s %s: force not quantised' % (t, lab))
            # truth and noise
            R = gen.Rec(x, x1, x2, F[0])
            Ft = gen.simulate(R, shape, e['p'], e['params'])
            res = [a - b for a, b in zip(F[1:], Ft[1:])]
            m = sum(res) / len(res); sd = math.sqrt(sum((r - m) ** 2 for r in res) / len(res))
            sd_exp = math.sqrt(e['noise_kip'] ** 2 + gen.Q_F ** 2 / 12)
            check(abs(sd / sd_exp - 1) < 0.05, '%s %s: residual SD %.4f vs %.4f' % (t, lab, sd, sd_exp))
            check(abs(m) < 5 * sd_exp / math.sqrt(len(res)) + 1e-4, '%s %s: residual mean %.5f' % (t, lab, m))
            check(abs(F[0] - Ft[0]) < 1e-6 and abs(R.base[0] - F[0]) < 1e-6, '%s %s: first sample' % (t, lab))
            for a_, b_ in zip(Ft, R.base):
                num += (a_ - b_) ** 2
            cnt += n
            if use_bb:
                od = os.path.join(root, '.verify_bb', t + lab)
                r = subprocess.run([BLACKBOX, 'damper', 'predict', '--no-fit', '--config', CONFIG, '--test', path,
                                    '--out', od, '--no-figure'], capture_output=True, text=True)
                if check(r.returncode == 0, '%s %s: black box failed: %s' % (t, lab, r.stderr.strip()[-200:])):
                    rows = list(csv.DictReader(open(glob.glob(os.path.join(od, '*.csv'))[0])))
                    check(len(rows) == n, '%s %s: black box row count' % (t, lab))
                    dm = max(abs(float(q['predicted_force_kip']) - b) for q, b in zip(rows, R.base))
                    bb_worst = max(bb_worst, dm)
                    check(dm < 1e-5, '%s %s: gen.py base differs from black box by %.2e' % (t, lab, dm))
        ratio = math.sqrt(num / max(cnt, 1)) / e['noise_kip']
        check(abs(ratio - e['ratio']) <= 1e-3 * max(1.0, e['ratio']), '%s: recomputed ratio %.4f vs key %.4f' % (t, ratio, e['ratio']))
        print('%s ok-so-far=%s' % (t, not fails), flush=True)
    if use_bb:
        shutil.rmtree(os.path.join(root, '.verify_bb'), ignore_errors=True)
        notes.append('black box vs gen.py base: worst |dF| = %.2e kip over 60 records' % bb_worst)
    else:
        notes.append('black box comparison skipped')
    check(n_early == 20, 'records with actuators moving in the first second: %d (want 20 of 60)' % n_early)
    notes.append('early-actuation records: %d / 60; durations %.1f-%.1f s' % (n_early, min(durs), max(durs)))
    # ------------------------------------------------------------ determinism
    if regen:
        tmp = os.path.join(root, '.verify_regen')
        shutil.rmtree(tmp, ignore_errors=True)
        specs = {s['tid']: s for s in gen.plan()}
        for t in ('t01', 't15', 't30'):
            tid, e2 = gen.run_trial((specs[t], tmp))
            for lab in 'AB':
                check(e2['records'][lab]['sha256'] == key[t]['records'][lab]['sha256'], '%s %s: regeneration differs' % (t, lab))
            check(e2['p'] == key[t]['p'] and e2['ratio'] == key[t]['ratio'], '%s: regenerated p/ratio differ' % t)
        shutil.rmtree(tmp, ignore_errors=True)
        notes.append('regenerated t01, t15, t30: identical')
    for s in notes:
        print('note:', s)
    for f in fails:
        print('FAIL:', f)
    print('VERIFY PASS' if not fails else 'VERIFY FAIL')
    return 0 if not fails else 1


if __name__ == '__main__':
    sys.exit(main())
