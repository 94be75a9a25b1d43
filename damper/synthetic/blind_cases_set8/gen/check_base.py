#!/usr/bin/env python3
"""Compare this generator's base model with `hybridsim damper predict --no-fit` on the
written records.

    python3 /work/blind8/gen/check_base.py [--out /work/blind8] [--all]

By default only the `none` trials (exact base model + noise) are checked; --all checks every
record (the binary's prediction is the base model whatever the record contains).
Prints per-record max |F_gen_base - F_binary| (kip) and the overall maximum.
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import model as M  # noqa: E402

BIN = '/work/runs/bin12/hybridsim'
CFG = '/work/main/configs/brfd-semiactive.yaml'


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--out', default='/work/blind8')
    ap.add_argument('--all', action='store_true')
    a = ap.parse_args()
    key = json.load(open(os.path.join(a.out, 'key.json')))
    worst = 0.0
    n = 0
    with tempfile.TemporaryDirectory() as td:
        for t in key['trials']:
            if t['category'] != 'none' and not a.all:
                continue
            for R in 'AB':
                fn = os.path.join(a.out, 'cases', t['id'], R + '.json')
                od = os.path.join(td, t['id'] + R)
                p = subprocess.run([BIN, 'damper', 'predict', '--no-fit', '--no-figure', '--config', CFG,
                                    '--test', fn, '--out', od], capture_output=True, text=True)
                if p.returncode != 0:
                    print(t['id'], R, 'binary failed:', p.stderr[-500:])
                    worst = float('inf')
                    continue
                csvf = [f for f in os.listdir(od) if f.endswith('_predict.csv')][0]
                rows = list(csv.DictReader(open(os.path.join(od, csvf))))
                D = json.load(open(fn))['data']
                r = M.Rec([d[1] for d in D], [d[4] for d in D], [d[5] for d in D], D[0][2])
                Fb = M.base_force(r)
                err = max(abs(x - float(row['predicted_force_kip'])) for x, row in zip(Fb, rows))
                if len(rows) != len(Fb):
                    err = float('inf')
                worst = max(worst, err)
                n += 1
                print('%s %s max|diff| = %.3g kip  (%s)' % (t['id'], R, err, p.stdout.strip().splitlines()[-1]))
    print('records=%d overall max|diff| = %.3g kip' % (n, worst))


if __name__ == '__main__':
    main()
