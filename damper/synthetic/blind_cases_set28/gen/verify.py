#!/usr/bin/env python3
"""Verify blind test set 28.  Checks layout, quantisation, final rest, early-motion share,
the base model against the black box, the effect ratios, and that every 'none' trial is
exactly the black-box base prediction plus the recorded Gaussian noise, quantised.
Last line: VERIFY PASS or VERIFY FAIL."""
import json, math, os, random, subprocess, sys, tempfile
from concurrent.futures import ThreadPoolExecutor

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import gen  # noqa: E402

BB = '/work/runs/binhead/hybridsim'
CFG = '/work/runs/brfd-semiactive.yaml'
REF = os.path.join(gen.SRC, 'harmonic0.015forward.json')
fails = []
warns = []


def fail(msg):
    fails.append(msg)
    print('FAIL', msg)


def frac_dev(x, q, off):
    k = (x - off) / q
    return abs(k - round(k))


def run_bb(path, outdir):
    r = subprocess.run([BB, 'damper', 'predict', '--no-fit', '--config', CFG, '--test', path,
                        '--out', outdir, '--no-figure'], capture_output=True, text=True)
    if r.returncode != 0:
        return None, r.stderr + r.stdout
    name = os.path.splitext(os.path.basename(path))[0]
    with open(os.path.join(outdir, name + '_predict.csv')) as fh:
        hdr = fh.readline().strip().split(',')
        j = hdr.index('predicted_force_kip')
        F = [float(line.split(',')[j]) for line in fh]
    return F, r.stdout


def main():
    with open(REF) as fh:
        ref = json.load(fh)
    ref_keys = list(ref.keys())
    ref_hdr = {k: ref[k] for k in ref if k != 'data'}
    with open(os.path.join(ROOT, 'key.json')) as fh:
        key = json.load(fh)
    tids = ['t%02d' % k for k in range(1, 31)]
    if sorted(key) != tids:
        fail('key.json trials %s' % sorted(key))
    src, act = gen.load_sources()
    # ---- set composition
    from collections import Counter, defaultdict
    cats = Counter(key[t]['category'] for t in tids)
    shapes = defaultdict(set)
    for t in tids:
        shapes[key[t]['category']].add(key[t]['shape'])
    for c in gen.CATS:
        if cats[c] != 3 or len(shapes[c]) != 3:
            fail('category %s: %d trials, %d shapes' % (c, cats[c], len(shapes[c])))
    if cats['none'] != 6:
        fail('none trials: %d' % cats['none'])
    st = Counter(key[t]['strength'] for t in tids if key[t]['category'] != 'none')
    print('strengths', dict(st))
    if st['strong'] != 12 or st['weak'] != 12:
        warns.append('strength split %s' % dict(st))
    tmp = tempfile.mkdtemp(prefix='bl28v_')
    jobs = []
    for t in tids:
        for lab in 'AB':
            jobs.append((t, lab, os.path.join(ROOT, 'cases', t, lab + '.json'), os.path.join(tmp, t)))
    with ThreadPoolExecutor(2) as ex:
        bbres = list(ex.map(lambda j: run_bb(j[2], j[3]), jobs))
    bb = {}
    for (t, lab, path, _), (F, msg) in zip(jobs, bbres):
        if F is None:
            fail('%s/%s: black box rejected the record: %s' % (t, lab, msg.strip()[-300:]))
        bb[(t, lab)] = F
    early = 0
    nrec = 0
    max_base_err = 0.0
    for t in tids:
        e = key[t]
        shape = e['shape']; noise = e['noise_kip']
        recs = {}
        for lab in 'AB':
            path = os.path.join(ROOT, 'cases', t, lab + '.json')
            with open(path) as fh:
                txt = fh.read()
            d = json.loads(txt)
            nrec += 1
            info = e['records'][lab]
            host = src[info['host_file']]
            if list(d.keys()) != ref_keys:
                fail('%s/%s keys %s' % (t, lab, list(d.keys())))
            for k, v in ref_hdr.items():
                if d.get(k) != v:
                    fail('%s/%s header %s=%r' % (t, lab, k, d.get(k)))
            D = d['data']
            n = len(D)
            dur = (n - 1) * gen.DT
            if not (6.5 <= dur <= 25.0):
                fail('%s/%s duration %.3f' % (t, lab, dur))
            bad = 0
            for i, r in enumerate(D):
                if len(r) != 8 or r[0] != i * gen.DT:
                    bad += 1
                    continue
                if (i * gen.DT) == int(i * gen.DT) and not isinstance(r[0], int):
                    bad += 1
                if frac_dev(r[2], gen.QF, 0.0) > 1e-6: bad += 1
                if frac_dev(r[1], gen.QD, host['offD']) > 0.01: bad += 1
                if frac_dev(r[4], gen.QA, host['offA1']) > 0.06: bad += 1
                if frac_dev(r[5], gen.QA, host['offA2']) > 0.06: bad += 1
                if frac_dev(r[6], gen.QA1F, host['offF1']) > 1e-6: bad += 1
                if frac_dev(r[7], gen.QA2F, host['offF2']) > 1e-6: bad += 1
            if bad:
                fail('%s/%s: %d layout/quantisation violations' % (t, lab, bad))
            x = [r[1] for r in D]; F = [r[2] for r in D]
            x1 = [r[4] for r in D]; x2 = [r[5] for r in D]
            v = gen.velocity(x)
            m = int(round(1.5 / gen.DT))
            tail = x[-m:]
            if max(tail) - min(tail) > 0.004 or max(abs(a) for a in v[-m:]) > 0.3:
                fail('%s/%s: no final rest of 1.5 s (range %.4f in)' % (t, lab, max(tail) - min(tail)))
            first = None
            for i in range(n):
                if abs(x1[i] - x1[0]) > 0.002 or abs(x2[i] - x2[0]) > 0.002:
                    first = i * gen.DT
                    break
            if first is not None and first < 1.0:
                early += 1
            if e['category'] in ('actuator_lag', 'pretension') and first is None:
                fail('%s/%s: effect needs actuator motion but none' % (t, lab))
            R = {'x': x, 'v': v, 'x1': x1, 'x2': x2, 'F0': F[0]}
            Fb_mine = gen.simulate(R)
            Fbb = bb.get((t, lab))
            if Fbb is None or len(Fbb) != n:
                fail('%s/%s: black-box output length' % (t, lab))
                continue
            err = max(abs(a - b) for a, b in zip(Fb_mine, Fbb))
            max_base_err = max(max_base_err, err)
            if err > 1e-6:
                fail('%s/%s: own base model differs from black box by %.3g kip' % (t, lab, err))
            nrng = random.Random(info['noise_seed'])
            nz = [nrng.gauss(0.0, noise) for _ in range(n)]
            if shape == 'none':
                Ft = Fb_mine
            else:
                Ft = gen.simulate(R, shape, e['params'][gen.SHAPES[shape][1]], e['params'])
            mism = sum(1 for i in range(1, n) if F[i] != gen.quantF(Ft[i] + nz[i]))
            if mism or F[0] != info['F0_kip']:
                fail('%s/%s: %d force samples differ from quant(F_true + noise)' % (t, lab, mism))
            recs[lab] = (F, Ft, Fbb, nz)
            if shape == 'none':
                lsb = [abs(F[i] - gen.quantF(Fbb[i] + nz[i])) / gen.QF for i in range(1, n)]
                off1 = sum(1 for a in lsb if a > 0.5)
                big = sum(1 for a in lsb if a > 1.5)
                res = [F[i] - Fbb[i] for i in range(1, n)]
                mu = sum(res) / len(res)
                sd = (sum((a - mu) ** 2 for a in res) / len(res)) ** 0.5
                print('  %s/%s none: residual vs black box mean %+.5f sd %.5f (noise %.5f), '
                      '%d/%d samples 1 LSB off from quant(bb+noise)' % (t, lab, mu, sd, noise, off1, n - 1))
                if big or off1 > 0.001 * n or abs(sd / noise - 1) > 0.1 or abs(mu) > 0.2 * noise:
                    fail('%s/%s: none trial is not black-box base + noise' % (t, lab))
        if len(recs) == 2:
            s = 0.0; nn = 0
            for lab in 'AB':
                F, Ft, Fbb, nz = recs[lab]
                s += sum((a - b) ** 2 for a, b in zip(Ft, Fbb)); nn += len(Ft)
            ratio = math.sqrt(s / nn) / noise
            ok = abs(ratio - e['ratio']) <= 0.01 * max(e['ratio'], 1.0)
            band = {'weak': (2.7, 3.8), 'strong': (8.5, 11.5), 'none': (0.0, 1e-4)}[e['strength']]
            inband = band[0] <= ratio <= band[1]
            print('%s %-6s ratio vs black box %.4f (key %.4f) %s' % (t, e['strength'], ratio, e['ratio'],
                                                                   'ok' if ok and inband else 'BAD'))
            if not (ok and inband):
                fail('%s ratio %.4f not as keyed/in band' % (t, ratio))
            if not (0.02 <= noise <= 0.06):
                fail('%s noise %.4f' % (t, noise))
    print('max |own base - black box| = %.3g kip over %d records' % (max_base_err, nrec))
    print('records with actuator motion before 1 s: %d of %d' % (early, nrec))
    if not (15 <= early <= 25):
        fail('early-motion share %d/%d' % (early, nrec))
    for w in warns:
        print('WARN', w)
    print('VERIFY PASS' if not fails else 'VERIFY FAIL')


if __name__ == '__main__':
    main()
