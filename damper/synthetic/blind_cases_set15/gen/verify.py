#!/usr/bin/env python3
"""Checks of blind set 15.  Last line: summary.
 1. base model (gen.simulate 'none') == `hybridsim damper predict --no-fit` on the six measured
    semi-active tests and on every synthetic record (force and derived velocity, CSV precision);
 2. each trial's achieved effect ratio (recomputed from the files and key.json), in its band;
 3. records 6-25 s, final rest >= 1.5 s (drum and actuators still), file format, noise sd.
"""
import csv, json, math, os, subprocess, sys, tempfile
HERE = os.path.dirname(os.path.abspath(__file__)); ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import gen

TOOL = '/work/runs/bin25/hybridsim'
CFG = '/work/runs/brfd-semiactive.yaml'
TOL_F = 5e-6   # kip (CSV carries 8 significant digits)
TOL_V = 2e-6   # in/s
KEYS = ['data', 'dt', 'sampling freq', 'displacement units', 'time units',
        'friction force units', 'actuator force units']


def tool_predict(path, tmp):
    out = os.path.join(tmp, os.path.basename(os.path.dirname(path)) + '_' + os.path.basename(path)[:-5])
    r = subprocess.run([TOOL, 'damper', 'predict', '--config', CFG, '--test', path, '--no-fit',
                        '--out', out, '--no-figure'], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(r.stderr[-500:])
    f = [x for x in os.listdir(out) if x.endswith('_predict.csv')][0]
    rows = list(csv.DictReader(open(os.path.join(out, f))))
    return [float(x['predicted_force_kip']) for x in rows], [float(x['drum_vel_in_per_s']) for x in rows]


def rec_from(path):
    D = json.load(open(path))
    rows = D['data']
    rec = dict(d=[r[1] for r in rows], x1=[r[4] for r in rows], x2=[r[5] for r in rows], F0=rows[0][2])
    return D, rows, rec


def main():
    fails = []
    tmp = tempfile.mkdtemp(prefix='b15v_')
    # 1a measured tests
    worst_meas = 0.0
    for name in gen.TESTS:
        path = os.path.join(gen.SEM, name + '.json')
        _, _, rec = rec_from(path)
        F = gen.simulate(rec, 'none', 0.0, {})
        Ft, Vt = tool_predict(path, tmp)
        eF = max(abs(a - b) for a, b in zip(F, Ft)); eV = max(abs(a - b) for a, b in zip(rec['v'], Vt))
        worst_meas = max(worst_meas, eF)
        ok = eF < TOL_F and eV < TOL_V and len(Ft) == len(F)
        print('measured %-24s max|dF|=%.2e max|dv|=%.2e %s' % (name, eF, eV, 'ok' if ok else 'FAIL'))
        if not ok: fails.append('measured ' + name)
    key = json.load(open(os.path.join(ROOT, 'key.json')))
    worst_syn = 0.0; nrec = 0; early = 0; ratio_ok = 0
    for tid in sorted(key):
        k = key[tid]
        recs = []; bases = []
        sd_res = []
        for m in k['records']:
            path = os.path.join(ROOT, 'cases', tid, m['file'])
            D, rows, rec = rec_from(path)
            nrec += 1
            # format
            if list(D.keys()) != KEYS or any(len(r) != 8 for r in rows) or D['sampling freq'] != 1024:
                fails.append('%s/%s format' % (tid, m['file']))
            dur = len(rows) * gen.DT
            if not (6.0 <= dur <= 25.0): fails.append('%s/%s duration %.2f' % (tid, m['file'], dur))
            # final rest: drum and actuators constant
            n = len(rows); j = n - 1
            while j > 0 and rows[j - 1][1] == rows[-1][1] and rows[j - 1][4] == rows[-1][4] and rows[j - 1][5] == rows[-1][5]:
                j -= 1
            rest = (n - j) * gen.DT
            if rest < 1.5: fails.append('%s/%s final rest %.2f s' % (tid, m['file'], rest))
            # early actuator motion (> 0.002 in from row 0 within the first second)
            x10, x20 = rows[0][4], rows[0][5]
            mv = [i for i in range(n) if max(abs(rows[i][4] - x10), abs(rows[i][5] - x20)) > 0.002]
            if mv and mv[0] * gen.DT < 1.0: early += 1
            # velocity quirk column
            gen.prep(rec)
            eq = max(abs(rows[i][3] - rec['v'][i] / gen.VEL_QUIRK) for i in range(n))
            if eq > 1e-8: fails.append('%s/%s velocity column' % (tid, m['file']))
            # 1b base model vs tool (z0 from the file's first force sample, as the tool does)
            Fb = gen.simulate(rec, 'none', 0.0, {})
            Ft, Vt = tool_predict(path, tmp)
            eF = max(abs(a - b) for a, b in zip(Fb, Ft)); eV = max(abs(a - b) for a, b in zip(rec['v'], Vt))
            worst_syn = max(worst_syn, eF)
            if not (eF < TOL_F and eV < TOL_V and len(Ft) == n):
                fails.append('%s/%s base!=tool (%.2e, %.2e)' % (tid, m['file'], eF, eV))
            # truth with the key's initial force
            tr = dict(d=rec['d'], x1=rec['x1'], x2=rec['x2'], F0=m['F0_true_kip'])
            gen.prep(tr)
            fb = gen.simulate(tr, 'none', 0.0, {})
            fe = gen.simulate(tr, k['shape'], k['p'], k['params']) if k['shape'] != 'none' else fb
            recs.append(tr); bases.append(fb)
            res = [rows[i][2] - fe[i] for i in range(n)]
            mu = sum(res) / n
            sd_res.append(math.sqrt(sum((x - mu) ** 2 for x in res) / n))
        if k['shape'] == 'none':
            ratio = 0.0; ok = True
        else:
            ratio = gen.rms_diff(recs, k['shape'], k['p'], k['params'], bases) / k['noise_kip']
            band = (2.7, 3.8) if k['strength'] == 'weak' else (8.5, 11.5)
            ok = band[0] <= ratio <= band[1] and abs(ratio - k['ratio']) < 1e-3 * max(1, ratio)
        sdok = all(abs(s / k['noise_kip'] - 1) < 0.05 for s in sd_res)
        if ok: ratio_ok += 1
        else: fails.append('%s ratio %.3f' % (tid, ratio))
        if not sdok: fails.append('%s noise sd %s' % (tid, sd_res))
        print('%s ratio=%.3f (key %.3f) noise_sd=%.4f/%.4f measured_sd=%s %s' % (
            tid, ratio, k['ratio'], k['noise_kip'], k['noise_kip'], ['%.4f' % s for s in sd_res],
            'ok' if ok and sdok else 'FAIL'))
    for f in fails: print('FAIL:', f)
    print('SUMMARY: trials=%d records=%d base==tool on 6 measured (max|dF| %.1e kip) and %d synthetic records (max|dF| %.1e kip); '
          'ratios in band %d/%d; final rest>=1.5s all; early-actuator records %d/%d; failures=%d %s' % (
              len(key), nrec, worst_meas, nrec, worst_syn, ratio_ok, len(key), early, nrec, len(fails),
              'PASS' if not fails else 'FAIL'))


if __name__ == '__main__':
    main()
