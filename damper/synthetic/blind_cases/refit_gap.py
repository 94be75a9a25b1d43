#!/usr/bin/env python3
"""Extra difficulty indicator: write each record's NOISE-FREE truth (same inputs) to a temp file,
run `hybridsim damper predict` with its default passive-window re-identification of the base,
and record NRMSE(CLI prediction vs noise-free truth) = what remains of the effect after the
base refit. Added to key.json as gap_after_passive_refit. (Uses only the public CLI; not diagnose.)"""
import sys, os, json, csv, math, subprocess, tempfile, random
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from brfd_gen import *
from make_cases import PARAMS, plan
ROOT = sys.argv[1] if len(sys.argv) > 1 else '/work/blind3'
env = dict(os.environ, LD_LIBRARY_PATH='/work/blind3/bin:' + os.environ.get('LD_LIBRARY_PATH', ''))
keyp = os.path.join(ROOT, 'key.json')
key = json.load(open(keyp)); byid = {k['trial']: k for k in key}
tmp = tempfile.mkdtemp(prefix='brfdrefit')
for t in plan():
    g = {}
    for lab, src in zip(('A', 'B'), t['inputs']):
        inp = prep(load_measured(src) if t['motion'] == 'harmonic' else synth_eq(src))
        truth = simulate(inp, t['category'], PARAMS[t['category']][t['strength']]) if t['category'] != 'none' else simulate(inp)
        a1, a2 = actuator_forces(truth, random.Random(1))
        f = os.path.join(tmp, t['trial'] + lab + '.json')
        write_record(f, inp, truth, a1, a2)
        out = os.path.join(tmp, 'o' + t['trial'] + lab)
        subprocess.run([ROOT + '/bin/hybridsim', 'damper', 'predict', '--config', ROOT + '/configs/brfd-semiactive.yaml',
                        '--test', f, '--out', out, '--no-figure'], capture_output=True, text=True, env=env)
        rows = list(csv.DictReader(open(os.path.join(out, t['trial'] + lab + '_predict.csv'))))
        Fp = [float(q['predicted_force_kip']) for q in rows]
        g[lab] = round(nrmse(Fp, truth), 4)
    byid[t['trial']]['gap_after_passive_refit'] = g
    print(t['trial'], t['category'], t['strength'], t['motion'], byid[t['trial']]['gap'], g, flush=True)
json.dump(key, open(keyp, 'w'), indent=1)
