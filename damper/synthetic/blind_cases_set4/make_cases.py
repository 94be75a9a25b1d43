#!/usr/bin/env python3
"""Generate the blind synthetic BRFD test set: /work/blind4/cases/tNN/{A,B}.json + key.json.

python3 make_cases.py [--seed 20261125] [--out /work/blind4] [--only t05,t17]
Standard library only.  Each record: inputs of a measured semi-active test (or an
earthquake-like broadband motion), force = base semi-active LuGre model (+ one hidden effect)
+ coloured Gaussian noise, quantised like the measured files.
"""
import argparse, json, math, os, random, sys, time, glob
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import brfd_io as io, brfd_model as bm, inputs, effects

import os
CONFIG = os.path.join(os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', '..')), 'configs', 'brfd-semiactive.yaml')
CATS = ['backlash', 'residual_static', 'actuator_lag', 'asymmetry', 'velocity',
        'pretension', 'self_energizing', 'transition_shape']
FWD = [s for s in inputs.SEMI if s.endswith('forward')]
BWD = [s for s in inputs.SEMI if s.endswith('backward')]


def actuator_force_table():
    """Median actuator forces (lb) vs friction force (kip), 0.25 kip bins, from the measured
    semi-active files (paper Fig. 6: band tension ~ proportional to damping force)."""
    bins = {}
    for f in sorted(glob.glob(inputs.DATA + '/semiactive/*.json')):
        r = io.load(f)
        for F, a, b in zip(r['F'], r['f1'], r['f2']):
            bins.setdefault(round(F * 4) / 4, []).append((a, b))
    tab = []
    for k in sorted(bins):
        L = bins[k]
        if len(L) < 30:
            continue
        A = sorted(a for a, _ in L); B = sorted(b for _, b in L)
        tab.append((k, A[len(A) // 2], B[len(B) // 2]))
    return tab


def interp_tab(tab, F, col):
    if F <= tab[0][0]:
        k0, k1 = tab[0], tab[1]
    elif F >= tab[-1][0]:
        k0, k1 = tab[-2], tab[-1]
    else:
        j = max(i for i in range(len(tab)) if tab[i][0] <= F)
        k0, k1 = tab[j], tab[min(j + 1, len(tab) - 1)]
    if k1[0] == k0[0]:
        return k0[col]
    w = (F - k0[0]) / (k1[0] - k0[0])
    return k0[col] + w * (k1[col] - k0[col])


def coloured_noise(n, rms, phi, rng):
    e = 0.0; out = []
    s = math.sqrt(1 - phi * phi)
    for _ in range(n):
        e = phi * e + s * rng.gauss(0.0, 1.0)
        out.append(e)
    m = math.sqrt(sum(a * a for a in out) / n)
    return [a * rms / m for a in out]


def make_record(P, d, eff, noise_rms, rng, tab):
    d = dict(d)
    d['v'] = bm.drum_velocity(d['x']); d['x10'] = d['a1'][0]; d['x20'] = d['a2'][0]
    base = bm.simulate(P, d)
    truth = bm.simulate(P, d, eff) if eff else base
    n = len(truth)
    phi = rng.uniform(0.0, 0.5)
    nz = coloured_noise(n, noise_rms, phi, rng)
    F = [io.quant(truth[i] + nz[i], io.Q_F) for i in range(n)]
    F[0] = io.quant(d['F_init'], io.Q_F)     # first sample = initial held force (see NOTES)
    # actuator load cells (lb): median relation to the friction force + coloured noise
    src = d['src']
    off1 = src['f1'][0] - io.Q_F1 * round(src['f1'][0] / io.Q_F1)
    off2 = src['f2'][0] - io.Q_F2 * round(src['f2'][0] / io.Q_F2)
    n1 = coloured_noise(n, 1.0, 0.7, rng); n2 = coloured_noise(n, 1.0, 0.7, rng)
    f1 = []; f2 = []
    for i in range(n):
        a = interp_tab(tab, truth[i], 1); b = interp_tab(tab, truth[i], 2)
        a += n1[i] * (2.0 + 0.02 * a); b += n2[i] * (2.0 + 0.02 * b)
        f1.append(io.quant(max(a, 5.0), io.Q_F1, off1))
        f2.append(io.quant(max(b, 5.0), io.Q_F2, off2))
    vel = io.velocity_column(d['x'], rng)
    rec = dict(x=d['x'], F=F, vel=vel, a1=d['a1'], a2=d['a2'], f1=f1, f2=f2)
    diff = [a - b for a, b in zip(truth, base)]
    rms = math.sqrt(sum(e * e for e in diff) / n)
    mx = max(abs(e) for e in diff)
    # RMS over the samples where the effect is "on" (|diff| > 0.05 kip), to describe local effects
    on = [e for e in diff if abs(e) > 0.05]
    rms_on = math.sqrt(sum(e * e for e in on) / len(on)) if on else 0.0
    act_noise = math.sqrt(sum((F[i] - truth[i]) ** 2 for i in range(1, n)) / (n - 1))
    return rec, dict(effect_rms_kip=round(rms, 4), effect_max_kip=round(mx, 4),
                     effect_rms_where_above_0p05_kip=round(rms_on, 4),
                     share_samples_above_0p05=round(len(on) / n, 4),
                     noise_phi=round(phi, 3), noise_rms_actual_kip=round(act_noise, 4))


def plan(seed):
    rng = random.Random(seed)
    trials = []
    for ci, cat in enumerate(CATS):
        shapes = list(effects.SHAPES[cat].keys())
        slots = [('weak', 0.02, 'harmonic'), ('weak', 0.06, 'harmonic'),
                 ('strong', 0.02, 'harmonic'), ('strong', 0.06, 'harmonic'),
                 (None, None, 'broadband')]
        order = list(range(5)); rng.shuffle(order)
        sh_order = shapes[:]; rng.shuffle(sh_order)
        for k, si in enumerate(order):
            st, nz, kind = slots[si]
            if st is None:
                st = 'strong' if cat in ('actuator_lag', 'pretension') else rng.choice(['weak', 'strong'])
                nz = rng.choice([0.02, 0.06])
            trials.append(dict(category=cat, strength=st, noise_rms_kip=nz, input_kind=kind,
                               shape=sh_order[k % len(sh_order)]))
    none_kinds = ['harmonic'] * 5 + ['broadband'] * 3
    none_noise = [0.02, 0.06] * 4
    rng.shuffle(none_noise)
    for k in range(8):
        trials.append(dict(category='none', strength=None, noise_rms_kip=none_noise[k],
                           input_kind=none_kinds[k], shape=None))
    rng.shuffle(trials)
    for i, t in enumerate(trials):
        t['id'] = 't%02d' % (i + 1)
        t['seed'] = seed * 100 + i + 1
        r2 = random.Random(t['seed'])
        if t['input_kind'] == 'harmonic':
            a = r2.choice(FWD); b = r2.choice(BWD)
            if r2.random() < 0.5:
                a, b = b, a
            t['sources'] = [a, b]
        else:
            a = r2.choice(inputs.SEMI); b = r2.choice([s for s in inputs.SEMI if s != a])
            eqs = ['KocaeliMCE', 'synthetic']; r2.shuffle(eqs)
            t['sources'] = ['%s+%s' % (a, eqs[0]), '%s+%s' % (b, eqs[1])]
    return trials


def gen_trial(P, tab, t):
    rng = random.Random(t['seed'])
    eff = None
    if t['category'] != 'none':
        p = effects.SHAPES[t['category']][t['shape']][0 if t['strength'] == 'weak' else 1]
        eff = dict(cat=t['category'], shape=t['shape'], p=p)
    recs = {}; stats = {}
    for lab, src in zip(('A', 'B'), t['sources']):
        if t['input_kind'] == 'harmonic':
            d = inputs.harmonic(src)
        else:
            b, e = src.split('+')
            d = inputs.broadband(b, e, rng.randrange(1 << 30))
        rec, st = make_record(P, d, eff, t['noise_rms_kip'], rng, tab)
        if d['kind'] == 'broadband':
            st['actuator_mode'] = d['actuator_mode']
            st['eq_scale'] = round(d['eq_scale'], 3); st['eq_time_stretch'] = round(d['eq_stretch'], 3)
            st['first_actuator_motion_s'] = round(next(i for i in range(len(d['a1'])) if
                abs(d['a1'][i] - d['a1'][0]) > 0.002 or abs(d['a2'][i] - d['a2'][0]) > 0.002) * io.DT, 3)
        recs[lab] = rec; stats[lab] = st
    return recs, stats, eff


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--seed', type=int, default=20261125)
    ap.add_argument('--out', default='/work/blind4')
    ap.add_argument('--only', default='')
    args = ap.parse_args()
    P = bm.read_config(CONFIG)
    tab = actuator_force_table()
    trials = plan(args.seed)
    only = set(s for s in args.only.split(',') if s)
    keyp = os.path.join(args.out, 'key.json')
    key = {}
    if only and os.path.exists(keyp):
        key = json.load(open(keyp))
    t0 = time.time()
    for t in trials:
        if only and t['id'] not in only:
            continue
        cdir = os.path.join(args.out, 'cases', t['id'])
        os.makedirs(cdir, exist_ok=True)
        recs, stats, eff = gen_trial(P, tab, t)
        if t['input_kind'] == 'broadband' and t['category'] != 'none' and t['strength'] == 'weak' \
                and min(s['effect_rms_kip'] for s in stats.values()) < 0.10:
            # extra trials: the weak setting was too faint on this motion -> strong setting
            t['strength'] = 'strong'
            t['note'] = 'weak setting gave < 0.10 kip RMS on this motion; strong used'
            recs, stats, eff = gen_trial(P, tab, t)
        for lab in ('A', 'B'):
            io.write(os.path.join(cdir, lab + '.json'), recs[lab])
        ent = dict(t)
        ent['params'] = eff['p'] if eff else None
        ent['records'] = stats
        ent['effect_rms_kip'] = round(math.sqrt((stats['A']['effect_rms_kip'] ** 2 +
                                                 stats['B']['effect_rms_kip'] ** 2) / 2), 4)
        key[t['id']] = ent
        print('%s done (%.1f s)' % (t['id'], time.time() - t0), flush=True)
    with open(keyp, 'w') as fh:
        json.dump(dict(sorted(key.items())), fh, indent=1)
    print('total %.1f s' % (time.time() - t0))


if __name__ == '__main__':
    main()
