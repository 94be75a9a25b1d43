#!/usr/bin/env python3
"""Base-model match: run `hybridsim damper predict --no-fit` on every record and compare, for the
'none' records, its prediction with the noise-free force written by generate.py (/tmp/blind6_clean, or argv[1])."""
import csv, glob, json, os, subprocess, sys
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIN = '/work/main/build/bin/hybridsim'; CFG = '/work/main/configs/brfd-semiactive.yaml'
out = '/tmp/blind6_verify'; os.makedirs(out, exist_ok=True)
worst = 0.0; lines = []
for d in sorted(glob.glob(os.path.join(ROOT, 'cases', 't*'))):
    tid = os.path.basename(d)
    for lab in 'AB':
        o = os.path.join(out, tid + lab)
        r = subprocess.run([BIN, 'damper', 'predict', '--no-fit', '--no-figure', '--config', CFG,
                            '--test', os.path.join(d, lab + '.json'), '--out', o],
                           capture_output=True, text=True)
        last = (r.stdout.strip().splitlines() or ['?'])[-1]
        clean = os.path.join(sys.argv[1] if len(sys.argv) > 1 else '/tmp/blind6_clean', '%s_%s.txt' % (tid, lab))
        extra = ''
        if os.path.exists(clean):
            ref = [float(v) for v in open(clean).read().split()]
            pred = [float(row['predicted_force_kip']) for row in csv.DictReader(open(glob.glob(o + '/*.csv')[0]))]
            m = max(abs(a - b) for a, b in zip(pred[1:], ref[1:]))
            worst = max(worst, m); extra = ' none-record max|pred-clean|=%.2e kip' % m
        lines.append('%s %s rc=%d %s%s' % (tid, lab, r.returncode, last, extra))
print('\n'.join(lines))
print('WORST base mismatch on none records (samples 1..N-1): %.3e kip' % worst)
