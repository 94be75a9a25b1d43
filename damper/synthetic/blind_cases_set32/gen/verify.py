#!/usr/bin/env python3
"""Checks of the blind32 set (standard library only).  Last line: VERIFY PASS or VERIFY FAIL.

 1. set composition (30 trials, 6 none, 3 distinct shapes per category, 12 strong / 12 weak, noise range);
 2. layout of every record equals the measured semi-active files (keys and their order, header
    values, 8 columns, 1024 Hz time base with integer seconds written as integers, measurement grids);
 3. motions are realistic (9-25 s, |x| <= 1.3 in, drum speed, rests, actuator range and speed, the
    velocity-column quirk);
 4. the black box (`hybridsim damper predict --no-fit`) equals this generator's base model on
    every record, and 'none' records equal the black box plus the regenerated noise;
 5. effect records equal the effect model plus the regenerated noise, and the strength ratio
    RMS(F_true - F_blackbox)/noise over both records hits its target (strong 8.5-11.5, weak 2.7-3.8);
 6. gen.py is reproducible (two trials regenerated into a temporary folder, byte-identical).

Usage: python3 verify.py [--no-blackbox] [--no-repro]
"""
import csv
import hashlib
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
BIN = '/work/runs/binhead/hybridsim'
FAILS = []
WARNS = []


def check(cond, msg):
    if not cond:
        FAILS.append(msg)
    return cond


def blackbox(path, tmp):
    out = os.path.join(tmp, os.path.basename(os.path.dirname(path)) + '_' + os.path.basename(path)[:-5])
    r = subprocess.run([BIN, 'damper', 'predict', '--config', gen.CONFIG, '--no-fit', '--test', path,
                        '--out', out, '--no-figure'], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError('black box failed on %s: %s' % (path, r.stderr[-500:]))
    csvs = [f for f in os.listdir(out) if f.endswith('_predict.csv')]
    with open(os.path.join(out, csvs[0])) as fh:
        rows = list(csv.DictReader(fh))
    return [float(r['predicted_force_kip']) for r in rows]


def on_grid(vals, q, off, tol):
    return max(abs((v - off) / q - round((v - off) / q)) for v in vals) <= tol


def main():
    use_bb = '--no-blackbox' not in sys.argv and os.path.exists(BIN)
    do_repro = '--no-repro' not in sys.argv
    with open(os.path.join(ROOT, 'key.json')) as fh:
        key = json.load(fh)
    with open(os.path.join(gen.DATA_DIR, gen.SOURCES[0])) as fh:
        ref = json.load(fh)
    ref_keys = list(ref.keys())
    ref_types = [type(v).__name__ for v in ref['data'][1]]

    # ---- 1. composition
    tids = ['t%02d' % k for k in range(1, 31)]
    check(sorted(key) == tids, 'key must hold t01..t30')
    cats = {}
    for t in tids:
        e = key[t]
        cats.setdefault(e['category'], []).append(e)
        check(0.02 <= e['noise_kip'] <= 0.06, '%s noise %s outside [0.02, 0.06]' % (t, e['noise_kip']))
        for f in ('category', 'shape', 'strength', 'ratio', 'noise_kip', 'params'):
            check(f in e, '%s: key lacks %s' % (t, f))
    check(len(cats.get('none', [])) == 6, 'need 6 none trials')
    for c in gen.CATEGORIES:
        sh = [e['shape'] for e in cats.get(c, [])]
        check(len(sh) == 3 and len(set(sh)) == 3, 'category %s needs 3 distinct shapes: %s' % (c, sh))
    st = [key[t]['strength'] for t in tids]
    check(st.count('strong') == 12 and st.count('weak') == 12, 'need 12 strong and 12 weak')
    check(len(set(tuple(key[t]['category'] for t in tids[k:k + 6]) for k in (0, 6, 12, 18, 24))) > 1,
          'trials look unshuffled')

    tmp = tempfile.mkdtemp(prefix='blind32_verify_')
    worst_bb = 0.0
    worst_none = 0.0
    worst_eff = 0.0
    nrec_act = 0
    summary = []
    try:
        for t in tids:
            e = key[t]
            Fts, Fbs = [], []
            for name in ('A', 'B'):
                path = os.path.join(ROOT, 'cases', t, name + '.json')
                with open(path) as fh:
                    raw = fh.read()
                obj = json.loads(raw)
                tag = '%s/%s' % (t, name)
                # ---- 2. layout
                check(list(obj.keys()) == ref_keys, '%s keys %s != %s' % (tag, list(obj.keys()), ref_keys))
                for k in ref_keys[1:]:
                    check(obj[k] == ref[k], '%s header %s=%r != %r' % (tag, k, obj[k], ref[k]))
                d = obj['data']
                n = len(d)
                check(all(len(r) == 8 for r in d), '%s: rows must have 8 columns' % tag)
                check(all(isinstance(v, (int, float)) and math.isfinite(v) for r in d for v in r),
                      '%s: non-finite values' % tag)
                check(all(d[i][0] == i * gen.DT for i in range(n)), '%s: time column not i/1024' % tag)
                check(all(isinstance(d[i][0], int) == (i % 1024 == 0) for i in range(n)),
                      '%s: integer seconds must be written as integers (as in the measured files)' % tag)
                check([type(v).__name__ for v in d[1]] == ref_types, '%s: column types differ' % tag)
                dur = (n - 1) * gen.DT
                check(9.0 <= dur <= 25.0, '%s: duration %.2f s' % (tag, dur))
                x = [r[1] for r in d]
                F = [r[2] for r in d]
                vcol = [r[3] for r in d]
                a1 = [r[4] for r in d]
                a2 = [r[5] for r in d]
                check(on_grid(x, gen.Q_X, gen.OFF_X, 1e-6), '%s: displacement off the sensor grid' % tag)
                check(on_grid(F, gen.Q_F, gen.OFF_F, 1e-6), '%s: force off the load-cell grid' % tag)
                check(on_grid([r[6] for r in d], gen.Q_L1, gen.OFF_L1, 1e-6), '%s: act1 force grid' % tag)
                check(on_grid([r[7] for r in d], gen.Q_L2, gen.OFF_L2, 1e-6), '%s: act2 force grid' % tag)
                check(all(gen.f32(v) == v for v in a1 + a2 + vcol), '%s: float32 columns' % tag)
                # ---- 3. motion realism
                check(max(abs(v) for v in x) <= 1.3, '%s: drum travel beyond 1.3 in' % tag)
                v = gen.bb_velocity(x)
                vmax = max(abs(u) for u in v)
                check(0.5 <= vmax <= 5.0, '%s: peak drum speed %.2f in/s' % (tag, vmax))
                rest = gen.rest_clock({'v': v, 'n': n})
                nrest = sum(1 for i in range(1, n) if rest[i] == 0.0 and rest[i - 1] < 0)
                check(nrest >= 1, '%s: no rest between strokes' % tag)
                check(all(0.3 <= u <= 1.2 for u in a1 + a2), '%s: actuator outside 0.3-1.2 in' % tag)
                s1 = gen.moving_average(a1, 20)
                s2 = gen.moving_average(a2, 20)
                avmax = max(abs(s[i + 1] - s[i - 1]) / (2 * gen.DT) for s in (s1, s2) for i in range(1, n - 1))
                check(avmax <= 0.6, '%s: actuator speed %.3f in/s' % (tag, avmax))
                dev = max(max(abs(u - a1[0]) for u in a1), max(abs(u - a2[0]) for u in a2))
                moves = dev > 0.005
                nrec_act += moves
                check(moves == e['records'][name]['actuators_move'], '%s: actuator flag' % tag)
                if e['category'] in ('actuator_lag', 'pretension'):
                    check(moves, '%s: actuator category needs actuator motion' % tag)
                num = sum(v[i - gen.VCOL_LAG] * vcol[i] for i in range(50, n))
                den = sum(vcol[i] ** 2 for i in range(50, n))
                check(abs(num / den / gen.VCOL_RATIO - 1.0) < 0.03, '%s: velocity column ratio %.1f' % (tag, num / den))
                # ---- 4/5. models
                R = gen.prep({'x': x, 'a1': a1, 'a2': a2}, F[0])
                Fpy = gen.base_force(R)
                if use_bb:
                    Fbb = blackbox(path, tmp)
                    check(len(Fbb) == n, '%s: black box length' % tag)
                    dbb = max(abs(p - q) for p, q in zip(Fbb, Fpy))
                    worst_bb = max(worst_bb, dbb)
                    check(dbb < 2e-6, '%s: black box differs from the base model by %.2e kip' % (tag, dbb))
                else:
                    Fbb = Fpy
                ns = e['records'][name]['noise_seed']
                noise = gen.noise_seq(ns, n, e['noise_sd_exact'])
                if e['category'] == 'none':
                    Ft = Fbb
                else:
                    Ft = gen.run_shape(e['shape'], R, e['amplitude'], e['params'])
                res = [F[i] - (Ft[i] + noise[i]) for i in range(1, n)]
                mres = max(abs(r) for r in res)
                if e['category'] == 'none':
                    worst_none = max(worst_none, mres)
                    r0 = F[0] - Fbb[0]
                    check(abs(r0) <= abs(gen.S2 * v[0]) + gen.Q_F, '%s: row 0 residual %.4f' % (tag, r0))
                    rr = [F[i] - Fbb[i] for i in range(1, n)]
                    sd = math.sqrt(sum(u * u for u in rr) / len(rr))
                    mean = sum(rr) / len(rr)
                    check(abs(sd / e['noise_sd_exact'] - 1.0) < 0.05, '%s: residual SD %.4f vs noise %.4f' % (tag, sd, e['noise_sd_exact']))
                    check(abs(mean) < 4 * e['noise_sd_exact'] / math.sqrt(len(rr)), '%s: residual mean %.5f' % (tag, mean))
                else:
                    worst_eff = max(worst_eff, mres)
                check(mres <= gen.Q_F / 2 + 2e-6, '%s: force != model + noise (max %.2e)' % (tag, mres))
                Fts.append(Ft)
                Fbs.append(Fbb)
            ratio = gen.ratio_of(Fts, Fbs, e['noise_sd_exact'])
            if e['category'] == 'none':
                check(ratio < 1e-5, '%s: none trial ratio %.2e' % (t, ratio))
            else:
                lo, hi = (8.5, 11.5) if e['strength'] == 'strong' else (2.7, 3.8)
                check(lo <= ratio <= hi, '%s: ratio %.3f outside %s band' % (t, ratio, e['strength']))
                check(abs(ratio - e['ratio_target']) < 0.01, '%s: ratio %.4f misses target %.4f' % (t, ratio, e['ratio_target']))
                check(abs(ratio - e['ratio']) < 0.005, '%s: ratio %.4f != key %.4f' % (t, ratio, e['ratio']))
                amp = e['amplitude']
                check(0 < amp <= e['params']['amplitude_bound'] + 1e-12, '%s: amplitude %.4g outside bound' % (t, amp))
            summary.append('%s ratio %.3f' % (t, ratio))
        check(5 <= nrec_act <= 55, 'actuators should move in some records, not all (%d of 60)' % nrec_act)

        # ---- 6. reproducibility
        if do_repro:
            jobs = {j[0]: j for j in gen.plan()}
            for t in ('t01', 't02'):
                saved = gen.ROOT
                alt = os.path.join(tmp, 'repro')
                gen.ROOT = alt
                try:
                    gen.run_trial(jobs[t])
                finally:
                    gen.ROOT = saved
                for name in ('A.json', 'B.json'):
                    h1 = hashlib.sha256(open(os.path.join(ROOT, 'cases', t, name), 'rb').read()).hexdigest()
                    h2 = hashlib.sha256(open(os.path.join(alt, 'cases', t, name), 'rb').read()).hexdigest()
                    check(h1 == h2, '%s/%s not reproducible' % (t, name))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)

    print('records with actuator motion: %d of 60' % nrec_act)
    print('black box used: %s; max |black box - base model| = %.2e kip' % (use_bb, worst_bb))
    print('none records: max |force - (black box + noise)| = %.2e kip (grid half-step %.2e)' % (worst_none, gen.Q_F / 2))
    print('effect records: max |force - (effect model + noise)| = %.2e kip' % worst_eff)
    print(' '.join(summary))
    for f in FAILS:
        print('FAIL:', f)
    print('VERIFY PASS' if not FAILS else 'VERIFY FAIL')


if __name__ == '__main__':
    main()
