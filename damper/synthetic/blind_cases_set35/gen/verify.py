#!/usr/bin/env python3
"""blind35 self-check (Python 3 standard library only).

  * layout: every case record has the measured semi-active layout (header keys and values,
    8 numeric columns, 1024 Hz time base, units, quantisation of the force column, float32
    displacement/actuator columns, velocity-column quirk), 9-25 s, |drum| <= 1.3 in;
  * the black box (`hybridsim damper predict --no-fit`) accepts every record;
  * 'none' trials: measured force == quantise(black box + the trial's noise sequence) sample by
    sample (k >= 1; sample 0 is the anchor of the model's initial state), residual SD == noise SD;
  * effect trials: ratio = RMS over both records of (F_true - F_base)/noise, with
    F_true = measured - noise (quantisation error only) and F_base = black box, equals the key's
    ratio and lies in its band (strong 8.5-11.5, weak 2.7-3.8);
  * key: 30 trials, 6 none, 3 different shapes per category, 12 strong + 12 weak, noise in
    [0.02, 0.06] kip.
Last line: VERIFY PASS or VERIFY FAIL.
"""
import csv, json, math, os, random, struct, subprocess, sys, tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = '/work/shared/data/brfd/semiactive'
BIN = '/work/runs/binhead/hybridsim'
CFG = '/work/main/configs/brfd-semiactive.yaml'
Q_FORCE = 0.00080087996
DT = 1.0 / 1024.0
CATS = ['backlash', 'residual_static', 'transition_shape', 'velocity', 'actuator_lag',
        'self_energizing', 'pretension', 'asymmetry']

fails = []
notes = []


def check(cond, msg):
    if not cond:
        fails.append(msg)
    return cond


def f32(x):
    return struct.unpack('f', struct.pack('f', x))[0]


def qforce(F):
    return round(F / Q_FORCE) * Q_FORCE


def smoothed_derivative(x):
    n = len(x)
    d = [0.0] * n
    d[0] = (x[1] - x[0]) / DT
    d[-1] = (x[-1] - x[-2]) / DT
    for i in range(1, n - 1):
        d[i] = (x[i + 1] - x[i - 1]) / (2 * DT)
    cs = [0.0]
    for a in d:
        cs.append(cs[-1] + a)
    return [(cs[min(n - 1, i + 7) + 1] - cs[max(0, i - 7)]) / (min(n - 1, i + 7) - max(0, i - 7) + 1) for i in range(n)]


def run_bb(path, outdir):
    p = subprocess.run([BIN, 'damper', 'predict', '--config', CFG, '--no-fit', '--test', path,
                        '--out', outdir, '--no-figure'], capture_output=True, text=True)
    if p.returncode != 0:
        return None, p.stdout + p.stderr
    stem = os.path.basename(path)[:-5]
    rows = list(csv.DictReader(open(os.path.join(outdir, stem + '_predict.csv'))))
    return [float(r['predicted_force_kip']) for r in rows], p.stdout


def main():
    # ---------------- reference layout from the measured files ----------------
    ref = json.load(open(os.path.join(DATA, 'harmonic0.015forward.json')))
    ref_keys = list(ref.keys())
    ref_hdr = {k: v for k, v in ref.items() if k != 'data'}
    ref_xp = set()
    for fn in os.listdir(DATA):
        if fn.endswith('.json'):
            r0 = json.load(open(os.path.join(DATA, fn)))['data'][0]
            ref_xp.add((r0[4], r0[5]))
    key = json.load(open(os.path.join(ROOT, 'key.json')))

    # ---------------- key structure ----------------
    check(sorted(key) == ['t%02d' % i for i in range(1, 31)], 'key must hold t01..t30')
    cats = [e['category'] for e in key.values()]
    check(cats.count('none') == 6, '6 none trials')
    for c in CATS:
        shapes = [e['shape'] for e in key.values() if e['category'] == c]
        check(len(shapes) == 3 and len(set(shapes)) == 3, 'category %s: 3 different shapes (%s)' % (c, shapes))
    strengths = [e['strength'] for e in key.values() if e['category'] != 'none']
    check(strengths.count('strong') == 12 and strengths.count('weak') == 12, '12 strong + 12 weak')
    for t, e in key.items():
        check(0.02 <= e['noise_kip'] <= 0.06, '%s noise %.4f outside [0.02, 0.06]' % (t, e['noise_kip']))

    tmp = tempfile.mkdtemp(prefix='blind35_verify_')
    worst_none = 0
    summary = []
    tot_exact = [0, 0]
    worst_rel = 0.0
    for t in sorted(key):
        e = key[t]
        sd = e['noise_kip']
        ss, cnt = 0.0, 0
        moved = []
        for lab in 'AB':
            path = os.path.join(ROOT, 'cases', t, lab + '.json')
            ok = check(os.path.exists(path), '%s/%s missing' % (t, lab))
            if not ok:
                continue
            d = json.load(open(path))
            # -------- layout --------
            check(list(d.keys()) == ref_keys, '%s/%s header keys %s' % (t, lab, list(d.keys())))
            for k, v in ref_hdr.items():
                check(d.get(k) == v, '%s/%s header %s=%r' % (t, lab, k, d.get(k)))
            D = d['data']
            n = len(D)
            dur = (n - 1) * DT
            check(9.0 <= dur <= 25.0, '%s/%s duration %.2f s' % (t, lab, dur))
            check(all(len(r) == 8 for r in D), '%s/%s rows must have 8 columns' % (t, lab))
            check(all(all(isinstance(a, (int, float)) and a == a and abs(a) != float('inf') for a in r) for r in D),
                  '%s/%s non-numeric/NaN value' % (t, lab))
            check(all(r[0] == k * DT for k, r in enumerate(D)), '%s/%s time column' % (t, lab))
            check(all(isinstance(r[0], int) == (r[0] == int(r[0])) for r in D), '%s/%s integer times as ints' % (t, lab))
            F = [r[2] for r in D]
            check(all(abs(a / Q_FORCE - round(a / Q_FORCE)) < 1e-6 for a in F), '%s/%s force not on the measured grid' % (t, lab))
            x = [r[1] for r in D]
            check(all(f32(a) == a for a in x), '%s/%s displacement not float32' % (t, lab))
            check(max(abs(a) for a in x) <= 1.3, '%s/%s |drum| > 1.3 in' % (t, lab))
            x1 = [r[4] for r in D]
            x2 = [r[5] for r in D]
            check(all(f32(a) == a for a in x1 + x2), '%s/%s actuator positions not float32' % (t, lab))
            check((x1[0], x2[0]) in ref_xp, "%s/%s x' differ from the measured tests" % (t, lab))
            dev = max(max(abs(a - x1[0]) for a in x1), max(abs(a - x2[0]) for a in x2))
            check(dev <= 0.06, '%s/%s actuator travel %.3f in' % (t, lab, dev))
            moved.append(dev > 0.002)
            vs = smoothed_derivative(x)
            check(max(abs(a) for a in vs) <= 5.0, '%s/%s drum speed %.2f in/s' % (t, lab, max(abs(a) for a in vs)))
            vc = [r[3] for r in D]
            num = sum(a * b for a, b in zip(vs[:-6], vc[6:]))
            den = sum(a * a for a in vs[:-6])
            ratio_col = den / num if num else 0
            check(120 < ratio_col < 131, '%s/%s velocity column ratio %.1f' % (t, lab, ratio_col))
            still = sum(1 for a in vs if abs(a) < 0.05) / n
            check(0.1 < still < 0.8, '%s/%s rest fraction %.2f' % (t, lab, still))
            check(all(r[6] > 0 and r[7] > 0 for r in D), '%s/%s actuator forces must be positive' % (t, lab))
            # -------- black box --------
            bb, msg = run_bb(path, os.path.join(tmp, t + lab))
            if not check(bb is not None and len(bb) == n, '%s/%s black box failed: %s' % (t, lab, msg[-300:] if msg else '')):
                continue
            rs = random.Random(e['records'][lab]['noise_seed'])
            nz = [rs.gauss(0.0, sd) for _ in range(n)]
            check(abs(F[0] - qforce(e['records'][lab]['F0_kip'])) < 1e-12, '%s/%s anchor sample' % (t, lab))
            if e['category'] == 'none':
                bad = 0
                exact = 0
                res = []
                for k in range(1, n):
                    q = qforce(bb[k] + nz[k])
                    if abs(F[k] - q) < 1e-9:
                        exact += 1
                    elif abs(F[k] - q) > Q_FORCE * 1.01:
                        bad += 1
                    res.append(F[k] - bb[k])
                    worst_none = max(worst_none, abs(F[k] - bb[k] - nz[k]))
                check(bad == 0, '%s/%s none record differs from black box + noise at %d samples' % (t, lab, bad))
                check(exact >= 0.999 * (n - 1), '%s/%s only %d/%d samples exact' % (t, lab, exact, n - 1))
                tot_exact[0] += exact
                tot_exact[1] += n - 1
                mu = sum(res) / len(res)
                sdr = math.sqrt(sum((a - mu) ** 2 for a in res) / len(res))
                check(abs(sdr / sd - 1) < 0.03 and abs(mu) < 0.1 * sd,
                      '%s/%s residual mean %.4f sd %.4f vs noise %.4f' % (t, lab, mu, sdr, sd))
                # F0 residual
                check(abs(F[0] - bb[0]) < 0.02, '%s/%s first sample residual %.4f' % (t, lab, F[0] - bb[0]))
            for k in range(n):
                ss += (F[k] - nz[k] - bb[k]) ** 2 if k > 0 else (F[0] - bb[0]) ** 2
                cnt += 1
        check(any(moved), '%s: no actuator motion in either record' % t)
        ratio = math.sqrt(ss / cnt) / sd if cnt else float('nan')
        if e['category'] == 'none':
            summary.append('%s none              ratio(bb) %.3f' % (t, ratio))
            check(ratio < 0.2, '%s none ratio %.3f' % (t, ratio))
        else:
            lo, hi = (8.5, 11.5) if e['strength'] == 'strong' else (2.7, 3.8)
            rel = abs(ratio - e['ratio']) / e['ratio']
            worst_rel = max(worst_rel, abs(ratio - e['target_ratio']) / e['target_ratio'])
            check(lo <= ratio <= hi, '%s ratio %.3f outside %s band' % (t, ratio, e['strength']))
            check(rel < 0.01, '%s ratio %.4f vs key %.4f' % (t, ratio, e['ratio']))
            check(abs(ratio - e['target_ratio']) / e['target_ratio'] < 0.01,
                  '%s ratio %.4f vs target %.4f' % (t, ratio, e['target_ratio']))
            nm, lo_b, hi_b = e['amplitude_name'], e['amplitude_bounds'][0], e['amplitude_bounds'][1]
            check(lo_b <= e['params'][nm] <= hi_b, '%s amplitude outside plausible bounds' % t)
            summary.append('%s %-6s target %.3f  ratio(bb) %.3f  key %.3f' % (t, e['strength'], e['target_ratio'], ratio, e['ratio']))
    for s in summary:
        print(s)
    print('largest |measured - black box - noise| over none records: %.2e kip (quantisation %.2e)' % (worst_none, Q_FORCE / 2))
    print('none records: %d of %d samples (k >= 1) exactly equal to q(black box + noise)' % tuple(tot_exact))
    print('effect trials: largest |ratio(black box) - target| / target = %.3f %%' % (100 * worst_rel))
    if fails:
        for f in fails[:50]:
            print('FAIL:', f)
        print('VERIFY FAIL')
        return 1
    print('%d records checked' % (2 * len(key)))
    print('VERIFY PASS')
    return 0


if __name__ == '__main__':
    sys.exit(main())
