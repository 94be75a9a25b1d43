#!/usr/bin/env python3
"""Verify /work/blind23: layout, quantisation, final rest, actuator timing, ratios, and that the
'none' trials are the black-box base model plus noise. Last line: VERIFY PASS or VERIFY FAIL."""
import csv, json, math, os, struct, subprocess, sys, tempfile
from collections import Counter, OrderedDict

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from model import simulate, velocity, DT  # noqa: E402
from gen import QX, QF, QA, SHAPES, NEEDS_ACT, FILES, SRC  # noqa: E402

ROOT = os.path.dirname(HERE)
BB = '/work/runs/binhead/hybridsim'
CFG = '/work/runs/brfd-semiactive.yaml'
fails = []


def fail(msg):
    fails.append(msg)
    print('FAIL', msg)


def f32(v):
    return struct.unpack('f', struct.pack('f', v))[0]


def ongrid(v, q, tol=1e-6):
    return abs(v / q - round(v / q)) < tol


ref = json.load(open(os.path.join(SRC, FILES[0])), object_pairs_hook=OrderedDict)
ref_keys = list(ref.keys())
key = json.load(open(os.path.join(ROOT, 'key.json')))
cases = sorted(os.listdir(os.path.join(ROOT, 'cases')))
if cases != ['t%02d' % i for i in range(1, 31)]:
    fail('case folders %s' % cases)
cats = Counter(e['category'] for e in key.values())
if cats.get('none') != 6 or any(cats.get(c) != 3 for c in SHAPES):
    fail('category counts %s' % cats)
for c in SHAPES:
    shs = sorted(e['shape'] for e in key.values() if e['category'] == c)
    if len(set(shs)) != 3:
        fail('shapes of %s not distinct' % c)
st = Counter(e['strength'] for e in key.values() if e['category'] != 'none')
if st.get('weak') != 12 or st.get('strong') != 12:
    print('NOTE strengths', st)
early_n = 0
tmp = tempfile.mkdtemp(prefix='b23v_')
for t in cases:
    e = key[t]
    noise = e['noise_kip']
    if not 0.02 <= noise <= 0.06:
        fail('%s noise %g' % (t, noise))
    s_num = 0.0; n_tot = 0; s_res = []
    for lab in 'AB':
        path = os.path.join(ROOT, 'cases', t, lab + '.json')
        obj = json.load(open(path), object_pairs_hook=OrderedDict)
        if list(obj.keys()) != ref_keys:
            fail('%s/%s keys %s' % (t, lab, list(obj.keys())))
        for k in ref_keys[1:]:
            if obj[k] != ref[k]:
                fail('%s/%s header %s' % (t, lab, k))
        D = obj['data']
        n = len(D)
        dur = (n - 1) * DT
        if not 6.5 <= dur <= 25.0:
            fail('%s/%s duration %.3f' % (t, lab, dur))
        bad = 0
        for i, r in enumerate(D):
            if len(r) != 8 or r[0] != i * DT:
                bad += 1; continue
            if not (ongrid(r[1], QX) and ongrid(r[2], QF) and f32(r[3]) == r[3]
                    and f32(r[4]) == r[4] and f32(r[5]) == r[5]
                    and ongrid(r[4], QA, 0.03) and ongrid(r[5], QA, 0.03)):
                bad += 1
        if bad:
            fail('%s/%s %d rows off layout/quantisation' % (t, lab, bad))
        x = [r[1] for r in D]; x1 = [r[4] for r in D]; x2 = [r[5] for r in D]; Fm = [r[2] for r in D]
        v = velocity(x)
        k0 = n - int(1.5 * 1024)
        if max(x[k0:]) - min(x[k0:]) > 0.01 or max(abs(a) for a in v[k0:-8]) > 0.08:
            fail('%s/%s final rest' % (t, lab))
        fm = None
        for i in range(n):
            if abs(x1[i] - x1[0]) > 0.002 or abs(x2[i] - x2[0]) > 0.002:
                fm = i * DT; break
        if fm is not None and fm < 1.0:
            early_n += 1
        if e['category'] in NEEDS_ACT and fm is None:
            fail('%s/%s needs actuator motion' % (t, lab))
        if e['records'][lab]['early_actuator'] != (fm is not None and fm < 1.0):
            fail('%s/%s early flag vs first motion %s' % (t, lab, fm))
        # black box base
        out = os.path.join(tmp, t + lab)
        p = subprocess.run([BB, 'damper', 'predict', '--no-fit', '--config', CFG, '--test', path,
                            '--out', out, '--no-figure'], capture_output=True, text=True)
        if p.returncode != 0:
            fail('%s/%s black box rc %d %s' % (t, lab, p.returncode, p.stderr[-300:])); continue
        csvf = [f for f in os.listdir(out) if f.endswith('.csv')][0]
        pred = [float(r['predicted_force_kip']) for r in csv.DictReader(open(os.path.join(out, csvf)))]
        mine = simulate(x, x1, x2, Fm[0])
        dmax = max(abs(a - b) for a, b in zip(pred, mine))
        if len(pred) != n or dmax > 2e-6:
            fail('%s/%s base model vs black box max diff %g' % (t, lab, dmax))
        if e['category'] != 'none':
            Ft = simulate(x, x1, x2, Fm[0], e['shape'], e['params']['a'])
        else:
            Ft = mine
        s_num += sum((a - b) ** 2 for a, b in zip(Ft, pred)); n_tot += n
        s_res += [Fm[i] - Ft[i] for i in range(1, n)]
    ratio = math.sqrt(s_num / n_tot) / noise
    m = sum(s_res) / len(s_res)
    sd = math.sqrt(sum((a - m) ** 2 for a in s_res) / len(s_res))
    mx = max(abs(a) for a in s_res)
    ok_noise = abs(sd / noise - 1) < 0.06 and abs(m) < 5 * noise / math.sqrt(len(s_res)) + 1e-4 and mx < 6 * noise
    if not ok_noise:
        fail('%s residual noise sd %.4f (noise %.4f) mean %.5f max %.4f' % (t, sd, noise, m, mx))
    if e['category'] == 'none':
        if ratio > 1e-5:
            fail('%s none ratio %g' % (t, ratio))
    else:
        band = (8.5, 11.5) if e['strength'] == 'strong' else (2.7, 3.8)
        if not band[0] <= ratio <= band[1] or abs(ratio - e['ratio']) > 1e-3 * ratio:
            fail('%s ratio %.4f key %.4f band %s' % (t, ratio, e['ratio'], band))
    print('%s ok ratio=%.3f noise=%.4f resid_sd/noise=%.3f' % (t, ratio, noise, sd / noise))
print('records with actuator motion in the first second: %d of 60' % early_n)
if not 14 <= early_n <= 26:
    fail('early actuator fraction %d/60' % early_n)
print('VERIFY PASS' if not fails else 'VERIFY FAIL')
