#!/usr/bin/env python3
"""Build the blind trials /work/blind3/cases/tNN/{A,B}.json and /work/blind3/key.json.
Usage: python3 make_cases.py [OUTROOT]   (default /work/blind3)"""
import sys, os, json, math, random
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from brfd_gen import *

ROOT = sys.argv[1] if len(sys.argv) > 1 else '/work/blind3'
MASTER_SEED = 20261123

SHAPES = {
    'backlash': ("3-stage slack band after each drum reversal: base LuGre unloading until the total force "
                 "crosses 0, then slack travel d0 with zero friction (band deflection released over travel lam), "
                 "then re-tensioning over travel d1 (engagement r = smoothstep scales both the bristle input and "
                 "the whole friction force), then normal LuGre"),
    'residual_static': ("at rest (|v| << vr) the locked band force relaxes by a Nutting/Guiu-Pratt-type power law "
                        "toward a fraction rho of the force locked when the drum stopped: "
                        "zdot += -q (z - rho z_lock)/(tau0 + t_rest); the record starts after trest0 s of rest"),
    'actuator_lag': ("band tension follows the measured actuator positions through a pure delay, then a "
                     "2nd-order (fn, zeta) band/actuator response with an optional rate limit on the effective "
                     "position; Eq. 4 is evaluated with the effective positions"),
    'asymmetry': ("direction-dependent band stiffness: bristle force = sigma0 (1 + a tanh(z/zt)) z, i.e. the "
                  "forward-loaded (taut end 2) band is stiffer than the backward-loaded one; steady sliding "
                  "levels unchanged, zdot = v - |v| F_bristle/g"),
    'velocity': ("rate-and-state direct effect at steady state with frictional lag: g multiplied by "
                 "[1 + alpha ln(1 + v_l/V0)] / [1 + alpha ln(1 + Vref/V0)], v_l = |v| through a first-order "
                 "lag tau (Hess-Soom frictional memory)"),
    'pretension': ("band pretension lost by Archard-type wear/bedding-in of the lining: friction work "
                   "W = int |sigma0 z v| dt lowers Fs and Fc (both directions, Eq. 4 included) by "
                   "dF (1 - exp(-W/W0)), floor 0.05 kip"),
    'self_energizing': ("capstan-like self-energizing: the friction limit grows with the force the band carries "
                        "in the sliding direction, g_eff = g exp(kappa [tanh(F+/Fref) - tanh(b_dir/Fref)]), "
                        "F+ = max(0, sigma0 z sgn v), normalized to the base at the nominal kinetic level b"),
    'transition_shape': ("Stribeck transition with exponent delta instead of 2 and frictional-memory hysteresis: "
                         "g = Fc + (Fs - Fc) exp(-(v_m/vs)^delta), v_m = |v| through a first-order lag tau "
                         "(accelerating and decelerating branches differ)"),
    'none': "base model of configs/brfd-semiactive.yaml exactly (paper Eqs. 1-5), plus noise",
}

PARAMS = {
    'backlash': {'weak': dict(d0=0.03, d1=0.04, lam=0.01), 'strong': dict(d0=0.07, d1=0.07, lam=0.01)},
    'residual_static': {'weak': dict(vr=0.02, rho=0.6, tau0=0.4, q=0.7, trest0=2.0),
                        'strong': dict(vr=0.02, rho=0.25, tau0=0.15, q=1.0, trest0=2.0)},
    'actuator_lag': {'weak': dict(delay=0.02, fn=6.0, zeta=0.7),
                     'strong': dict(delay=0.07, fn=1.8, zeta=0.45, rate_limit=0.15)},
    'asymmetry': {'weak': dict(a=0.2, zt=0.01), 'strong': dict(a=0.5, zt=0.01)},
    'velocity': {'weak': dict(alpha=0.3, V0=0.2, Vref=1.5, tau=0.10),
                 'strong': dict(alpha=0.8, V0=0.2, Vref=1.5, tau=0.12)},
    'pretension': {'weak': dict(dF=0.35, W0=40.0), 'strong': dict(dF=0.9, W0=40.0)},
    'self_energizing': {'weak': dict(kappa=0.5, Fref=2.0), 'strong': dict(kappa=1.3, Fref=2.0)},
    'transition_shape': {'weak': dict(delta=1.2, tau=0.025), 'strong': dict(delta=0.7, tau=0.07)},
    'none': {'none': {}},
}
CATS = ['backlash', 'residual_static', 'actuator_lag', 'asymmetry', 'velocity', 'pretension',
        'self_energizing', 'transition_shape']
MEASURED = ['harmonic0.015backward.json', 'harmonic0.015forward.json', 'harmonic0.03ea1backward.json',
            'harmonic0.03ea1forward.json', 'harmonic0.03ea2backward.json', 'harmonic0.03ea2forward.json']


def plan():
    rng = random.Random(MASTER_SEED)
    trials = []
    for c in CATS:
        for s in ('weak', 'strong'):
            for nz in (0.02, 0.06):
                trials.append(dict(category=c, strength=s, noise_kip=nz, motion='harmonic'))
    for nz in (0.02, 0.02, 0.02, 0.06, 0.06, 0.06):
        trials.append(dict(category='none', strength='none', noise_kip=nz, motion='harmonic'))
    # earthquake-like trials: one per category (strength alternating), plus two 'none'
    eqs = {'backlash': 'weak', 'residual_static': 'strong', 'actuator_lag': 'strong', 'asymmetry': 'strong',
           'velocity': 'strong', 'pretension': 'weak', 'self_energizing': 'weak', 'transition_shape': 'weak'}
    for c, s in eqs.items():
        trials.append(dict(category=c, strength=s, noise_kip=rng.choice([0.02, 0.06]), motion='earthquake'))
    trials.append(dict(category='none', strength='none', noise_kip=0.02, motion='earthquake'))
    trials.append(dict(category='none', strength='none', noise_kip=0.06, motion='earthquake'))
    ids = list(range(1, len(trials) + 1))
    rng.shuffle(ids)
    for k, t in enumerate(trials):
        t['trial'] = 't%02d' % ids[k]
        t['seed'] = MASTER_SEED + 17 * ids[k]
        if t['motion'] == 'harmonic':
            t['inputs'] = rng.sample(MEASURED, 2)
        else:
            t['inputs'] = [1000 + 2 * ids[k], 1001 + 2 * ids[k]]
    trials.sort(key=lambda t: t['trial'])
    return trials


def main():
    trials = plan()
    key = []
    os.makedirs(os.path.join(ROOT, 'cases'), exist_ok=True)
    for t in trials:
        d = os.path.join(ROOT, 'cases', t['trial'])
        os.makedirs(d, exist_ok=True)
        E = PARAMS[t['category']][t['strength']]
        rng = random.Random(t['seed'])
        rho = 0.3 if t['motion'] == 'earthquake' else 0.0
        recs = {}; gaps = {}; gaps_kip = {}
        for lab, src in zip(('A', 'B'), t['inputs']):
            inp = prep(load_measured(src) if t['motion'] == 'harmonic' else synth_eq(src))
            base = simulate(inp)
            truth = simulate(inp, t['category'], E) if t['category'] != 'none' else base
            e = noise_series(len(truth), t['noise_kip'], rng, rho)
            Fm = [quant(a + b, 0.0008) for a, b in zip(truth, e)]
            a1f, a2f = actuator_forces(truth, rng)
            write_record(os.path.join(d, lab + '.json'), inp, Fm, a1f, a2f)
            recs[lab] = inp['src'] + ' (%d samples at 1024 Hz, %.2f s)' % (len(truth), (len(truth) - 1) * DT)
            gaps[lab] = round(nrmse(base, truth), 4)
            gaps_kip[lab] = round(math.sqrt(sum((p - q) ** 2 for p, q in zip(base, truth)) / len(base)), 4)
        key.append(dict(trial=t['trial'], category=t['category'], shape=SHAPES[t['category']],
                        parameters=E, strength=t['strength'], noise_kip=t['noise_kip'],
                        noise_kind=('AR(1) rho=0.3, white-equivalent RMS' if rho else 'white Gaussian') +
                        ' + force quantization 0.0008 kip', motion=t['motion'], records=recs,
                        gap=gaps, gap_rmse_kip=gaps_kip, seed=t['seed']))
        print(t['trial'], t['category'], t['strength'], t['noise_kip'], t['motion'], gaps, flush=True)
    with open(os.path.join(ROOT, 'key.json'), 'w') as f:
        json.dump(key, f, indent=1)


if __name__ == '__main__':
    main()
