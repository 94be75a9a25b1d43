#!/usr/bin/env python3
"""Checks the blind set: layout, quantisation, final rest, actuator timing, ratios, noise,
and that the base model of gen.py equals the black box (so 'none' = black-box base + noise)."""
import csv, json, math, os, struct, subprocess, sys, tempfile
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gen

ROOT = gen.ROOT
BB = '/work/runs/binhead/hybridsim'
CFG = '/work/runs/brfd-semiactive.yaml'
fails = []


def check(cond, msg):
    if not cond:
        fails.append(msg)
        print('FAIL', msg)


def isf32(x):
    return gen.f32(x) == x


def main():
    key = json.load(open(os.path.join(ROOT, 'key.json')))
    meas = json.load(open(os.path.join(gen.SEMI, 'harmonic0.015forward.json')))
    mtext = open(os.path.join(gen.SEMI, 'harmonic0.015forward.json')).read()
    Q = gen.quantizers()
    check(sorted(key) == ['t%02d' % i for i in range(1, 31)], 'trial set')
    cats = {}
    for s, o in key.items():
        cats.setdefault(o['category'], []).append(o)
    check(len(cats.get('none', [])) == 6, 'six none trials')
    for c, _ in gen.EFFECTS.items():
        shp = [o['shape'] for o in cats.get(c, [])]
        check(len(shp) == 3 and len(set(shp)) == 3, 'three distinct shapes for ' + c)
    st = [o['strength'] for o in key.values() if o['category'] != 'none']
    check(st.count('strong') == 12 and st.count('weak') == 12, '12 strong / 12 weak')
    n_early = 0; n_rec = 0
    tmp = tempfile.mkdtemp()
    maxdiff_bb = 0.0
    for s, o in key.items():
        recs = []
        for k in 'AB':
            path = os.path.join(ROOT, 'cases', s, k + '.json')
            text = open(path).read()
            d = json.loads(text)
            check(list(d.keys()) == list(meas.keys()), s + k + ' header keys/order')
            for h in meas:
                if h != 'data':
                    check(d[h] == meas[h], s + k + ' header ' + h)
            D = d['data']; n = len(D)
            dur = (n - 1) * gen.DT
            check(6.5 <= dur <= 25.0, s + k + ' duration %.2f' % dur)
            check(all(len(r) == 8 for r in D), s + k + ' 8 columns')
            check(all(D[i][0] == i * gen.DT for i in range(n)), s + k + ' time column')
            check(all((type(D[i][0]) is int) == (i % 1024 == 0) for i in range(n)), s + k + ' integral times as int')
            check(text.startswith('{"data": [[0, ') and text.endswith('"actuator force units": "lb"}'), s + k + ' text layout')
            for c in (2, 6, 7):
                off, q = Q[c]
                check(max(abs((r[c] - off) / q - round((r[c] - off) / q)) for r in D) < 1e-4, s + k + ' quantisation col %d' % c)
            off, q = Q[1]
            check(max(abs((r[1] - off) / q - round((r[1] - off) / q)) for r in D) < 2e-3, s + k + ' quantisation disp')
            check(all(isf32(r[c]) for r in D for c in (1, 3, 4, 5)), s + k + ' float32 columns')
            x = [r[1] for r in D]; v = gen.velocity(x)
            m = int(1.5 * 1024)
            check(max(abs(a) for a in v[-m:-8]) < 0.05 and (max(x[-m:]) - min(x[-m:])) < 4.5 * q, s + k + ' final rest >= 1.5 s')
            # velocity column quirk: ~1/125.4 of the derived velocity
            a1 = [r[4] for r in D]; a2 = [r[5] for r in D]
            fm = next((i * gen.DT for i in range(n) if abs(a1[i] - a1[0]) > 0.002 or abs(a2[i] - a2[0]) > 0.002), None)
            n_rec += 1
            if fm is not None and fm < 1.0:
                n_early += 1
            check(fm == o['records'][k]['first_actuator_motion_s'], s + k + ' first actuator motion matches key')
            if o['category'] in gen.NEEDS_ACT:
                check(fm is not None, s + k + ' actuator motion present')
            rec = {'x': x, 'v': v, 'a1': a1, 'a2': a2, 's0': D[0][2], 'F': [r[2] for r in D], 'path': path}
            rec['Fb'] = gen.simulate(rec, rec['s0'])
            recs.append(rec)
            # black box
            out = os.path.join(tmp, s + k)
            p = subprocess.run([BB, 'damper', 'predict', '--no-fit', '--config', CFG, '--test', path, '--out', out,
                                '--no-figure'], capture_output=True, text=True)
            check(p.returncode == 0, s + k + ' black box accepts the record')
            if p.returncode == 0:
                fn = [f for f in os.listdir(out) if f.endswith('.csv')][0]
                pr = [float(r['predicted_force_kip']) for r in csv.DictReader(open(os.path.join(out, fn)))]
                check(len(pr) == n, s + k + ' bb length')
                dmax = max(abs(a - b) for a, b in zip(pr, rec['Fb']))
                maxdiff_bb = max(maxdiff_bb, dmax)
                check(dmax < 2e-5, s + k + ' gen base == black box (max diff %.2e)' % dmax)
                rec['bb'] = pr
        # ratio and noise
        eff = None if o['category'] == 'none' else o['shape']
        se = 0.0; nn = 0; res = []
        for rec in recs:
            Ft = gen.simulate(rec, rec['s0'], eff, o['params']['p'])
            se += sum((a - b) ** 2 for a, b in zip(Ft, rec['Fb'])); nn += len(Ft)
            res += [a - b for a, b in zip(rec['F'][1:], Ft[1:])]
        r = math.sqrt(se / nn) / o['noise_kip']
        check(abs(r - o['ratio']) < 1e-6 * max(1, r), s + ' ratio recomputed %.4f vs key %.4f' % (r, o['ratio']))
        if o['strength'] == 'weak':
            check(2.7 <= r <= 3.8, s + ' weak ratio %.2f in [2.7,3.8]' % r)
        elif o['strength'] == 'strong':
            check(8.5 <= r <= 11.5, s + ' strong ratio %.2f in [8.5,11.5]' % r)
        check(0.02 <= o['noise_kip'] <= 0.06, s + ' noise range')
        mu = sum(res) / len(res); sd = math.sqrt(sum((a - mu) ** 2 for a in res) / len(res))
        check(abs(sd / o['noise_kip'] - 1) < 0.08 and abs(mu) < 0.1 * o['noise_kip'], s + ' noise sd %.4f vs %.4f' % (sd, o['noise_kip']))
        if o['category'] == 'none':
            rb = []
            for rec in recs:
                rb += [a - b for a, b in zip(rec['F'][1:], rec['bb'][1:])]
            mu = sum(rb) / len(rb); sd = math.sqrt(sum((a - mu) ** 2 for a in rb) / len(rb))
            check(abs(sd / o['noise_kip'] - 1) < 0.08 and abs(mu) < 0.1 * o['noise_kip'],
                  s + ' none: measured - black box sd %.4f vs noise %.4f' % (sd, o['noise_kip']))
            print(s, 'none: measured - blackbox mean %.5f sd %.5f (noise %.5f)' % (mu, sd, o['noise_kip']))
        print(s, 'ratio %.3f ok' % r)
    print('records with actuator motion before 1 s: %d of %d' % (n_early, n_rec))
    check(abs(n_early - n_rec / 3) <= 3, 'about 1/3 early actuator records')
    print('max |gen base - black box| over all records: %.2e kip' % maxdiff_bb)
    print('VERIFY PASS' if not fails else 'VERIFY FAIL (%d)' % len(fails))


if __name__ == '__main__':
    main()
