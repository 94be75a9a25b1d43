#!/usr/bin/env python3
"""Checks the blind test set: layout, quantisation, record rules, ratios against the black box,
'none' = black-box base + noise.  Last line: VERIFY PASS or VERIFY FAIL."""
import csv, json, math, os, subprocess, sys, tempfile, collections
HERE = os.path.dirname(os.path.abspath(__file__)); ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE); import gen
BB = '/work/runs/binhead/hybridsim'; CFG = '/work/runs/brfd-semiactive.yaml'
REF = os.path.join(gen.SRC, 'harmonic0.015forward.json')
fails = []
def fail(msg): fails.append(msg); print('FAIL', msg)

def raw_layout(path):
    txt = open(path).read(); d = json.loads(txt)
    return txt, d

ref_txt, ref = raw_layout(REF)
ref_keys = list(ref.keys())
ref_tail = ref_txt[ref_txt.index(']]')+2:]
key = json.load(open(os.path.join(ROOT, 'key.json')))
trials = {t['trial']: t for t in gen.plan()}
gen.load_sources()
if sorted(key) != ['t%02d' % i for i in range(1, 31)]: fail('trial list')
cats = collections.Counter(k['category'] for k in key.values())
want = {c: 3 for c in gen.SHAPES}; want['none'] = 6
if dict(cats) != want: fail('category counts %s' % dict(cats))
for c in gen.SHAPES:
    if len({k['shape'] for k in key.values() if k['category'] == c}) != 3: fail('shapes of %s not distinct' % c)
strengths = collections.Counter(k['strength'] for k in key.values())
print('strengths', dict(strengths))
early = 0; nrec = 0
tmp = tempfile.mkdtemp(prefix='v29_')
for name in sorted(key):
    k = key[name]; tr = dict(trials[name]); tr['category'] = k['category']; tr['shape'] = k['shape']
    recs, prm = gen.build_trial(tr)
    a = k['params']['amplitude']
    ss = 0.0; n = 0
    for rec in recs:
        nrec += 1
        path = os.path.join(ROOT, 'cases', name, rec['name'] + '.json')
        txt, d = raw_layout(path)
        if list(d.keys()) != ref_keys: fail('%s/%s header keys' % (name, rec['name']))
        for kk in ref_keys[1:]:
            if d[kk] != ref[kk] or type(d[kk]) != type(ref[kk]): fail('%s header %s' % (name, kk))
        if txt[txt.index(']]')+2:] != ref_tail: fail('%s/%s header text' % (name, rec['name']))
        D = d['data']; N = len(D); dur = (N-1)*gen.DT
        if not 6.5 <= dur <= 25.0: fail('%s duration %.2f' % (name, dur))
        for i, r in enumerate(D):
            if len(r) != 8: fail('%s row width' % name); break
            if r[0] != i*gen.DT or (i % 1024 == 0) != isinstance(r[0], int): fail('%s time col row %d' % (name, i)); break
            qf = r[2]/gen.QF
            if abs(qf-round(qf)) > 0.002 or (r[2] == 0 and not isinstance(r[2], int)): fail('%s force quantisation row %d' % (name, i)); break
            qx = r[1]/gen.QX
            if abs(qx-round(qx)) > 0.002: fail('%s disp quantisation row %d' % (name, i)); break
            if gen.f32(r[3]) != r[3] or gen.f32(r[4]) != r[4] or gen.f32(r[5]) != r[5]: fail('%s float32 columns row %d' % (name, i)); break
        # final rest >= 1.5 s: displacement constant within measurement noise, and a designed rest
        last = [r[1] for r in D[-int(1.5/gen.DT):]]
        if max(last)-min(last) > 0.004 or not all(rec['rest'][-int(1.5/gen.DT):]): fail('%s final rest' % name)
        # records equal the regeneration
        x = [r[1] for r in D]
        if x != rec['x']: fail('%s regeneration differs' % name)
        fm = rec['first_move']
        moves = fm is not None
        if moves and fm < 1.0: early += 1
        if k['category'] in gen.NEEDS_MOTION and not moves: fail('%s needs actuator motion' % name)
        # black box base
        out = os.path.join(tmp, name + rec['name'])
        p = subprocess.run([BB, 'damper', 'predict', '--no-fit', '--config', CFG, '--test', path, '--out', out, '--no-figure'], capture_output=True, text=True)
        if p.returncode != 0: fail('%s black box rc %d' % (name, p.returncode)); continue
        csvs = [f for f in os.listdir(out) if f.endswith('_predict.csv')]
        R = list(csv.DictReader(open(os.path.join(out, csvs[0]))))
        Fbb = [float(r['predicted_force_kip']) for r in R]
        if len(Fbb) != N: fail('%s bb length' % name); continue
        Fmine = gen.lugre(rec['v'], gen.base_G(rec), rec['z0'])
        e = max(abs(p_-q) for p_, q in zip(Fbb, Fmine))
        if e > 2e-6: fail('%s base model differs from black box by %.2e' % (name, e))
        Ft = gen.simulate(rec, k['shape'], a, prm, rec['z0'])
        Fm = [r[2] for r in D]
        # measured = Q(truth + noise)
        bad = sum(1 for i in range(1, N) if Fm[i] != gen.qforce(Ft[i] + rec['noise'][i]))
        if bad: fail('%s measured != Q(truth+noise) at %d samples' % (name, bad))
        if k['category'] == 'none':
            mis = [i for i in range(1, N) if abs(gen.qforce(Fbb[i] + rec['noise'][i]) - Fm[i]) > 1e-9]
            if len(mis) > 2 or any(abs(gen.qforce(Fbb[i] + rec['noise'][i]) - Fm[i]) > 1.01*gen.QF for i in mis):
                fail('%s none != bb base + noise (%d samples)' % (name, len(mis)))
            res = [Fm[i]-Fbb[i] for i in range(1, N)]
            sd = math.sqrt(sum(r*r for r in res)/len(res))
            if abs(sd/k['noise_kip']-1) > 0.05: fail('%s none residual sd %.4f vs %.4f' % (name, sd, k['noise_kip']))
        ss += sum((p_-q)**2 for p_, q in zip(Ft, Fbb)); n += N
    r = math.sqrt(ss/n)/k['noise_kip']
    ok = True
    if k['category'] == 'none': ok = r < 1e-3
    elif k['strength'] == 'strong': ok = 8.5 <= r <= 11.5
    else: ok = 2.7 <= r <= 3.8
    if k['category'] != 'none' and abs(r-k['ratio']) > 0.01*k['ratio']: ok = False
    if not 0.02 <= k['noise_kip'] <= 0.06: ok = False
    print('%s %-6s ratio(bb)=%.3f key=%.3f noise=%.4f %s' % (name, k['strength'], r, k['ratio'], k['noise_kip'], 'ok' if ok else 'BAD'))
    if not ok: fail('%s ratio %.3f' % (name, r))
print('records with actuator motion in the first second: %d of %d' % (early, nrec))
if not 15 <= early <= 25: fail('early-motion share')
print('VERIFY PASS' if not fails else 'VERIFY FAIL')
