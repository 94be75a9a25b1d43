#!/usr/bin/env python3
"""Blind test set 19 for the BRFD model-discrepancy tool (generator).

Writes /work/blind19/cases/tNN/{A,B}.json and /work/blind19/key.json.
Deterministic: master seed 19019, standard library only.

    nice -n 10 python3 /work/blind19/gen/gen.py [--out /work/blind19] [--jobs 2]

Units: kip, in, s.  Conventions of the base model (inferred with the black box
`hybridsim damper predict --no-fit`, reproduced here to ~5e-8 kip):
  * drum velocity v = 15-sample centred moving average (window shrinks
    symmetrically at the ends) of the central difference of the displacement
    (one-sided differences at the two end samples);
  * LuGre state advanced from sample i-1 to i with v[i], g(v[i]), Fc[i]
    (exact exponential update for frozen a = s0|v|/g); F[i] = s0 z[i] + s2 v[i];
  * z(0) = F_record(0) / s0 (the record's first force sample = initial band force);
  * Fc from Eq. 4 with x'_1, x'_2 = the actuator positions of the first row,
    direction v >= 0 -> forward row, clipped below at 0.05 kip.
See NOTES.md for everything else.
"""
import json, math, os, random, sys, hashlib, struct

MASTER_SEED = 19019
SRC_DIR = '/work/shared/data/brfd/semiactive'
SRC_FILES = ['harmonic0.015forward', 'harmonic0.015backward', 'harmonic0.03ea1forward',
             'harmonic0.03ea1backward', 'harmonic0.03ea2forward', 'harmonic0.03ea2backward']
DT = 0.0009765625
FS_HZ = 1024

# ----------------------------------------------------------------- base model (config)
S0 = 15.36; S1 = 0.0; S2 = 0.5; VS = 1.3
FSF = 7.116; FSB = 3.760; BF = 2.648; BB = 1.253; FLOOR = 0.05
M = [-0.14, -0.15, -15.29, -13.00, -16.66, -15.77, -0.13, -0.15]
C = [119.68, 2.10, 1.94, 123.31]
K1F = C[0] * M[0] + C[1] * M[2]; K2F = C[0] * M[1] + C[1] * M[3]
K1B = C[2] * M[4] + C[3] * M[6]; K2B = C[2] * M[5] + C[3] * M[7]

# quantisation of the measured files
Q_X = 5.89197e-05        # drum displacement (in)
Q_F = 0.00080088         # friction force (kip)
Q_A = 2.4e-06            # actuator positions (in)
Q_FA1 = 0.3179           # actuator 1 force (lb)
Q_FA2 = 0.39985          # actuator 2 force (lb)
VEL_QUIRK = 125.4        # velocity column = (in/s) / 125.4, as in the measured semi-active files


def qz(v, q):
    return round(v / q) * q


def velocity(x, dt=DT):
    n = len(x); d = [0.0] * n
    for i in range(1, n - 1):
        d[i] = (x[i + 1] - x[i - 1]) / (2 * dt)
    d[0] = (x[1] - x[0]) / dt; d[-1] = (x[-1] - x[-2]) / dt
    P = [0.0]
    for a in d:
        P.append(P[-1] + a)
    out = [0.0] * n
    for i in range(n):
        k = min(7, i, n - 1 - i)
        out[i] = (P[i + k + 1] - P[i - k]) / (2 * k + 1)
    return out


# ------------------------------------------------------------------ record container
class Rec:
    """Precomputed arrays of one record used by every model evaluation."""
    def __init__(self, x, x1, x2, F0):
        self.n = n = len(x)
        self.x = x; self.x1 = x1; self.x2 = x2; self.F0 = F0
        self.v = v = velocity(x)
        self.d1 = [a - x1[0] for a in x1]
        self.d2 = [a - x2[0] for a in x2]
        self.E = [math.exp(-(a / VS) ** 2) for a in v]
        self.fwd = [a >= 0 for a in v]
        xc = 0.5 * (max(x) + min(x))
        self.xr = [a - xc for a in x]          # drum position about the centre of travel
        self.lam = [math.exp(-(a / 0.01) ** 2) if abs(a) < 0.05 else 0.0 for a in v]
        self.base = simulate(self, 'base', 0.0, {})


def fc_arrays(R, d1, d2):
    fcf = [max(BF + K1F * a + K2F * b, FLOOR) for a, b in zip(d1, d2)]
    fcb = [max(BB + K1B * a + K2B * b, FLOOR) for a, b in zip(d1, d2)]
    return fcf, fcb


# -------------------------------------------------------------- actuator transforms
def act_lag1(d, tau):
    a = 1.0 - math.exp(-DT / tau); y = d[0]; out = []
    for u in d:
        y += (u - y) * a; out.append(y)
    return out


def act_delay(d, td):
    n = len(d); s = td / DT; out = []
    for i in range(n):
        t = i - s
        if t <= 0:
            out.append(d[0]); continue
        j = int(t); f = t - j
        out.append(d[j] + f * (d[min(j + 1, n - 1)] - d[j]))
    return out


def act_second(d, Tn, zeta):
    w = 2 * math.pi / Tn; sub = max(1, int(math.ceil(w * DT / 0.05))); h = DT / sub
    y = d[0]; yd = 0.0; out = []
    for u in d:
        for _ in range(sub):          # semi-implicit Euler
            yd += h * (w * w * (u - y) - 2 * zeta * w * yd)
            y += h * yd
        out.append(y)
    return out


# --------------------------------------------------------------------------- models
FAMILY_A = {'base', 'soft_takeup', 'maxwell_relax', 'log_relax', 'equalize_relax', 'bilinear_band',
            'band_fade', 'band_runin', 'ratestate_log', 'frictional_lag', 'shear_thinning',
            'power_clamp', 'archard_wear', 'thermal_tighten', 'capstan_wrap', 'drum_runout',
            'servo_feedback', 'act_firstorder', 'act_deadtime', 'act_secondorder'}


def simulate(R, shape, p, P):
    """Noise-free force (kip) of the 'true' device for effect `shape` with strength p.
    p = 0 (or shape 'base') gives the base model exactly."""
    if shape == 'base' or p == 0.0:
        shape = 'base'
    if shape in ('deadzone_gap', 'stretch_slack'):
        return sim_deadzone(R, shape, p, P)
    if shape == 'dahl_exponent':
        return sim_dahl(R, p, P)
    if shape == 'elastoplastic':
        return sim_elastoplastic(R, p, P)
    if shape == 'maxwell_slip':
        return sim_maxwell_slip(R, p, P)
    n = R.n; v = R.v; dt = DT
    d1, d2 = R.d1, R.d2
    if shape == 'act_firstorder':
        d1 = act_lag1(d1, p); d2 = act_lag1(d2, p)
    elif shape == 'act_deadtime':
        d1 = act_delay(d1, p); d2 = act_delay(d2, p)
    elif shape == 'act_secondorder':
        d1 = act_second(d1, p, P['zeta']); d2 = act_second(d2, p, P['zeta'])
    fcf, fcb = fc_arrays(R, d1, d2)
    if shape == 'power_clamp':
        ex = 1.0 - p
        fcf = [max(BF * (f / BF) ** ex, FLOOR) for f in fcf]
        fcb = [max(BB * (f / BB) ** ex, FLOOR) for f in fcb]
    E = R.E
    visc = [S2 * a for a in v]
    if shape == 'frictional_lag':
        a = 1.0 - math.exp(-dt / p); vl = 0.0; vls = []
        for a_ in v:
            vl += (a_ - vl) * a; vls.append(vl)
        E = [math.exp(-(a_ / VS) ** 2) for a_ in vls]
        visc = [S2 * a_ for a_ in vls]
    elif shape == 'shear_thinning':
        vc = P['vc']; ex = 1.0 - p
        visc = [(S2 * vc * (abs(a_) / vc) ** ex if a_ >= 0 else -S2 * vc * (abs(a_) / vc) ** ex) for a_ in v]
    # static multiplicative factor on g
    gf = None
    if shape == 'ratestate_log':
        vstar = P['vstar']; gf = [1.0 + p * math.log(1.0 + abs(a_) / vstar) for a_ in v]
    elif shape == 'capstan_wrap':
        gf = [math.exp(p * (xr if f else -xr)) for xr, f in zip(R.xr, R.fwd)]
    elif shape == 'drum_runout':
        lamb = P['wavelength_in']; ph = P['phase_rad']
        gf = [1.0 + p * math.sin(2 * math.pi * xr / lamb + ph) for xr in R.xr]
    g0 = []
    fw = R.fwd
    for i in range(n):
        if fw[i]:
            c = fcf[i]; g0.append(c + (FSF - c) * E[i])
        else:
            c = fcb[i]; g0.append(c + (FSB - c) * E[i])
    if gf is not None:
        g0 = [a * b for a, b in zip(g0, gf)]
    Fe = R.F0
    out = [Fe + visc[0]]
    exp = math.exp
    if shape in ('base', 'act_firstorder', 'act_deadtime', 'act_secondorder', 'power_clamp',
                 'frictional_lag', 'shear_thinning', 'ratestate_log', 'capstan_wrap', 'drum_runout'):
        for i in range(1, n):
            vi = v[i]
            if vi != 0.0:
                g = g0[i]
                if vi > 0:
                    Fe = g + (Fe - g) * exp(-S0 * vi / g * dt)
                else:
                    Fe = -g + (Fe + g) * exp(S0 * vi / g * dt)
            out.append(Fe + visc[i])
        return out
    # ------------------------------------------------ shapes with extra state
    lam = R.lam
    th = 0.0; W = 0.0; srun = 0.0; t_rest = 0.0; F_hold = Fe
    for i in range(1, n):
        vi = v[i]; g = g0[i]
        if shape == 'band_fade':
            if fw[i] == (P['band'] == 'forward'):
                g = g / (1.0 + p * th)
        elif shape == 'band_runin':
            if fw[i] == (P['band'] == 'forward'):
                g = g * (1.0 + P['sign'] * p * (1.0 - exp(-srun / P['s0_in'])))
        elif shape == 'archard_wear':
            g = g / (1.0 + p * W / P['Wref_kip_in'])
        elif shape == 'thermal_tighten':
            g = g * (1.0 + p * th)
        elif shape == 'servo_feedback':
            g = g * (1.0 + p * abs(Fe) / P['Fref_kip'])
        h = 1.0
        if shape == 'soft_takeup':
            T = abs(Fe) + P['T0_kip']; T3 = T * T * T
            h = T3 / (T3 + p * p * p)
        elif shape == 'bilinear_band':
            h = (1.0 + p) if (Fe >= 0) == (P['stiff_band'] == 'forward') else 1.0 / (1.0 + p)
        if vi != 0.0:
            k = S0 * h * abs(vi) / g * dt
            if vi > 0:
                Fe = g + (Fe - g) * exp(-k)
            else:
                Fe = -g + (Fe + g) * exp(-k)
        # rest behaviour
        if shape == 'maxwell_relax':
            if lam[i] > 0.0:
                Fe *= exp(-lam[i] * p * dt)
        elif shape == 'log_relax':
            if abs(vi) < 0.005:
                t_rest += dt
                Fe = F_hold * max(0.0, 1.0 - p * math.log(1.0 + t_rest / P['t0_s']))
            else:
                t_rest = 0.0; F_hold = Fe
        elif shape == 'equalize_relax':
            if abs(vi) < 0.005:
                tgt = (1.0 - p) * F_hold + p * P['F_res_kip']
                Fe = tgt + (Fe - tgt) * exp(-lam[i] * dt / P['tau_s'])
            else:
                F_hold = Fe
        # slow states (use this step's dissipation)
        pw = abs(Fe * vi)
        if shape == 'band_fade':
            pb = pw if (fw[i] == (P['band'] == 'forward')) else 0.0
            th += dt * (pb / P['Pref_kip_in_s'] - th / P['tau_th_s'])
        elif shape == 'thermal_tighten':
            th += dt * (pw / P['Pref_kip_in_s'] - th / P['tau_th_s'])
        elif shape == 'archard_wear':
            W += pw * dt
        elif shape == 'band_runin':
            if fw[i] == (P['band'] == 'forward'):
                srun += abs(vi) * dt
        out.append(Fe + visc[i])
    return out


def g_array(R):
    fcf, fcb = fc_arrays(R, R.d1, R.d2)
    return [(fcf[i] + (FSF - fcf[i]) * R.E[i]) if R.fwd[i] else (fcb[i] + (FSB - fcb[i]) * R.E[i])
            for i in range(R.n)]


def sim_deadzone(R, shape, p, P):
    """Clearance (dead zone) in the compliant band path: force = s0 * (z beyond the gap)."""
    n = R.n; v = R.v; dt = DT; g0 = g_array(R); exp = math.exp
    Fref = P.get('Fref_kip', 3.0)
    if shape == 'deadzone_gap':
        G = p
    else:
        G = p * abs(R.F0) / Fref
    F0 = R.F0
    z = F0 / S0 + (G if F0 > 0 else (-G if F0 < 0 else 0.0))
    out = [F0 + S2 * v[0]]
    dirn = 1 if v[0] >= 0 else -1
    Fe = F0
    for i in range(1, n):
        vi = v[i]; g = g0[i]
        if shape == 'stretch_slack':
            nd = dirn
            if vi > 0.02: nd = 1
            elif vi < -0.02: nd = -1
            if nd != dirn:                      # reversal: new slack from the band stretch
                dirn = nd
                e = z - G if z > G else (z + G if z < -G else 0.0)
                Gn = p * abs(Fe) / Fref
                if e > 0: z = Gn + e
                elif e < 0: z = -Gn + e
                else: z = z * (Gn / G) if G > 0 else 0.0
                G = Gn
        if z > G or z < -G:
            zs = G if z > G else -G
            e = z - zs
            if vi != 0.0:
                a = S0 * abs(vi) / g
                ess = vi / a
                e = ess + (e - ess) * exp(-a * dt)
            z = zs + e
        else:
            z += vi * dt
        Fe = S0 * (z - G if z > G else (z + G if z < -G else 0.0))
        out.append(Fe + S2 * vi)
    return out


def sim_dahl(R, p, P):
    """Dahl (1968) curve exponent: dF/dx = s0 |1 - F sgn(v)/g|^alpha sgn(.); alpha=1 is LuGre's."""
    n = R.n; v = R.v; dt = DT; g0 = g_array(R)
    alpha = (1.0 + p) if P['direction'] == 'ductile' else 1.0 / (1.0 + p)
    Fe = R.F0; out = [Fe + S2 * v[0]]
    for i in range(1, n):
        vi = v[i]
        if vi != 0.0:
            g = g0[i]; s = 1.0 if vi > 0 else -1.0
            u = 1.0 - s * Fe / g
            c = S0 * abs(vi) / g * dt
            w = abs(u)
            if w > 0.0:
                if alpha < 1.0:
                    b = 1.0 - alpha
                    w = max(0.0, w ** b - b * c) ** (1.0 / b)
                elif alpha > 1.0:
                    b = alpha - 1.0
                    w = (w ** (-b) + b * c) ** (-1.0 / b)
                else:
                    w = w * math.exp(-c)
            u = w if u >= 0 else -w
            Fe = s * g * (1.0 - u)
        out.append(Fe + S2 * vi)
    return out


def sim_elastoplastic(R, p, P):
    """Elasto-plastic pre-sliding (Dupont et al. 2002): no plastic drift below the break-away
    deflection z_ba = p z_ss, smooth (sine) onset between p and 1.5 p of z_ss."""
    n = R.n; v = R.v; dt = DT; g0 = g_array(R); exp = math.exp
    Fe = R.F0; out = [Fe + S2 * v[0]]
    lo = p; hi = 1.5 * p
    for i in range(1, n):
        vi = v[i]
        if vi != 0.0:
            g = g0[i]
            r = abs(Fe) / g
            if r <= lo: al = 0.0
            elif r >= hi: al = 1.0
            else: al = 0.5 * math.sin(math.pi * ((r - lo) / (hi - lo) - 0.5)) + 0.5
            if al > 0.0:
                k = S0 * al * abs(vi) / g * dt
                Fss = (g if vi > 0 else -g) / al
                Fe = Fss + (Fe - Fss) * exp(-k)
            else:
                Fe += S0 * vi * dt
        out.append(Fe + S2 * vi)
    return out


def sim_maxwell_slip(R, p, P):
    """Maxwell-slip / Iwan parallel elasto-slide elements (Iwan 1966; Lampaert et al. 2002):
    N elements of stiffness s0/N with break-away forces w_i g(v), w_i = (2i-1)/N^2
    (uniform slip-displacement density -> Masing parabolic pre-sliding). Mixed with LuGre:
    F = (1-p) F_LuGre + p F_MS."""
    n = R.n; v = R.v; dt = DT; g0 = g_array(R)
    N = P['N']; k = S0 / N; w = [(2 * j - 1) / float(N * N) for j in range(1, N + 1)]
    F0 = R.F0
    gst = FSF if F0 >= 0 else FSB
    lo, hi = 0.0, 10.0
    tgt = abs(F0)
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        s = sum(min(k * mid, wj * gst) for wj in w)
        if s < tgt: lo = mid
        else: hi = mid
    d0 = 0.5 * (lo + hi) * (1 if F0 >= 0 else -1)
    phi = [max(-wj * gst, min(wj * gst, k * d0)) for wj in w]
    out = [F0 + S2 * v[0]]
    base = R.base
    for i in range(1, n):
        vi = v[i]; g = g0[i]; dphi = k * vi * dt; tot = 0.0
        for j in range(N):
            f = phi[j] + dphi; lim = w[j] * g
            if f > lim: f = lim
            elif f < -lim: f = -lim
            phi[j] = f; tot += f
        out.append((1.0 - p) * base[i] + p * (tot + S2 * vi))
    return out


# --------------------------------------------------------------------------- shapes
# category -> list of (shape, p_max, fixed-parameter drawer, literature source)
def draw_fixed(shape, rng):
    P = {}
    if shape == 'stretch_slack': P['Fref_kip'] = 3.0
    elif shape == 'soft_takeup': P['T0_kip'] = round(rng.uniform(0.10, 0.25), 3)
    elif shape == 'log_relax': P['t0_s'] = round(rng.uniform(0.03, 0.10), 3)
    elif shape == 'equalize_relax':
        P['F_res_kip'] = round(rng.uniform(0.8, 2.8), 3); P['tau_s'] = round(rng.uniform(0.25, 0.6), 3)
    elif shape == 'act_secondorder': P['zeta'] = round(rng.uniform(0.2, 0.35), 3)
    elif shape == 'bilinear_band': P['stiff_band'] = rng.choice(['forward', 'backward'])
    elif shape == 'band_fade':
        P['band'] = rng.choice(['forward', 'backward']); P['Pref_kip_in_s'] = 10.0
        P['tau_th_s'] = round(rng.uniform(4.0, 8.0), 2)
    elif shape == 'band_runin':
        P['band'] = rng.choice(['forward', 'backward']); P['sign'] = rng.choice([1, -1])
        P['s0_in'] = round(rng.uniform(4.0, 10.0), 2)
    elif shape == 'ratestate_log': P['vstar'] = round(rng.uniform(0.1, 0.3), 3)
    elif shape == 'shear_thinning': P['vc'] = round(rng.uniform(1.5, 2.5), 3)
    elif shape == 'archard_wear': P['Wref_kip_in'] = 50.0
    elif shape == 'thermal_tighten':
        P['Pref_kip_in_s'] = 10.0; P['tau_th_s'] = round(rng.uniform(3.0, 6.0), 2)
    elif shape == 'drum_runout':
        P['wavelength_in'] = round(rng.uniform(1.2, 3.0), 3); P['phase_rad'] = round(rng.uniform(0, 2 * math.pi), 3)
    elif shape == 'servo_feedback': P['Fref_kip'] = 3.0
    elif shape == 'dahl_exponent': P['direction'] = rng.choice(['ductile', 'brittle'])
    elif shape == 'maxwell_slip': P['N'] = 12
    return P


CATEGORIES = {
    'backlash': [('deadzone_gap', 0.4), ('soft_takeup', 4.0), ('stretch_slack', 0.4)],
    'residual_static': [('maxwell_relax', 5.0), ('log_relax', 0.3), ('equalize_relax', 1.0)],
    'actuator_lag': [('act_firstorder', 0.8), ('act_deadtime', 0.6), ('act_secondorder', 1.5)],
    'asymmetry': [('bilinear_band', 4.0), ('band_fade', 4.0), ('band_runin', 0.85)],
    'velocity': [('ratestate_log', 0.6), ('frictional_lag', 0.6), ('shear_thinning', 0.95)],
    'pretension': [('power_clamp', 0.97), ('archard_wear', 6.0), ('thermal_tighten', 3.0)],
    'self_energizing': [('capstan_wrap', 0.8), ('drum_runout', 0.6), ('servo_feedback', 0.38)],
    'transition_shape': [('dahl_exponent', 4.0), ('maxwell_slip', 1.0), ('elastoplastic', 0.66)],
}


P_MEANING = {
    'deadzone_gap': 'half-width G of the clearance in the band path (in of drum travel)',
    'soft_takeup': 'sag force P (kip) of the Ernst tangent stiffness h = T^3/(T^3+P^3)',
    'stretch_slack': 'slack half-width per band force: G = p |F at last reversal| / Fref (in)',
    'maxwell_relax': 'relaxation rate of the held force at rest (1/s)',
    'log_relax': 'logarithmic relaxation coefficient: F = F_hold (1 - p ln(1 + t/t0))',
    'equalize_relax': 'fraction of the held force that relaxes toward F_res at rest',
    'act_firstorder': 'time constant of the clamping response (s)',
    'act_deadtime': 'dead time of the clamping response (s)',
    'act_secondorder': 'natural period of the clamping response (s)',
    'bilinear_band': 'stiffness ratio - 1 of the stiff band (other band softer by 1/(1+p))',
    'band_fade': 'fade coefficient: g_band / (1 + p theta)',
    'band_runin': 'run-in amplitude: g_band (1 + sign p (1 - exp(-s/s0)))',
    'ratestate_log': 'a-b of the steady rate-state law: g (1 + p ln(1 + |v|/v*))',
    'frictional_lag': 'time lag of the velocity seen by the friction law (s)',
    'shear_thinning': '1 - n of the power-law viscous term',
    'power_clamp': '1 - n of Fc = b (Fc_Eq4 / b)^n',
    'archard_wear': 'wear coefficient: g / (1 + p W / Wref)',
    'thermal_tighten': 'tightening coefficient: g (1 + p theta)',
    'capstan_wrap': 'mu * dtheta/dx of the wrap-angle change (1/in): g exp(p s x)',
    'drum_runout': 'runout modulation amplitude: g (1 + p sin(2 pi x / lambda + phi))',
    'servo_feedback': 'servo gain: g (1 + p |F_el| / Fref)',
    'dahl_exponent': 'exponent alpha = (1+p) (ductile) or 1/(1+p) (brittle)',
    'maxwell_slip': 'weight of the Maxwell-slip force: (1-p) F_LuGre + p F_MS',
    'elastoplastic': 'break-away deflection as a fraction of the steady deflection g/s0',
}


# ----------------------------------------------------------------- source pieces
def load_sources():
    S = []
    for name in SRC_FILES:
        d = json.load(open(os.path.join(SRC_DIR, name + '.json')))['data']
        x = [r[1] for r in d]; x1 = [r[4] for r in d]; x2 = [r[5] for r in d]
        n = len(x); v = velocity(x)
        d1 = [a - x1[0] for a in x1]; d2 = [a - x2[0] for a in x2]
        act = [abs(a) > 0.0015 or abs(b) > 0.0015 for a, b in zip(d1, d2)]
        # reversals
        rev = []; s = 0
        for i in range(int(0.3 * FS_HZ), int(13.6 * FS_HZ)):
            if v[i] > 0.1 and s <= 0:
                if s < 0:
                    rev.append(min(range(max(0, i - 150), i + 1), key=lambda j: x[j]))
                s = 1
            elif v[i] < -0.1 and s >= 0:
                if s > 0:
                    rev.append(max(range(max(0, i - 150), i + 1), key=lambda j: x[j]))
                s = -1
        first_act = act.index(True)
        last_act = n - 1 - act[::-1].index(True)
        strokes = []
        for a, b in zip(rev, rev[1:]):
            if abs(x[a]) < 0.9 or abs(x[b]) < 0.9:
                continue
            nact = sum(act[a:b])
            direction = 1 if x[b] > x[a] else -1
            if nact > 0.3 * (b - a):
                # actuator tail after the end reversal
                tail = b
                for j in range(b, min(n, b + int(0.3 * FS_HZ))):
                    if act[j]: tail = j
                tail = min(n - 1, tail + 8)
                assert not act[a], 'active stroke starts with actuators off rest'
                strokes.append(dict(a=a, b=b, tail=tail, dir=direction, active=True))
            elif not any(act[max(0, a - 20):b + 1]):
                strokes.append(dict(a=a, b=b, tail=b, dir=direction, active=False))
        # ramp-up block ends (reversal before the first actuator motion)
        ups = [r for r in rev if r < first_act - int(0.2 * FS_HZ) and r > int(1.0 * FS_HZ)]
        # ramp-down block starts: full-amplitude reversals after the last actuator motion
        downs = [r for r in rev if r > last_act + int(0.3 * FS_HZ) and abs(x[r]) > 0.9]
        lastrev = rev[-1]; dl = 1 if x[lastrev] < 0 else -1
        stop = None
        for j in range(lastrev + int(0.3 * FS_HZ), n):
            if v[j] * dl <= 0.0:
                stop = j; break
        if stop is None: stop = int(14.1 * FS_HZ)
        S.append(dict(name=name, x=x, d1=d1, d2=d2, v=v, rev=rev, strokes=strokes, ups=ups,
                      downs=downs, stop=stop))
    return S


def resample(arr, a, b, scale):
    """Samples of arr on [a, b) (source indices) time-stretched by `scale` (linear interp.)."""
    N = max(2, int(round((b - a) * scale)))
    out = []
    nmax = len(arr) - 1
    for j in range(N):
        t = a + j / scale
        i = int(t); f = t - i
        if i >= nmax: out.append(arr[nmax]); continue
        out.append(arr[i] + f * (arr[i + 1] - arr[i]))
    return out


class Builder:
    def __init__(self, rng, x1r, x2r):
        self.rng = rng; self.x = []; self.d1 = []; self.d2 = []; self.ov1 = {}; self.ov2 = {}
        self.x1r = x1r; self.x2r = x2r; self.log = []

    def piece(self, src, a, b, scale, mirror, tail=None, label=''):
        xs = resample(src['x'], a, b, scale)
        e = tail if tail is not None else b
        d1 = resample(src['d1'], a, e, scale); d2 = resample(src['d2'], a, e, scale)
        if mirror:
            xs = [-u for u in xs]; d1, d2 = d2, d1
        off = (self.x[-1] - xs[0]) if self.x else 0.0
        i0 = len(self.x)
        npx = len(xs)
        self.x.extend(u + off for u in xs)
        self.d1.extend(d1[:npx]); self.d2.extend(d2[:npx])
        if len(d1) < npx:       # (never: tail >= b)
            self.d1.extend([d1[-1]] * (npx - len(d1))); self.d2.extend([d2[-1]] * (npx - len(d2)))
        for j in range(npx, len(d1)):     # actuator tail overlaps the next segment
            self.ov1[i0 + j] = self.ov1.get(i0 + j, 0.0) + d1[j]
            self.ov2[i0 + j] = self.ov2.get(i0 + j, 0.0) + d2[j]
        self.log.append('%s:%s[%.3f-%.3f]x%.3f%s' % (label, src['name'], a / FS_HZ, b / FS_HZ, scale,
                                                      ' mirrored' if mirror else ''))

    def rest(self, dur, label='rest'):
        """Drum and actuators still (the actuators at their rest offset; a tail of the previous
        actuator motion, if any, is overlaid on the first ~0.3 s)."""
        N = int(round(dur * FS_HZ))
        xl = self.x[-1] if self.x else 0.0
        self.x.extend([xl] * N)
        self.d1.extend([0.0] * N)
        self.d2.extend([0.0] * N)
        self.log.append('%s %.3fs' % (label, dur))


def build_record(rng, S, early):
    """Return dict(x, x1, x2, log, meta) for one record."""
    allstrokes = [(si, st) for si, s in enumerate(S) for st in s['strokes']]
    act_st = [a for a in allstrokes if a[1]['active']]
    pas_st = [a for a in allstrokes if not a[1]['active']]
    for attempt in range(200):
        scale0 = rng.uniform(0.78, 1.3)
        T_target = rng.uniform(6.5, 24.5)
        x1r = qz(0.655 + rng.uniform(-0.01, 0.01), Q_A); x2r = qz(0.8559 + rng.uniform(-0.01, 0.01), Q_A)
        B = Builder(rng, x1r, x2r)
        p_act = rng.uniform(0.35, 0.8)
        rest_p = rng.uniform(0.05, 0.25)
        nd = None     # required direction of the next stroke (+1 forward, -1 backward)

        def sc():
            return scale0 * rng.uniform(0.93, 1.07)

        def add_stroke(active, need):
            si, st = rng.choice(act_st if active else pas_st)
            mirror = (st['dir'] != need)
            B.piece(S[si], st['a'], st['b'], sc(), mirror, tail=st['tail'], label='A' if active else 'P')
            return -need

        if early:
            B.rest(rng.uniform(0.05, 0.45), 'rest0')
            nd = rng.choice([1, -1])
            nd = add_stroke(True, nd)
            n_active = 1
        else:
            r0 = rng.uniform(0.05, 0.9)
            B.rest(r0, 'rest0')
            if rng.random() < 0.5:
                si = rng.randrange(len(S)); s = S[si]
                end = rng.choice(s['ups'])
                mirror = rng.random() < 0.5
                B.piece(s, 0, end, sc(), mirror, label='RU')
                xe = -s['x'][end] if mirror else s['x'][end]
                nd = -1 if xe > 0 else 1
            else:
                nd = rng.choice([1, -1])
            need_passive_t = r0 + scale0 * rng.uniform(5.2, 7.0)     # >= ~2.5 drum cycles
            while len(B.x) / FS_HZ < need_passive_t:
                nd = add_stroke(False, nd)
            n_active = 0
        # middle strokes
        final_rest = rng.uniform(1.7, 3.2)
        use_down = rng.random() < 0.5
        est_end = (3.2 * scale0 if use_down else 0.0) + final_rest + 0.45
        while True:
            tnow = len(B.x) / FS_HZ
            if tnow + 1.05 * scale0 + est_end > T_target and n_active >= 2:
                break
            if tnow > 24.0:
                break
            if rng.random() < rest_p:
                B.rest(rng.uniform(0.3, 2.0), 'rest')
            act = rng.random() < p_act or (n_active < 2 and tnow + 2.2 * scale0 + est_end > T_target)
            nd = add_stroke(act, nd)
            n_active += int(act)
        if use_down:
            si = rng.randrange(len(S)); s = S[si]
            r = rng.choice(s['downs'])
            # direction of the first stroke of the block
            d0 = 1 if s['x'][r] < 0 else -1
            mirror = (d0 != nd)
            B.piece(s, r, s['stop'], sc(), mirror, label='RD')
        B.rest(final_rest + 0.45, 'final_rest')
        T = len(B.x) / FS_HZ
        if not (6.5 <= T <= 25.0):
            continue
        n = len(B.x)
        d1 = B.d1[:n]; d2 = B.d2[:n]
        for j, u in B.ov1.items():
            if j < n: d1[j] += u
        for j, u in B.ov2.items():
            if j < n: d2[j] += u
        # recentre the drum travel and quantise
        xc = 0.5 * (max(B.x) + min(B.x))
        x = [qz(u - xc, Q_X) for u in B.x]
        x1 = [qz(x1r + u, Q_A) for u in d1]
        x2 = [qz(x2r + u, Q_A) for u in d2]
        x1[0] = x1r; x2[0] = x2r
        # length of the final still stretch (drum and both actuators constant)
        j = n - 1
        while j > 0 and x[j - 1] == x[-1] and x1[j - 1] == x1[-1] and x2[j - 1] == x2[-1]:
            j -= 1
        still = (n - j) / FS_HZ
        if still < 1.55:
            continue
        # first actuator motion (> 0.002 in from the t = 0 position)
        fa = None
        for j in range(n):
            if abs(x1[j] - x1[0]) > 0.002 or abs(x2[j] - x2[0]) > 0.002:
                fa = j / FS_HZ; break
        if fa is None:
            continue
        if early and fa >= 1.0:
            continue
        if (not early) and fa < 4.2:
            continue
        meta = dict(duration_s=round(T, 4), scale=round(scale0, 4), first_actuator_motion_s=round(fa, 4),
                    n_active_strokes=n_active, final_still_s=round(still, 3), early_actuation=early)
        return dict(x=x, x1=x1, x2=x2, log=B.log, meta=meta)
    raise RuntimeError('could not build a record')


# --------------------------------------------------------------------------- trials
def ratio_of(recs, shape, p, P, sd):
    num = 0.0; cnt = 0
    for R in recs:
        F = simulate(R, shape, p, P)
        for a, b in zip(F, R.base):
            num += (a - b) ** 2
        cnt += R.n
    return math.sqrt(num / cnt) / sd


def solve_p(recs, shape, pmax, P, sd, target):
    """Smallest-bracket root of ratio(p) = target on (0, pmax] (first crossing, Illinois)."""
    # geometric scan up from pmax/256 to bracket the first crossing
    p_lo, r_lo = 0.0, 0.0
    p = pmax / 256.0
    evals = 0
    while True:
        r = ratio_of(recs, shape, p, P, sd); evals += 1
        if r >= target:
            p_hi, r_hi = p, r; break
        p_lo, r_lo = p, r
        if p >= pmax:
            return None, r, evals
        p = min(pmax, p * 2.0)
    # Illinois regula falsi
    side = 0
    for _ in range(40):
        pm = p_hi - (r_hi - target) * (p_hi - p_lo) / (r_hi - r_lo)
        if not (p_lo < pm < p_hi):
            pm = 0.5 * (p_lo + p_hi)
        rm = ratio_of(recs, shape, pm, P, sd); evals += 1
        if abs(rm - target) <= 0.002 * target:
            return pm, rm, evals
        if rm < target:
            p_lo, r_lo = pm, rm
            if side == -1: r_hi = target + (r_hi - target) / 2.0
            side = -1
        else:
            p_hi, r_hi = pm, rm
            if side == 1: r_lo = target - (target - r_lo) / 2.0
            side = 1
    return pm, rm, evals


def f32(v):
    return struct.unpack('f', struct.pack('f', v))[0]


def write_record(path, rec, Ftrue, sd, rng):
    n = len(Ftrue)
    v = velocity(rec['x'])
    base1 = rng.uniform(22.0, 45.0); base2 = rng.uniform(22.0, 45.0)
    rows = []
    Fout = []
    for i in range(n):
        Fi = Ftrue[i] + (rng.gauss(0.0, sd) if i > 0 else 0.0)
        Fq = qz(Fi, Q_F)
        Fout.append(Fq)
        Ft = Ftrue[i]
        if Ft >= 0:
            fa2 = base2 + 1000.0 * Ft / C[1]; fa1 = base1 + 1000.0 * Ft / C[0]
        else:
            fa1 = base1 - 1000.0 * Ft / C[2]; fa2 = base2 - 1000.0 * Ft / C[3]
        fa1 = qz(fa1 + rng.gauss(0.0, 4.0), Q_FA1); fa2 = qz(fa2 + rng.gauss(0.0, 4.0), Q_FA2)
        rows.append([i * DT, float('%.9g' % rec['x'][i]), float('%.9g' % Fq), float('%.9g' % (v[i] / VEL_QUIRK)),
                     float('%.9g' % rec['x1'][i]), float('%.9g' % rec['x2'][i]),
                     float('%.9g' % fa1), float('%.9g' % fa2)])
    doc = {'data': rows, 'dt': DT, 'sampling freq': FS_HZ, 'displacement units': 'in', 'time units': 's',
           'friction force units': 'kip', 'actuator force units': 'lb'}
    s = json.dumps(doc)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, 'w') as f:
        f.write(s)
    return hashlib.sha256(s.encode()).hexdigest()


def make_records(rng, S, early_flags):
    recs = []; infos = []
    for early in early_flags:
        r = build_record(rng, S, early)
        F0 = qz(rng.uniform(-1.5, 3.0), Q_F)
        r['F0'] = F0
        r['R'] = Rec(r['x'], r['x1'], r['x2'], F0)
        recs.append(r)
    return recs


def run_trial(args):
    spec, outdir = args
    S = load_sources_cached()
    rng = random.Random(spec['seed'])
    sd = round(rng.uniform(0.02, 0.06), 4)
    shape = spec['shape']
    P = draw_fixed(shape, rng) if shape != 'none' else {}
    tries = 0
    while True:
        tries += 1
        recs = make_records(rng, S, spec['early'])
        if shape == 'none':
            p, ratio, evals = 0.0, 0.0, 0
            break
        pmax = dict(CATEGORIES[spec['category']])[shape]
        p, ratio, evals = solve_p([r['R'] for r in recs], shape, pmax, P, sd, spec['target_ratio'])
        if p is not None:
            break
        if tries > 12:
            raise RuntimeError('target not reachable for %s %s' % (spec['tid'], shape))
    entry = dict(category=spec['category'], shape=shape, strength=spec['strength'],
                 p=(p if p else 0.0), noise_kip=sd, ratio=round(ratio, 4),
                 target_ratio=(round(spec['target_ratio'], 4) if spec['target_ratio'] else 0.0),
                 params=P, p_meaning=P_MEANING.get(shape, 'none'), record_attempts=tries, root_evals=evals, records={})
    for lab, r in zip('AB', recs):
        R = r['R']
        F = simulate(R, shape if shape != 'none' else 'base', p, P)
        path = os.path.join(outdir, 'cases', spec['tid'], lab + '.json')
        h = write_record(path, r, F, sd, rng)
        ratio_rec = math.sqrt(sum((a - b) ** 2 for a, b in zip(F, R.base)) / R.n) / sd
        m = dict(r['meta']); m.update(initial_band_force_kip=round(r['F0'], 6), sha256=h,
                                      ratio_this_record=round(ratio_rec, 4), pieces=r['log'],
                                      x1_initial_in=r['x1'][0], x2_initial_in=r['x2'][0])
        entry['records'][lab] = m
    return spec['tid'], entry


_SRC = None


def load_sources_cached():
    global _SRC
    if _SRC is None:
        _SRC = load_sources()
    return _SRC


def plan():
    """Trial specifications (deterministic from the master seed)."""
    rng = random.Random(MASTER_SEED)
    cats = list(CATEGORIES)
    two_weak = set(rng.sample(cats, 4))
    specs = []
    for c in cats:
        shapes = [s for s, _ in CATEGORIES[c]]
        nweak = 2 if c in two_weak else 1
        st = ['weak'] * nweak + ['strong'] * (3 - nweak)
        rng.shuffle(st)
        for s, strength in zip(shapes, st):
            tr = rng.uniform(2.7, 3.8) if strength == 'weak' else rng.uniform(8.5, 11.5)
            specs.append(dict(category=c, shape=s, strength=strength, target_ratio=tr))
    for _ in range(6):
        specs.append(dict(category='none', shape='none', strength='none', target_ratio=None))
    # early actuation: exactly 20 of the 60 records
    flags = [True] * 20 + [False] * 40
    rng.shuffle(flags)
    rng.shuffle(specs)
    for k, s in enumerate(specs):
        s['tid'] = 't%02d' % (k + 1)
        s['early'] = flags[2 * k:2 * k + 2]
        s['seed'] = rng.randrange(1 << 30)
    return specs


def main():
    outdir = '/work/blind19'; jobs = 2
    a = sys.argv[1:]
    if '--out' in a: outdir = a[a.index('--out') + 1]
    if '--jobs' in a: jobs = int(a[a.index('--jobs') + 1])
    only = a[a.index('--only') + 1].split(',') if '--only' in a else None
    specs = plan()
    if only:
        specs = [s for s in specs if s['tid'] in only]
    work = [(s, outdir) for s in specs]
    if jobs > 1:
        import multiprocessing as mp
        with mp.Pool(jobs) as pool:
            res = pool.map(run_trial, work, chunksize=1)
    else:
        res = [run_trial(w) for w in work]
    key = {}
    for tid, e in sorted(res):
        key[tid] = e
        print(tid, e['category'], e['shape'], e['strength'], 'p=%.5g' % e['p'], 'ratio=%.3f' % e['ratio'],
              'sd=%.4f' % e['noise_kip'], 'tries=%d evals=%d' % (e['record_attempts'], e['root_evals']), flush=True)
    if not only:
        with open(os.path.join(outdir, 'key.json'), 'w') as f:
            json.dump(key, f, indent=1, sort_keys=True)


if __name__ == '__main__':
    main()
