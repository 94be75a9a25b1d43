#!/usr/bin/env python3
"""Check every generated record against the project's CLI: `hybridsim damper predict --no-fit`
must equal this generator's base model (same inputs, z0 = measured F(0)/sigma0 as the CLI does).
Also: for 'none' trials, CLI prediction vs noise-free truth, and the realized noise RMS."""
import sys, os, json, csv, math, subprocess, tempfile
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from brfd_gen import *
from make_cases import PARAMS, plan
ROOT = sys.argv[1] if len(sys.argv) > 1 else '/work/blind3'
env = dict(os.environ, LD_LIBRARY_PATH='/work/blind3/bin:' + os.environ.get('LD_LIBRARY_PATH', ''))
key = {k['trial']: k for k in json.load(open(os.path.join(ROOT, 'key.json')))}
res = []
tmp = tempfile.mkdtemp(prefix='brfdverify')
for t in plan():
    for lab, src in zip(('A', 'B'), t['inputs']):
        f = os.path.join(ROOT, 'cases', t['trial'], lab + '.json')
        D = json.load(open(f))['data']
        out = os.path.join(tmp, t['trial'] + lab)
        r = subprocess.run([ROOT + '/bin/hybridsim', 'damper', 'predict', '--config', ROOT + '/configs/brfd-semiactive.yaml',
                            '--test', f, '--no-fit', '--out', out, '--no-figure'], capture_output=True, text=True, env=env)
        rows = list(csv.DictReader(open(os.path.join(out, lab + '_predict.csv'))))
        Fp = [float(q['predicted_force_kip']) for q in rows]
        inp = prep(load_measured(src) if t['motion'] == 'harmonic' else synth_eq(src))
        Fmeas = [r_[2] for r_ in D]
        mine = simulate(inp, z0F=Fmeas[0])
        truth = simulate(inp, t['category'], PARAMS[t['category']][t['strength']]) if t['category'] != 'none' else simulate(inp)
        n = len(Fp)
        d = dict(trial=t['trial'], record=lab, category=t['category'], n=n,
                 cli_vs_generator_base_max_kip=max(abs(a - b) for a, b in zip(Fp, mine)),
                 cli_vs_generator_base_rms_kip=math.sqrt(sum((a - b) ** 2 for a, b in zip(Fp, mine)) / n),
                 noise_rms_kip=math.sqrt(sum((a - b) ** 2 for a, b in zip(Fmeas, truth)) / n),
                 cli_vs_truth_rms_kip=math.sqrt(sum((a - b) ** 2 for a, b in zip(Fp, truth)) / n),
                 cli_last_line=r.stdout.strip().splitlines()[-1])
        res.append(d)
        print(d['trial'], lab, d['category'], '%.2e %.2e noise %.4f cli-vs-truth %.4f' % (
            d['cli_vs_generator_base_max_kip'], d['cli_vs_generator_base_rms_kip'], d['noise_rms_kip'], d['cli_vs_truth_rms_kip']), flush=True)
json.dump(res, open(os.path.join(os.path.dirname(os.path.abspath(__file__)), 'verify_results.json'), 'w'), indent=1)
print('overall max |CLI - generator base| = %.3e kip' % max(d['cli_vs_generator_base_max_kip'] for d in res))
