#!/usr/bin/env python3
"""Checks of the blind12 test set (standard library only).

    python3 gen/verify.py [--seed 12012] [--out /work/blind12]

(0) the hard-coded base-model parameters equal /work/runs/brfd-semiactive.yaml;
(1) the 'none' trials regenerated WITHOUT noise are replayed by
    `hybridsim damper predict --no-fit` and compared with our base model (CSV
    prediction column and the printed nrmse line);
(2) all 60 noisy records are replayed by the tool and by our base model; the largest
    difference is reported;
(3) every record ends with >= 1.5 s at rest (drum and actuators held);
plus a summary of key.json.  Writes gen/verify_report.txt.
"""
import argparse
import csv
import json
import math
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import gen  # noqa: E402

TOOL = '/work/runs/bin20/hybridsim'
CONFIG = '/work/runs/brfd-semiactive.yaml'


def run_tool(path, outdir):
    r = subprocess.run([TOOL, 'damper', 'predict', '--no-fit', '--config', CONFIG,
                        '--test', path, '--out', outdir, '--no-figure'],
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError('tool failed on %s: %s' % (path, r.stderr))
    line = [l for l in r.stdout.splitlines() if l.startswith('nrmse=')][0].strip()
    name = os.path.basename(path)[:-5]
    rows = list(csv.reader(open(os.path.join(outdir, name + '_predict.csv'))))
    hdr = rows[0]
    data = [[float(t) for t in l] for l in rows[1:]]
    return r.stdout, line, hdr, data


def compare(path, tmp):
    """Tool vs our base replay of one record file."""
    stdout, line, hdr, data = run_tool(path, tmp)
    Fp, Fm, v, fc = gen.replay_file(path)
    ip = hdr.index('predicted_force_kip')
    iv = hdr.index('drum_vel_in_per_s')
    ik = hdr.index('kinetic_friction_kip')
    dF = max(abs(a - r[ip]) for a, r in zip(Fp, data))
    dv = max(abs(a - r[iv]) for a, r in zip(v, data))
    dk = max(abs(a - r[ik]) for a, r in zip(fc, data))
    mine = gen.nrmse_line(Fp, Fm)
    derived = 'derived from the displacement' in stdout
    return dict(dF=dF, dv=dv, dk=dk, tool_line=line, my_line=mine, same_line=(line == mine),
                derived=derived, tool_pred=[r[ip] for r in data], tool_vel=[r[iv] for r in data],
                Fm=Fm)


def rest_at_end(path, tool_vel=None):
    d = json.load(open(path))['data']
    last = d[-1]
    k = len(d) - 1
    while k > 0 and all(d[k - 1][c] == last[c] for c in (1, 4, 5, 6, 7)):
        k -= 1
    held = (len(d) - 1 - k) * gen.DT
    vzero = None
    if tool_vel is not None:
        j = len(tool_vel) - 1
        while j > 0 and tool_vel[j - 1] == 0.0:
            j -= 1
        vzero = (len(tool_vel) - 1 - j) * gen.DT
    return held, vzero


def check_yaml():
    txt = open(CONFIG).read()
    def num(key):
        return float(re.search(r'^\s*%s:\s*([-0-9.eE+]+)' % key, txt, re.M).group(1))
    def lst(key):
        return [float(t) for t in re.search(r'^\s*%s:\s*\[([^\]]*)\]' % key, txt, re.M).group(1).split(',')]
    P = gen.P
    ok = (num('sigma0_kip_per_in') == P['s0'] and num('sigma1_kip_s_per_in') == P['s1'] and
          num('sigma2_kip_s_per_in') == P['s2'] and num('fs_fwd_kip') == P['fsf'] and
          num('fs_bwd_kip') == P['fsb'] and num('fc_fwd_kip') == P['fcf'] and
          num('fc_bwd_kip') == P['fcb'] and num('vs_in_per_s') == P['vs'] and
          lst('slopes_kip_per_in') == P['m'] and lst('scaling') == P['C'] and
          num('fc_floor_kip') == P['floor'])
    return ok


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--seed', type=int, default=12012)
    ap.add_argument('--out', default='/work/blind12')
    a = ap.parse_args()
    t0 = time.time()
    rep = []
    say = lambda s='': (rep.append(s), print(s))
    say('blind12 verify report (seed %d, out %s)' % (a.seed, a.out))
    say('tool: %s damper predict --no-fit --config %s --test FILE --out DIR --no-figure' % (TOOL, CONFIG))
    say()
    say('(0) base-model parameters equal the yaml: %s' % check_yaml())
    key = json.load(open(os.path.join(a.out, 'key.json')))
    tmp = tempfile.mkdtemp(prefix='blind12v_')
    try:
        # ---------------------------------------------------------------- (1)
        none_ids = sorted(t for t, e in key.items() if e['category'] == 'none')
        say()
        say('(1) noise-free regeneration of the %d none trials: %s' % (len(none_ids), ' '.join(none_ids)))
        nf_dir = os.path.join(tmp, 'nf')
        gen.generate(a.seed, nf_dir, noise_free_none=True, only=set(none_ids),
                     log=open(os.devnull, 'w'))
        worst1 = 0.0
        worst1_col = 0.0
        lines_ok = True
        inputs_same = True
        for tid in none_ids:
            for tag in 'AB':
                p_nf = os.path.join(nf_dir, 'cases', tid, tag + '.json')
                p_noisy = os.path.join(a.out, 'cases', tid, tag + '.json')
                c = compare(p_nf, tmp)
                dcol = max(abs(x - y) for x, y in zip(c['tool_pred'], c['Fm']))
                worst1 = max(worst1, c['dF'])
                worst1_col = max(worst1_col, dcol)
                lines_ok &= c['same_line']
                dn = json.load(open(p_noisy))['data']
                df = json.load(open(p_nf))['data']
                same = len(dn) == len(df) and all(r1[k] == r2[k] for r1, r2 in zip(dn, df)
                                                  for k in (0, 1, 3, 4, 5, 6, 7))
                inputs_same &= same
                res = [r1[2] - r2[2] for r1, r2 in zip(dn, df)]
                mu = sum(res) / len(res)
                sd = math.sqrt(sum((r - mu) ** 2 for r in res) / len(res))
                say('  %s/%s  tool "%s" | ours "%s" | max|tool-ours| %.2e kip | max|tool-force column| %.2e kip'
                    ' | noisy-file residual mean %+.4f sd %.4f (noise_kip %.4f)' %
                    (tid, tag, c['tool_line'], c['my_line'], c['dF'], dcol, mu, sd, key[tid]['noise_kip']))
        say('  => largest |tool - our base model| on noise-free none records: %.3g kip '
            '(CSV prints 8 significant digits)' % worst1)
        say('  => largest |tool prediction - noise-free force column|: %.3g kip' % worst1_col)
        say('  => printed nrmse lines identical: %s; noisy files have the same inputs: %s' %
            (lines_ok, inputs_same))
        # ---------------------------------------------------------------- (2)+(3)
        say()
        say('(2) tool vs our base model on all noisy records; (3) rest at the end')
        worstF = worstv = worstk = 0.0
        nl_ok = 0
        n = 0
        derived_all = True
        min_held = 1e9
        min_vzero = 1e9
        for tid in sorted(key):
            for tag in 'AB':
                p = os.path.join(a.out, 'cases', tid, tag + '.json')
                c = compare(p, tmp)
                held, vzero = rest_at_end(p, c['tool_vel'])
                min_held = min(min_held, held)
                min_vzero = min(min_vzero, vzero)
                worstF = max(worstF, c['dF'])
                worstv = max(worstv, c['dv'])
                worstk = max(worstk, c['dk'])
                nl_ok += c['same_line']
                derived_all &= c['derived']
                n += 1
                say('  %s/%s  tool "%s"  ours "%s"  %s  max|dF| %.2e  end held %.3f s, tool v==0 last %.3f s' %
                    (tid, tag, c['tool_line'], c['my_line'], 'same' if c['same_line'] else 'DIFF',
                     c['dF'], held, vzero))
        say('  => %d records; largest |tool - ours|: force %.3g kip, velocity %.3g in/s, Fc %.3g kip' %
            (n, worstF, worstv, worstk))
        say('  => printed nrmse lines identical on %d/%d records; tool derived the velocity from the '
            'displacement on all: %s' % (nl_ok, n, derived_all))
        say('  => shortest final rest (displacement, actuator positions and forces exactly constant): '
            '%.3f s; shortest final run of tool velocity == 0: %.3f s; >= 1.5 s: %s' %
            (min_held, min_vzero, min_held >= 1.5 and min_vzero >= 1.5))
        # ---------------------------------------------------------------- key summary
        say()
        say('key summary')
        cats = {}
        for tid, e in sorted(key.items()):
            cats.setdefault(e['category'], []).append(e)
        for cat, es in sorted(cats.items()):
            say('  %-17s %d trials, shapes %s, strengths %s' %
                (cat, len(es), sorted(set(e['shape'] for e in es)), sorted(e['strength'] for e in es)))
        dev = [abs(e['achieved_ratio'] / e['target_ratio'] - 1) for e in key.values()
               if e['category'] != 'none']
        say('  largest |achieved/target - 1| = %.4f' % max(dev))
        nw = sum(e['strength'] == 'weak' for e in key.values())
        ns = sum(e['strength'] == 'strong' for e in key.values())
        say('  weak %d, strong %d, none %d' % (nw, ns, len(key) - nw - ns))
        ok_ab = all(not set(e['records']['A']['sources']) & set(e['records']['B']['sources'])
                    and e['records']['A']['end'] != e['records']['B']['end'] for e in key.values())
        say('  A/B from different source tests and with different endings in every trial: %s' % ok_ab)
        say()
        say('verify took %.1f s' % (time.time() - t0))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    with open(os.path.join(HERE, 'verify_report.txt'), 'w') as f:
        f.write('\n'.join(rep) + '\n')


if __name__ == '__main__':
    main()
