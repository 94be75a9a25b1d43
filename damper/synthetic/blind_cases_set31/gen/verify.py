#!/usr/bin/env python3
"""blind31 self-check (Python 3 standard library only).

 1. key.json: 30 trials, 24 effects (3 per category, all shapes different), 6 'none',
    12 strong / 12 weak, noise SD in [0.02, 0.06] kip, amplitudes inside their bounds.
 2. layout: every record has the measured semi-active files' header (same keys, same order,
    same values), 8 columns, 1024 Hz, 9-25 s, quantisation grids of the measured columns,
    |drum| <= 1.3 in, realistic drum and actuator speeds, rests between strokes.
 3. black box: every record is replayed through
       /work/runs/binhead/hybridsim damper predict --config .../brfd-semiactive.yaml --no-fit
    and the noise is regenerated from the key's seeds:
      'none'   : record == quantise(black box + noise) sample by sample, residual SD == noise SD
      effects  : ratio = RMS_{A,B}(record - noise - black box) / noise SD hits the key's target
                 (within 2 %) and lies in the strong / weak range.
Last line: VERIFY PASS or VERIFY FAIL.
"""
import csv, json, math, os, random, shutil, struct, subprocess, sys, tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
BIN = '/work/runs/binhead/hybridsim'
CFG = '/work/main/configs/brfd-semiactive.yaml'
TEMPLATE = '/work/shared/data/brfd/semiactive/harmonic0.015forward.json'
CATS = ['backlash', 'residual_static', 'transition_shape', 'velocity', 'actuator_lag',
        'self_energizing', 'pretension', 'asymmetry']
QF = 0.000800879964
QX, QX_OFF = 5.89421674706e-05, 0.6631
QA = 1.0 / 409600.0
QT1, QT1_OFF = 0.31793998, 0.0521
QT2, QT2_OFF = 0.39989996, 0.3294
DT = 1.0 / 1024.0

fails = []
warns = []


def fail(msg):
    fails.append(msg)
    print('  FAIL', msg)


def f32(x):
    return struct.unpack('f', struct.pack('f', x))[0]


def on_grid(v, q, off, tol):
    k = v / q - off
    return abs(k - round(k)) < tol


def qforce(y):
    return round(y / QF) * QF


def bb_velocity(x):
    n = len(x)
    v0 = [0.0] * n
    v0[0] = (x[1] - x[0]) / DT
    v0[-1] = (x[-1] - x[-2]) / DT
    for i in range(1, n - 1):
        v0[i] = (x[i + 1] - x[i - 1]) / (2 * DT)
    p = [0.0]
    for q in v0:
        p.append(p[-1] + q)
    return [(p[min(n, i + 8)] - p[max(0, i - 7)]) / (min(n, i + 8) - max(0, i - 7)) for i in range(n)]


def check_key(key):
    print('== key.json')
    tids = ['t%02d' % k for k in range(1, 31)]
    if sorted(key) != tids:
        fail('trial ids are not t01..t30')
    eff = {t: e for t, e in key.items() if e['category'] != 'none'}
    none = [t for t, e in key.items() if e['category'] == 'none']
    if len(eff) != 24 or len(none) != 6:
        fail('expected 24 effect and 6 none trials, got %d / %d' % (len(eff), len(none)))
    for c in CATS:
        sh = [e['shape'] for e in eff.values() if e['category'] == c]
        if len(sh) != 3 or len(set(sh)) != 3:
            fail('category %s: shapes %s' % (c, sh))
    if len(set(e['shape'] for e in eff.values())) != 24:
        fail('effect shapes are not all different')
    ns = sum(1 for e in eff.values() if e['strength'] == 'strong')
    nw = sum(1 for e in eff.values() if e['strength'] == 'weak')
    if ns != 12 or nw != 12:
        fail('strong/weak = %d/%d' % (ns, nw))
    for t, e in key.items():
        for fld in ('category', 'shape', 'strength', 'ratio', 'noise_kip', 'params', 'records'):
            if fld not in e:
                fail('%s: key lacks %s' % (t, fld))
        if not 0.02 <= e['noise_kip'] <= 0.06:
            fail('%s: noise SD %.4f out of U(0.02, 0.06)' % (t, e['noise_kip']))
        if e['category'] == 'none':
            if e['strength'] is not None or e['ratio'] != 0.0 or e['params']:
                fail('%s: none trial with strength/ratio/params' % t)
            continue
        lo, hi = (8.5, 11.5) if e['strength'] == 'strong' else (2.7, 3.8)
        if not lo <= e['ratio_target'] <= hi or not lo <= e['ratio'] <= hi:
            fail('%s: ratio %.3f / target %.3f outside %s' % (t, e['ratio'], e['ratio_target'], (lo, hi)))
        if abs(e['ratio'] / e['ratio_target'] - 1) > 0.002:
            fail('%s: generator ratio %.4f misses target %.4f' % (t, e['ratio'], e['ratio_target']))
        th = e['params'][e['amplitude_param']]
        b0, b1 = e['amplitude_bounds']
        if not b0 < th <= b1:
            fail('%s: amplitude %s = %g outside (%g, %g]' % (t, e['amplitude_param'], th, b0, b1))
    print('  %d trials checked' % len(key))


def check_layout(path, ref_keys, ref_hdr):
    obj = json.load(open(path))
    if list(obj.keys()) != ref_keys:
        fail('%s: keys %s != measured %s' % (path, list(obj.keys()), ref_keys))
    for k, v in ref_hdr.items():
        if obj.get(k) != v or type(obj.get(k)) != type(v):
            fail('%s: header %s = %r, measured %r' % (path, k, obj.get(k), v))
    d = obj['data']
    n = len(d)
    dur = (n - 1) * DT
    if not 9.0 <= dur <= 25.0:
        fail('%s: duration %.2f s' % (path, dur))
    bad = 0
    for i, r in enumerate(d):
        if len(r) != 8 or not all(isinstance(q, (int, float)) and math.isfinite(q) for q in r):
            bad += 1
            continue
        if r[0] != i / 1024.0:
            bad += 1
        if not on_grid(r[2], QF, 0.0, 1e-6) or not on_grid(r[1], QX, QX_OFF, 1e-4):
            bad += 1
        if f32(r[4]) != r[4] or f32(r[5]) != r[5] or not on_grid(r[4], QA, 0, 0.05) \
                or not on_grid(r[5], QA, 0, 0.05) or f32(r[3]) != r[3]:
            bad += 1
        if not on_grid(r[6], QT1, QT1_OFF, 1e-3) or not on_grid(r[7], QT2, QT2_OFF, 1e-3):
            bad += 1
    if bad:
        fail('%s: %d rows off the measured layout / grids' % (path, bad))
    x = [r[1] for r in d]
    v = bb_velocity(x)
    if max(abs(q) for q in x) > 1.3:
        fail('%s: drum beyond +-1.3 in' % path)
    vmax = max(abs(q) for q in v)
    if vmax > 5.0 or vmax < 0.3:
        fail('%s: peak drum speed %.2f in/s' % (path, vmax))
    # velocity column: the measured quirk (1/125.4 of the derivative)
    num = sum(a * r[3] for a, r in zip(v, d))
    den = sum(r[3] ** 2 for r in d)
    if not 110 < num / den < 140:
        fail('%s: velocity column ratio %.1f' % (path, num / den))
    # rests: at least two stretches of >= 0.4 s with |v| < 0.05 in/s
    rests = 0
    run = 0
    for q in v:
        if abs(q) < 0.05:
            run += 1
        else:
            if run >= 410:
                rests += 1
            run = 0
    if run >= 410:
        rests += 1
    if rests < 2:
        fail('%s: only %d rests' % (path, rests))
    # actuators: within 0.065 in of x', inside the actuator range, speeds <= 0.6 in/s (0.1 s)
    moved = False
    for c in (4, 5):
        a = [r[c] for r in d]
        dev = max(abs(q - a[0]) for q in a)
        if dev > 0.065 or min(a) < 0.3 or max(a) > 1.2:
            fail('%s: actuator %d excursion %.4f' % (path, c - 3, dev))
        sp = max(abs(a[i + 102] - a[i]) / (102 * DT) for i in range(0, n - 102, 10))
        if sp > 0.6:
            fail('%s: actuator %d speed %.2f in/s' % (path, c - 3, sp))
        moved = moved or dev > 0.002
    return d, dur, vmax, rests, moved


def run_bb(path, tmp):
    name = os.path.splitext(os.path.basename(path))[0]
    out = os.path.join(tmp, os.path.basename(os.path.dirname(path)) + '_' + name)
    p = subprocess.run([BIN, 'damper', 'predict', '--config', CFG, '--no-fit', '--test', path,
                        '--out', out, '--no-figure'], capture_output=True, text=True)
    if p.returncode != 0:
        fail('%s: black box rc %d: %s' % (path, p.returncode, p.stderr[-300:]))
        return None, ''
    rows = list(csv.DictReader(open(os.path.join(out, name + '_predict.csv'))))
    shutil.rmtree(out, ignore_errors=True)
    return [float(r['predicted_force_kip']) for r in rows], p.stdout


def main():
    key = json.load(open(os.path.join(ROOT, 'key.json')))
    check_key(key)
    ref = json.load(open(TEMPLATE))
    ref_keys = list(ref.keys())
    ref_hdr = {k: v for k, v in ref.items() if k != 'data'}
    del ref
    tmp = tempfile.mkdtemp(prefix='blind31_verify_')
    print('== records and black box')
    n_moved = 0
    n_rec = 0
    for tid in sorted(key):
        e = key[tid]
        sd = e['noise_kip']
        ss = 0.0
        nn = 0
        ssn = 0.0
        mism = 0
        info = []
        for rn in 'AB':
            path = os.path.join(ROOT, 'cases', tid, rn + '.json')
            d, dur, vmax, rests, moved = check_layout(path, ref_keys, ref_hdr)
            n_rec += 1
            n_moved += moved
            m = e['records'][rn]
            if m['samples'] != len(d):
                fail('%s %s: sample count differs from key' % (tid, rn))
            Fbb, log = run_bb(path, tmp)
            if Fbb is None:
                continue
            if 'velocity column is 1/125' not in log:
                fail('%s %s: black box did not treat the velocity column as in the measured files' % (tid, rn))
            if len(Fbb) != len(d):
                fail('%s %s: black box output length' % (tid, rn))
                continue
            rng = random.Random(m['noise_seed'])
            noise = [rng.gauss(0.0, sd) for _ in range(len(d))]
            F = [r[2] for r in d]
            if abs(F[0] - qforce(m['f0_kip'] + noise[0])) > 1e-9:
                fail('%s %s: first force sample is not quantise(f0 + noise)' % (tid, rn))
            for i in range(1, len(d)):
                r = F[i] - noise[i] - Fbb[i]
                ss += r * r
                ssn += (F[i] - Fbb[i]) ** 2
                if e['category'] == 'none' and abs(F[i] - qforce(Fbb[i] + noise[i])) > 1e-9:
                    # the CSV carries 8 significant digits: a flip is only excusable right at a
                    # quantisation boundary
                    u = (Fbb[i] + noise[i]) / QF
                    if abs(abs(u - math.floor(u)) - 0.5) > 1e-3 or abs(F[i] - qforce(Fbb[i] + noise[i])) > 1.5 * QF:
                        mism += 1
            nn += len(d)
            info.append('%s %.1fs v%.1f rests%d act%s' % (rn, dur, vmax, rests, 'Y' if moved else 'n'))
        if nn == 0:
            continue
        ratio = math.sqrt(ss / nn) / sd
        if e['category'] == 'none':
            resid = math.sqrt(ssn / nn) / sd
            ok_n = mism == 0
            if not ok_n:
                fail('%s: %d samples differ from quantise(black box + noise)' % (tid, mism))
            if ratio > 0.05 or not 0.95 < resid < 1.05:
                fail('%s: none trial ratio %.3f, residual SD/noise %.3f' % (tid, ratio, resid))
            print('  %s none              ratio %.4f  resid/SD %.3f  mismatches %d  | %s'
                  % (tid, ratio, resid, mism, ' | '.join(info)))
        else:
            lo, hi = (8.5, 11.5) if e['strength'] == 'strong' else (2.7, 3.8)
            tgt = e['ratio_target']
            ok = abs(ratio / tgt - 1) < 0.02 and lo <= ratio <= hi
            if not ok:
                fail('%s: black-box ratio %.3f vs target %.3f (%s)' % (tid, ratio, tgt, e['strength']))
            print('  %s %-16s %-6s ratio %.3f (target %.3f, key %.3f)  | %s'
                  % (tid, e['category'], e['strength'], ratio, tgt, e['ratio'], ' | '.join(info)))
    shutil.rmtree(tmp, ignore_errors=True)
    # every shape must reduce to the base model at zero amplitude (on two records of the set)
    print('== shapes at zero amplitude vs base model')
    sys.path.insert(0, HERE)
    import gen
    recs = []
    for tid, rn in (('t01', 'A'), ('t02', 'B')):
        d = json.load(open(os.path.join(ROOT, 'cases', tid, rn + '.json')))['data']
        R = gen.Rec([r[1] for r in d], [r[4] for r in d], [r[5] for r in d])
        recs.append((R, d[0][2], R.base(d[0][2])))
    rnd = random.Random(1)
    worst = 0.0
    for shape, (cat, sim, thmax, thname, draw) in gen.SHAPES.items():
        P = draw(rnd)
        if cat == 'pretension':
            P['u_ref_in'] = 0.03
        for R, w0, B in recs:
            F = sim(R, w0, 0.0, P)
            dev = max(abs(a - b) for a, b in zip(F, B))
            worst = max(worst, dev)
            if dev > 1e-6:
                fail('%s: %.2e kip from the base model at zero amplitude' % (shape, dev))
    print('  largest deviation %.1e kip over %d shapes' % (worst, len(gen.SHAPES)))
    if not 0 < n_moved < n_rec:
        fail('actuators move in %d of %d records (should be some, not all/none)' % (n_moved, n_rec))
    print('== actuators move in %d of %d records' % (n_moved, n_rec))
    print('%d failure(s)' % len(fails))
    print('VERIFY PASS' if not fails else 'VERIFY FAIL')
    return 0 if not fails else 1


if __name__ == '__main__':
    sys.exit(main())
