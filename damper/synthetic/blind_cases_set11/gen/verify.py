#!/usr/bin/env python3
"""Check of the blind11 base model against the project's replay (`damper predict --no-fit`).

1. The 'none' trials are regenerated WITHOUT noise (same seed, same designs), written to a
   scratch folder and replayed with `hybridsim damper predict --no-fit`; the predicted force must
   equal the generated (noise-free) force to ~1e-6 kip.
2. Every shipped record (all 30 trials, noisy) is replayed by the tool and by gen.py's base model
   (z0 = F(0)/sigma0, velocity derived from the displacement); the two predictions must agree.

Usage: python3 gen/verify.py [--root /work/blind11] [--seed 11011]
Only `damper predict` is run.  Writes ROOT/gen/verify_report.txt.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gen  # noqa: E402

BIN = '/work/runs/bin17/hybridsim'
CONFIG = '/work/main/configs/brfd-semiactive.yaml'


def predict(path, outdir):
    r = subprocess.run([BIN, 'damper', 'predict', '--config', CONFIG, '--test', path, '--no-fit',
                        '--out', outdir, '--no-figure'], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError('predict failed on %s: %s' % (path, r.stderr + r.stdout))
    stem = os.path.splitext(os.path.basename(path))[0]
    rows = list(csv.DictReader(open(os.path.join(outdir, stem + '_predict.csv'))))
    return [float(r['predicted_force_kip']) for r in rows], r.stdout + r.stderr


def own_replay(path):
    d = json.load(open(path))['data']
    x = [r[1] for r in d]
    seq = dict(x=x, a1=[r[4] for r in d], a2=[r[5] for r in d], v=gen.derive_velocity(x),
               xp1=d[0][4], xp2=d[0][5])
    st = gen.init_state('none', 0.0, {}, d[0][2] / gen.params()['s0'], x[0], d[0][4], d[0][5])
    return gen.simulate('none', 0.0, {}, seq, st), [r[2] for r in d]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--root', default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    ap.add_argument('--seed', type=int, default=11011)
    a = ap.parse_args()
    lines = []
    tmp = tempfile.mkdtemp(prefix='blind11_verify_')
    # ---- 1. noise-free 'none' trials
    none = [t for t in gen.plan(a.seed) if t['shape'] == 'none']
    worst = 0.0
    for t in none:
        tid, key, out = gen.make_trial((a.seed, t))
        gen.write_trial(tmp, tid, out, noisy=False)
        for lab in 'AB':
            p = os.path.join(tmp, 'cases', tid, lab + '.json')
            pred, log = predict(p, os.path.join(tmp, 'out', tid + lab))
            F = out[lab]['F']
            assert len(pred) == len(F), (len(pred), len(F))
            dmax = max(abs(u - w) for u, w in zip(pred, F))
            worst = max(worst, dmax)
            lines.append('none-check %s/%s n=%d max|tool - generator| = %.3g kip' % (tid, lab, len(F), dmax))
    lines.append('NONE TRIALS (noise-free): max |difference| = %.3g kip over %d records' % (worst, 2 * len(none)))
    # ---- 2. shipped records: tool replay vs own base replay
    worst2 = 0.0
    for tid in sorted(os.listdir(os.path.join(a.root, 'cases'))):
        for lab in 'AB':
            p = os.path.join(a.root, 'cases', tid, lab + '.json')
            pred, log = predict(p, os.path.join(tmp, 'ship', tid + lab))
            mine, meas = own_replay(p)
            dmax = max(abs(u - w) for u, w in zip(pred, mine))
            worst2 = max(worst2, dmax)
            d = json.load(open(p))
            rest = d['data'][-1][1] == d['data'][-int(1.5 * 1024)][1]
            lines.append('shipped %s/%s n=%d max|tool - own base replay| = %.3g kip, held >= 1.5 s at end: %s'
                         % (tid, lab, len(pred), dmax, rest))
    lines.append('SHIPPED RECORDS: max |tool - own base replay| = %.3g kip' % worst2)
    txt = '\n'.join(lines)
    print(txt)
    with open(os.path.join(a.root, 'gen', 'verify_report.txt'), 'w') as fh:
        fh.write(txt + '\n')
    ok = worst < 5e-6 and worst2 < 5e-6
    print('VERIFY', 'OK' if ok else 'FAILED')
    return 0 if ok else 1


if __name__ == '__main__':
    sys.exit(main())
