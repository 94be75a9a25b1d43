#!/usr/bin/env python3
"""Run `hybridsim damper predict --no-fit` on generated records and compare its predicted
force with this generator's noise-free base model on the same records.

    python3 gen/check_base.py [--ids t06,t12,...] [--all]
Default: the trials whose key category is 'none'."""
import argparse, csv, json, os, subprocess, sys, tempfile
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blindgen as bg

ap = argparse.ArgumentParser()
ap.add_argument('--out', default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
ap.add_argument('--bin', default='/work/runs/bin12/hybridsim')
ap.add_argument('--config', default='/work/main/configs/brfd-semiactive.yaml')
ap.add_argument('--ids', default=None)
ap.add_argument('--all', action='store_true')
a = ap.parse_args()
key = json.load(open(os.path.join(a.out, 'key.json')))['trials']
if a.ids:
    ids = a.ids.split(',')
elif a.all:
    ids = [t['id'] for t in key]
else:
    ids = [t['id'] for t in key if t['category'] == 'none']
worst = 0.0
with tempfile.TemporaryDirectory() as td:
    for tid in ids:
        for lab in 'AB':
            f = os.path.join(a.out, 'cases', tid, lab + '.json')
            p = subprocess.run([a.bin, 'damper', 'predict', '--no-fit', '--no-figure', '--config', a.config,
                                '--test', f, '--out', td], capture_output=True, text=True)
            csvf = [x for x in os.listdir(td) if x.endswith('_predict.csv')][0]
            rows = list(csv.DictReader(open(os.path.join(td, csvf))))
            os.remove(os.path.join(td, csvf))
            d = json.load(open(f))['data']
            rec = bg.prepare({'x': [r[1] for r in d], 'a1': [r[4] for r in d], 'a2': [r[5] for r in d], 'F0': d[0][2]})
            F = bg.base_force(rec)
            err = max(abs(F[i] - float(rows[i]['predicted_force_kip'])) for i in range(len(F)))
            worst = max(worst, err)
            first = [l for l in (p.stdout + p.stderr).splitlines() if 'first electric' in l or 'quirk' in l]
            print('%s/%s  max|base - hybridsim| = %.3g kip   %s' % (tid, lab, err, ' | '.join(s.split(': ', 1)[-1][:60] for s in first)))
print('worst max|base - hybridsim| = %.3g kip over %d records' % (worst, 2 * len(ids)))
