#!/usr/bin/env python3
"""Verify /work/blind22: layout, quantisation, final rest, actuator rules, black-box base, ratios, 'none' = base + noise.
Last line: VERIFY PASS or VERIFY FAIL."""
import csv, json, math, os, struct, subprocess, sys, tempfile
HERE = os.path.dirname(os.path.abspath(__file__)); sys.path.insert(0, HERE)
import gen
ROOT = gen.ROOT
BB = '/work/runs/binhead/hybridsim'; CFG = '/work/runs/brfd-semiactive.yaml'
fails = []
def fail(msg): fails.append(msg); print('FAIL', msg)
def f32ok(x): return struct.unpack('f', struct.pack('f', x))[0] == x

ref = json.load(open(os.path.join(gen.SRC, 'harmonic0.03ea1forward.json')))
key = json.load(open(os.path.join(ROOT, 'key.json')))
tids = ['t%02d' % i for i in range(1, 31)]
if sorted(key) != tids: fail('key trials')
cats = {}; nstrong = nweak = nnone = 0; notes = 0
for t in tids:
    e = key[t]
    if e['category'] == 'none': nnone += 1
    else:
        cats.setdefault(e['category'], set()).add(e['shape'])
        if e['strength'] == 'strong': nstrong += 1
        else: nweak += 1
        if 'note' in e: notes += 1
if nnone != 6: fail('none count %d' % nnone)
if len(cats) != 8 or any(len(s) != 3 for s in cats.values()): fail('categories/shapes %s' % cats)
print('strong %d weak %d none %d (demoted with note: %d)' % (nstrong, nweak, nnone, notes))
if nstrong + nweak != 24 or nstrong + notes < 12: fail('strength split')

tmp = tempfile.mkdtemp(prefix='v22_')
early_count = 0; nrec = 0
for t in tids:
    e = key[t]; recs = []; meas = []; preds = []
    for nm in 'AB':
        p = os.path.join(ROOT, 'cases', t, nm + '.json'); nrec += 1
        txt = open(p).read()
        if not txt.startswith('{"data": [[0, '): fail('%s/%s prefix' % (t, nm))
        obj = json.loads(txt)
        if list(obj.keys()) != list(ref.keys()): fail('%s/%s key order' % (t, nm))
        for k in gen.HEAD:
            if obj[k] != ref[k] or type(obj[k]) != type(ref[k]): fail('%s/%s header %s' % (t, nm, k))
        d = obj['data']; n = len(d); L = (n - 1) * gen.DT
        if not (6.5 <= L <= 25): fail('%s/%s length %.2f' % (t, nm, L))
        for i, r in enumerate(d):
            if len(r) != 8: fail('%s/%s row width' % (t, nm)); break
            tt = i / 1024
            if r[0] != tt or (isinstance(r[0], int) != (tt == int(tt))): fail('%s/%s time at %d' % (t, nm, i)); break
            if abs(r[2] / gen.QF - round(r[2] / gen.QF)) > 1e-6: fail('%s/%s force quantisation %d' % (t, nm, i)); break
            if abs((r[1] - gen.OD) / gen.QD - round((r[1] - gen.OD) / gen.QD)) > 1e-6: fail('%s/%s disp quantisation %d' % (t, nm, i)); break
            if not (f32ok(r[3]) and f32ok(r[4]) and f32ok(r[5])): fail('%s/%s float32 columns %d' % (t, nm, i)); break
        p1, p2 = d[0][4], d[0][5]
        # final rest >= 1.5 s
        tail = d[-int(1.5 * 1024) - 1:]
        if max(r[1] for r in tail) - min(r[1] for r in tail) > 4.5 * gen.QD: fail('%s/%s final rest (drum)' % (t, nm))
        if any(abs(r[4] - p1) > 1e-4 or abs(r[5] - p2) > 1e-4 for r in tail): fail('%s/%s final rest (actuators)' % (t, nm))
        fm = next((i * gen.DT for i, r in enumerate(d) if abs(r[4] - p1) > 0.002 or abs(r[5] - p2) > 0.002), None)
        info = e['records'][nm]
        early = fm is not None and fm < 1.0
        early_count += early
        if early != info['early_actuator_motion']: fail('%s/%s early-motion flag' % (t, nm))
        if e['shape'] in gen.NEED_ACT and fm is None: fail('%s/%s needs actuator motion' % (t, nm))
        if e['shape'] in gen.NEED_BOTH and not any(abs(r[4] - p1) > 0.002 for r in d) or e['shape'] in gen.NEED_BOTH and not any(abs(r[5] - p2) > 0.002 for r in d):
            fail('%s/%s needs both actuators' % (t, nm))
        rest = [False] * n
        for a, b in info['rest_runs']:
            for i in range(a, b): rest[i] = True
        rec = {'x': [r[1] for r in d], 'x1': [r[4] for r in d], 'x2': [r[5] for r in d], 'rest': rest,
               'F0': d[0][2], 'p1': p1, 'p2': p2}
        # black box
        od = os.path.join(tmp, t + nm)
        cp = subprocess.run([BB, 'damper', 'predict', '--no-fit', '--config', CFG, '--test', p, '--out', od, '--no-figure'],
                            capture_output=True, text=True)
        if cp.returncode != 0: fail('%s/%s black box rc %d %s' % (t, nm, cp.returncode, cp.stderr[-300:])); continue
        csvp = [f for f in os.listdir(od) if f.endswith('_predict.csv')][0]
        P = [float(r['predicted_force_kip']) for r in csv.DictReader(open(os.path.join(od, csvp)))]
        Fb = gen.simulate(rec)
        dev = max(abs(a - b) for a, b in zip(P, Fb))
        if len(P) != n or dev > 2e-5: fail('%s/%s base mismatch %.2e' % (t, nm, dev))
        recs.append(rec); meas.append([r[2] for r in d]); preds.append(P)
    if len(preds) != 2: continue
    noise = e['noise_kip']
    if not (0.02 <= noise <= 0.06): fail('%s noise' % t)
    if e['category'] == 'none':
        Ft = preds
    else:
        Ft = [gen.simulate(r, e['shape'], e['params']) for r in recs]
        s = sum((a - b) ** 2 for F, P in zip(Ft, preds) for a, b in zip(F, P)); m = sum(len(P) for P in preds)
        ratio = math.sqrt(s / m) / noise
        band = (2.7, 3.8) if e['strength'] == 'weak' else (8.5, 11.5)
        ok = band[0] <= ratio <= band[1] and abs(ratio / e['ratio'] - 1) < 0.01
        print('%s ratio %.3f (key %.3f, %s)' % (t, ratio, e['ratio'], e['strength']))
        if not ok: fail('%s ratio %.3f' % (t, ratio))
    res = [a - b for F, Mz in zip(Ft, meas) for a, b in zip(Mz[1:], F[1:])]
    rms = math.sqrt(sum(r * r for r in res) / len(res))
    if not (0.9 <= rms / noise <= 1.1) or max(abs(r) for r in res) > 6.5 * noise:
        fail('%s residual rms %.4f vs noise %.4f' % (t, rms, noise))
    if e['category'] == 'none': print('%s none: residual rms/noise %.3f, base dev ok' % (t, rms / noise))
print('records with actuator motion before 1 s: %d of %d' % (early_count, nrec))
if not (15 <= early_count <= 25): fail('early-motion fraction')
print('VERIFY PASS' if not fails else 'VERIFY FAIL (%d problems)' % len(fails))
