#!/usr/bin/env python3
"""Sanity checks of the written cases (format and input constraints).

    python3 /work/blind8/gen/validate.py [--out /work/blind8]

Checks per record: 15361 rows x 8 columns, uniform 1024 Hz time from 0 to 15 s, header keys;
for the custom inputs also: peak derived drum speed, peak |displacement|, actuator excursion
from the first row, and the number of full sliding cycles (both ways) before the first
actuator motion (> 0.002 in from the first row, the binary's definition).
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import model as M  # noqa: E402

KEYS = ['data', 'dt', 'sampling freq', 'displacement units', 'time units', 'friction force units',
        'actuator force units']


def cycles_before(x, v, i_end, vmin=0.3):
    """Count direction changes of sliding (|v| > vmin) before index i_end; 4 changes with
    both directions = 2 full cycles."""
    last = 0
    changes = 0
    for i in range(i_end):
        if abs(v[i]) > vmin:
            s = 1 if v[i] > 0 else -1
            if last and s != last:
                changes += 1
            last = s
    return changes / 2.0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--out', default='/work/blind8')
    a = ap.parse_args()
    key = json.load(open(os.path.join(a.out, 'key.json')))
    bad = 0
    for t in key['trials']:
        for R in 'AB':
            fn = os.path.join(a.out, 'cases', t['id'], R + '.json')
            d = json.load(open(fn))
            D = d['data']
            ok = list(d.keys()) == KEYS and len(D) == 15361 and all(len(r) == 8 for r in D)
            ok = ok and all(abs(r[0] - i / 1024.0) < 1e-12 for i, r in enumerate(D))
            msg = ''
            if t['input_kind'] == 'custom':
                x = [r[1] for r in D]
                v = M.derived_velocity(x)
                x1 = [r[4] for r in D]
                x2 = [r[5] for r in D]
                mv = [i for i in range(len(D)) if abs(x1[i] - x1[0]) > 0.002 or abs(x2[i] - x2[0]) > 0.002]
                i0 = mv[0] if mv else len(D)
                cyc = cycles_before(x, v, i0)
                ex = max(max(abs(u - x1[0]) for u in x1), max(abs(u - x2[0]) for u in x2))
                vmax = max(abs(u) for u in v)
                xmax = max(abs(u) for u in x)
                ok = ok and cyc >= 2 and ex <= 0.0305 and vmax <= 4.05 and xmax <= 1.25
                msg = ('custom: first actuator motion %.2f s after %.1f sliding cycles, max |dx_act| %.4f in, '
                       'max |v| %.2f in/s, max |x| %.3f in' % (i0 / 1024.0, cyc, ex, vmax, xmax))
            bad += 0 if ok else 1
            print(t['id'], R, 'OK ' if ok else 'BAD', msg)
    print('bad records:', bad)


if __name__ == '__main__':
    main()
