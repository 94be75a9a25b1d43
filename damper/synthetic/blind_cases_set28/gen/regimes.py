#!/usr/bin/env python3
"""Diagnostic: share of the effect energy sum((F_true-F_base)^2) per regime, per effect trial.
Regimes (first match): post-reversal (from the turning point until 0.15 in of drum travel after a
reversal), rest (|v| < 0.05 in/s), sliding with actuators moving (|dx_act| > 0.002 in within +-0.1 s), other sliding.
Note: LuGre holds the force reached when the drum stops, so an effect that changes the force at
the end of a stroke also shows as a constant offset during the following rest."""
import json, os, sys
HERE = os.path.dirname(os.path.abspath(__file__)); ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import gen
key = json.load(open(os.path.join(ROOT, 'key.json')))
print('trial shape    rest  act  rev  slide  fwd/bwd(sliding)')
for t in sorted(key):
    e = key[t]
    if e['shape'] == 'none':
        continue
    acc = {'rest': 0.0, 'act': 0.0, 'rev': 0.0, 'slide': 0.0}; fw = bw = 0.0
    for lab in 'AB':
        D = json.load(open(os.path.join(ROOT, 'cases', t, lab + '.json')))['data']
        x = [r[1] for r in D]; v = gen.velocity(x); x1 = [r[4] for r in D]; x2 = [r[5] for r in D]
        R = {'x': x, 'v': v, 'x1': x1, 'x2': x2, 'F0': D[0][2]}
        Fb = gen.simulate(R); Ft = gen.simulate(R, e['shape'], e['params'][gen.SHAPES[e['shape']][1]], e['params'])
        n = len(x); mv = [abs(x1[i] - x1[0]) > 0.002 or abs(x2[i] - x2[0]) > 0.002 for i in range(n)]
        w = 100; near = [False] * n
        for i in range(n):
            if mv[i]:
                for j in range(max(0, i - w), min(n, i + w)):
                    near[j] = True
        d = 0; xext = x[0]; iext = 0; rev = [False] * n; xturn = None
        for i in range(n):
            if d == 0:
                if abs(v[i]) > 0.3: d = 1 if v[i] > 0 else -1; xext = x[i]; iext = i
            else:
                if (d > 0 and x[i] > xext) or (d < 0 and x[i] < xext): xext = x[i]; iext = i
                if d * v[i] < -0.3 and abs(x[i] - xext) > 0.02:
                    d = -d; xturn = xext
                    for j in range(iext, i): rev[j] = True
                    xext = x[i]; iext = i
            if xturn is not None and abs(x[i] - xturn) < 0.15: rev[i] = True
        for i in range(n):
            q = (Ft[i] - Fb[i]) ** 2
            if abs(v[i]) < 0.05 and not rev[i]: acc['rest'] += q
            elif rev[i]: acc['rev'] += q
            elif near[i]: acc['act'] += q
            else:
                acc['slide'] += q
                if v[i] > 0: fw += q
                else: bw += q
    tot = sum(acc.values()) or 1.0
    print('%s %-5s %s  %s' % (t, e['shape'], '  '.join('%4.0f%%' % (100 * acc[k] / tot) for k in ('rest', 'act', 'rev', 'slide')),
                          '%.0f/%.0f' % (100 * fw / (fw + bw + 1e-30), 100 * bw / (fw + bw + 1e-30))))
