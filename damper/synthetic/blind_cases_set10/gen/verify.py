#!/usr/bin/env python3
"""Check the generated records against `hybridsim damper predict --no-fit` (black box).

For every trial and record: rms(predict - noise-free base of the generator) must be ~0 (the
generator's base model is the tool's base model), and rms(predict - written force) should be
about sqrt(noise^2 + effect_rms^2).  For 'none' trials the written force minus the prediction
is the noise alone.  Usage: python3 gen/verify.py [--out /work/blind10]
"""
import argparse
import csv
import glob
import json
import math
import os
import subprocess
import tempfile

BIN = '/work/main/build/bin/hybridsim'
CONFIG = '/work/main/configs/brfd-semiactive.yaml'


def rms(a, b):
    return math.sqrt(sum((p - q) ** 2 for p, q in zip(a, b)) / len(a))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--out', default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    a = ap.parse_args()
    key = json.load(open(os.path.join(a.out, 'key.json')))['trials']
    worst = 0.0
    with tempfile.TemporaryDirectory() as td:
        for tid in sorted(key):
            k = key[tid]
            clean = json.load(open(os.path.join(a.out, 'gen', 'work', tid + '.json')))
            line = []
            for name in 'AB':
                f = os.path.join(a.out, 'cases', tid, name + '.json')
                od = os.path.join(td, tid + name)
                subprocess.run([BIN, 'damper', 'predict', '--config', CONFIG, '--test', f,
                                '--no-fit', '--out', od, '--no-figure'],
                               check=True, capture_output=True)
                rows = list(csv.reader(open(glob.glob(os.path.join(od, '*_predict.csv'))[0])))
                pred = [float(r[6]) for r in rows[1:]]
                meas = [float(r[5]) for r in rows[1:]]
                d_base = rms(pred, clean[name]['base'])
                d_eff = rms(clean[name]['effect'], clean[name]['base'])
                d_meas = rms(pred[1:], meas[1:])
                worst = max(worst, d_base)
                line.append('%s: pred-base %.1e  effect %.3f  pred-written %.3f' % (
                    name, d_base, d_eff, d_meas))
            print('%s %-5s noise %.4f | %s' % (tid, 'none' if k['category'] == 'none' else '',
                                                k['noise_kip'], ' | '.join(line)))
    print('max rms(predict - generator base) = %.2e kip' % worst)


if __name__ == '__main__':
    main()
