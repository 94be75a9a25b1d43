#!/usr/bin/env python3
"""Checks of blind test set 18 (/work/blind18).  Python 3 standard library only.

usage:  nice -n 10 python3 verify.py [--no-blackbox] [--no-regen]

  * key.json: 30 trials, 6 'none', 8 categories x 3 different shapes, 12 weak / 12 strong,
    every category mixed, noise SD in [0.02, 0.06], achieved ratio on target;
  * every record: measured-data JSON format, 1024 Hz, 6.5-25 s, force quantized, final rest
    >= 1.5 s (drum and actuators still), early actuation (< 1 s) or a passive stretch of at
    least 3 drum cycles, varied initial band force;
  * the base model of gen.py equals `hybridsim damper predict --no-fit` on every record;
  * force column - recomputed (base + effect) is white noise of the key's SD, and the
    recomputed effect/noise ratio equals the key's;
  * determinism: two trials regenerated into a scratch folder are byte-identical.
The last line printed is VERIFY PASS or VERIFY FAIL.
"""
import csv
import json
import math
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import gen  # noqa: E402

BLACKBOX = '/work/runs/binhead/hybridsim'
FAILS = []


def check(cond, msg):
    if not cond:
        FAILS.append(msg)
        print('FAIL:', msg)
    return cond


def load_record(path):
    obj = json.load(open(path))
    return obj


def still_tail(rec, a1, a2, x):
    """Length (s) of the final stretch where drum and actuators are still."""
    n = rec.n
    xf, a1f, a2f = x[-1], a1[-1], a2[-1]
    i = n - 1
    while i > 0 and abs(x[i] - xf) <= 4e-4 and abs(a1[i] - a1f) <= 3e-5 \
            and abs(a2[i] - a2f) <= 3e-5 and (abs(rec.v[i]) < gen.V_REST or i > n - 9):
        i -= 1
    return (n - 1 - i) * gen.DT


def reversals_before(x, i_end, amp=0.1):
    """Drum reversals (turning points with swings > amp in) in x[0:i_end]."""
    cnt = 0
    direction = 0
    hi = lo = ext = x[0]
    for i in range(1, i_end):
        xi = x[i]
        if direction == 0:
            hi, lo = max(hi, xi), min(lo, xi)
            if xi - lo > amp:
                direction, ext = 1, xi
            elif hi - xi > amp:
                direction, ext = -1, xi
        elif direction == 1:
            if xi > ext:
                ext = xi
            elif ext - xi > amp:
                cnt += 1
                direction, ext = -1, xi
        else:
            if xi < ext:
                ext = xi
            elif xi - ext > amp:
                cnt += 1
                direction, ext = 1, xi
    return cnt


def main(argv):
    do_bb = '--no-blackbox' not in argv
    do_regen = '--no-regen' not in argv
    key = json.load(open(os.path.join(ROOT, 'key.json')))
    # ------------------------------------------------------------------ key
    tids = ['t%02d' % k for k in range(1, 31)]
    check(sorted(key) == tids, 'key.json must hold t01..t30')
    cats = {}
    for tid in tids:
        e = key[tid]
        for fld in ('category', 'shape', 'strength', 'p', 'noise_kip', 'ratio', 'params'):
            check(fld in e, '%s: key lacks %s' % (tid, fld))
        cats.setdefault(e['category'], []).append(e)
        check(0.02 <= e['noise_kip'] <= 0.06, '%s: noise SD %.4f out of range' % (tid, e['noise_kip']))
        if e['category'] == 'none':
            check(e['strength'] == 'none' and e['p'] == 0.0 and e['ratio'] == 0.0,
                  '%s: none trial must have p = ratio = 0' % tid)
        else:
            check(e['shape'] in gen.SHAPES.get(e['category'], []),
                  '%s: shape %s not of category %s' % (tid, e['shape'], e['category']))
            lo, hi = {'weak': (2.7, 3.8), 'strong': (8.5, 11.5)}[e['strength']]
            check(lo * 0.995 <= e['ratio'] <= hi * 1.005,
                  '%s: ratio %.3f outside the %s band' % (tid, e['ratio'], e['strength']))
            check(abs(e['ratio'] - e['target_ratio']) <= 0.005 * e['target_ratio'],
                  '%s: ratio %.4f misses target %.4f' % (tid, e['ratio'], e['target_ratio']))
    check(len(cats.get('none', [])) == 6, 'need 6 none trials')
    nweak = sum(1 for e in key.values() if e['strength'] == 'weak')
    nstrong = sum(1 for e in key.values() if e['strength'] == 'strong')
    check(nweak == 12 and nstrong == 12, 'need 12 weak + 12 strong (have %d/%d)' % (nweak, nstrong))
    for c in gen.SHAPES:
        es = cats.get(c, [])
        check(len(es) == 3, 'category %s needs 3 trials' % c)
        check(len(set(e['shape'] for e in es)) == 3, 'category %s needs 3 different shapes' % c)
        st = set(e['strength'] for e in es)
        check(st == {'weak', 'strong'}, 'category %s needs a weak/strong mix' % c)
    allshapes = [e['shape'] for e in key.values() if e['category'] != 'none']
    check(len(set(allshapes)) == 24, '24 different effect shapes expected')

    # ------------------------------------------------------------------ records
    bbdir = os.path.join(HERE, '_bb')
    if do_bb:
        shutil.rmtree(bbdir, ignore_errors=True)
        os.makedirs(bbdir)
    n_early = 0
    F0s = []
    durations = []
    worst_bb = 0.0
    for tid in tids:
        e = key[tid]
        recs, frecs, paths = [], [], []
        for rn in 'AB':
            path = os.path.join(ROOT, 'cases', tid, rn + '.json')
            if not check(os.path.exists(path), '%s missing' % path):
                continue
            obj = load_record(path)
            for mk, mv in gen.META.items():
                check(obj.get(mk) == mv, '%s: meta %s' % (path, mk))
            D = obj['data']
            check(all(len(r) == 8 for r in D), '%s: 8 columns expected' % path)
            n = len(D)
            t = [r[0] for r in D]
            x = [r[1] for r in D]
            F = [r[2] for r in D]
            vcol = [r[3] for r in D]
            a1 = [r[4] for r in D]
            a2 = [r[5] for r in D]
            check(all(abs(t[i] - i * gen.DT) < 1e-9 for i in range(n)), '%s: time base' % path)
            check(all(math.isfinite(u) for r in D for u in r), '%s: non-finite value' % path)
            dur = (n - 1) * gen.DT
            durations.append(dur)
            check(6.5 <= dur <= 25.0, '%s: duration %.2f s' % (path, dur))
            check(all(abs(f / gen.Q_F - round(f / gen.Q_F)) < 1e-5 for f in F),
                  '%s: force not quantized' % path)
            rec = gen.Rec(t, x, a1, a2, F[0])
            check(max(abs(vcol[i] * gen.VEL_QUIRK - rec.v[i]) for i in range(n)) < 1e-6,
                  '%s: velocity column (quirk 1/125.4) inconsistent' % path)
            tail = still_tail(rec, a1, a2, x)
            check(tail >= 1.5, '%s: final rest %.2f s < 1.5 s' % (path, tail))
            fm = gen.first_motion(rec)
            check(fm is not None, '%s: actuators never move' % path)
            lay = e['records'][rn]
            if lay['active_early']:
                n_early += 1
                check(fm is not None and fm < 1.0, '%s: early record moves actuators at %s s' % (path, fm))
            else:
                ifm = int(round(fm / gen.DT)) if fm is not None else n
                rv = reversals_before(x, ifm)
                check(rv >= 6 and fm >= 5.0,
                      '%s: passive stretch too short (%d reversals, %.2f s)' % (path, rv, fm or 0))
            F0s.append(F[0])
            recs.append(rec)
            frecs.append(F)
            paths.append(path)
            # black box
            if do_bb:
                out = os.path.join(bbdir, tid + rn)
                r = subprocess.run([BLACKBOX, 'damper', 'predict', '--no-fit', '--config', gen.CONFIG,
                                    '--test', path, '--out', out, '--no-figure'],
                                   stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
                if check(r.returncode == 0, '%s: black box failed: %s' % (path, r.stdout[-300:])):
                    csvs = [f for f in os.listdir(out) if f.endswith('_predict.csv')]
                    rows = list(csv.DictReader(open(os.path.join(out, csvs[0]))))
                    P = [float(rw['predicted_force_kip']) for rw in rows]
                    Fb = gen.simulate(rec)
                    dmax = max(abs(a - b) for a, b in zip(P, Fb))
                    worst_bb = max(worst_bb, dmax)
                    check(len(P) == n and dmax < 2e-6,
                          '%s: base model differs from black box by %.2e kip' % (path, dmax))
                    if e['category'] == 'none':
                        res = [F[i] - P[i] for i in range(1, n)]
                        sdr = math.sqrt(sum(u * u for u in res) / len(res))
                        check(abs(sdr / e['noise_kip'] - 1) < 0.05,
                              '%s: none trial, residual to black box SD %.4f vs noise %.4f'
                              % (path, sdr, e['noise_kip']))
        if len(recs) != 2:
            continue
        # recomputed truth: noise whiteness and SD, effect ratio
        num = 0.0
        cnt = 0
        for rec, F in zip(recs, frecs):
            Fb = gen.simulate(rec)
            Ft = gen.simulate(rec, e['shape'], e['p'], e['params']) if e['category'] != 'none' else Fb
            res = [F[i] - Ft[i] for i in range(1, rec.n)]
            m = sum(res) / len(res)
            sdr = math.sqrt(sum((u - m) ** 2 for u in res) / len(res))
            r1 = sum((res[i] - m) * (res[i + 1] - m) for i in range(len(res) - 1)) / (len(res) * sdr * sdr)
            check(abs(sdr / e['noise_kip'] - 1) < 0.05, '%s: noise SD %.4f vs key %.4f'
                  % (tid, sdr, e['noise_kip']))
            check(abs(m) < 5 * sdr / math.sqrt(len(res)), '%s: noise mean %.4f' % (tid, m))
            check(abs(r1) < 0.05, '%s: noise lag-1 correlation %.3f' % (tid, r1))
            for a, b in zip(Ft, Fb):
                num += (a - b) ** 2
            cnt += rec.n
        ratio = math.sqrt(num / cnt) / e['noise_kip']
        check(abs(ratio - e['ratio']) <= 1e-6 * max(1.0, e['ratio']),
              '%s: recomputed ratio %.5f vs key %.5f' % (tid, ratio, e['ratio']))
        print('%s ok  %-6s dur %5.1f/%5.1f s  ratio %6.3f' % (
            tid, e['strength'], recs[0].n * gen.DT, recs[1].n * gen.DT, ratio))
    check(18 <= n_early <= 22, 'about a third of the records should start with actuation (%d/60)' % n_early)
    mF = sum(F0s) / len(F0s)
    sF = math.sqrt(sum((f - mF) ** 2 for f in F0s) / len(F0s))
    check(sF > 0.8, 'initial band force must vary (SD %.3f kip)' % sF)
    print('records: %d early-actuation of 60; durations %.1f-%.1f s; F0 %.2f-%.2f kip (SD %.2f)'
          % (n_early, min(durations), max(durations), min(F0s), max(F0s), sF))
    if do_bb:
        print('black box vs gen.py base model: max |dF| = %.2e kip over 60 records' % worst_bb)
        shutil.rmtree(bbdir, ignore_errors=True)

    # ------------------------------------------------------------------ determinism
    if do_regen:
        scratch = os.path.join(HERE, '_regen')
        shutil.rmtree(scratch, ignore_errors=True)
        os.makedirs(scratch)
        pick = ['t01', 't%02d' % (1 + sum(ord(c) for c in json.dumps(sorted(key))) % 30)]
        r = subprocess.run([sys.executable, os.path.join(HERE, 'gen.py'), '--out', scratch,
                            '--only', ','.join(pick), '--jobs', '1'],
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        check(r.returncode == 0, 'regeneration failed: ' + r.stdout[-300:])
        part = json.load(open(os.path.join(scratch, 'key_partial.json')))
        for tid in pick:
            check(part.get(tid) == key[tid], 'determinism: key entry of %s differs' % tid)
            for rn in 'AB':
                a = open(os.path.join(ROOT, 'cases', tid, rn + '.json'), 'rb').read()
                b = open(os.path.join(scratch, 'cases', tid, rn + '.json'), 'rb').read()
                check(a == b, 'determinism: %s/%s.json differs' % (tid, rn))
        print('determinism: regenerated %s byte-identical' % ','.join(pick))
        shutil.rmtree(scratch, ignore_errors=True)

    if FAILS:
        print('%d check(s) failed' % len(FAILS))
        print('VERIFY FAIL')
        return 1
    print('VERIFY PASS')
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
