#!/usr/bin/env python3
"""Checks the blind20 set: format, noise SD, ratios, base model == black box on all records,
determinism (regenerates everything in a temporary folder and compares byte for byte).
Last line: VERIFY PASS or VERIFY FAIL."""
import csv, hashlib, json, math, os, shutil, struct, subprocess, sys, tempfile, time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import gen  # noqa: E402

BB = '/work/runs/binhead/hybridsim'
CFG = '/work/runs/brfd-semiactive.yaml'
MEASURED = os.path.join(gen.SRC, 'harmonic0.015forward.json')

fails = []
notes = []


def check(cond, msg):
    if not cond:
        fails.append(msg)
    return cond


def is_f32(x):
    return struct.unpack('f', struct.pack('f', x))[0] == x


def on_grid(x, q, o, tol=1e-9):
    return abs(x - (o + q * round((x - o) / q))) < tol


def sha(path):
    return hashlib.sha256(open(path, 'rb').read()).hexdigest()


def main():
    t0 = time.time()
    key = json.load(open(os.path.join(ROOT, 'key.json')))
    trials = ['t%02d' % i for i in range(1, 31)]
    check(sorted(key) == trials, 'key.json must list t01..t30')

    # ---------------------------------------------------------------- determinism
    tmp = tempfile.mkdtemp(prefix='blind20_verify_')
    try:
        key2, results = gen.generate(tmp, verbose=False, write=True)
        for t in trials:
            for r in 'AB':
                a = os.path.join(ROOT, 'cases', t, r + '.json')
                b = os.path.join(tmp, 'cases', t, r + '.json')
                check(os.path.exists(a), 'missing ' + a)
                if os.path.exists(a):
                    check(sha(a) == sha(b), 'not deterministic: %s/%s' % (t, r))
        check(sha(os.path.join(ROOT, 'key.json')) == sha(os.path.join(tmp, 'key.json')), 'key.json not deterministic')
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    extra = sorted(set(os.listdir(os.path.join(ROOT, 'cases'))) - set(trials))
    check(not extra, 'unexpected entries in cases/: %s' % extra)
    notes.append('determinism: regenerated in %.1f s, all 60 records + key identical' % (time.time() - t0))

    # ---------------------------------------------------------------- design counts
    cats = {}
    ns = {'weak': 0, 'strong': 0, 'none': 0}
    for t in trials:
        k = key[t]
        ns[k['strength']] += 1
        if k['category'] != 'none':
            cats.setdefault(k['category'], []).append(k['shape'])
        check(0.02 <= k['noise_kip'] <= 0.06, '%s noise SD out of range' % t)
    check(ns == {'weak': 12, 'strong': 12, 'none': 6}, 'strength counts %s' % ns)
    check(len(cats) == 8 and all(len(v) == 3 and len(set(v)) == 3 for v in cats.values()),
          'need 8 categories x 3 distinct shapes: %s' % cats)
    allshapes = [s for v in cats.values() for s in v]
    check(len(set(allshapes)) == 24, 'shapes must all differ')

    # ---------------------------------------------------------------- per record
    ref = json.load(open(MEASURED))
    ref_keys = [k for k in ref]
    early = 0
    maxdiff = 0.0
    bbdir = tempfile.mkdtemp(prefix='blind20_bb_')
    try:
        for t in trials:
            k = key[t]
            res = results[t]
            sd = k['noise_kip']
            resid, num, nall = [], 0.0, 0
            for ri, r in enumerate('AB'):
                path = os.path.join(ROOT, 'cases', t, r + '.json')
                doc = json.load(open(path))
                check(list(doc.keys()) == ref_keys, '%s/%s keys differ from the measured files' % (t, r))
                for kk in ref_keys:
                    if kk != 'data':
                        check(doc[kk] == ref[kk], '%s/%s %s differs' % (t, r, kk))
                D = doc['data']
                n = len(D)
                dur = (n - 1) * gen.DT
                check(6.5 <= dur <= 25.0 + 1e-9, '%s/%s duration %.2f s' % (t, r, dur))
                check(all(len(row) == 8 for row in D), '%s/%s rows must have 8 columns' % (t, r))
                bad_t = [i for i, row in enumerate(D) if row[0] != i * gen.DT or
                         (i % 1024 == 0) != isinstance(row[0], int)]
                check(not bad_t, '%s/%s time column' % (t, r))
                flat = [c for row in D for c in row]
                check(all(isinstance(c, (int, float)) and math.isfinite(c) for c in flat), '%s/%s non-finite' % (t, r))
                x = [row[1] for row in D]
                F = [row[2] for row in D]
                check(all(on_grid(a, gen.QX, gen.OX) for a in x), '%s/%s displacement not quantised' % (t, r))
                check(all(on_grid(a, gen.QF, gen.OF) for a in F), '%s/%s force not quantised' % (t, r))
                check(all(is_f32(row[3]) and is_f32(row[4]) and is_f32(row[5]) for row in D),
                      '%s/%s velocity/actuator columns must be float32 values' % (t, r))
                check(all(on_grid(row[6], gen.QL1, gen.OL1, 1e-7) and on_grid(row[7], gen.QL2, gen.OL2, 1e-7) for row in D),
                      '%s/%s actuator forces not quantised' % (t, r))
                # velocity column quirk ~1/125 of dx/dt
                dd = [(x[i + 1] - x[i - 1]) / (2 * gen.DT) for i in range(1, n - 1)]
                vc = [D[i][3] for i in range(1, n - 1)]
                fac = sum(a * a for a in dd) / max(1e-12, sum(a * b for a, b in zip(dd, vc)))
                check(120 < fac < 131, '%s/%s velocity column factor %.1f' % (t, r, fac))
                # final rest >= 1.5 s, initial rest: range below 3 mil (measured rests: 2-3 mil of
                # jitter/drift) and 0.1 s-averaged drum speed below 0.02 in/s
                m = int(1.5 * 1024)
                vsm = gen.moving_average(gen.drum_velocity(x), 50)
                tail = x[-m:]
                check(max(tail) - min(tail) < 3e-3 and max(abs(a) for a in vsm[-m:]) < 0.02,
                      '%s/%s no 1.5 s final rest (range %.2g in)' % (t, r, max(tail) - min(tail)))
                h = int(0.25 * 1024)
                head = x[:h]
                check(max(head) - min(head) < 3e-3 and max(abs(a) for a in vsm[:h]) < 0.02,
                      '%s/%s does not start at rest' % (t, r))
                check(max(abs(a) for a in x) < 1.3, '%s/%s drum displacement too large' % (t, r))
                a1 = [row[4] for row in D]
                a2 = [row[5] for row in D]
                check(max(abs(a - a1[0]) for a in a1) < 0.08 and max(abs(a - a2[0]) for a in a2) < 0.08,
                      '%s/%s actuator travel too large' % (t, r))
                mv = next((i for i in range(n) if abs(a1[i] - a1[0]) > 0.002 or abs(a2[i] - a2[0]) > 0.002), None)
                if mv is not None and mv * gen.DT < 1.0:
                    early += 1
                check((mv is not None and mv * gen.DT < 1.0) == k['records'][r]['actuators_move_in_first_second'],
                      '%s/%s early-motion flag in key' % (t, r))
                # black box
                out = os.path.join(bbdir, t + r)
                p = subprocess.run([BB, 'damper', 'predict', '--no-fit', '--config', CFG, '--test', path,
                                    '--out', out, '--no-figure'], capture_output=True, text=True)
                if not check(p.returncode == 0, '%s/%s black box failed: %s' % (t, r, p.stderr[-300:])):
                    continue
                rows = list(csv.DictReader(open(os.path.join(out, r + '_predict.csv'))))
                pb = [float(q['predicted_force_kip']) for q in rows]
                rec = res['recs'][ri]
                check(len(pb) == rec.n, '%s/%s black box length' % (t, r))
                dmax = max(abs(a - b) for a, b in zip(pb, rec.Fbase))
                maxdiff = max(maxdiff, dmax)
                check(dmax < 1e-6, '%s/%s base model differs from black box by %.3g kip' % (t, r, dmax))
                check(F == res['Ffile'][ri], '%s/%s force column differs from regenerated' % (t, r))
                truth = res['truth'][ri]
                resid += [F[i] - truth[i] for i in range(1, n)]
                num += sum((a - b) ** 2 for a, b in zip(truth, pb))
                nall += n
                if k['category'] == 'none':
                    check(truth == rec.Fbase, '%s none trial truth != base' % t)
            if not resid:
                continue
            mu = sum(resid) / len(resid)
            s_hat = math.sqrt(sum((a - mu) ** 2 for a in resid) / (len(resid) - 1))
            check(abs(s_hat / sd - 1) < 0.03, '%s noise SD %.4f vs %.4f' % (t, s_hat, sd))
            check(abs(mu) < 4 * sd / math.sqrt(len(resid)) + 2e-4, '%s noise mean %.4g' % (t, mu))
            ratio_bb = math.sqrt(num / nall) / sd
            if k['category'] == 'none':
                check(ratio_bb < 1e-3, '%s none ratio %.3g' % (t, ratio_bb))
            else:
                check(abs(ratio_bb / k['ratio'] - 1) < 1e-3, '%s ratio vs black box %.4f / key %.4f' % (t, ratio_bb, k['ratio']))
                check(abs(k['ratio'] / k['target_ratio'] - 1) < 0.01, '%s ratio %.3f vs target %.3f' % (t, k['ratio'], k['target_ratio']))
                lo, hi = (2.7, 3.8) if k['strength'] == 'weak' else (8.5, 11.5)
                check(lo <= k['target_ratio'] <= hi, '%s target %.3f outside %s range' % (t, k['target_ratio'], k['strength']))
                check(lo * 0.99 <= ratio_bb <= hi * 1.01, '%s ratio %.3f outside %s range' % (t, ratio_bb, k['strength']))
            notes.append('%s sd=%.4f est=%.4f ratio(bb)=%.3f' % (t, sd, s_hat, ratio_bb))
    finally:
        shutil.rmtree(bbdir, ignore_errors=True)
    check(15 <= early <= 25, 'records with actuator motion in the first second: %d of 60' % early)
    notes.append('records with actuator motion in the first second: %d of 60' % early)
    notes.append('max |base - black box| over all 60 records: %.3g kip' % maxdiff)
    for s in notes:
        print(s)
    for f in fails:
        print('FAIL:', f)
    print('verify time %.1f s' % (time.time() - t0))
    print('VERIFY PASS' if not fails else 'VERIFY FAIL')


if __name__ == '__main__':
    main()
