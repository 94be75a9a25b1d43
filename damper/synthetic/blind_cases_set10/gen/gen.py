#!/usr/bin/env python3
"""Blind hidden-effect test set for the BRFD model-discrepancy tool (blind10).

Usage:  python3 gen/gen.py [--seed 10010] [--out /work/blind10] [--jobs 2]

Makes 30 trials (8 categories x 3 shapes + 6 'none'), each two records A.json / B.json in
the format of the measured semi-active files, from the semi-active base model of
configs/brfd-semiactive.yaml driven by the replayed measured drum displacement and actuator
positions (possibly cut at reversals, mirrored, or two tests concatenated), with one hidden
effect added and white force noise.  Writes:
  cases/tNN/{A,B}.json   the records given to the tool
  trials.txt             trial ids
  key.json, NOTES.md     the answers (never give them to the tool)
  gen/work/tNN.json      noise-free base and effect forces (for gen/verify.py)
Deterministic for a given seed.  Python 3 standard library only.
"""
import argparse
import json
import math
import multiprocessing
import os
import random
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import brfdsim as bs  # noqa: E402

DT = bs.DT
DATA = '/work/shared/data/brfd/semiactive'
CONFIG = '/work/main/configs/brfd-semiactive.yaml'
SOURCES = {
    'f015': 'harmonic0.015forward.json', 'b015': 'harmonic0.015backward.json',
    'f1': 'harmonic0.03ea1forward.json', 'b1': 'harmonic0.03ea1backward.json',
    'f2': 'harmonic0.03ea2forward.json', 'b2': 'harmonic0.03ea2backward.json',
}
FWD = ['f015', 'f1', 'f2']
BWD = ['b015', 'b1', 'b2']

CATEGORIES = {
    'backlash': ['bl_deadzone', 'bl_soft', 'bl_dip'],
    'residual_static': ['rs_relax', 'rs_creep', 'rs_settle'],
    'actuator_lag': ['al_first', 'al_delay', 'al_second'],
    'asymmetry': ['as_stiff', 'as_gain', 'as_tanh'],
    'velocity': ['ve_power', 've_stribeck', 've_memory'],
    'pretension': ['pt_gain', 'pt_offset', 'pt_wear'],
    'self_energizing': ['se_angle', 'se_capstan', 'se_servo'],
    'transition_shape': ['ts_dahl', 'ts_elastoplastic', 'ts_multi'],
}

# p (the strength parameter scaled to hit the target ratio) : upper bound, and a description
PMAX = {
    'bl_deadzone': 0.5, 'bl_soft': 1.0, 'bl_dip': 0.97,
    'rs_relax': 10.0, 'rs_creep': 2.0, 'rs_settle': 4.0,
    'al_first': 0.6, 'al_delay': 0.6, 'al_second': 0.25,
    'as_stiff': 4.0, 'as_gain': 2.0, 'as_tanh': 0.8,
    've_power': 3.0, 've_stribeck': 1.0, 've_memory': 1.5,
    'pt_gain': 1.5, 'pt_offset': 2.5, 'pt_wear': 0.9,
    'se_angle': 3.0, 'se_capstan': 2.0, 'se_servo': 0.75,
    'ts_dahl': 5.0, 'ts_elastoplastic': 0.95, 'ts_multi': 1.0,
}

SHAPE_TEXT = {
    'bl_deadzone': 'Gap (dead zone) in series with the band stiffness: the elastic force is '
                   'sigma0*sign(z)*max(|z|-d,0) and the bristle law is dz/dt = v - |v| F_el(z)/g(v), '
                   'so after a reversal the force unloads, stays at zero over a travel of 2d, then '
                   're-tensions. p = d (in).',
    'bl_soft': 'Soft re-tensioning of the slack band: quadratic engagement F_el = sigma0 z^2/(2 zs) '
               'for |z| < zs, then sigma0(|z| - zs/2) (smoothed gap); same generalized bristle law. '
               'p = zs (in).',
    'bl_dip': 'Band tension lost at each reversal and rebuilt with travel: the elastic force is '
              'multiplied by 1 - a exp(-s/sr), s = drum travel since the last reversal (hysteretic '
              'direction detector, |v| > 0.05 in/s). p = a; sr in extras.',
    'rs_relax': 'Stress relaxation of the held force: once the drum has been at rest (|v| < 0.05 '
                'in/s) for 0.1 s, dz/dt gains -w(t) z / tau (w ramps in with 0.05 s), so the held '
                'force decays exponentially to zero. p = 1/tau (1/s).',
    'rs_creep': 'Held force grows logarithmically with hold time (band settling / contact aging): '
                'after 0.1 s at rest the elastic force is multiplied by 1 + c ln(1 + (t_r - 0.1)/t0). '
                'p = c; t0 in extras.',
    'rs_settle': 'Held residual force settles to a different level: after 0.1 s at rest the bristle '
                 'state relaxes with time constant tau to (z at rest onset) + sign*D/sigma0, i.e. '
                 'the held force moves by D kip and is kept. p = D (kip); sign, tau in extras.',
    'al_first': 'Band clamping follows the actuator positions through a first-order lag '
                '(x_eff\' = (x - x_eff)/tau) before Eq. 4. p = tau (s).',
    'al_delay': 'Band clamping follows the actuator positions with a pure transport delay. '
                'p = delay (s).',
    'al_second': 'Band clamping follows the actuator positions through an under-damped '
                 'second-order response (wn = 1/tn, damping zeta). p = tn (s); zeta in extras.',
    'as_stiff': 'Bristle/band stiffness depends on the direction of deflection: sigma0 multiplied '
                'by (1+p) (stiffer) or 1/(1+p) (softer) for z on one side only; same friction '
                'levels. side, stiffer in extras.',
    'as_gain': 'Friction in one direction of rotation only (whole g(v): Fs and Fc incl. the '
               'actuator term) scaled by (1+p) or 1/(1+p). dir (+1 fwd), sign in extras.',
    'as_tanh': 'Smooth antisymmetric friction coefficient: g(v) multiplied by 1 + sign*p*tanh(v/va) '
               '(friction higher in one direction, lower in the other). p; va, sign in extras.',
    've_power': 'Extra power-law viscous friction c*sign(v)|v|^alpha added to the output force '
                '(or, with inside=True, to g(v) through the bristles). p = c; alpha in extras.',
    've_stribeck': 'Different Stribeck shape: the decay exp(-(v/vs)^2) is blended with '
                   'exp(-(|v|/vs2)^delta): (1-p)*base + p*new. p = blend; vs2, delta in extras.',
    've_memory': 'Frictional memory (Hess-Soom type): the Stribeck decay uses a lagged sliding '
                 'speed u, du/dt = (|v| - u)/tau, instead of |v|. p = tau (s).',
    'pt_gain': 'Clamping gain error: the whole friction level g(v) (Fs, Fc and the actuator term) '
               'scaled by (1+p) or 1/(1+p). sign in extras.',
    'pt_offset': 'Pre-tension offset: Fs and Fc of both directions shifted by sign*p kip (Fc floor '
                 'of the config kept). p = offset (kip).',
    'pt_wear': 'Loss of pre-tension by wear: g(v) multiplied by 1 - p(1 - exp(-S/Sw)), S = '
               'cumulative sliding distance (record B continues the wear of record A). p; Sw in extras.',
    'se_angle': 'Angle tightening: friction grows with drum rotation away from centre in either '
                'direction, g multiplied by 1 + p|x|^beta. p; beta in extras.',
    'se_capstan': 'Capstan/wrap self-energizing: the taut band\'s wrap grows with rotation in the '
                  'sliding direction, g multiplied by exp(p * x * sign(v)). p (1/in).',
    'se_servo': 'Self-servo: the band force feeds back on the clamping, g_eff = g (1 + p |sigma0 z|/Fr) '
                'inside the bristle law. p; Fr in extras.',
    'ts_dahl': 'Dahl-type exponent of the stick-to-slip transition: dz/dt = v phi(1 - sign(v) '
               'sigma0 z/g), phi(u) = sign(u)|u|^alpha, alpha = 1+p (soft) or 1/(1+p) (sharp). '
               'soft in extras.',
    'ts_elastoplastic': 'Elasto-plastic pre-sliding (Dupont type): pure elastic stick while the '
                        'deflection grows in the sliding direction up to z_ba = p z_ss, smooth '
                        'sine transition to full sliding at z_ss = g/sigma0. p = z_ba/z_ss.',
    'ts_multi': 'Several contact populations (Maxwell-slip/GMS-like): a fraction p of the '
                'friction carried by three LuGre elements with stiffnesses sigma0*k_j and '
                'capacities w_j*g. p = fraction; k, w in extras.',
}


# ----------------------------------------------------------------------------- inputs
def load_sources():
    out = {}
    for key, fn in SOURCES.items():
        d = json.load(open(os.path.join(DATA, fn)))['data']
        out[key] = dict(x=[r[1] for r in d], F=[r[2] for r in d],
                        x1=[r[4] for r in d], x2=[r[5] for r in d])
    return out


def full_rec(src, key, mirror):
    s = src[key]
    sg = -1.0 if mirror else 1.0
    x = [sg * a for a in s['x']] if mirror else list(s['x'])
    return dict(x=x, x1=list(s['x1']), x2=list(s['x2']), F0=sg * s['F'][0])


def reversal_index(x, t_target):
    i0 = int((t_target - 0.35) / DT)
    i1 = int((t_target + 0.35) / DT)
    sg = 1.0 if x[int(t_target / DT)] >= 0 else -1.0
    return max(range(i0, i1), key=lambda i: sg * x[i])


def build_record(P, src, spec):
    """spec: dict(kind=full|cut|combo, src, mirror, [t0, t1], [src2, mirror2])."""
    r = full_rec(src, spec['src'], spec['mirror'])
    if spec['kind'] == 'full':
        x, x1, x2, z0 = r['x'], r['x1'], r['x2'], r['F0'] / P['s0']
    elif spec['kind'] == 'cut':
        n = len(r['x'])
        i0 = reversal_index(r['x'], spec['t0']) if spec.get('t0') else 0
        i1 = reversal_index(r['x'], spec['t1']) + 1 if spec.get('t1') else n
        rr = dict(x=r['x'], v=bs.drum_velocity(r['x']), x1=r['x1'], x2=r['x2'],
                  z0=r['F0'] / P['s0'])
        _, info = bs.simulate(P, rr, 'none', return_z=True)
        z0 = info['z'][i0] if i0 > 0 else rr['z0']
        x, x1, x2 = r['x'][i0:i1], r['x1'][i0:i1], r['x2'][i0:i1]
    elif spec['kind'] == 'combo':
        r2 = full_rec(src, spec['src2'], spec['mirror2'])
        dx = r['x'][-1] - r2['x'][0]
        d1 = r['x1'][-1] - r2['x1'][0]
        d2 = r['x2'][-1] - r2['x2'][0]
        x = r['x'] + [a + dx for a in r2['x']]
        x1 = r['x1'] + [a + d1 for a in r2['x1']]
        x2 = r['x2'] + [a + d2 for a in r2['x2']]
        z0 = r['F0'] / P['s0']
    else:
        raise ValueError(spec)
    return dict(x=x, x1=x1, x2=x2, v=bs.drum_velocity(x), z0=z0, S0=0.0)


def describe(spec):
    s = SOURCES[spec['src']] + (' mirrored' if spec['mirror'] else '')
    if spec['kind'] == 'cut':
        s += ' cut %s..%s s (at reversals)' % (spec.get('t0') or 0, spec.get('t1') or 'end')
    if spec['kind'] == 'combo':
        s += ' + ' + SOURCES[spec['src2']] + (' mirrored' if spec['mirror2'] else '')
    return s


# ----------------------------------------------------------------------------- design
def draw_extras(shape, rng):
    ex = {}
    if shape == 'bl_dip':
        ex['sr'] = round(rng.uniform(0.04, 0.15), 3)
    elif shape == 'rs_creep':
        ex['t0'] = round(rng.uniform(0.03, 0.2), 3)
    elif shape == 'rs_settle':
        ex['sign'] = rng.choice([1, -1])
        ex['tau'] = round(rng.uniform(0.1, 0.4), 3)
    elif shape == 'al_second':
        ex['zeta'] = round(rng.uniform(0.25, 0.6), 3)
    elif shape == 'as_stiff':
        ex['side'] = rng.choice([1, -1])
        ex['stiffer'] = rng.random() < 0.5
    elif shape == 'as_gain':
        ex['dir'] = rng.choice([1, -1])
        ex['sign'] = rng.choice([1, -1])
    elif shape == 'as_tanh':
        ex['va'] = round(rng.uniform(0.2, 0.8), 3)
        ex['sign'] = rng.choice([1, -1])
    elif shape == 've_power':
        ex['alpha'] = round(rng.uniform(0.4, 1.6), 3)
        ex['inside'] = rng.random() < 0.4
    elif shape == 've_stribeck':
        if rng.random() < 0.5:
            ex['vs2'] = round(rng.uniform(2.0, 4.0) * 1.3, 3)
        else:
            ex['vs2'] = round(rng.uniform(0.2, 0.5) * 1.3, 3)
        ex['delta'] = round(rng.uniform(0.6, 1.3), 3)
    elif shape in ('pt_gain', 'pt_offset'):
        ex['sign'] = rng.choice([1, -1])
    elif shape == 'pt_wear':
        ex['Sw'] = round(rng.uniform(8.0, 40.0), 2)
    elif shape == 'se_angle':
        ex['beta'] = round(rng.uniform(1.0, 2.0), 3)
    elif shape == 'se_servo':
        ex['Fr'] = 10.0
    elif shape == 'ts_dahl':
        ex['soft'] = rng.random() < 0.6
    elif shape == 'ts_multi':
        ex['k'] = [round(rng.uniform(2.5, 5.0), 3), round(rng.uniform(0.8, 1.2), 3),
                   round(rng.uniform(0.2, 0.45), 3)]
        w = [rng.uniform(0.2, 0.5) for _ in range(3)]
        ex['w'] = [round(a / sum(w), 4) for a in w]
        ex['w'][2] = round(1 - ex['w'][0] - ex['w'][1], 4)
    return ex


def draw_input_spec(rng, src_key, category):
    spec = dict(src=src_key, mirror=rng.random() < 0.2)
    u = rng.random()
    if category == 'residual_static':
        kind = 'combo' if u < 0.2 else 'full'
    else:
        kind = 'full' if u < 0.55 else ('cut' if u < 0.85 else 'combo')
    spec['kind'] = kind
    if kind == 'cut':
        m = rng.choice(['start', 'end', 'both'])
        starts = [1.5, 2.5] + ([3.5] if src_key in BWD else [])
        if m in ('start', 'both'):
            spec['t0'] = rng.choice(starts)
        if m in ('end', 'both'):
            spec['t1'] = rng.choice([10.5, 11.5, 12.5])
    if kind == 'combo':
        spec['src2'] = rng.choice([k for k in SOURCES if k != src_key])
        spec['mirror2'] = rng.random() < 0.2
    return spec


def design(seed):
    rng = random.Random(seed)
    labels = []
    cats = list(CATEGORIES)
    two_weak = set(rng.sample(cats, 4))
    for c in cats:
        shapes = list(CATEGORIES[c])
        rng.shuffle(shapes)
        nweak = 2 if c in two_weak else 1
        for j, sh in enumerate(shapes):
            labels.append((c, sh, 'weak' if j < nweak else 'strong'))
    labels += [('none', 'none', 'none')] * 6
    rng.shuffle(labels)
    trials = []
    for k, (c, sh, st) in enumerate(labels):
        tid = 't%02d' % (k + 1)
        trng = random.Random(seed * 1000 + k + 1)
        fa, fb = trng.choice(FWD), trng.choice(BWD)
        if trng.random() < 0.5:
            fa, fb = fb, fa
        specA = draw_input_spec(trng, fa, c)
        specB = draw_input_spec(trng, fb, c)
        noise = round(trng.uniform(0.02, 0.06), 4)
        if st == 'weak':
            ratio = round(trng.uniform(2.5, 4.0), 3)
        elif st == 'strong':
            ratio = round(trng.uniform(8.0, 12.0), 3)
        else:
            ratio = 0.0
        ex = draw_extras(sh, trng)
        trials.append(dict(id=tid, category=c, shape=sh, strength=st, noise=noise,
                           target_ratio=ratio, extras=ex, specA=specA, specB=specB,
                           noise_seed=seed * 7919 + k + 1))
    return trials


# ----------------------------------------------------------------------------- one trial
def rms_diff(a, b):
    s = 0.0
    n = 0
    for p, q in zip(a, b):
        s += (p - q) ** 2
        n += 1
    return s, n


def run_effect(P, recs, shape, p, ex):
    outs = []
    S0 = 0.0
    for rec in recs:
        rec = dict(rec)
        rec['S0'] = S0
        F, info = bs.simulate(P, rec, shape, p, ex)
        S0 = info.get('S_end', 0.0)
        outs.append(F)
    return outs


def effect_rms(P, recs, bases, shape, p, ex):
    outs = run_effect(P, recs, shape, p, ex)
    s = n = 0
    for F, B in zip(outs, bases):
        ds, dn = rms_diff(F[1:], B[1:])
        s += ds
        n += dn
    return math.sqrt(s / n), outs


def make_trial(args):
    tr, src, P, outdir = args
    t0 = time.time()
    recs = [build_record(P, src, tr['specA']), build_record(P, src, tr['specB'])]
    bases = [bs.simulate(P, r, 'none')[0] for r in recs]
    shape, ex = tr['shape'], tr['extras']
    noise = tr['noise']
    res = dict(tr)
    if shape == 'none':
        outs, p, achieved = bases, 0.0, 0.0
    else:
        target = tr['target_ratio']
        pmax = PMAX[shape]
        rmax, outs = effect_rms(P, recs, bases, shape, pmax, ex)
        if rmax < target * noise:
            noise = max(0.02, round(rmax / target, 4))
        if rmax <= target * noise:
            p = pmax
            achieved = rmax / noise
        else:
            lo, hi = 0.0, pmax
            for _ in range(22):
                mid = 0.5 * (lo + hi)
                r, _ = effect_rms(P, recs, bases, shape, mid, ex)
                if r < target * noise:
                    lo = mid
                else:
                    hi = mid
                if abs(r / noise - target) < 0.01 * target:
                    break
            p = mid
            r, outs = effect_rms(P, recs, bases, shape, p, ex)
            achieved = r / noise
        res['noise_adjusted'] = noise != tr['noise']
    res['noise'] = noise
    res['p'] = p
    res['achieved_ratio'] = round(achieved, 3)
    res['effect_rms_kip'] = round(achieved * noise, 4)

    # write the records
    rng = random.Random(tr['noise_seed'])
    cdir = os.path.join(outdir, 'cases', tr['id'])
    os.makedirs(cdir, exist_ok=True)
    clean = {}
    for name, rec, F, B in zip('AB', recs, outs, bases):
        n = len(rec['x'])
        v = rec['v']
        rows = []
        for i in range(n):
            if i == 0:
                f = P['s0'] * rec['z0']  # the tool starts z at F(0)/sigma0
            else:
                f = F[i] + rng.gauss(0.0, noise)
            fc = F[i]
            vcol = v[max(0, i - 8)] / 125.4 + rng.gauss(0.0, 7e-5)
            a2 = 30.0 + 560.0 * max(fc, 0.0) + 15.0 * max(-fc, 0.0) + rng.gauss(0.0, 4.0)
            a1 = 30.0 + 540.0 * max(-fc, 0.0) + 15.0 * max(fc, 0.0) + rng.gauss(0.0, 4.0)
            rows.append([i * DT, rec['x'][i], f, vcol, rec['x1'][i], rec['x2'][i], a1, a2])
        doc = {'data': rows, 'dt': DT, 'sampling freq': 1024, 'displacement units': 'in',
               'time units': 's', 'friction force units': 'kip', 'actuator force units': 'lb'}
        with open(os.path.join(cdir, name + '.json'), 'w') as fh:
            json.dump(doc, fh)
        clean[name] = dict(base=[round(a, 7) for a in B], effect=[round(a, 7) for a in F])
    wdir = os.path.join(outdir, 'gen', 'work')
    os.makedirs(wdir, exist_ok=True)
    with open(os.path.join(wdir, tr['id'] + '.json'), 'w') as fh:
        json.dump(clean, fh)
    res['inputs'] = {'A': describe(tr['specA']), 'B': describe(tr['specB'])}
    res['seconds'] = round(time.time() - t0, 1)
    return res


# ----------------------------------------------------------------------------- main
def write_notes(outdir, results, seed):
    L = ['# blind10: hidden-effect test set (ANSWERS: never show to the tool)', '',
         'Generated by `python3 gen/gen.py --seed %d` (Python 3 stdlib only).' % seed, '',
         'Base model: semi-active LuGre, Eqs. 1-5 of the seed paper, parameters from '
         '/work/main/configs/brfd-semiactive.yaml (x\'_1, x\'_2 = positions at t = 0 of each '
         'record). Drum velocity from the displacement column (central difference + 15-sample '
         'centred moving average), z(0) = F(0)/sigma0, the file\'s first force sample is '
         'sigma0*z(0) without noise. "none" trials are exactly this base model plus white noise '
         '(checked with `hybridsim damper predict --no-fit`, gen/verify.py).', '',
         'Inputs: drum displacement and actuator positions of the six measured semi-active '
         'tests; a record is a whole test, a test cut at drum reversals (before the actuators '
         'move / after they stop), a mirrored test (x -> -x), or two tests concatenated '
         '(continuity offsets). Record A and B of a trial use different tests.', '',
         'Columns written: time, drum displacement (in), force (kip, model + N(0, noise)), '
         'velocity column = drum velocity/125.4 delayed 8 samples + small noise (the measured '
         'files\' quirk), actuator 1/2 positions (in), actuator 1/2 forces (lb, synthetic: '
         '30 + ~550 lb/kip on the taut side).', '',
         'Strength: ratio = RMS over both records of (effect model - base model), noise-free, '
         'divided by the noise SD. weak: target 2.5-4; strong: target 8-12. Where the effect '
         'could not reach the target at its parameter cap, the noise was lowered (not below '
         '0.02 kip); achieved ratios are in the table.', '',
         'Caveats (physics, not bugs): a gap/soft-engagement backlash also changes the force '
         'held after the drum stops (the small last ramp-down cycles do not re-tension the band '
         'fully), so part of its RMS lies in the rest windows; residual-force effects that '
         'change the held state also change the first cycle after a mid-record restart '
         '(concatenated records); wear (pt_wear) carries over from record A to record B.', '',
         'Check: `python3 gen/verify.py` runs `hybridsim damper predict --no-fit` on every record '
         'and prints rms(predict - generator base) (about 1e-8 kip) and the effect RMS.', '',
         '## Shapes', '']
    for c, shs in CATEGORIES.items():
        L.append('### ' + c)
        for sh in shs:
            L.append('- `%s`: %s' % (sh, SHAPE_TEXT[sh]))
        L.append('')
    L += ['## Trials', '',
          '| trial | category | shape | strength | noise kip | target | achieved | p | extras | A | B |',
          '|---|---|---|---|---|---|---|---|---|---|---|']
    for r in results:
        L.append('| %s | %s | %s | %s | %.4f | %.2f | %.2f | %.4g | %s | %s | %s |' % (
            r['id'], r['category'], r['shape'], r['strength'], r['noise'], r['target_ratio'],
            r['achieved_ratio'], r['p'], json.dumps(r['extras']), r['inputs']['A'],
            r['inputs']['B']))
    open(os.path.join(outdir, 'NOTES.md'), 'w').write('\n'.join(L) + '\n')


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--seed', type=int, default=10010)
    ap.add_argument('--out', default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    ap.add_argument('--jobs', type=int, default=2)
    ap.add_argument('--only', default='')
    a = ap.parse_args()
    t0 = time.time()
    P = bs.load_config(CONFIG)
    src = load_sources()
    trials = design(a.seed)
    if a.only:
        trials = [t for t in trials if t['id'] in a.only.split(',')]
    # longest first for load balance
    order = sorted(trials, key=lambda t: (t['shape'] == 'none', t['id']))
    jobs = [(t, src, P, a.out) for t in order]
    if a.jobs > 1:
        with multiprocessing.Pool(a.jobs) as pool:
            res = pool.map(make_trial, jobs, chunksize=1)
    else:
        res = [make_trial(j) for j in jobs]
    res.sort(key=lambda r: r['id'])
    for r in res:
        print('%s %-16s %-16s %-6s noise=%.4f target=%.2f achieved=%.2f p=%.4g (%.0fs)' % (
            r['id'], r['category'], r['shape'], r['strength'], r['noise'], r['target_ratio'],
            r['achieved_ratio'], r['p'], r['seconds']), file=sys.stderr)
    if a.only:
        return
    key = {r['id']: dict(category=r['category'], shape=r['shape'], strength=r['strength'],
                         noise_kip=r['noise'], target_ratio=r['target_ratio'],
                         achieved_ratio=r['achieved_ratio'], effect_rms_kip=r['effect_rms_kip'],
                         p=r['p'], extras=r['extras'], inputs=r['inputs'])
           for r in res}
    with open(os.path.join(a.out, 'key.json'), 'w') as fh:
        json.dump({'seed': a.seed, 'trials': key}, fh, indent=1)
    with open(os.path.join(a.out, 'trials.txt'), 'w') as fh:
        fh.write('\n'.join(r['id'] for r in res) + '\n')
    write_notes(a.out, res, a.seed)
    print('wrote %d trials to %s in %.0f s' % (len(res), a.out, time.time() - t0), file=sys.stderr)


if __name__ == '__main__':
    main()
