#!/usr/bin/env python3
"""Checks the blind37 set written by gen.py.  Python 3 standard library only.

1. layout: every record has the measured semi-active layout (same header keys in the same
   order, dt, sampling freq, unit strings, 8 columns, uniform 1024 Hz time, finite values,
   float32 channels, force on the measured quantisation grid), 9..25 s, |x| <= 1.3 in,
   realistic speeds and actuator travel.
2. black box: `hybridsim damper predict --no-fit` is run on every record; gen.py's replica of
   the base model must equal its predicted_force_kip (to the CSV's 8 significant digits).
3. 'none' records: F_meas == quantise(F_blackbox + n) sample by sample, n regenerated from the
   key's noise seed and SD (sample 0 is the model's initial condition, F_meas[0] exactly).
4. effect records: F_meas == quantise(F_true + n) with F_true re-simulated from the key's
   parameters, and the strength ratio RMS(F_true - F_blackbox)/SD over both records equals the
   key's ratio and hits its target (strong in [8.5, 11.5], weak in [2.7, 3.8]), amplitude within
   the shape's bounds.
5. the set: 30 trials, 6 none, 3 per category with 3 different shapes, 12 strong + 12 weak,
   SD in [0.02, 0.06].
Last line: VERIFY PASS or VERIFY FAIL.
"""
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import gen  # noqa: E402

BIN = '/work/runs/binhead/hybridsim'
CONFIG = '/work/main/configs/brfd-semiactive.yaml'
CATS = ['backlash', 'residual_static', 'transition_shape', 'velocity', 'actuator_lag',
        'self_energizing', 'pretension', 'asymmetry']

failures = []
notes = []


def fail(msg):
    failures.append(msg)
    print('FAIL: ' + msg, flush=True)


def load_raw(path):
    with open(path) as fh:
        txt = fh.read()
    return txt, json.loads(txt)


def measured_reference():
    refs = []
    for name in gen.TEMPLATES:
        with open(os.path.join(gen.DATA_DIR, name + '.json')) as fh:
            d = json.load(fh)
        refs.append(d)
    keys = [list(d.keys()) for d in refs]
    assert all(k == keys[0] for k in keys)
    hdr = {k: v for k, v in refs[0].items() if k != 'data'}
    x0 = sorted(set((d['data'][0][4], d['data'][0][5]) for d in refs))
    return keys[0], hdr, x0, refs


def check_layout(tid, lab, d, txt, ref_keys, ref_hdr, ref_x0):
    where = '%s/%s' % (tid, lab)
    if list(d.keys()) != ref_keys:
        fail('%s header keys %s != measured %s' % (where, list(d.keys()), ref_keys))
    for k, v in ref_hdr.items():
        if d.get(k) != v or type(d.get(k)) is not type(v):
            fail('%s header %r = %r, measured %r' % (where, k, d.get(k), v))
    rows = d['data']
    n = len(rows)
    dur = (n - 1) * gen.DT
    if not (9.0 <= dur <= 25.0):
        fail('%s duration %.3f s outside 9..25' % (where, dur))
    for i, r in enumerate(rows):
        if len(r) != 8:
            fail('%s row %d has %d columns' % (where, i, len(r)))
            break
        if any((not isinstance(a, (int, float))) or isinstance(a, bool) or
               not math.isfinite(a) for a in r):
            fail('%s row %d non-numeric/non-finite' % (where, i))
            break
        if r[0] != i * gen.DT:
            fail('%s row %d time %r != %r' % (where, i, r[0], i * gen.DT))
            break
        if (i % gen.FSAMP == 0) != isinstance(r[0], int):
            fail('%s row %d time type differs from the measured files (int at whole s)' % (where, i))
            break
    # float32 channels and grids
    bad32 = sum(1 for r in rows if any(gen.f32(r[c]) != r[c] for c in (1, 2, 4, 5)))
    if bad32:
        fail('%s %d rows with non-float32 x/F/x1/x2 values' % (where, bad32))
    offgrid = sum(1 for r in rows if abs(r[2] / gen.QF - round(r[2] / gen.QF)) > 2e-3)
    if offgrid:
        fail('%s %d force samples off the measured quantisation grid' % (where, offgrid))
    x = [r[1] for r in rows]
    if max(abs(a) for a in x) > 1.3:
        fail('%s drum travel %.3f in beyond +-1.3' % (where, max(abs(a) for a in x)))
    v = gen.vel(x)
    vmax = max(abs(a) for a in v)
    if vmax > 4.0:
        fail('%s drum speed %.2f in/s unrealistic' % (where, vmax))
    if (rows[0][4], rows[0][5]) not in ref_x0:
        fail('%s initial actuator positions %r not those of the measured tests' %
             (where, (rows[0][4], rows[0][5])))
    a1 = max(abs(r[4] - rows[0][4]) for r in rows)
    a2 = max(abs(r[5] - rows[0][5]) for r in rows)
    if max(a1, a2) > 0.06:
        fail('%s actuator travel %.4f in too large' % (where, max(a1, a2)))
    fl = [r[c] for r in rows for c in (6, 7)]
    if min(fl) < 0 or max(fl) > 4500:
        fail('%s actuator load cells outside 0..4500 lb' % where)
    # velocity column quirk: ~ derivative / 125.4
    num = sum(r[3] * vv for r, vv in zip(rows, v))
    den = sum(vv * vv for vv in v)
    if den > 0:
        k = num / den
        if not (1 / 140 < k < 1 / 110):
            fail('%s velocity column scale 1/%.1f, measured quirk is ~1/125' % (where, 1 / k))
    return dict(n=n, dur=dur, vmax=vmax, act=max(a1, a2))


def run_blackbox(path, outdir):
    r = subprocess.run([BIN, 'damper', 'predict', '--config', CONFIG, '--no-fit', '--test', path,
                        '--out', outdir, '--no-figure'], capture_output=True, text=True)
    if r.returncode != 0:
        fail('black box failed on %s: %s' % (path, r.stderr[-300:]))
        return None
    name = os.path.splitext(os.path.basename(path))[0]
    with open(os.path.join(outdir, name + '_predict.csv')) as fh:
        return [float(q['predicted_force_kip']) for q in csv.DictReader(fh)]


def main():
    keyp = os.path.join(ROOT, 'key.json')
    with open(keyp) as fh:
        key = json.load(fh)
    ref_keys, ref_hdr, ref_x0, _ = measured_reference()
    tmp = tempfile.mkdtemp(prefix='blind37_verify_')
    # ---- set-level checks
    tids = ['t%02d' % i for i in range(1, 31)]
    if sorted(key) != tids:
        fail('key.json trials %s' % sorted(key))
    cats = {}
    for t in tids:
        e = key[t]
        cats.setdefault(e['category'], []).append(e)
    if len(cats.get('none', [])) != 6:
        fail('%d none trials, expected 6' % len(cats.get('none', [])))
    for c in CATS:
        L = cats.get(c, [])
        if len(L) != 3 or len(set(e['shape'] for e in L)) != 3:
            fail('category %s: %d trials, shapes %s' % (c, len(L), [e['shape'] for e in L]))
    if set(cats) - set(CATS) - {'none'}:
        fail('unknown categories %s' % (set(cats) - set(CATS) - {'none'}))
    nstrong = sum(1 for e in key.values() if e['strength'] == 'strong')
    nweak = sum(1 for e in key.values() if e['strength'] == 'weak')
    if (nstrong, nweak) != (12, 12):
        fail('%d strong / %d weak, expected 12 / 12' % (nstrong, nweak))
    for t in tids:
        sd = key[t]['noise_kip']
        if not (0.02 <= sd <= 0.06):
            fail('%s noise SD %.4f outside [0.02, 0.06]' % (t, sd))
    # ---- per trial
    maxrep = 0.0
    summary = []
    for t in tids:
        e = key[t]
        sd = e['noise_kip']
        shape = e['shape']
        eff = {} if shape == 'none' else dict(shape=shape, params=e['params_exact'])
        if shape != 'none':
            shp = [s for s in gen.SHAPES[e['category']] if s['shape'] == shape]
            if not shp:
                fail('%s shape %s not in category %s' % (t, shape, e['category']))
            else:
                sh = shp[0]
                amp = e['params_exact'][sh['amp']]
                if not (sh.get('lo', 0.0) <= amp <= sh['hi']):
                    fail('%s amplitude %s = %g outside [%g, %g]' %
                         (t, sh['amp'], amp, sh.get('lo', 0.0), sh['hi']))
        ss = 0.0
        nn = 0
        noise_ss = 0.0
        for lab in ('A', 'B'):
            path = os.path.join(ROOT, 'cases', t, lab + '.json')
            txt, d = load_raw(path)
            info = check_layout(t, lab, d, txt, ref_keys, ref_hdr, ref_x0)
            rows = d['data']
            rec = dict(x=[r[1] for r in rows], x1=[r[4] for r in rows], x2=[r[5] for r in rows],
                       F0=rows[0][2])
            gen.rec_prepare(rec)
            Fm = [r[2] for r in rows]
            out = os.path.join(tmp, t + lab)
            Fbb = run_blackbox(path, out)
            if Fbb is None:
                continue
            Frep = gen.simulate_base(rec)
            rep = max(abs(a - b) / max(1.0, abs(b)) for a, b in zip(Frep, Fbb))
            maxrep = max(maxrep, rep)
            if rep > 2e-7:
                fail('%s/%s replica differs from the black box by %.3g' % (t, lab, rep))
            Ft = Fbb if shape == 'none' else gen.simulate(rec, eff)
            nrng = gen.random.Random(e['records'][lab]['noise_seed'])
            bad = 0
            if Fm[0] != rec['F0']:
                bad += 1
            for i in range(1, len(Fm)):
                ni = nrng.gauss(0, sd)
                noise_ss += ni * ni
                if abs(Fm[i] - (Ft[i] + ni)) > gen.QF / 2 + 2e-6:
                    bad += 1
            if bad:
                fail('%s/%s %d samples are not quantise(F_%s + noise)' %
                     (t, lab, bad, 'blackbox' if shape == 'none' else 'true'))
            for a, b in zip(Ft, Fbb):
                ss += (a - b) ** 2
            nn += len(Ft)
            resid = math.sqrt(sum((a - b) ** 2 for a, b in zip(Fm, Fbb)) / len(Fm))
            summary.append('%s/%s %5.2f s vmax %.2f act %.4f  rms(F_meas - F_blackbox) %.4f kip'
                           % (t, lab, info['dur'], info['vmax'], info['act'], resid))
        ratio_bb = math.sqrt(ss / nn) / sd if nn else float('nan')
        noise_rms = math.sqrt(noise_ss / max(1, nn - 2))
        if shape == 'none':
            if ratio_bb > 1e-6:
                fail('%s none trial differs from the black box (ratio %.3g)' % (t, ratio_bb))
        else:
            if abs(ratio_bb - e['ratio']) > 0.002 * e['ratio'] + 1e-3:
                fail('%s ratio with the black box %.4f != key %.4f' % (t, ratio_bb, e['ratio']))
            if abs(ratio_bb - e['target_ratio']) > 0.01 * e['target_ratio']:
                fail('%s ratio %.4f misses target %.4f' % (t, ratio_bb, e['target_ratio']))
            lo, hi = (8.5, 11.5) if e['strength'] == 'strong' else (2.7, 3.8)
            if not (lo <= e['target_ratio'] <= hi and lo * 0.99 <= ratio_bb <= hi * 1.01):
                fail('%s %s ratio %.3f outside [%g, %g]' % (t, e['strength'], ratio_bb, lo, hi))
        print('%s %-16s %-38s %-6s ratio(black box) %7.3f target %7.3f sd %.4f noise rms %.4f'
              % (t, e['category'], shape, e['strength'], ratio_bb, e['target_ratio'], sd,
                 noise_rms), flush=True)
    print()
    for s in summary:
        print(s)
    print()
    print('replica vs black box: max relative difference %.3g (CSV carries 8 significant digits)'
          % maxrep)
    shutil.rmtree(tmp, ignore_errors=True)
    print('%d failure(s)' % len(failures))
    print('VERIFY PASS' if not failures else 'VERIFY FAIL')


if __name__ == '__main__':
    main()
