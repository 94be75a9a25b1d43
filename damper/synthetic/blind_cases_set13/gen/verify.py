#!/usr/bin/env python3
"""Checks of blind set 13 (run from anywhere):  python3 gen/verify.py

 1. format: 30 trials t01..t30, A.json / B.json with the keys, 8 columns, dt and sampling rate of the
    measured semi-active files; time column = i*dt; 6-26 s; A and B from different source tests;
 2. rest: every record ends with >= 1.5 s in which drum displacement and both actuator positions
    (and the load cells) are exactly constant;
 3. base model: `hybridsim damper predict --no-fit` run on (a) the noise-free force of every 'none'
    trial (the record with its force column replaced by the base-model force) and (b) every record
    as written (predict only uses the first force sample, which is noise-free): its predicted force
    must equal this generator's base model to the CSV's printed precision;
 4. ratios: RMS(F_effect - F_base)/noise over both records, recomputed from key.json's parameters,
    within 1 % of the target and equal to key.json's achieved_ratio;
 5. noise: recorded force minus the re-simulated true force has mean ~0 and SD ~ noise_kip;
 6. design counts: 6 none, 8 categories x 3 distinct shapes, 12 weak / 12 strong, drawn ranges.
"""
import csv, json, math, os, subprocess, sys, tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import gen  # noqa: E402

TOOL = '/work/runs/bin25/hybridsim'
CONFIG = '/work/runs/brfd-semiactive.yaml'
KEYS = ['data', 'dt', 'sampling freq', 'displacement units', 'time units', 'friction force units',
        'actuator force units']


def predict(path, outdir):
    r = subprocess.run([TOOL, 'damper', 'predict', '--no-fit', '--config', CONFIG, '--test', path,
                        '--out', outdir, '--no-figure'], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(r.stdout + r.stderr)
    stem = os.path.splitext(os.path.basename(path))[0]
    rows = list(csv.reader(open(os.path.join(outdir, stem + '_predict.csv'))))[1:]
    return [float(q[6]) for q in rows], r.stdout.strip().splitlines()[-1]


def main():
    key = json.load(open(os.path.join(ROOT, 'key.json')))
    fails = []
    err_base_clean = 0.0
    err_base_rec = 0.0
    err_ratio = 0.0
    err_ratio_key = 0.0
    noise_dev = 0.0
    min_rest = 1e9
    tmp = tempfile.mkdtemp(prefix='blind13v_')
    ids = ['t%02d' % k for k in range(1, 31)]
    if sorted(key) != ids:
        fails.append('key ids')
    cats = {}
    for tid in ids:
        k = key[tid]
        d = os.path.join(ROOT, 'cases', tid)
        recs, fbase, forces = [], [], []
        for lab in ('A', 'B'):
            path = os.path.join(d, lab + '.json')
            rec, raw = gen.load_record(path)
            if list(raw.keys()) != KEYS or raw['dt'] != gen.DT or raw['sampling freq'] != 1024:
                fails.append(tid + lab + ' keys/dt')
            if any(len(r) != 8 for r in raw['data']):
                fails.append(tid + lab + ' columns')
            n = rec['n']
            if any(rec['t'][i] != i * gen.DT for i in range(n)):
                fails.append(tid + lab + ' time column')
            dur = (n - 1) * gen.DT
            if not (6.0 <= dur <= 26.0):
                fails.append(tid + lab + ' duration %.2f' % dur)
            # final exact rest
            cols = [rec['x'], rec['a1'], rec['a2'], rec['L1'], rec['L2']]
            j = n - 1
            while j > 0 and all(c[j - 1] == c[n - 1] for c in cols):
                j -= 1
            rest = (n - 1 - j) * gen.DT
            min_rest = min(min_rest, rest)
            if rest < 1.5:
                fails.append(tid + lab + ' final rest %.3f s' % rest)
            fb = gen.sim_base(rec)
            # (b) damper predict on the record as written
            pf, _ = predict(path, tmp)
            e = max(abs(a - b) / max(1.0, abs(b)) for a, b in zip(pf, fb))
            err_base_rec = max(err_base_rec, e)
            # (a) noise-free force of the none trials
            if k['category'] == 'none':
                clean = os.path.join(tmp, 'clean.json')
                gen.write_record(clean, rec, fb)
                pc, _ = predict(clean, tmp)
                e = max(abs(a - b) / max(1.0, abs(b)) for a, b in zip(pc, fb))
                err_base_clean = max(err_base_clean, e)
            recs.append(rec); fbase.append(fb); forces.append(rec['force'])
        if k['records']['A']['source'] == k['records']['B']['source']:
            fails.append(tid + ' A and B from the same source')
        # truth
        if k['category'] == 'none':
            ftrue = fbase
        else:
            e = dict(k['params']); e['shape'] = k['shape']; e['p'] = k['p']
            ftrue = [gen.simulate(r, e) for r in recs]
            ratio = gen.ratio_of(recs, fbase, e, k['noise_kip'])
            err_ratio = max(err_ratio, abs(ratio / k['target_ratio'] - 1))
            err_ratio_key = max(err_ratio_key, abs(ratio - k['achieved_ratio']))
            if abs(ratio / k['target_ratio'] - 1) > 0.01:
                fails.append(tid + ' ratio %.4f vs target %.4f' % (ratio, k['target_ratio']))
            lo, hi = (2.7, 3.8) if k['strength'] == 'weak' else (8.5, 11.5)
            if not lo <= k['target_ratio'] <= hi:
                fails.append(tid + ' target range')
        res = []
        for fr, ft in zip(forces, ftrue):
            if abs(fr[0] - ft[0]) > 1e-7:
                fails.append(tid + ' first force sample')
            res.extend(a - b for a, b in zip(fr[1:], ft[1:]))
        m = sum(res) / len(res)
        sdv = math.sqrt(sum((q - m) ** 2 for q in res) / len(res))
        dev = abs(sdv / k['noise_kip'] - 1)
        noise_dev = max(noise_dev, dev)
        if dev > 0.03 or abs(m) > 4 * k['noise_kip'] / math.sqrt(len(res)):
            fails.append(tid + ' noise sd %.4f (key %.4f) mean %.4f' % (sdv, k['noise_kip'], m))
        if not 0.02 <= k['noise_kip'] <= 0.06:
            fails.append(tid + ' noise range')
        cats.setdefault(k['category'], set()).add((k['shape'], k['strength']))
        print('%s ok-so-far  base err %.1e' % (tid, err_base_rec), flush=True)
    # design counts
    if len([t for t in key.values() if t['category'] == 'none']) != 6:
        fails.append('none count')
    eff = [t for t in key.values() if t['category'] != 'none']
    if len(eff) != 24 or len({t['category'] for t in eff}) != 8:
        fails.append('effect count')
    for c in {t['category'] for t in eff}:
        shapes = [t['shape'] for t in eff if t['category'] == c]
        if len(shapes) != 3 or len(set(shapes)) != 3:
            fails.append('shapes of ' + c)
    if sum(t['strength'] == 'strong' for t in eff) != 12:
        fails.append('strong count')
    tol = 5.1e-8  # CSV precision: 8 significant digits -> |err| <= 5e-8 * max(1, |F|)
    if err_base_clean > tol or err_base_rec > tol:
        fails.append('base-model mismatch %.2e / %.2e' % (err_base_clean, err_base_rec))
    if err_ratio_key > 1e-3:
        fails.append('achieved ratio differs from key by %.2e' % err_ratio_key)
    print('max |predict - base|/max(1,|F|) on none trials noise-free force: %.2e' % err_base_clean)
    print('max |predict - base|/max(1,|F|) on all 60 records as written:     %.2e' % err_base_rec)
    print('max |ratio/target - 1|: %.4f %%   max |ratio - key achieved|: %.1e' % (100 * err_ratio, err_ratio_key))
    print('max |noise SD / key - 1|: %.4f %%   min final rest: %.3f s' % (100 * noise_dev, min_rest))
    print('PASS' if not fails else 'FAIL: ' + '; '.join(fails))
    return 0 if not fails else 1


if __name__ == '__main__':
    sys.exit(main())
