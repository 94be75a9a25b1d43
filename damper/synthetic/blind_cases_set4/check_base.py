#!/usr/bin/env python3
"""Base-model check: replay records through `hybridsim damper predict --no-fit` and compare its
predicted force with this generator's base model (compares outputs only).
usage: python3 check_base.py cases/t07/A.json [...]"""
import csv, math, os, subprocess, sys, json
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import brfd_io as io, brfd_model as bm
import os
H = os.path.join(os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', '..')), 'build', 'bin', 'hybridsim')
import os
CONFIG = os.path.join(os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', '..')), 'configs', 'brfd-semiactive.yaml')
P = bm.read_config(CONFIG)
worst = 0.0
for path in sys.argv[1:]:
    tag = path.replace('/', '_').replace('.json', '')
    out = '/tmp/blind4_check/' + tag
    os.makedirs(out, exist_ok=True)
    res = subprocess.run([H, 'damper', 'predict', '--config', CONFIG, '--test', path, '--no-fit',
                          '--out', out, '--no-figure'], capture_output=True, text=True)
    last = [l for l in res.stdout.splitlines() if l.startswith('nrmse=')]
    csvp = [f for f in os.listdir(out) if f.endswith('_predict.csv')][0]
    rows = list(csv.DictReader(open(os.path.join(out, csvp))))
    Ft = [float(q['predicted_force_kip']) for q in rows]
    r = io.load(path)
    d = dict(x=r['x'], v=bm.drum_velocity(r['x']), a1=r['a1'], a2=r['a2'], x10=r['a1'][0],
             x20=r['a2'][0], F_init=r['F'][0])
    mine = bm.simulate(P, d)
    diff = [abs(a - b) for a, b in zip(mine, Ft)]
    res_meas = math.sqrt(sum((a - b) ** 2 for a, b in zip(r['F'], Ft)) / len(Ft))
    worst = max(worst, max(diff))
    print('%-28s max|mine-predict| = %.2e kip  rms = %.2e  | predict vs record rmse = %.4f  (%s)' % (
        path, max(diff), math.sqrt(sum(e * e for e in diff) / len(diff)), res_meas,
        last[0] if last else 'rc=%d' % res.returncode))
print('worst max difference: %.2e kip' % worst)
