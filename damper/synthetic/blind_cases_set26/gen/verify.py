#!/usr/bin/env python3
"""Checks blind set 26: layout, quantisation, final rest, ratios, 'none' = black-box base + noise.
Last line: VERIFY PASS or VERIFY FAIL.   Usage: python3 gen/verify.py"""
import csv, json, math, os, subprocess, sys, tempfile, struct
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import gen  # noqa: E402

ROOT = gen.OUTDIR
BB = '/work/runs/binhead/hybridsim'
fails = []; notes = []


def check(cond, msg):
    if not cond:
        fails.append(msg)
    return cond


def f32ok(v):
    return struct.unpack('f', struct.pack('f', v))[0] == v


def on_grid(v, q, off, tol=1e-6):
    r = v / q - off
    return abs(r - round(r)) < tol


def min_step(vals):
    s = sorted(set(vals))
    d = sorted(b - a for a, b in zip(s, s[1:]))
    return d[len(d) // 20] if d else 0.0     # 5th percentile of the distinct-value spacings


def run_bb(path, outdir):
    p = subprocess.run([BB, 'damper', 'predict', '--no-fit', '--config', gen.CONFIG, '--test', path,
                        '--out', outdir, '--no-figure'], capture_output=True, text=True)
    if p.returncode != 0:
        return None, p.stdout + p.stderr
    name = os.path.splitext(os.path.basename(path))[0]
    rows = list(csv.DictReader(open(os.path.join(outdir, name + '_predict.csv'))))
    return rows, p.stdout + p.stderr


def main():
    key = json.load(open(os.path.join(ROOT, 'key.json')))
    meas_raw = open(os.path.join(gen.DATADIR, gen.MEASURED[0])).read()
    meas = json.loads(meas_raw)
    meas_keys = list(meas.keys())
    mdata = meas['data']
    ref_qF = min_step([r[2] for r in mdata]); ref_qx = min_step([r[1] for r in mdata])
    # ---- set level ----
    trials = sorted(key)
    check(trials == ['t%02d' % k for k in range(1, 31)], 'trial names')
    cats = {}
    for t in trials:
        cats.setdefault(key[t]['category'], []).append(key[t]['shape'])
    check(len(cats.get('none', [])) == 6, 'six none trials')
    for c in gen.SHAPES:
        check(sorted(cats.get(c, [])) == sorted(gen.SHAPES[c]), 'category %s has its 3 distinct shapes' % c)
    strong = [t for t in trials if key[t]['strength'] == 'strong']
    weak = [t for t in trials if key[t]['strength'] == 'weak']
    check(len(strong) == 12 and len(weak) == 12, '12 strong / 12 weak (got %d/%d)' % (len(strong), len(weak)))
    order = [key[t]['category'] for t in trials]
    check(any(order[i] != order[i + 1] for i in range(29)) and order[:3] != ['backlash'] * 3, 'shuffled')
    early = 0; nrec = 0
    tmp = tempfile.mkdtemp(prefix='blind26_verify_')
    summary = []
    for t in trials:
        k = key[t]
        noise = k['noise_kip_exact']
        check(0.02 <= noise <= 0.06, '%s noise %.4f in [0.02, 0.06]' % (t, noise))
        s_eff = 0.0; n_eff = 0; s_gen = 0.0
        resid_stats = []
        for R in 'AB':
            path = os.path.join(ROOT, 'cases', t, R + '.json')
            raw = open(path).read()
            obj = json.loads(raw)
            tag = '%s/%s' % (t, R)
            # ---- layout ----
            check(list(obj.keys()) == meas_keys, tag + ' header keys/order')
            for hk in meas_keys[1:]:
                check(obj[hk] == meas[hk] and type(obj[hk]) == type(meas[hk]), tag + ' header ' + hk)
            check(raw.startswith('{"data": [[0, ') and meas_raw.startswith('{"data": [[0, '), tag + ' JSON text layout')
            d = obj['data']; n = len(d)
            check(all(len(r) == 8 for r in d), tag + ' 8 columns')
            check(all(r[0] == i / 1024 for i, r in enumerate(d)), tag + ' time column k/1024')
            check(all((type(r[0]) is int) == (i % 1024 == 0) for i, r in enumerate(d)), tag + ' integral times as ints')
            dur = (n - 1) / 1024
            check(6.5 <= dur <= 25.0, tag + ' duration %.2f s in [6.5, 25]' % dur)
            # ---- quantisation ----
            check(all(on_grid(r[2], gen.Q_FORCE, gen.OFF_FORCE) for r in d), tag + ' force on grid')
            check(all(on_grid(r[1], gen.Q_DISP, gen.OFF_DISP) for r in d), tag + ' displacement on grid')
            check(all(f32ok(r[4]) and f32ok(r[5]) and on_grid(r[4], gen.Q_ACT, 0, 1e-3) and on_grid(r[5], gen.Q_ACT, 0, 1e-3)
                      for r in d), tag + ' actuator positions float32 on 10/2^22 in grid')
            check(all(f32ok(r[3]) for r in d), tag + ' velocity column float32')
            check(all(on_grid(r[6], gen.Q_F1, gen.OFF_F1) and on_grid(r[7], gen.Q_F2, gen.OFF_F2) for r in d),
                  tag + ' actuator forces on load-cell grids')
            qF = min_step([r[2] for r in d]); qx = min_step([r[1] for r in d])
            check(abs(qF / ref_qF - 1) < 0.02 and abs(qx / ref_qx - 1) < 0.02,
                  tag + ' quantisation steps like measured (F %.6g vs %.6g, x %.6g vs %.6g)' % (qF, ref_qF, qx, ref_qx))
            x = [r[1] for r in d]
            v = gen.velocity(x)
            ratio_vcol = sum(a * b for a, b in zip(v, [r[3] for r in d])) / max(1e-30, sum(r[3] ** 2 for r in d))
            check(115 < ratio_vcol < 135, tag + ' velocity column ~1/125 of d(disp)/dt (%.1f)' % ratio_vcol)
            # ---- final rest ----
            m = int(1.5 * 1024)
            tail = x[-m:]
            vt = max(abs(a) for a in v[-m:-8])   # last 8 samples: one-sided end of the black-box filter
            check(max(tail) - min(tail) < 0.004 and vt < 0.05,
                  tag + ' final rest >= 1.5 s (range %.4f in, max|v| %.3f)' % (max(tail) - min(tail), vt))
            # ---- actuators ----
            a1 = [r[4] for r in d]; a2 = [r[5] for r in d]
            on = next((i / 1024 for i in range(n) if abs(a1[i] - a1[0]) > 0.002 or abs(a2[i] - a2[0]) > 0.002), None)
            nrec += 1
            if on is not None and on < 1.0:
                early += 1
            if k['category'] in gen.NEEDS_MOTION:
                check(on is not None, tag + ' actuator motion present (needed by category)')
            check(bool(k['records'][R]['actuators_move_in_first_second']) == (on is not None and on < 1.0),
                  tag + ' early-motion flag matches data')
            # ---- black box ----
            rows, log = run_bb(path, tmp)
            if not check(rows is not None, tag + ' black box accepts the record: ' + (log or '')[-300:]):
                continue
            Fbb = [float(r['predicted_force_kip']) for r in rows]
            rec = dict(x=x, a1=a1, a2=a2, F0=d[0][2])
            Fbase = gen.simulate(rec, v=v)
            check(max(abs(a - b) for a, b in zip(Fbase, Fbb)) < 2e-6, tag + ' gen base == black box')
            if k['category'] == 'none':
                Ftrue = Fbase
            else:
                Ftrue = gen.simulate(rec, k['shape'], k['amplitude'], k['params'], v=v)
            s_eff += sum((a - b) ** 2 for a, b in zip(Ftrue, Fbb)); n_eff += n
            Fm = [r[2] for r in d]
            check(abs(Fm[0] - Fbb[0]) < 1e-6 and abs(Fm[0] - Ftrue[0]) < 1e-9, tag + ' first force sample = model initial state')
            res = [a - b for a, b in zip(Fm, Ftrue)][1:]
            mu = sum(res) / len(res); sd = math.sqrt(sum((r - mu) ** 2 for r in res) / len(res))
            rho = sum((res[i] - mu) * (res[i + 1] - mu) for i in range(len(res) - 1)) / (len(res) * sd * sd)
            resid_stats.append((mu, sd / noise, rho))
            check(abs(mu) < 5 * noise / math.sqrt(len(res)) + 2e-4, tag + ' noise mean ~0 (%.5f)' % mu)
            check(0.95 < sd / noise < 1.05, tag + ' noise SD / noise_kip = %.3f' % (sd / noise))
            check(abs(rho) < 0.04, tag + ' noise white (lag-1 rho %.3f)' % rho)
            if k['category'] == 'none':
                rb = [a - b for a, b in zip(Fm, Fbb)]
                sdb = math.sqrt(sum(r * r for r in rb) / len(rb))
                check(0.95 < sdb / noise < 1.05, tag + ' none: measured - black box = noise (rms/noise %.3f)' % (sdb / noise))
        ratio = math.sqrt(s_eff / max(n_eff, 1)) / noise
        if k['category'] == 'none':
            check(ratio < 0.01, '%s none ratio %.4f ~ 0' % (t, ratio))
        else:
            check(abs(ratio - k['ratio']) / k['ratio'] < 0.01, '%s ratio recomputed %.3f vs key %.3f' % (t, ratio, k['ratio']))
            band = (8.5, 11.5) if k['strength'] == 'strong' else (2.7, 3.8)
            check(band[0] <= ratio <= band[1], '%s %s ratio %.3f in %s' % (t, k['strength'], ratio, band))
        summary.append('%s %-7s ratio %7.3f noise %.4f resid(mean, sd/noise, rho) %s' % (
            t, k['strength'], ratio, noise, ' '.join('(%.4f, %.3f, %.3f)' % s for s in resid_stats)))
    frac = early / max(nrec, 1)
    check(0.25 <= frac <= 0.42, 'about 1/3 of records move actuators within 1 s (%d/%d)' % (early, nrec))
    for s in summary:
        print(s)
    print('records with actuator motion in the first second: %d/%d' % (early, nrec))
    for f in fails:
        print('FAIL:', f)
    print('VERIFY PASS' if not fails else 'VERIFY FAIL')


if __name__ == '__main__':
    main()
