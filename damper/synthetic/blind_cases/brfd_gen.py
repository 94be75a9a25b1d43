#!/usr/bin/env python3
"""Blind synthetic BRFD test generator (Python 3 stdlib only).

Truth force = semi-active LuGre model of the paper (Eqs. 1-5, config parameters)
              + one hidden physical effect (see EFFECTS below and README.md)
              + measurement noise.
Output records use exactly the 8-column JSON layout of the measured semi-active files.

Drum velocity: the semi-active files' velocity column is ~1/125.4 of d(disp)/dt (data README).
The truth model uses the drum velocity DERIVED FROM THE DISPLACEMENT COLUMN by central
differences (one-sided at the ends) followed by a 15-sample zero-phase (centred, symmetric,
shrinking at the ends) moving average, so that the 'none' cases are the base model exactly.
The velocity column written to synthetic-motion files keeps the quirk (derived velocity / 125.4).
"""
import json, math, random, os, sys

DT = 1.0 / 1024
# ---- base parameters (configs/brfd-semiactive.yaml) ----
BASE = dict(s0=15.36, s1=0.0, s2=0.5, fsf=7.116, fsb=3.760, fcf=2.648, fcb=1.253, vs=1.3,
            m=[-0.14, -0.15, -15.29, -13.00, -16.66, -15.77, -0.13, -0.15],
            C=[119.68, 2.10, 1.94, 123.31], floor=0.05)
VEL_QUIRK = 125.4
SEMI = os.environ.get('BRFD_SEMIACTIVE', '/work/shared/data/brfd/semiactive')
META = {"dt": 0.0009765625, "sampling freq": 1024, "displacement units": "in", "time units": "s",
        "friction force units": "kip", "actuator force units": "lb"}


# ------------------------------------------------------------------ inputs
def derive_velocity(x):
    n = len(x)
    d = [0.0] * n
    for i in range(1, n - 1):
        d[i] = (x[i + 1] - x[i - 1]) / (2 * DT)
    d[0] = (x[1] - x[0]) / DT
    d[-1] = (x[-1] - x[-2]) / DT
    # centred 15-sample moving average, symmetric window shrinking at the ends
    pre = [0.0]
    for q in d:
        pre.append(pre[-1] + q)
    out = [0.0] * n
    for i in range(n):
        k = min(i, n - 1 - i, 7)
        out[i] = (pre[i + k + 1] - pre[i - k]) / (2 * k + 1)
    return out


def load_measured(name):
    D = json.load(open(os.path.join(SEMI, name)))['data']
    return dict(name=name, t=[r[0] for r in D], x=[r[1] for r in D], vcol=[r[3] for r in D],
                x1=[r[4] for r in D], x2=[r[5] for r in D], F0=D[0][2], src='measured:' + name)


def quant(v, q):
    return round(v / q) * q


def synth_eq(seed, dur=32.0, passive=7.0):
    """Earthquake-like broadband drum motion (sum of random-phase sinusoids with a
    building-response-like spectrum, 0.25-3 Hz, envelope build-up / strong / decay / rest)
    and smooth electric-actuator moves (raised-cosine pulses) after a passive window."""
    rng = random.Random(seed)
    n = int(dur * 1024) + 1
    comps = []
    for k in range(40):
        f = math.exp(rng.uniform(math.log(0.25), math.log(3.0)))
        a = 1.0 / (1 + ((f - 0.7) / 0.5) ** 2) / f  # displacement spectrum peaked ~0.5-0.9 Hz
        comps.append((f, a * rng.uniform(0.5, 1.5), rng.uniform(0, 2 * math.pi)))
    def env(t):
        if t < 0.3: return 0.0
        if t < 3.0: return ((t - 0.3) / 2.7) ** 2
        if t < dur - 9: return 1.0
        if t < dur - 2.5: return math.exp(-3 * (t - (dur - 9)) / 6.5) * (1 - (t - (dur - 9)) / 6.5)
        return 0.0
    raw = []
    for i in range(n):
        t = i * DT
        raw.append(env(t) * sum(a * math.sin(2 * math.pi * f * t + p) for f, a, p in comps))
    pk = max(abs(q) for q in raw)
    scale = rng.uniform(0.8, 1.1) / pk
    x = [quant(q * scale + rng.gauss(0, 2e-5), 5.865e-5) for q in raw]
    # actuator moves: 4-6 raised-cosine pulses / holds, amplitudes <= 0.03 in
    x10, x20 = 0.6549999713897705, 0.8559008240699768
    d1 = [0.0] * n; d2 = [0.0] * n
    t = passive
    mode = rng.choice(['one', 'two', 'both'])
    while t < dur - 6:
        T = rng.uniform(0.4, 1.0)
        a = rng.choice([-1, 1]) * rng.uniform(0.012, 0.03)
        hold = rng.uniform(0.0, 0.8)
        i0 = int(t * 1024); i1 = int((t + T / 2) * 1024); i2 = int((t + T / 2 + hold) * 1024); i3 = int((t + T + hold) * 1024)
        for i in range(i0, min(i3, n)):
            if i < i1: s = 0.5 - 0.5 * math.cos(math.pi * (i - i0) / (i1 - i0))
            elif i < i2: s = 1.0
            else: s = 0.5 + 0.5 * math.cos(math.pi * (i - i2) / (i3 - i2))
            if mode in ('one', 'both'): d1[i] += a * s * (0.5 if mode == 'both' else 1)
            if mode in ('two', 'both'): d2[i] += a * s * (0.5 if mode == 'both' else 1)
        t += T + hold + rng.uniform(0.8, 2.5)
    x1 = [quant(x10 + d1[i] + rng.gauss(0, 1.5e-6), 2.384e-6) for i in range(n)]
    x2 = [quant(x20 + d2[i] + rng.gauss(0, 1.5e-6), 2.384e-6) for i in range(n)]
    x1[0], x2[0] = x10, x20
    v = derive_velocity(x)
    vcol = [q / VEL_QUIRK + rng.gauss(0, 2e-5) for q in v]
    tt = [i * DT for i in range(n)]
    return dict(name='eq_seed%d' % seed, t=tt, x=x, vcol=vcol, x1=x1, x2=x2,
                F0=rng.uniform(-0.2, 0.4), src='synthetic earthquake-like, seed %d' % seed)


# ------------------------------------------------------------------ model
def fc_eq4(P, vv, a, b, x10, x20):
    m, C = P['m'], P['C']
    if vv >= 0:
        r = P['fcf'] + (C[0] * m[0] + C[1] * m[2]) * (a - x10) + (C[0] * m[1] + C[1] * m[3]) * (b - x20)
    else:
        r = P['fcb'] + (C[2] * m[4] + C[3] * m[6]) * (a - x10) + (C[2] * m[5] + C[3] * m[7]) * (b - x20)
    return max(r, P['floor'])


def simulate(inp, effect='none', E=None, P=BASE, z0F=None):
    """Return the noise-free truth force (kip). effect='none' is the paper's model exactly,
    integrated like the reference: z_i = RK4 step of Eq. 1 from z_{i-1} with inputs held at
    sample i; F_i = sigma0 z_i + sigma1 zdot_i + sigma2 v_i; z_0 = F(0)/sigma0."""
    E = E or {}
    v = inp['v']; X1 = inp['x1']; X2 = inp['x2']; n = len(v)
    x10, x20 = X1[0], X2[0]
    s0, s1, s2, vs = P['s0'], P['s1'], P['s2'], P['vs']
    F0 = inp['F0'] if z0F is None else z0F
    z = F0 / s0
    out = [0.0] * n
    # ---- effect states
    x1e, x2e = X1[0], X2[0]          # actuator_lag: effective positions
    y1 = [0.0, 0.0]; y2 = [0.0, 0.0]  # 2nd-order states (deviation, rate)
    direction = 0; travel = 0.0; phase = 'engaged'; tslack = 0.0  # backlash
    trest = E.get('trest0', 2.0); zlock = z; resting = True  # residual_static
    vl = abs(v[0])                    # lagged speed (velocity / transition_shape)
    work = 0.0                        # pretension (friction work)
    delay = int(round(E.get('delay', 0.0) / DT))

    def sig_of(zz):  # asymmetry: direction-dependent band stiffness
        if effect == 'asymmetry':
            return s0 * (1 + E['a'] * math.tanh(zz / E['zt']))
        return s0

    for i in range(n):
        vi = v[i]
        a1, a2 = X1[i], X2[i]
        # ----------------------------------------------- effect state updates (explicit, per sample)
        if effect == 'actuator_lag':
            j = max(0, i - delay)
            for (ys, xc, x0) in ((y1, X1[j], x10), (y2, X2[j], x20)):
                wn = 2 * math.pi * E['fn']; ze = E['zeta']
                target = xc - x0
                # semi-implicit Euler of y'' + 2 ze wn y' + wn^2 y = wn^2 target
                acc = wn * wn * (target - ys[0]) - 2 * ze * wn * ys[1]
                ys[1] += DT * acc
                rl = E.get('rate_limit')
                if rl:
                    ys[1] = max(-rl, min(rl, ys[1]))
                ys[0] += DT * ys[1]
            a1, a2 = x10 + y1[0], x20 + y2[0]
        if effect == 'backlash':
            veps = 0.02
            Ftot = s0 * z + s2 * vi
            if vi > veps and direction != 1:   # reversal: unload the loaded end unless already loaded this way
                direction = 1; travel = 0.0; phase = 'unload' if Ftot < 0 else 'engaged'
            elif vi < -veps and direction != -1:
                direction = -1; travel = 0.0; phase = 'unload' if Ftot > 0 else 'engaged'
            travel += abs(vi) * DT
            if phase == 'unload' and (s0 * z + s2 * vi) * direction >= 0:  # loaded band end fully unloaded
                phase = 'slack'; tslack = travel
        if effect == 'residual_static':
            w = math.exp(-(vi / E['vr']) ** 2)
            if w > 0.5 and not resting:
                resting = True; zlock = z; trest = 0.0
            elif w < 0.5:
                resting = False
            trest = trest + DT if resting else 0.0
        if effect in ('velocity', 'transition_shape'):
            tau = E['tau']
            vl += (1 - math.exp(-DT / tau)) * (abs(vi) - vl) if tau > 0 else (abs(vi) - vl)
        if effect == 'pretension':
            work += abs((s0 * z) * vi) * DT

        eng = 1.0
        if effect == 'backlash' and phase == 'slack':
            s_ = travel - tslack
            if s_ < E['d0']:
                eng = 0.0
            elif s_ < E['d0'] + E['d1']:
                u = (s_ - E['d0']) / E['d1']; eng = u * u * (3 - 2 * u)
        # ----------------------------------------------- g(v) of Eq. 5 with the effect
        fs = P['fsf'] if vi >= 0 else P['fsb']
        fc = fc_eq4(P, vi, a1, a2, x10, x20)
        if effect == 'pretension':
            d = -E['dF'] * (1 - math.exp(-work / E['W0']))
            fc = max(fc + d, P['floor']); fs = max(fs + d, P['floor'])
        if effect == 'transition_shape':
            g = fc + (fs - fc) * math.exp(-((vl / vs) ** E['delta']))
        else:
            g = fc + (fs - fc) * math.exp(-(vi / vs) ** 2)
        if effect == 'velocity':
            g *= (1 + E['alpha'] * math.log(1 + vl / E['V0'])) / (1 + E['alpha'] * math.log(1 + E['Vref'] / E['V0']))
        bdir = P['fcf'] if vi >= 0 else P['fcb']
        sgn = 1.0 if vi >= 0 else -1.0

        def rhs(zz):
            gg = g
            if effect == 'self_energizing':
                Fp = max(0.0, sig_of(zz) * zz * sgn)
                gg = g * math.exp(E['kappa'] * (math.tanh(Fp / E['Fref']) - math.tanh(bdir / E['Fref'])))
            Fb = sig_of(zz) * zz
            if effect == 'backlash':
                r = eng
                ve = r * vi
                # slack band: the bristle/band deflection left at the onset is released over a short
                # travel lam; re-tensioning loads it with the engaged share r of the drum motion
                return ve - abs(ve) * Fb / gg - (1 - r) * abs(vi) * zz / E['lam']
            zd = vi - abs(vi) * Fb / gg
            if effect == 'residual_static' and resting:
                zd += -E['q'] * (zz - E['rho'] * zlock) / (E['tau0'] + trest)
            return zd

        if i > 0:
            k1 = rhs(z); k2 = rhs(z + DT / 2 * k1); k3 = rhs(z + DT / 2 * k2); k4 = rhs(z + DT * k3)
            z += DT / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        zd = rhs(z)
        if effect == 'backlash':   # slack band: no contact pressure, the whole friction scales with engagement
            out[i] = eng * (sig_of(z) * z + s1 * zd + s2 * vi)
        else:
            out[i] = sig_of(z) * z + s1 * zd + s2 * vi
    return out


# ------------------------------------------------------------------ record writing
def actuator_forces(F, rng):
    """Band-end load cells (lb): taut end carries F/C_taut, slack end F/C_slack (Table 2),
    plus a slack baseline and load-cell noise."""
    C = BASE['C']
    a1 = []; a2 = []
    for f in F:
        if f >= 0:
            t1, t2 = f / C[0], f / C[1]
        else:
            t1, t2 = -f / C[2], -f / C[3]
        a1.append(quant(30.0 + 1000 * t1 + rng.gauss(0, 1.2), 0.3179))
        a2.append(quant(30.0 + 1000 * t2 + rng.gauss(0, 1.2), 0.3179))
    return a1, a2


def noise_series(n, rms, rng, rho=0.0):
    e = []; s = 0.0; k = math.sqrt(1 - rho * rho)
    for i in range(n):
        s = rho * s + k * rng.gauss(0, 1)
        e.append(rms * s)
    return e


def write_record(path, inp, Fmeas, a1f, a2f):
    rows = []
    for i in range(len(Fmeas)):
        rows.append([inp['t'][i], inp['x'][i], float('%.10g' % Fmeas[i]), inp['vcol'][i],
                     inp['x1'][i], inp['x2'][i], float('%.8g' % a1f[i]), float('%.8g' % a2f[i])])
    d = {"data": rows}
    d.update(META)
    with open(path, 'w') as f:
        json.dump(d, f)


def nrmse(a, b):
    n = len(a)
    mb = sum(b) / n
    sd = math.sqrt(sum((q - mb) ** 2 for q in b) / n)
    return math.sqrt(sum((p - q) ** 2 for p, q in zip(a, b)) / n) / sd


def prep(inp):
    inp['v'] = derive_velocity(inp['x'])
    return inp
