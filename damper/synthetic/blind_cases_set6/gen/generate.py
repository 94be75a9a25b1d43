#!/usr/bin/env python3
"""Blind synthetic test set for the BRFD model-discrepancy tool (blind6).

Usage:  python3 gen/generate.py [--seed 20261126] [--out /work/blind6]
Deterministic from the seed; standard-library Python only.
Writes OUT/cases/tNN/{A,B}.json, OUT/key.json, OUT/trials.txt, and (for the base-match
check) /tmp/blind6_clean/*.txt (--clean) with the noise-free force of the 'none' records.
"""
import argparse, json, math, os, random, struct, sys, time
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from base import velocity, DT
import effects

SRC = '/work/shared/data/brfd/semiactive'
SRC_FILES = ['harmonic0.015backward.json', 'harmonic0.015forward.json',
             'harmonic0.03ea1backward.json', 'harmonic0.03ea1forward.json',
             'harmonic0.03ea2backward.json', 'harmonic0.03ea2forward.json']
N = 15361
Q_X, Q_A, Q_F = 5.8829784e-05, 2.384186e-06, 0.000800490379
Q_L1, Q_L2 = 0.317841768265, 0.399798154831
VEL_COL_SCALE, VEL_COL_LAG = 125.4, 8

def f32(v):
    return struct.unpack('f', struct.pack('f', v))[0]

def quant(v, q):
    return f32(q * round(v / q))

def quant_d(v, q):
    # force and load-cell columns of the measured files are doubles (count * scale), not float32
    return q * round(v / q)

# ----------------------------------------------------------------------------- inputs
def replay_input(name):
    d = json.load(open(os.path.join(SRC, name)))['data']
    return dict(x=[r[1] for r in d], x1=[r[4] for r in d], x2=[r[5] for r in d],
                fb0=d[0][2], src=name)

def envelope_taper(t, t0, t1, r):
    if t <= t0 or t >= t1: return 0.0
    if t < t0 + r: return 0.5 - 0.5 * math.cos(math.pi * (t - t0) / r)
    if t > t1 - r: return 0.5 - 0.5 * math.cos(math.pi * (t1 - t) / r)
    return 1.0

def drum_eq_synth(rng):
    """Earthquake-like broadband drum displacement: Clough-Penzien spectrum (Kanai-Tajimi
    ground filter + high-pass) of random-phase harmonics, Saragoni-Hart-type envelope."""
    fg, zg = rng.uniform(1.0, 2.2), rng.uniform(0.4, 0.7)
    ff, zf = rng.uniform(0.15, 0.3), 0.6
    comps = []
    for j in range(70):
        f = 0.12 + j * (3.0 - 0.12) / 69 + rng.uniform(-0.01, 0.01)
        r = f / fg; rf = f / ff
        kt = (1 + 4 * zg * zg * r * r) / ((1 - r * r) ** 2 + 4 * zg * zg * r * r)
        hp = rf ** 4 / ((1 - rf * rf) ** 2 + 4 * zf * zf * rf * rf)
        a = math.sqrt(kt * hp) / (2 * math.pi * f) ** 2
        comps.append((a, f, rng.uniform(0, 2 * math.pi)))
    t0 = rng.uniform(0.3, 0.7); tr = t0 + rng.uniform(1.0, 2.0); tp = tr + rng.uniform(3.0, 5.0)
    t1 = rng.uniform(12.0, 13.0); c = rng.uniform(0.25, 0.5)
    x = []
    for k in range(N):
        t = k * DT
        if t <= t0 or t >= t1: e = 0.0
        elif t < tr: e = ((t - t0) / (tr - t0)) ** 2
        elif t < tp: e = 1.0
        else: e = math.exp(-c * (t - tp))
        e *= envelope_taper(t, t0, t1, 0.6)
        x.append(e * sum(a * math.sin(2 * math.pi * f * t + p) for a, f, p in comps) if e > 0 else 0.0)
    pk = max(abs(v) for v in x); s = rng.uniform(0.8, 1.3) / pk
    return [v * s for v in x], (t0, t1)

def drum_harmonic(rng):
    """0.5 Hz, ~1 in sinusoid ramped up and down (like the validation tests)."""
    A = rng.uniform(0.8, 1.15); f = rng.choice([0.5, 0.5, 0.75]); t0 = rng.uniform(0.08, 0.3)
    t1 = t0 + rng.uniform(12.5, 13.6)
    x = [A * envelope_taper(k * DT, t0, t1, 2.0) * math.sin(2 * math.pi * f * (k * DT - t0)) for k in range(N)]
    return x, (t0, t1)

def drum_pauses(rng):
    """Bursts of half-cycle-ended cosine motion separated by rests (drum stops loaded)."""
    x = [0.0] * N; p = 0.0; t = rng.uniform(0.3, 0.8); windows = []
    while True:
        f = rng.uniform(0.4, 0.9); ncyc = rng.choice([1, 2, 2, 3]) + 0.5
        dur = ncyc / f
        if t + dur > 14.0: break
        A = rng.uniform(0.8, 1.8); s = -1.0 if p > 0 else 1.0
        if abs(p) < 0.1: s = rng.choice([-1.0, 1.0])
        k0, k1 = int(t / DT), int((t + dur) / DT)
        for k in range(k0, min(k1, N)):
            x[k] = p + s * A * 0.5 * (1 - math.cos(2 * math.pi * f * (k * DT - t)))
        pend = p + s * A
        windows.append((t, t + dur))
        t = t + dur + rng.uniform(1.0, 2.5); p = pend
        for k in range(k1, N): x[k] = p
    return x, (windows[0][0], windows[-1][1])

def actuator_commands(rng, t0, t1, x1p, x2p, n_ev):
    c1 = [0.0] * N; c2 = [0.0] * N
    t = t0 + rng.uniform(0.8, 2.0)
    for _ in range(n_ev):
        hold = rng.uniform(0.8, 2.2)
        if t + hold > t1: break
        which = rng.choice(['1', '2', 'both'])
        a = rng.choice([-1, 1]) * rng.uniform(0.01, 0.03)
        a2 = a if rng.random() < 0.7 else -a
        for k in range(int(t / DT), int((t + hold) / DT)):
            if which in ('1', 'both'): c1[k] = a
            if which in ('2', 'both'): c2[k] = a2 if which == 'both' else a
        t += hold + rng.uniform(0.4, 1.5)
    out = []
    for c, xp in ((c1, x1p), (c2, x2p)):
        # electric actuator servo: rate limit + first-order response, then quantized
        rl = rng.uniform(0.15, 0.4) * DT; tau = rng.uniform(0.01, 0.03); al = 1 - math.exp(-DT / tau)
        y = 0.0; z = 0.0; r = []
        for k in range(N):
            y += max(-rl, min(rl, c[k] - y)); z += al * (y - z)
            jitter = Q_A * rng.choice([0, 0, 0, 0, 0, 0, 1, -1])
            r.append(quant(xp + z + jitter, Q_A))
        out.append(r)
    return out

def designed_input(kind, rng):
    if kind == 'eq_synth': x, (t0, t1) = drum_eq_synth(rng)
    elif kind == 'harmonic_steps': x, (t0, t1) = drum_harmonic(rng)
    else: x, (t0, t1) = drum_pauses(rng)
    off = rng.uniform(-0.006, 0.004)
    xr = [quant(v + off + rng.gauss(0, 2.0e-5), Q_X) for v in x]
    x1p, x2p = 0.655 + rng.uniform(-0.002, 0.002), 0.8559 + rng.uniform(-0.002, 0.002)
    n_ev = rng.randint(3, 6)
    x1, x2 = actuator_commands(rng, t0, t1, x1p, x2p, n_ev)
    fb0 = quant_d(rng.uniform(-0.6, 1.2), Q_F)
    return dict(x=xr, x1=x1, x2=x2, fb0=fb0, src=kind)

# ----------------------------------------------------------------------------- noise, columns
def make_noise(n, rms, kind, rng):
    if kind == 'white':
        e = [rng.gauss(0, 1) for _ in range(n)]
    elif kind == 'ar1':
        tau = rng.uniform(0.005, 0.03); a = math.exp(-DT / tau); y = 0.0; e = []
        for _ in range(n):
            y = a * y + rng.gauss(0, 1); e.append(y)
    elif kind == 'white_hum':
        f = 60.0; ph = rng.uniform(0, 6.3); h = rng.uniform(0.6, 1.0)
        e = [rng.gauss(0, 1) + h * math.sqrt(2) * math.sin(2 * math.pi * f * k * DT + ph) for k in range(n)]
    else:  # 'pink3': sum of three AR(1) bands (1/f-like)
        e = [0.0] * n
        for tau in (0.002, 0.02, 0.2):
            a = math.exp(-DT / tau); y = 0.0; g = math.sqrt(1 - a * a)
            for k in range(n):
                y = a * y + g * rng.gauss(0, 1); e[k] += y
    m = sum(e) / n; s = math.sqrt(sum((v - m) ** 2 for v in e) / n)
    return [(v - m) * rms / s for v in e]

def softplus(f, w=0.25):
    z = f / w
    return w * (z + math.log1p(math.exp(-z))) if z > 0 else w * math.log1p(math.exp(z))

def write_record(path, inp, F_true, noise, rng):
    x, x1, x2 = inp['x'], inp['x1'], inp['x2']
    v = velocity(x)
    # velocity column: like the files' (~1/125.4 of in/s, lagging ~8 samples); near the record
    # ends a truncated (not shrinking) 15-sample window keeps it quiet as in the measured files
    raw = [(x[min(k + 1, N - 1)] - x[max(k - 1, 0)]) / ((min(k + 1, N - 1) - max(k - 1, 0)) * DT) for k in range(N)]
    vcol = []
    for k in range(N):
        c = k - VEL_COL_LAG; lo = max(0, c - 7); hi = min(N - 1, max(c + 7, lo + 7))
        vcol.append(sum(raw[lo:hi + 1]) / (hi - lo + 1))
    T1, T2 = rng.uniform(25, 45), rng.uniform(25, 45)
    k1, k2 = rng.uniform(440, 500), rng.uniform(505, 560)
    lc_tau = math.exp(-DT / 0.05); c1 = c2 = 0.0
    rows = []
    for k in range(N):
        t = k * DT
        tcol = int(t) if t == int(t) else t
        fk = inp['fb0'] if k == 0 else quant_d(F_true[k] + noise[k], Q_F)
        vc = f32(vcol[k] / VEL_COL_SCALE + rng.gauss(0, 4e-5))
        ft = F_true[k]
        l1 = T1 + k1 * softplus(-ft) - 140.0 * (x1[k] - x1[0])
        l2 = T2 + k2 * softplus(ft) - 150.0 * (x2[k] - x2[0])
        c1 = lc_tau * c1 + rng.gauss(0, 1); c2 = lc_tau * c2 + rng.gauss(0, 1)
        l1 += rng.gauss(0, 0.5) + 0.02 * l1 * c1 * 0.3 * 0.3
        l2 += rng.gauss(0, 0.5) + 0.02 * l2 * c2 * 0.3 * 0.3
        rows.append([tcol, x[k], fk, vc, x1[k], x2[k], quant_d(l1, Q_L1), quant_d(l2, Q_L2)])
    doc = {"data": rows, "dt": 0.0009765625, "sampling freq": 1024, "displacement units": "in",
           "time units": "s", "friction force units": "kip", "actuator force units": "lb"}
    with open(path, 'w') as fh:
        json.dump(doc, fh)

# ----------------------------------------------------------------------------- trial plan
SHAPES = {
    'backlash': ['zero_cross_gap', 'progressive_takeup', 'load_dependent_gap'],
    'residual_static': ['exp_relaxation', 'log_creep', 'recovery_to_preload'],
    'actuator_lag': ['first_order', 'dead_time_first_order', 'second_order', 'rate_limited'],
    'asymmetry': ['stiffness_one_dir', 'lining_one_dir', 'stribeck_viscous_one_dir'],
    'velocity': ['log_strengthening', 'speed_weakening', 'power_viscous'],
    'pretension': ['power_law_clamp', 'saturating', 'fs_tracks_clamp'],
    'self_energizing': ['capstan_wrap', 'thermal_fade', 'servo_buildup'],
    'transition_shape': ['dahl_exponent', 'maxwell_slip', 'elastoplastic'],
}

def shape_params(cat, sh, rng):
    """Fixed (non-calibrated) parameters and the amp range [lo, hi] of the calibrated one."""
    p = {}
    if cat == 'backlash':
        p['c_gap'] = round(rng.uniform(0.03, 0.1), 3)
        if sh == 'zero_cross_gap': rng_ = (0.01, 0.45)
        elif sh == 'progressive_takeup': rng_ = (0.005, 0.3)
        else: p['gap0'] = round(rng.uniform(0.01, 0.04), 3); rng_ = (0.002, 0.08)
    elif cat == 'residual_static':
        p['v_rest'] = 0.05; p['t_hold'] = 0.15
        if sh == 'exp_relaxation': p['tau'] = round(rng.uniform(0.3, 1.5), 2); rng_ = (0.02, 0.9)
        elif sh == 'log_creep': p['tc'] = round(rng.uniform(0.05, 0.3), 3); rng_ = (0.01, 0.45)
        else:
            p['tau'] = round(rng.uniform(0.3, 1.5), 2); p['f_eq'] = round(rng.choice([-1, 1]) * rng.uniform(0.8, 2.5), 2)
            rng_ = (0.05, 1.0)
    elif cat == 'actuator_lag':
        if sh == 'first_order': rng_ = (0.01, 1.0)
        elif sh == 'dead_time_first_order': p['tau'] = round(rng.uniform(0.01, 0.05), 3); rng_ = (0.01, 0.5)
        elif sh == 'second_order': p['zeta'] = round(rng.uniform(0.15, 0.5), 2); rng_ = (0.02, 0.4)
        else: p['tau'] = 0.02; rng_ = (0.5, 60.0)
    elif cat == 'asymmetry':
        p['dir'] = rng.choice(['fwd', 'bwd']); p['sign'] = rng.choice([-1, 1])
        if sh == 'stiffness_one_dir': rng_ = (0.02, 0.85) if p['sign'] < 0 else (0.05, 3.0)
        elif sh == 'lining_one_dir': rng_ = (0.01, 0.6)
        else: rng_ = (0.02, 2.0); p.pop('sign')
    elif cat == 'velocity':
        if sh == 'log_strengthening': p['v0'] = round(rng.uniform(0.05, 0.3), 3); rng_ = (0.005, 0.5)
        elif sh == 'speed_weakening': p['vw'] = round(rng.uniform(0.5, 3.0), 2); rng_ = (0.01, 0.8)
        else: p['delta'] = round(rng.uniform(1.8, 2.4), 2); rng_ = (0.005, 1.0)
    elif cat == 'pretension':
        if sh == 'power_law_clamp':
            p['sign'] = rng.choice([-1, 1]); rng_ = (0.05, 0.8) if p['sign'] < 0 else (0.05, 2.5)
        elif sh == 'saturating': rng_ = (0.1, 10.0)
        else: rng_ = (0.05, 3.0)
    elif cat == 'self_energizing':
        if sh == 'capstan_wrap': p['x0'] = round(rng.uniform(-0.2, 0.2), 3); rng_ = (0.02, 1.2)
        elif sh == 'thermal_fade': p['tau_th'] = round(rng.uniform(5, 30), 1); rng_ = (1e-4, 0.1)
        else: p['tau_b'] = round(rng.uniform(0.1, 0.6), 2); rng_ = (0.02, 1.5)
    elif cat == 'transition_shape':
        if sh == 'dahl_exponent':
            p['branch'] = rng.choice(['lt1', 'gt1']); rng_ = (0.05, 0.9) if p['branch'] == 'lt1' else (0.1, 4.0)
        elif sh == 'maxwell_slip':
            nn = rng.randint(6, 10); pw = rng.uniform(0.5, 1.5)
            kf = [(i + 1) ** -pw for i in range(nn)]; s = sum(kf)
            p['n_elements'] = nn; p['stiffness_power'] = round(pw, 3)
            p['weights'] = [1.0 / nn] * nn; p['kfrac'] = [v / s for v in kf]
            rng_ = (0.5, 8.0)
        else: rng_ = (0.05, 0.95)
    return p, rng_

def eff_for(cat, sh, p, amp):
    e = dict(p); e['category'] = cat; e['shape'] = sh; e['amp'] = amp
    if cat == 'transition_shape' and sh == 'dahl_exponent':
        e['alpha'] = 1 - amp if p['branch'] == 'lt1' else 1 + amp
    return e

def rms_diff(Fs, Bs):
    s = 0.0; n = 0
    for F, B in zip(Fs, Bs):
        for a, b in zip(F[1:], B[1:]):
            s += (a - b) ** 2; n += 1
    return math.sqrt(s / n)

def plan(rng):
    trials = []
    for cat, shapes in SHAPES.items():
        sh = shapes[:]; rng.shuffle(sh)
        shp = (sh * 3)[:5]
        st = ['weak', 'strong', 'weak', 'strong', rng.choice(['weak', 'strong'])]; rng.shuffle(st)
        if cat == 'residual_static':
            kinds = ['replay', 'pauses', 'pauses', 'pauses', 'eq_synth']
        elif cat in ('pretension', 'actuator_lag'):
            kinds = ['replay', 'replay', 'replay', rng.choice(['eq_synth', 'harmonic_steps']), 'harmonic_steps']
        elif cat == 'backlash':
            kinds = ['replay', 'replay', 'replay', 'pauses', 'eq_synth']
        else:
            kinds = ['replay', 'replay', 'replay', 'eq_synth', rng.choice(['harmonic_steps', 'pauses'])]
        rng.shuffle(kinds)
        for i in range(5):
            trials.append(dict(category=cat, shape=shp[i], strength=st[i], input_kind=kinds[i]))
    nk = ['replay'] * 5 + ['eq_synth', 'harmonic_steps', 'pauses']
    for i in range(8):
        trials.append(dict(category='none', shape='none', strength='weak', input_kind=nk[i]))
    rng.shuffle(trials)
    noises = [0.02, 0.06] * 24; rng.shuffle(noises)
    colours = ['white'] * 30 + ['ar1'] * 7 + ['white_hum'] * 5 + ['pink3'] * 6; rng.shuffle(colours)
    for i, t in enumerate(trials):
        t['id'] = 't%02d' % (i + 1); t['noise_rms_kip'] = noises[i]; t['noise_kind'] = colours[i]
    return trials

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--seed', type=int, default=20261126)
    ap.add_argument('--out', default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    ap.add_argument('--only', default='')
    ap.add_argument('--clean', default='/tmp/blind6_clean', help='where the noise-free force of the none records goes (for gen/verify.py); kept out of the set')
    a = ap.parse_args()
    rng = random.Random(a.seed)
    trials = plan(rng)
    os.makedirs(a.clean, exist_ok=True)
    key = []
    t_start = time.time()
    for t in trials:
        trng = random.Random('%d-%s' % (a.seed, t['id']))
        if t['input_kind'] == 'replay':
            i, j = trng.sample(range(6), 2)
            inps = [replay_input(SRC_FILES[i]), replay_input(SRC_FILES[j])]
        else:
            k2 = t['input_kind'] if trng.random() < 0.6 else trng.choice(['eq_synth', 'harmonic_steps', 'pauses'])
            if t['category'] == 'residual_static': k2 = 'pauses' if t['input_kind'] == 'pauses' else 'eq_synth'
            inps = [designed_input(t['input_kind'], trng), designed_input(k2, trng)]
        for inp in inps:
            inp['v'] = velocity(inp['x'])
        if a.only and t['id'] not in a.only.split(','):
            continue
        base = [effects.simulate(inp, dict(category='none')) for inp in inps]
        cat, sh = t['category'], t['shape']
        entry = dict(id=t['id'], category=cat, shape=sh, strength=t['strength'],
                     noise_rms_kip=t['noise_rms_kip'], noise_kind=t['noise_kind'],
                     input_kind=t['input_kind'], inputs=[inp['src'] for inp in inps])
        if cat == 'none':
            Fs = base; params = {}; rms = 0.0; amp = 0.0
        else:
            p, (lo, hi) = shape_params(cat, sh, trng)
            target = trng.uniform(0.15, 0.3) if t['strength'] == 'weak' else trng.uniform(0.45, 0.8)
            best = None
            for gi in range(14):
                amp = lo * (hi / lo) ** (gi / 13)
                e = eff_for(cat, sh, p, amp)
                F = [effects.simulate(inp, e) for inp in inps]
                r = rms_diff(F, base)
                if best is None or abs(r - target) < abs(best[0] - target):
                    best = (r, amp, F)
            rms, amp, Fs = best
            params = eff_for(cat, sh, p, amp); params.pop('category'); params.pop('shape')
            params = {k: (round(v, 6) if isinstance(v, float) else v) for k, v in params.items()}
            entry['target_effect_rms_kip'] = round(target, 4)
            # label by the achieved size of the effect
            entry['strength'] = 'strong' if rms >= 0.4 else 'weak'
        entry['effect_rms_kip'] = round(rms, 4)
        entry['parameters'] = params
        d = os.path.join(a.out, 'cases', t['id']); os.makedirs(d, exist_ok=True)
        for lab, inp, F, B in zip('AB', inps, Fs, base):
            nz = make_noise(N, t['noise_rms_kip'], t['noise_kind'], trng)
            write_record(os.path.join(d, lab + '.json'), inp, F, nz, trng)
            if cat == 'none':
                with open(os.path.join(a.clean, '%s_%s.txt' % (t['id'], lab)), 'w') as fh:
                    fh.write('\n'.join(repr(v) for v in F))
        key.append(entry)
        print(t['id'], cat, sh, entry['strength'], entry['effect_rms_kip'], t['input_kind'],
              '%.0fs' % (time.time() - t_start), flush=True)
    if not a.only:
        with open(os.path.join(a.out, 'key.json'), 'w') as fh:
            json.dump({'seed': a.seed, 'trials': key}, fh, indent=1)
        with open(os.path.join(a.out, 'trials.txt'), 'w') as fh:
            fh.write('\n'.join(t['id'] for t in trials) + '\n')

if __name__ == '__main__':
    main()
