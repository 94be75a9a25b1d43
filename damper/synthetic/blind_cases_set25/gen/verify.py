#!/usr/bin/env python3
"""Verify blind test set 25: layout, quantisation, final rest, actuator timing, ratios
(against the black-box base model), and 'none' = black-box base + noise.
Last line: VERIFY PASS or VERIFY FAIL."""
import csv, json, math, os, re, subprocess, sys, tempfile, statistics
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gen

ROOT = gen.ROOT
BB = '/work/runs/binhead/hybridsim'
CFG = '/work/runs/brfd-semiactive.yaml'
HEADER_KEYS = ['data', 'dt', 'sampling freq', 'displacement units', 'time units', 'friction force units', 'actuator force units']
fails = []


def fail(msg):
    fails.append(msg)
    print('FAIL', msg)


def ongrid(v, q, ph, tol=1e-6):
    s = v / q - ph
    return abs(s - round(s)) < tol


def run_bb(path, outdir):
    r = subprocess.run([BB, 'damper', 'predict', '--no-fit', '--config', CFG, '--test', path, '--out', outdir, '--no-figure'],
                       capture_output=True, text=True)
    if r.returncode != 0:
        return None, r.stdout + r.stderr
    stem = os.path.splitext(os.path.basename(path))[0]
    rows = list(csv.DictReader(open(os.path.join(outdir, stem + '_predict.csv'))))
    return rows, r.stdout


def main():
    key = json.load(open(os.path.join(ROOT, 'key.json')))
    plan = {p['trial']: p for p in gen.make_plan()}
    ref = json.load(open(os.path.join(gen.DATA, 'harmonic0.015forward.json')))
    ref_hdr = {k: v for k, v in ref.items() if k != 'data'}
    tmp = tempfile.mkdtemp(prefix='verify25_')
    n_early = 0; n_rec = 0
    cats = {}
    global none_exact
    none_exact = []
    print('%-4s %-16s %-7s %6s %6s %7s  %s' % ('trial', 'category', 'str', 'ratio', 'target', 'noise', 'effect share: rest / <0.3s after reversal / actuator motion / other sliding'))
    for t in sorted(key):
        k = key[t]; pl = plan[t]
        cats.setdefault(k['category'], []).append(k['strength'])
        if pl['category'] != k['category'] or pl['shape'] != k['shape']:
            fail('%s plan/key mismatch' % t)
        recs, Ftrue, eff = gen.regenerate_truth(k, pl)
        sse = 0.0; nn = 0; share = [0.0, 0.0, 0.0, 0.0]
        nrng = gen.random.Random(pl['seed'] ^ 0x5A5A5)
        resid_all = []
        for j, nm in enumerate('AB'):
            path = os.path.join(ROOT, 'cases', t, nm + '.json')
            raw = open(path).read()
            d = json.loads(raw)
            n_rec += 1
            # ---- layout
            if list(d.keys()) != HEADER_KEYS:
                fail('%s/%s header keys %s' % (t, nm, list(d.keys())))
            for hk, hv in ref_hdr.items():
                if d.get(hk) != hv or type(d.get(hk)) != type(hv):
                    fail('%s/%s header %s' % (t, nm, hk))
            if not raw.startswith('{"data": [[0, '):
                fail('%s/%s raw start' % (t, nm))
            data = d['data']; n = len(data)
            if any(len(r) != 8 for r in data):
                fail('%s/%s row width' % (t, nm))
            dur = (n - 1) / 1024
            if not (6.5 <= dur <= 25.0):
                fail('%s/%s duration %.3f' % (t, nm, dur))
            for i, r in enumerate(data):
                tt = r[0]
                if i % 1024 == 0:
                    if not isinstance(tt, int) or tt != i // 1024:
                        fail('%s/%s time int at %d' % (t, nm, i)); break
                elif not isinstance(tt, float) or tt != i / 1024:
                    fail('%s/%s time at %d' % (t, nm, i)); break
            # ---- quantisation
            bad = 0
            for r in data:
                F = r[2]
                if not ongrid(F, gen.QF, 0.0, 1e-6): bad += 1
                if gen.f32(r[1]) != r[1] or not ongrid(r[1], gen.QX, gen.QX_PH, 2e-3): bad += 1
                if gen.f32(r[3]) != r[3]: bad += 1
                for c in (4, 5):
                    if gen.f32(r[c]) != r[c] or not ongrid(r[c], gen.QA, 0.0, 2e-2): bad += 1
                if not ongrid(r[6], gen.QA1, gen.QA1_PH, 1e-6) or not ongrid(r[7], gen.QA2, gen.QA2_PH, 1e-6): bad += 1
                if F == 0.0 and not isinstance(F, int): bad += 1
            if bad:
                fail('%s/%s %d quantisation violations' % (t, nm, bad))
            # ---- regenerated record identical to the file
            rec = recs[j]
            if any(rec['x'][i] != data[i][1] or rec['a1'][i] != data[i][4] or rec['a2'][i] != data[i][5] for i in range(n)) or rec['F0'] != data[0][2]:
                fail('%s/%s regeneration mismatch' % (t, nm))
            # ---- black box
            rows, msg = run_bb(path, tmp)
            if rows is None:
                fail('%s/%s black box refused: %s' % (t, nm, msg[-300:])); continue
            Fbb = [float(r['predicted_force_kip']) for r in rows]
            vbb = [float(r['drum_vel_in_per_s']) for r in rows]
            if len(Fbb) != n:
                fail('%s/%s bb length' % (t, nm))
            Fb_mine = gen.simulate(rec)
            dmax = max(abs(a - b) for a, b in zip(Fb_mine, Fbb))
            if dmax > 1e-6:
                fail('%s/%s replica differs from black box by %.3g' % (t, nm, dmax))
            # ---- final rest >= 1.5 s (last 8 samples excluded: one-sided derivative at the record end,
            #      a quirk the measured files share)
            m = int(1.5 * 1024)
            tail = data[-m:]
            if max(abs(v) for v in vbb[-m:-8]) > 0.05 or max(r[1] for r in tail) - min(r[1] for r in tail) > 0.006:
                fail('%s/%s final rest: drum moves in last 1.5 s' % (t, nm))
            a10 = data[0][4]; a20 = data[0][5]
            if any(abs(r[4] - a10) > 0.002 or abs(r[5] - a20) > 0.002 for r in tail):
                fail('%s/%s final rest: actuators move' % (t, nm))
            # ---- actuator timing
            first = None
            for i, r in enumerate(data):
                if abs(r[4] - a10) > 0.002 or abs(r[5] - a20) > 0.002:
                    first = i / 1024; break
            early = first is not None and first < 1.0
            n_early += early
            if early != k['records'][nm]['actuators_move_in_first_second']:
                fail('%s/%s early flag' % (t, nm))
            if k['category'] in ('actuator_lag', 'pretension') and first is None:
                fail('%s/%s needs actuator motion' % (t, nm))
            # ---- effect / noise
            Fm = [r[2] for r in data]
            ft = Ftrue[j]
            for i in range(n):
                dd = ft[i] - Fbb[i]
                sse += dd * dd; nn += 1
                # regime share
                moving_act = abs(data[i][4] - a10) > 0.0005 or abs(data[i][5] - a20) > 0.0005
                if abs(vbb[i]) < 0.01:
                    share[0] += dd * dd
                elif moving_act:
                    share[2] += dd * dd
                else:
                    share[3] += dd * dd
            # reversal windows (<0.3 s after a sign change of the sliding direction) moved out of 'other'
            sd = 0; last = -10 ** 9
            for i in range(n):
                if abs(vbb[i]) > 0.05:
                    s_ = 1 if vbb[i] > 0 else -1
                    if sd != 0 and s_ != sd:
                        last = i
                    sd = s_
                if 0 <= i - last < 307 and abs(vbb[i]) >= 0.01:
                    dd = ft[i] - Fbb[i]
                    moving_act = abs(data[i][4] - a10) > 0.0005 or abs(data[i][5] - a20) > 0.0005
                    if moving_act: share[2] -= dd * dd
                    else: share[3] -= dd * dd
                    share[1] += dd * dd
            res = [Fm[i] - ft[i] for i in range(1, n)]
            resid_all += res
            if k['category'] == 'none':
                rb = [Fm[i] - Fbb[i] for i in range(1, n)]
                sdv = statistics.pstdev(rb); mu = statistics.mean(rb)
                if abs(sdv / k['noise_kip'] - 1) > 0.06:
                    fail('%s/%s none: residual sd %.4f vs noise %.4f' % (t, nm, sdv, k['noise_kip']))
                if abs(mu) > 4 * sdv / math.sqrt(len(rb)):
                    fail('%s/%s none: residual mean %.5f' % (t, nm, mu))
                r1 = sum((rb[i] - mu) * (rb[i + 1] - mu) for i in range(len(rb) - 1)) / (len(rb) * sdv * sdv)
                if abs(r1) > 0.05:
                    fail('%s/%s none: residual lag-1 autocorrelation %.3f' % (t, nm, r1))
                # exact: file force = quantise(black-box base + the trial's own noise draw); the
                # black-box CSV has 8 digits, so a rare 1-LSB flip at a rounding edge is allowed
                Fexp, _, _, _ = gen.finish_record(nrng, rec, Fbb, k['noise_kip'])
                mism = [abs(Fm[i] - Fexp[i]) for i in range(n) if abs(Fm[i] - Fexp[i]) > 1e-9]
                if len(mism) > 0.001 * n or (mism and max(mism) > 1.01 * gen.QF):
                    fail('%s/%s none: force differs from quantise(black-box base + noise) at %d samples' % (t, nm, len(mism)))
                none_exact.append(len(mism))
        ratio = math.sqrt(sse / nn) / k['noise_kip']
        tot = sum(share) or 1.0
        print('%-4s %-16s %-7s %6.2f %6.2f %7.4f  %s' % (t, k['category'], k['strength'], ratio, k['target_ratio'], k['noise_kip'],
                                                    ' / '.join('%3.0f%%' % (100 * s / tot) for s in share) if k['category'] != 'none' else '-'))
        sdr = statistics.pstdev(resid_all)
        if abs(sdr / k['noise_kip'] - 1) > 0.06:
            fail('%s measured - true residual sd %.4f vs noise %.4f' % (t, sdr, k['noise_kip']))
        if not (0.02 <= k['noise_kip'] <= 0.06):
            fail('%s noise_kip out of range' % t)
        if k['category'] == 'none':
            if ratio > 1e-5:
                fail('%s none ratio %.3g' % (t, ratio))
        else:
            lo, hi = (2.7, 3.8) if k['strength'] == 'weak' else (8.5, 11.5)
            if not (lo <= ratio <= hi):
                fail('%s ratio %.3f outside %s range' % (t, ratio, k['strength']))
            if abs(ratio - k['ratio']) > 0.02:
                fail('%s ratio %.3f differs from key %.3f' % (t, ratio, k['ratio']))
    # ---- set-level checks
    ncat = {c: len(v) for c, v in cats.items()}
    nstrong = sum(v.count('strong') for v in cats.values()); nweak = sum(v.count('weak') for v in cats.values())
    shapes = {}
    for t, k in key.items():
        shapes.setdefault(k['category'], set()).add(k['shape'])
    print('trials', len(key), 'per category', ncat, 'strong', nstrong, 'weak', nweak)
    print('none records: samples differing from quantise(black-box base + noise):', none_exact)
    print('records with actuator motion in the first second: %d of %d' % (n_early, n_rec))
    if len(key) != 30 or ncat.get('none') != 6 or any(ncat[c] != 3 or len(shapes[c]) != 3 for c in ncat if c != 'none') or len(ncat) != 9:
        fail('set composition')
    if nstrong != 12 or nweak != 12:
        fail('strong/weak counts %d/%d' % (nstrong, nweak))
    if not (15 <= n_early <= 25):
        fail('early actuator records %d' % n_early)
    print('VERIFY PASS' if not fails else 'VERIFY FAIL (%d problems)' % len(fails))


if __name__ == '__main__':
    main()
