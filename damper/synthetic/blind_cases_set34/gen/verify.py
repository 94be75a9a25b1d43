#!/usr/bin/env python3
"""blind34 self-check.  Python 3 standard library only.  Last line: VERIFY PASS or VERIFY FAIL.

1. layout: every record has the measured semi-active layout (same keys in the same order, same header
   values, 8 columns, 1024 Hz time base, same number formatting, quantisation grids, ranges, 9-25 s);
2. 'none' records: the force column equals quant(black box + the trial's noise) sample by sample, where
   the black box is `hybridsim damper predict --no-fit` run on the written record itself;
3. effect records: the force column equals quant(F_true + noise) and the strength ratio
   RMS(F_true - F_blackbox) / noise SD over both records equals the key's ratio and its target;
4. the plan: 30 trials, 6 none, 3 per category with 3 different shapes, 12 strong / 12 weak, ranges.
"""
import csv, json, math, os, subprocess, sys, tempfile, statistics

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import gen  # noqa: E402

ROOT = gen.ROOT
BIN = '/work/runs/binhead/hybridsim'
CFG = '/work/main/configs/brfd-semiactive.yaml'
fails = []


def check(cond, msg):
    if not cond:
        fails.append(msg)
        print('  FAIL:', msg)
    return cond


def on_grid(v, L, off, tol=0.02):
    u = v / L - off
    return abs(u - round(u)) < tol


def blackbox(path, outdir):
    r = subprocess.run([BIN, 'damper', 'predict', '--config', CFG, '--no-fit', '--test', path,
                        '--out', outdir, '--no-figure'], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError('black box failed on %s: %s' % (path, r.stderr[-500:]))
    name = os.path.splitext(os.path.basename(path))[0]
    rows = list(csv.DictReader(open(os.path.join(outdir, name + '_predict.csv'))))
    return [float(q['predicted_force_kip']) for q in rows], r.stdout.strip().splitlines()


def main():
    key = json.load(open(os.path.join(ROOT, 'key.json')))
    ref_raw = open(os.path.join(gen.DATA, gen.TEMPLATES[0] + '.json')).read()
    ref = json.loads(ref_raw)
    ref_keys = list(ref.keys())
    tmp = tempfile.mkdtemp(prefix='blind34_verify_')

    # ---------------------------------------------------------------- plan
    print('[plan]')
    tids = ['t%02d' % i for i in range(1, 31)]
    check(sorted(key) == tids, 'key has t01..t30')
    cats = {}
    for t in tids:
        e = key[t]
        cats.setdefault(e['category'], []).append(e)
        check(0.02 <= e['noise_kip'] <= 0.06, '%s noise %.4f in [0.02, 0.06]' % (t, e['noise_kip']))
        check(os.path.isfile(os.path.join(ROOT, 'cases', t, 'A.json')) and
              os.path.isfile(os.path.join(ROOT, 'cases', t, 'B.json')), '%s has A.json and B.json' % t)
    check(len(cats.get('none', [])) == 6, '6 none trials')
    for c in gen.CATS:
        es = cats.get(c, [])
        check(len(es) == 3, '%s has 3 trials' % c)
        check(len(set(e['shape'] for e in es)) == 3, '%s: 3 different shapes' % c)
    st = [e['strength'] for e in key.values() if e['category'] != 'none']
    check(st.count('strong') == 12 and st.count('weak') == 12, '12 strong / 12 weak')
    for t in tids:
        e = key[t]
        if e['category'] == 'none':
            continue
        lo, hi = (8.5, 11.5) if e['strength'] == 'strong' else (2.7, 3.8)
        check(lo <= e['ratio_target'] <= hi, '%s target %.3f in [%g, %g]' % (t, e['ratio_target'], lo, hi))
        a = e['params'][e['strength_param']]
        b = e['strength_bounds']
        check(b[0] < a <= b[1], '%s %s = %.4g inside plausible bounds %s' % (t, e['strength_param'], a, b))

    # ---------------------------------------------------------------- records
    worst = {}
    for t in tids:
        e = key[t]
        shape = None if e['shape'] == 'none' else e['shape']
        p = dict(e['params'])
        amp = p.pop(e['strength_param']) if e['strength_param'] else 0.0
        sd = e['noise_kip']
        ssum, nsum = 0.0, 0
        line = []
        for name in ('A', 'B'):
            path = os.path.join(ROOT, 'cases', t, name + '.json')
            raw = open(path).read()
            d = json.loads(raw)
            rows = d['data']
            n = len(rows)
            tag = '%s/%s' % (t, name)
            # -- layout
            check(list(d.keys()) == ref_keys, tag + ' keys/order equal the measured files')
            for k in ref_keys[1:]:
                check(d[k] == ref[k] and type(d[k]) is type(ref[k]), tag + ' header %s' % k)
            check(all(len(r) == 8 for r in rows), tag + ' 8 columns')
            check(all(r[0] == k / 1024.0 for k, r in enumerate(rows)) and isinstance(rows[0][0], int),
                  tag + ' time = k/1024 s, first stamp written as 0')
            dur = (n - 1) / 1024.0
            check(9.0 <= dur <= 25.0, tag + ' duration %.2f s in [9, 25]' % dur)
            check(gen.dump_record(rows) == raw, tag + ' number formatting identical to the measured files')
            x = [r[1] for r in rows]
            F = [r[2] for r in rows]
            x1 = [r[4] for r in rows]
            x2 = [r[5] for r in rows]
            check(max(abs(a) for a in x) <= 1.3, tag + ' drum within +-1.3 in')
            check(all(on_grid(a, gen.LX, gen.OX, 0.05) for a in x), tag + ' displacement on the measured grid')
            check(all(on_grid(a, gen.LF, 0.0, 0.01) for a in F), tag + ' force on the measured LSB grid')
            check(all(gen.f32(a) == a and on_grid(a, gen.LA, 0.0, 0.05) for a in x1 + x2),
                  tag + ' actuator positions float32 on the measured grid')
            check(all(on_grid(r[6], gen.LA1, gen.OA1, 0.05) and on_grid(r[7], gen.LA2, gen.OA2, 0.05) for r in rows),
                  tag + ' actuator forces on the measured grids')
            check(all(0.3 <= a <= 1.2 for a in x1 + x2), tag + ' actuators inside 0.3..1.2 in')
            check(max(abs(a - x1[0]) for a in x1) < 0.06 and max(abs(a - x2[0]) for a in x2) < 0.06,
                  tag + ' actuator travel < 0.06 in')
            v = gen.derive_velocity(x)
            check(max(abs(a) for a in v) <= 6.5, tag + ' drum speed <= 6.5 in/s (max %.2f)' % max(abs(a) for a in v))
            num = sum(a * r[3] for a, r in zip(v, rows))
            den = sum(a * a for a in v)
            sc = den / num if num else 0
            check(120 < sc < 131, tag + ' velocity column = d(disp)/dt / %.1f (measured quirk 125.4)' % sc)
            # -- black box
            Fbb, msg = blackbox(path, tmp)
            check(len(Fbb) == n, tag + ' black box length')
            rec = dict(x=x, x1=x1, x2=x2, v=v, F0=F[0], n=n)
            Fb = gen.simulate(rec)
            dmax = max(abs(a - b) for a, b in zip(Fb, Fbb))
            check(dmax < 1e-6, tag + ' base re-implementation equals the black box (max |diff| %.2e kip)' % dmax)
            Ft = gen.simulate(rec, shape, p, amp) if shape else Fbb
            nz = gen.noise_seq(t, name, n, sd)
            mism = [k for k in range(1, n) if gen.q_force(Ft[k] + nz[k]) != F[k]]
            far = [k for k in mism if abs(gen.q_force(Ft[k] + nz[k]) - F[k]) > 1.5 * gen.LF]
            what = 'black box' if not shape else 'F_true'
            check(len(mism) <= max(2, n // 5000) and not far,
                  tag + ' force = quant(%s + noise) (%d boundary mismatches of %d, %d beyond 1 LSB)'
                  % (what, len(mism), n - 1, len(far)))
            check(abs(F[0] - (Fbb[0] - gen.S2 * v[0])) < 1e-6, tag + ' first sample = initial state of the black box')
            res = [F[k] - Fbb[k] for k in range(1, n)]
            if not shape:
                sdr = statistics.pstdev(res)
                expect = math.sqrt(sd * sd + gen.LF ** 2 / 12)
                check(abs(sdr / expect - 1) < 0.04 and abs(statistics.fmean(res)) < 4 * sd / math.sqrt(n),
                      tag + ' residual vs black box: sd %.4f (noise %.4f), mean %.5f' % (sdr, sd, statistics.fmean(res)))
                worst[tag] = sdr / expect
            ssum += sum((a - b) ** 2 for a, b in zip(Ft, Fbb))
            nsum += n
            line.append('%s %.1fs' % (name, dur))
        if shape:
            ratio = math.sqrt(ssum / nsum) / sd
            ok1 = check(abs(ratio / e['ratio'] - 1) < 0.002, '%s ratio %.4f equals key ratio %.4f' % (t, ratio, e['ratio']))
            ok2 = check(abs(ratio / e['ratio_target'] - 1) < 0.01, '%s ratio %.4f hits target %.4f' % (t, ratio, e['ratio_target']))
            lo, hi = (8.5, 11.5) if e['strength'] == 'strong' else (2.7, 3.8)
            ok3 = check(lo * 0.995 <= ratio <= hi * 1.005, '%s ratio %.3f inside the %s range' % (t, ratio, e['strength']))
            print('[%s] %-16s %-32s %-6s ratio %.3f (target %.3f) noise %.4f  %s  %s' % (
                t, e['category'], e['shape'], e['strength'], ratio, e['ratio_target'], sd, ', '.join(line),
                'ok' if ok1 and ok2 and ok3 else 'BAD'))
        else:
            print('[%s] none: records = black box + noise  %s' % (t, ', '.join(line)))
    print('%d checks failed' % len(fails))
    print('VERIFY PASS' if not fails else 'VERIFY FAIL')


if __name__ == '__main__':
    main()
