#!/usr/bin/env python3
"""Blind test set 26 for the BRFD model-discrepancy tool.

Deterministic from MASTER_SEED: regenerates cases/t01..t30 (A.json, B.json) and key.json.
Python 3 standard library only.  Usage:  python3 gen/gen.py   (from /work/blind26 or anywhere)

Layout of the work:
  * base model  : exact re-implementation of the black box `damper predict --no-fit` (see NOTES.md)
  * records     : built from pieces of the measured semi-active tests (strokes, rests, actuator motions)
  * shapes      : 24 effect models (8 categories x 3) written as modifications of the base model
  * amplitudes  : solved so that RMS(F_true - F_base)/noise_kip over both records hits a drawn target
"""
import json, math, os, random, struct, sys, time

HERE = os.path.dirname(os.path.abspath(__file__))
OUTDIR = os.path.dirname(HERE)                      # /work/blind26
MASTER_SEED = 26026
CONFIG = '/work/runs/brfd-semiactive.yaml'
DATADIR = '/work/shared/data/brfd/semiactive'
MEASURED = ['harmonic0.03ea1forward.json', 'harmonic0.03ea1backward.json',
            'harmonic0.03ea2forward.json', 'harmonic0.03ea2backward.json',
            'harmonic0.015forward.json', 'harmonic0.015backward.json']
DT = 0.0009765625
FS = 1024
HEADER = [('dt', 0.0009765625), ('sampling freq', 1024), ('displacement units', 'in'),
          ('time units', 's'), ('friction force units', 'kip'), ('actuator force units', 'lb')]

# Quantisation grids of the measured files (value = q * (k + frac)), estimated from the six tests.
Q_FORCE, OFF_FORCE = 0.0008005, 0.4115          # kip
Q_DISP, OFF_DISP = 5.88e-5, 0.63                # in
Q_ACT = 10.0 / 2 ** 22                          # in (actuator positions, stored as float32)
Q_F1, OFF_F1 = 0.31794, 0.0521                  # lb, actuator 1 load cell
Q_F2, OFF_F2 = 0.39982, 0.58                    # lb, actuator 2 load cell
VEL_COLUMN_FACTOR = 125.4                       # measured velocity column = d(disp)/dt / ~125.4


def f32(v):
    return struct.unpack('f', struct.pack('f', v))[0]


def quant(v, q, off):
    return q * (round(v / q - off) + off)


# ----------------------------------------------------------------------------------------------
# Base model (inferred from the black box, verified to 5e-8 kip on the measured tests)
# ----------------------------------------------------------------------------------------------
def load_config(path=CONFIG):
    p = {}
    for line in open(path):
        line = line.split('#', 1)[0].strip()
        if ':' not in line:
            continue
        k, v = [s.strip() for s in line.split(':', 1)]
        if not v:
            continue
        if v.startswith('['):
            p[k] = [float(s) for s in v.strip('[]').split(',')]
        else:
            try:
                p[k] = float(v)
            except ValueError:
                p[k] = v
    return p


CFG = load_config()
S0 = CFG['sigma0_kip_per_in']; S1 = CFG['sigma1_kip_s_per_in']; S2 = CFG['sigma2_kip_s_per_in']
FSF = CFG['fs_fwd_kip']; FSB = CFG['fs_bwd_kip']; FCF = CFG['fc_fwd_kip']; FCB = CFG['fc_bwd_kip']
VS = CFG['vs_in_per_s']; FLOOR = CFG['fc_floor_kip']
_M = CFG['slopes_kip_per_in']; _C = CFG['scaling']
# Eq. (4) coefficients (kip/in): forward uses rows 1,2 (C1, C2); backward rows 3,4 (C3, C4)
KF1 = _C[0] * _M[0] + _C[1] * _M[2]; KF2 = _C[0] * _M[1] + _C[1] * _M[3]
KB1 = _C[2] * _M[4] + _C[3] * _M[6]; KB2 = _C[2] * _M[5] + _C[3] * _M[7]
assert S1 == 0.0


def velocity(x):
    """Black-box drum velocity: central differences (one-sided at the ends) and a centred 15-sample
    moving average whose half-width shrinks to fit at the record ends (zero phase)."""
    n = len(x)
    d = [0.0] * n
    for i in range(1, n - 1):
        d[i] = (x[i + 1] - x[i - 1]) / (2 * DT)
    d[0] = (x[1] - x[0]) / DT
    d[-1] = (x[-1] - x[-2]) / DT
    c = [0.0]
    for a in d:
        c.append(c[-1] + a)
    out = [0.0] * n
    for i in range(n):
        h = min(7, i, n - 1 - i)
        out[i] = (c[i + h + 1] - c[i - h]) / (2 * h + 1)
    return out


def lin_increment(e1, e2, v, x1p, x2p):
    """Eq. (4) increment u (kip) of kinetic friction from actuator travel, per direction."""
    if v >= 0:
        return KF1 * (e1 - x1p) + KF2 * (e2 - x2p)
    return KB1 * (e1 - x1p) + KB2 * (e2 - x2p)


# ----------------------------------------------------------------------------------------------
# Shapes: (category, shape id, amplitude range, short description)
# ----------------------------------------------------------------------------------------------
SHAPES = {
    'backlash': ['deadzone_gap', 'load_scaled_slack', 'onesided_gap_hertz'],
    'residual_static': ['zener_settle', 'log_aging_relax', 'thermal_contraction_hold'],
    'transition_shape': ['elastoplastic_blend', 'maxwell_slip_spread', 'dahl_exponent'],
    'velocity': ['ratestate_log', 'bo_pavelescu_exponent', 'frictional_memory'],
    'actuator_lag': ['second_order_band', 'transport_delay', 'zener_creep'],
    'self_energizing': ['wrap_angle_capstan', 'progressive_wrap', 'sprag_slip_servo'],
    'pretension': ['exponential_clamp', 'liftoff_kink', 'actuator_coupling'],
    'asymmetry': ['band_stiffness_dir', 'stribeck_velocity_dir', 'one_band_fade'],
}
AMAX = {  # largest amplitude considered physically plausible (solver bracket)
    'deadzone_gap': 0.35, 'load_scaled_slack': 0.40, 'onesided_gap_hertz': 0.45,
    'zener_settle': 1.0, 'log_aging_relax': 0.30, 'thermal_contraction_hold': 1.0,
    'elastoplastic_blend': 1.0, 'maxwell_slip_spread': 3.0, 'dahl_exponent': 4.0,
    'ratestate_log': 0.5, 'bo_pavelescu_exponent': 3.0, 'frictional_memory': 0.25,
    'second_order_band': 0.25, 'transport_delay': 0.35, 'zener_creep': 1.5,
    'wrap_angle_capstan': 1.0, 'progressive_wrap': 1.2, 'sprag_slip_servo': 1.0,
    'exponential_clamp': 12.0, 'liftoff_kink': 1.0, 'actuator_coupling': 10.0,
    'band_stiffness_dir': 1.6, 'stribeck_velocity_dir': 1.6, 'one_band_fade': 0.2,
}
# strength plan: 12 strong (S) / 12 weak (W).  Shapes whose signature is confined to short
# regimes (actuator motion windows, lift-off kink, one-sided gap) are planned weak.
STRENGTH = {
    'deadzone_gap': 'S', 'load_scaled_slack': 'S', 'onesided_gap_hertz': 'S',
    'zener_settle': 'S', 'log_aging_relax': 'S', 'thermal_contraction_hold': 'W',
    'elastoplastic_blend': 'W', 'maxwell_slip_spread': 'S', 'dahl_exponent': 'S',
    'ratestate_log': 'S', 'bo_pavelescu_exponent': 'W', 'frictional_memory': 'W',
    'second_order_band': 'W', 'transport_delay': 'W', 'zener_creep': 'W',
    'wrap_angle_capstan': 'S', 'progressive_wrap': 'W', 'sprag_slip_servo': 'S',
    'exponential_clamp': 'S', 'liftoff_kink': 'W', 'actuator_coupling': 'W',
    'band_stiffness_dir': 'S', 'stribeck_velocity_dir': 'W', 'one_band_fade': 'W',
}
NEEDS_MOTION = {'actuator_lag', 'pretension'}


def draw_shape_params(shape, rng):
    """Secondary (fixed) parameters of a shape; the amplitude A is solved later."""
    P = {}
    if shape == 'deadzone_gap':
        P['arm_kip'] = 0.3
    elif shape == 'load_scaled_slack':
        P['f_ref_kip'] = 3.0; P['arm_kip'] = 0.3
    elif shape == 'onesided_gap_hertz':
        P['hertz_len_per_A'] = rng.uniform(0.5, 1.0); P['arm_kip'] = 0.3
        P['gap_side'] = rng.choice(['fwd_to_bwd', 'bwd_to_fwd'])
    elif shape == 'zener_settle':
        P['tau_s'] = rng.uniform(0.25, 0.9); P['f_eq_kip'] = rng.uniform(-0.6, 0.8)
    elif shape == 'log_aging_relax':
        P['t_c_s'] = rng.uniform(0.03, 0.15)
    elif shape == 'thermal_contraction_hold':
        P['tau_th_s'] = rng.uniform(3.0, 9.0)
    elif shape == 'elastoplastic_blend':
        P['z_ba_frac'] = rng.uniform(0.4, 0.75)
    elif shape == 'maxwell_slip_spread':
        P['weights'] = [0.3, 0.4, 0.3]; P['spread'] = [-1.0, rng.uniform(-0.3, 0.3), 1.0]
    elif shape == 'dahl_exponent':
        P['sense'] = rng.choice([1, -1])   # +1: n = 1 + A (rounder); -1: n = 1/(1 + A) (sharper)
    elif shape == 'ratestate_log':
        P['v0_in_s'] = rng.uniform(0.03, 0.15)
    elif shape == 'bo_pavelescu_exponent':
        P['sense'] = 1   # delta = 2/(1+A): Bo & Pavelescu report delta in 0.5..1
    elif shape == 'frictional_memory':
        pass
    elif shape == 'second_order_band':
        P['zeta'] = rng.uniform(0.15, 0.45)
    elif shape == 'transport_delay':
        pass
    elif shape == 'zener_creep':
        P['beta'] = rng.uniform(0.8, 0.95)
        P['tau_per_A_s'] = 1.0
    elif shape == 'wrap_angle_capstan':
        P['x_neutral_in'] = rng.uniform(-0.2, 0.2)
    elif shape == 'progressive_wrap':
        P['lambda_in'] = rng.uniform(0.25, 0.7); P['bwd_ratio'] = rng.uniform(0.2, 0.6)
    elif shape == 'sprag_slip_servo':
        P['g_ref_kip'] = 8.0; P['lead'] = rng.choice(['fwd', 'bwd'])
    elif shape == 'exponential_clamp':
        pass
    elif shape == 'liftoff_kink':
        P['u_kink_kip'] = rng.uniform(0.0, 0.1)
    elif shape == 'actuator_coupling':
        P['sign'] = rng.choice([1, -1])
    elif shape == 'band_stiffness_dir':
        P['sign'] = rng.choice([1, -1]); P['band'] = rng.choice(['bwd', 'fwd'])
    elif shape == 'stribeck_velocity_dir':
        P['sign'] = rng.choice([1, -1]); P['band'] = rng.choice(['bwd', 'fwd'])
    elif shape == 'one_band_fade':
        P['tau_th_s'] = rng.uniform(4.0, 12.0); P['band'] = rng.choice(['bwd', 'fwd'])
    return P


# ----------------------------------------------------------------------------------------------
# Simulator: base model plus an optional shape of amplitude A
# ----------------------------------------------------------------------------------------------
def _lowpass2(x, tau, zeta):
    """x_e'' = w^2 (x - x_e) - 2 zeta w x_e', w = 1/tau; semi-implicit Euler, 8 substeps."""
    if tau <= 0:
        return list(x)
    w = 1.0 / tau; out = []; e = x[0]; de = 0.0; h = DT / 8
    for xi in x:
        for _ in range(8):
            de += h * (w * w * (xi - e) - 2 * zeta * w * de)
            e += h * de
        out.append(e)
    return out


def _lowpass1(x, tau):
    if tau <= 0:
        return list(x)
    a = math.exp(-DT / tau); e = x[0]; out = []
    for xi in x:
        e = xi + (e - xi) * a
        out.append(e)
    return out


def _delay(x, tau):
    k = tau / DT; k0 = int(k); fr = k - k0; out = []
    for i in range(len(x)):
        i0 = max(0, i - k0); i1 = max(0, i - k0 - 1)
        out.append((1 - fr) * x[i0] + fr * x[i1])
    return out


def simulate(rec, shape=None, A=0.0, P=None, v=None):
    """Force (kip) of the base model (shape None or A == 0) or of base + shape.
    rec: dict with 'x', 'a1', 'a2' lists and 'F0' (first force sample, kip)."""
    P = P or {}
    x = rec['x']; a1 = rec['a1']; a2 = rec['a2']
    n = len(x)
    if v is None:
        v = velocity(x)
    x1p = a1[0]; x2p = a2[0]
    if shape is None or A == 0.0:
        shape = None
    # --- effective actuator positions (actuator_lag) ---
    e1, e2 = a1, a2
    if shape == 'second_order_band':
        e1 = _lowpass2(a1, A, P['zeta']); e2 = _lowpass2(a2, A, P['zeta'])
    elif shape == 'transport_delay':
        e1 = _delay(a1, A); e2 = _delay(a2, A)
    elif shape == 'zener_creep':
        b = P['beta']; tau = A * P['tau_per_A_s']
        l1 = _lowpass1(a1, tau); l2 = _lowpass1(a2, tau)
        e1 = [(1 - b) * p + b * q for p, q in zip(a1, l1)]
        e2 = [(1 - b) * p + b * q for p, q in zip(a2, l2)]
    # --- kinetic friction Fc (Eq. 4 or modified clamping law) and g(v) ---
    vl = None
    if shape == 'frictional_memory':
        vl = _lowpass1(v, A)
    pos_x = x
    travel = None
    if shape == 'progressive_wrap':
        travel = [0.0] * n; s = 0.0; sg = 1
        for i in range(1, n):
            vi = v[i]
            if abs(vi) > 0.02:
                sgi = 1 if vi > 0 else -1
                if sgi != sg:
                    s = 0.0; sg = sgi
                s += abs(vi) * DT
            travel[i] = s
    g = [0.0] * n
    for i in range(n):
        vi = v[i]
        fwd = vi >= 0
        b = FCF if fwd else FCB
        u = lin_increment(e1[i], e2[i], vi, x1p, x2p)
        if shape == 'exponential_clamp':
            fc = b + u + A * (b * math.exp(max(min(u / b, 3.0), -3.0)) - b - u)
        elif shape == 'liftoff_kink':
            uk = P['u_kink_kip']
            fc = b + u if u >= -uk else b - uk + (1 - A) * (u + uk)
        elif shape == 'actuator_coupling':
            if fwd:
                u1 = KF1 * (e1[i] - x1p); u2 = KF2 * (e2[i] - x2p)
            else:
                u1 = KB1 * (e1[i] - x1p); u2 = KB2 * (e2[i] - x2p)
            fc = b + u + P['sign'] * A * u1 * u2 / b
        else:
            fc = b + u
        if fc < FLOOR:
            fc = FLOOR
        fs = FSF if fwd else FSB
        vs = VS
        if shape == 'stribeck_velocity_dir' and ((P['band'] == 'bwd') != fwd):
            vs = VS * math.exp(P['sign'] * A)
        vv = vi if vl is None else vl[i]
        r = abs(vv) / vs
        if shape == 'bo_pavelescu_exponent':
            delta = 2.0 / (1 + A) if P['sense'] > 0 else 2.0 * (1 + A)
            gi = fc + (fs - fc) * math.exp(-r ** delta)
        else:
            gi = fc + (fs - fc) * math.exp(-r * r)
        if shape == 'ratestate_log':
            gi *= 1 + A * math.asinh(abs(vi) / (2 * P['v0_in_s']))
        elif shape == 'wrap_angle_capstan':
            gi *= math.exp(A * (1 if fwd else -1) * (pos_x[i] - P['x_neutral_in']))
        elif shape == 'progressive_wrap':
            k = A if fwd else A * P['bwd_ratio']
            gi *= 1 + k * (1 - math.exp(-travel[i] / P['lambda_in']))
        elif shape == 'sprag_slip_servo':
            lead = fwd if P['lead'] == 'fwd' else (not fwd)
            den = 1 - (1 if lead else -1) * A * gi / P['g_ref_kip']
            gi /= max(den, 0.25)
        if gi < FLOOR:
            gi = FLOOR
        g[i] = gi
    # --- integration of the elastic force y = sigma0 * z ---
    F = [0.0] * n
    y = rec['F0']                      # black box: z0 = F(0)/sigma0 (v(0) = 0 in these records)
    h = DT
    # shape state
    if shape in ('deadzone_gap', 'load_scaled_slack', 'onesided_gap_hertz'):
        gap = 0.0; armed = abs(y) > P['arm_kip']; ypk = abs(y); since = 1e9
    if shape in ('zener_settle', 'log_aging_relax', 'thermal_contraction_hold'):
        slow = 0; resting = False; slid = False; yh = 0.0; tr = 0.0; T = 0.0; Tstop = 0.0; add = 0.0
    if shape == 'maxwell_slip_spread':
        W = P['weights']; K = [w * S0 * math.exp(A * c) for w, c in zip(W, P['spread'])]
        ys = [w * y for w in W]
    if shape == 'one_band_fade':
        T = 0.0
    if shape == 'elastoplastic_blend':
        zb = P['z_ba_frac']
    if shape == 'dahl_exponent':
        nexp = 1 + A if P['sense'] > 0 else 1.0 / (1 + A)
    for i in range(n):
        F[i] = y + S2 * v[i]
        if i == n - 1:
            break
        vi = v[i + 1]; gi = g[i + 1]; av = abs(vi)
        if shape is None or shape in ('second_order_band', 'transport_delay', 'zener_creep',
                                      'exponential_clamp', 'liftoff_kink', 'actuator_coupling',
                                      'ratestate_log', 'bo_pavelescu_exponent', 'frictional_memory',
                                      'wrap_angle_capstan', 'progressive_wrap', 'sprag_slip_servo',
                                      'stribeck_velocity_dir'):
            a = S0 * vi; bb = S0 * av / gi
            k1 = a - bb * y; k2 = a - bb * (y + h / 2 * k1); k3 = a - bb * (y + h / 2 * k2)
            k4 = a - bb * (y + h * k3)
            y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        elif shape in ('deadzone_gap', 'load_scaled_slack', 'onesided_gap_hertz'):
            if gap > 0:
                gap -= av * h
                if gap > 0:
                    continue
                since = 0.0
                y = 0.0
                continue
            s0 = S0
            if shape == 'onesided_gap_hertz' and since < 1e8:
                dh = A * P['hertz_len_per_A']
                if since < dh:
                    s0 = S0 * math.sqrt(max(since, 0.02 * dh) / dh)
            a = s0 * vi; bb = s0 * av / gi
            k1 = a - bb * y; k2 = a - bb * (y + h / 2 * k1); k3 = a - bb * (y + h / 2 * k2)
            k4 = a - bb * (y + h * k3)
            yn = y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
            since += av * h
            if abs(yn) > ypk:
                ypk = abs(yn)
            if abs(yn) > P['arm_kip']:
                armed = True
            if armed and av > 0.02 and (yn == 0 or (yn > 0) != (y > 0)):
                trig = True
                if shape == 'onesided_gap_hertz':
                    trig = (y > 0) if P['gap_side'] == 'fwd_to_bwd' else (y < 0)
                if trig:
                    if shape == 'load_scaled_slack':
                        G = 2 * A * ypk / P['f_ref_kip']
                    else:
                        G = 2 * A
                    armed = False; ypk = 0.0
                    # lost motion: the part of this step beyond the zero crossing goes into the gap
                    frac = abs(yn) / max(abs(yn - y), 1e-12)
                    gap = G - frac * av * h
                    y = 0.0
                    if gap <= 0:
                        gap = 0.0; since = 0.0
                    continue
                armed = False; ypk = 0.0
            y = yn
        elif shape in ('zener_settle', 'log_aging_relax', 'thermal_contraction_hold'):
            a = S0 * vi; bb = S0 * av / gi
            k1 = a - bb * y; k2 = a - bb * (y + h / 2 * k1); k3 = a - bb * (y + h / 2 * k2)
            k4 = a - bb * (y + h * k3)
            y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
            Told = T
            if shape == 'thermal_contraction_hold':
                # band heated by the frictional work, Newton cooling; T in kip*in of stored heat
                T += h * (abs(F[i] * vi) - T / P['tau_th_s'])
            if av > 0.3:
                slid = True
            if not resting:
                slow = slow + 1 if av < 0.02 else 0
                if slow >= 40 and slid:          # 40 ms below 0.02 in/s after sliding: rest
                    resting = True; slid = False; yh = y; tr = 0.0
            else:
                if av > 0.05:
                    resting = False; slow = 0
                else:
                    t0 = tr; tr += h
                    if shape == 'zener_settle':
                        tau = P['tau_s']
                        y += A * (P['f_eq_kip'] - yh) * (math.exp(-t0 / tau) - math.exp(-tr / tau))
                    elif shape == 'log_aging_relax':
                        tc = P['t_c_s']
                        y -= A * yh * (math.log(1 + tr / tc) - math.log(1 + t0 / tc))
                    else:
                        # cooling band contracts: held tension (force magnitude) grows
                        y += A * (1 if yh >= 0 else -1) * (Told - T)
        elif shape == 'maxwell_slip_spread':
            tot = 0.0
            for k in range(3):
                a = K[k] * vi; bb = K[k] * av / (W[k] * gi); yk = ys[k]
                k1 = a - bb * yk; k2 = a - bb * (yk + h / 2 * k1); k3 = a - bb * (yk + h / 2 * k2)
                k4 = a - bb * (yk + h * k3)
                yk += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
                ys[k] = yk; tot += yk
            y = tot
        elif shape == 'elastoplastic_blend':
            def rhs(yy):
                zs = gi
                if vi == 0:
                    return 0.0
                if (yy > 0) != (vi > 0) or yy == 0:
                    al = 0.0
                else:
                    r = abs(yy) / zs
                    if r <= zb:
                        al = 0.0
                    elif r >= 1:
                        al = 1.0
                    else:
                        al = 0.5 * math.sin(math.pi * (r - (1 + zb) / 2) / (1 - zb)) + 0.5
                return S0 * vi - S0 * av * yy / gi * ((1 - A) + A * al)
            k1 = rhs(y); k2 = rhs(y + h / 2 * k1); k3 = rhs(y + h / 2 * k2); k4 = rhs(y + h * k3)
            y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        elif shape == 'dahl_exponent':
            sg = 1.0 if vi >= 0 else -1.0
            def rhs(yy):
                q = 1 - sg * yy / gi
                return S0 * vi * (abs(q) ** nexp) * (1 if q >= 0 else -1)
            k1 = rhs(y); k2 = rhs(y + h / 2 * k1); k3 = rhs(y + h / 2 * k2); k4 = rhs(y + h * k3)
            y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        elif shape == 'band_stiffness_dir':
            fwd = vi >= 0
            s0 = S0 * math.exp(P['sign'] * A) if ((P['band'] == 'fwd') == fwd) else S0
            a = s0 * vi; bb = s0 * av / gi
            k1 = a - bb * y; k2 = a - bb * (y + h / 2 * k1); k3 = a - bb * (y + h / 2 * k2)
            k4 = a - bb * (y + h * k3)
            y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        elif shape == 'one_band_fade':
            fwd = vi >= 0
            mine = (P['band'] == 'fwd') == fwd
            if mine:
                T += h * abs(F[i] * vi)
            T -= h * T / P['tau_th_s']
            if mine:
                gi = max(gi / (1 + A * T), FLOOR)
            a = S0 * vi; bb = S0 * av / gi
            k1 = a - bb * y; k2 = a - bb * (y + h / 2 * k1); k3 = a - bb * (y + h / 2 * k2)
            k4 = a - bb * (y + h * k3)
            y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        else:
            raise ValueError(shape)
    return F


# ----------------------------------------------------------------------------------------------
# Pieces of the measured semi-active tests
# ----------------------------------------------------------------------------------------------
class Pool:
    def __init__(self):
        self.strokes = []     # (file, i0, i1, span_in, has_motion)
        self.motions = []     # dict(file, actuators, d1, d2, start_row)
        self.rests = []       # detrended displacement noise at rest (list of floats)
        self.quiet1 = []; self.quiet2 = []   # actuator deviations while the actuators hold
        self.xprime = []      # (x'_1, x'_2) of each test
        for fn in MEASURED:
            d = json.load(open(os.path.join(DATADIR, fn)))['data']
            x = [r[1] for r in d]; a1 = [r[4] for r in d]; a2 = [r[5] for r in d]
            n = len(x)
            self.xprime.append((a1[0], a2[0]))
            r1 = sorted(a1[:3000])[1500]; r2 = sorted(a2[:3000])[1500]
            mv = [i for i in range(n) if abs(a1[i] - r1) > 0.001 or abs(a2[i] - r2) > 0.001]
            segs = []
            if mv:
                s = p = mv[0]
                for i in mv[1:]:
                    if i - p > 100:
                        segs.append((s, p)); s = i
                    p = i
                segs.append((s, p))
            segs = [(max(0, s - 26), min(n - 1, e + 26)) for s, e in segs if e - s > 200]
            acts = 'both' if '0.015' in fn else ('one' if 'ea1' in fn else 'two')
            for s, e in segs:
                self.motions.append(dict(file=fn, actuators=acts, start_row=s, end_row=e,
                                         d1=[a1[i] - a1[s] for i in range(s, e + 1)],
                                         d2=[a2[i] - a2[s] for i in range(s, e + 1)]))
            # quiet actuator windows: before the first motion (minus 0.2 s)
            q_end = (segs[0][0] - 200) if segs else 3000
            q1 = [a1[i] - r1 for i in range(0, q_end)]; q2 = [a2[i] - r2 for i in range(0, q_end)]
            self.quiet1.append(q1); self.quiet2.append(q2)
            # strokes: zigzag extrema of the smoothed displacement, threshold 0.2 in
            w = 50; c = [0.0]
            for a in x:
                c.append(c[-1] + a)
            sm = [(c[min(n, i + w + 1)] - c[max(0, i - w)]) / (min(n, i + w + 1) - max(0, i - w))
                  for i in range(n)]
            ext = [0]; trend = 0; cand = 0
            for i in range(1, n):
                if trend >= 0:
                    if sm[i] > sm[cand] or trend == 0 and sm[i] < sm[cand]:
                        cand = i
                    if trend == 0 and abs(sm[i] - sm[0]) > 0.2:
                        trend = 1 if sm[i] > sm[0] else -1; cand = i
                        continue
                    if trend == 1 and sm[cand] - sm[i] > 0.2:
                        ext.append(cand); trend = -1; cand = i
                else:
                    if sm[i] < sm[cand]:
                        cand = i
                    if sm[i] - sm[cand] > 0.2:
                        ext.append(cand); trend = 1; cand = i
            ext.append(cand)
            for i0, i1 in zip(ext[1:], ext[2:]):
                span = abs(x[i1] - x[i0])
                if span < 0.25:
                    continue
                hasm = any(not (e < i0 or s > i1) for s, e in segs)
                self.strokes.append((fn, i0, i1, span, hasm, x[i0:i1 + 1]))
            # final rest: from 14.15 s
            k0 = int(14.15 * FS)
            rx = x[k0:]; m = len(rx); tm = (m - 1) / 2.0
            mx = sum(rx) / m
            sl = sum((k - tm) * (r - mx) for k, r in enumerate(rx)) / sum((k - tm) ** 2 for k in range(m))
            self.rests.append([r - mx - sl * (k - tm) for k, r in enumerate(rx)])

    def rest_noise(self, rng, nsamp):
        out = []
        while len(out) < nsamp:
            r = self.rests[rng.randrange(len(self.rests))]
            if rng.random() < 0.5:
                r = r[::-1]
            if out:
                off = out[-1] - r[0]
                r = [a + off for a in r]
            out.extend(r)
        out = out[:nsamp]
        return [a - out[0] for a in out]

    def quiet(self, rng, nsamp):
        o1 = []; o2 = []
        while len(o1) < nsamp:
            k = rng.randrange(len(self.quiet1))
            q1 = self.quiet1[k]; q2 = self.quiet2[k]
            s = rng.randrange(0, max(1, len(q1) - 1024))
            e = min(len(q1), s + rng.randrange(1024, 3000))
            o1.extend(q1[s:e]); o2.extend(q2[s:e])
        return o1[:nsamp], o2[:nsamp]


POOL = None


def pool():
    global POOL
    if POOL is None:
        POOL = Pool()
    return POOL


def build_record(rng, n_motion, early, motion_tests):
    """Displacement, actuator positions and construction log of one record."""
    P = pool()
    plain = [s for s in P.strokes if not s[4]]
    motions = [m for m in P.motions if m['actuators'] in motion_tests]
    for attempt in range(50):
        log = []
        final_rest = rng.uniform(1.6, 3.2)
        T_target = rng.uniform(6.5 - final_rest + 1.0, 25.0 - final_rest - 2.2)
        x = []; m1 = []; m2 = []
        p = rng.uniform(-0.5, 0.5)
        init = rng.uniform(0.10, 0.30) if early else rng.uniform(0.3, 1.4)
        nr = int(init * FS)
        x.extend(p + e for e in P.rest_noise(rng, nr)); m1.extend([0.0] * nr); m2.extend([0.0] * nr)
        log.append(['rest', 0.0, round(nr / FS, 4)])
        dirn = rng.choice([1, -1]); placed = 0; onset = None; kstroke = 0
        while len(x) / FS < T_target:
            t_now = len(x) / FS
            carry = False
            if placed < n_motion:
                if early and kstroke == 0:
                    carry = True
                elif t_now + 0.05 >= 1.05 and (rng.random() < 0.45 or t_now > T_target - 2.5):
                    carry = True
            # stroke geometry
            L = rng.uniform(1.4, 2.3) if carry else rng.uniform(0.3, 2.1)
            if carry and abs(p + dirn * L) > 1.25 and abs(p - dirn * L) > 1.25:
                dirn = -1 if p > 0 else 1; L = 1.25 + abs(p)
            if abs(p + dirn * L) > 1.25:
                if abs(p - dirn * L) <= 1.25:
                    dirn = -dirn
                else:
                    L = max(0.25, 1.25 - dirn * p if dirn > 0 else 1.25 + p)
                    if abs(p + dirn * L) > 1.25:
                        dirn = -dirn; L = min(L, 1.25 + abs(p))
            src = rng.choice(plain)
            rel = [(a - src[5][0]) / (src[5][-1] - src[5][0]) for a in src[5]]   # 0 -> 1
            dur0 = (len(rel) - 1) / FS
            mot = None
            if carry:
                mot = rng.choice(motions)
                Lm = len(mot['d1']) / FS
                r = rng.uniform(max(1.2, (Lm + 0.12) / dur0), max(1.6, (Lm + 0.2) / dur0))
            else:
                r = rng.uniform(0.65, 1.6)
            m = int(round((len(rel) - 1) * r))
            seg = []
            for k in range(1, m + 1):
                s = k / r; j = min(int(s), len(rel) - 2); fr = s - j
                seg.append(p + dirn * L * ((1 - fr) * rel[j] + fr * rel[j + 1]))
            i_start = len(x)
            x.extend(seg); m1.extend([0.0] * m); m2.extend([0.0] * m)
            entry = ['stroke', round(i_start / FS, 4), round(m / FS, 4), src[0], src[1], src[2],
                     round(dirn * L, 4), round(r, 4)]
            if mot is not None:
                Lm = len(mot['d1'])
                if early and kstroke == 0:
                    lo = 0.03; hi = min((m - Lm) / FS - 0.03, 0.9 - i_start / FS)
                else:
                    lo = max(0.03, 1.06 - i_start / FS); hi = (m - Lm) / FS - 0.03
                if hi < lo:
                    del x[i_start:]; del m1[i_start:]; del m2[i_start:]
                    continue
                o = i_start + int(rng.uniform(lo, hi) * FS)
                for k in range(Lm):
                    m1[o + k] = mot['d1'][k]; m2[o + k] = mot['d2'][k]
                placed += 1
                if onset is None:
                    onset = o / FS
                entry += ['motion', mot['file'], mot['start_row'], round(o / FS, 4)]
            log.append(entry)
            p = seg[-1]; kstroke += 1
            if rng.random() < 0.45 and len(x) / FS < T_target:
                rd = rng.uniform(0.25, 2.5)
                nr = int(rd * FS)
                x.extend(p + e for e in P.rest_noise(rng, nr)); m1.extend([0.0] * nr); m2.extend([0.0] * nr)
                log.append(['rest', round((len(x) - nr) / FS, 4), round(nr / FS, 4)])
                if rng.random() < 0.3:
                    dirn = -dirn        # next stroke continues in the same direction
            dirn = -dirn
        if placed < n_motion:
            continue
        nr = int(final_rest * FS)
        x.extend(p + e for e in P.rest_noise(rng, nr)); m1.extend([0.0] * nr); m2.extend([0.0] * nr)
        log.append(['rest', round((len(x) - nr) / FS, 4), round(nr / FS, 4)])
        n = len(x) + 1 - (len(x) % 2 == 0)
        n = len(x)
        dur = (n - 1) / FS
        if not (6.5 <= dur <= 25.0):
            continue
        # quantise the displacement like the measured files; v(0) = 0
        xq = [quant(a, Q_DISP, OFF_DISP) for a in x]
        xq[1] = xq[0]
        k = rng.randrange(len(P.xprime)); xp1, xp2 = P.xprime[k]
        q1, q2 = P.quiet(rng, n)
        a1 = [f32(quant(xp1 + q1[i] - q1[0] + m1[i], Q_ACT, 0.0)) for i in range(n)]
        a2 = [f32(quant(xp2 + q2[i] - q2[0] + m2[i], Q_ACT, 0.0)) for i in range(n)]
        on = None
        for i in range(n):
            if abs(a1[i] - a1[0]) > 0.002 or abs(a2[i] - a2[0]) > 0.002:
                on = i / FS; break
        if n_motion and (on is None or (early and on >= 1.0) or (not early and on < 1.0)):
            continue
        if not n_motion and on is not None:
            continue
        return dict(x=xq, a1=a1, a2=a2, log=log, n_motion=placed, early=early,
                    motion_onset_s=on, xprime_from=MEASURED[k], final_rest_s=round(nr / FS, 4),
                    duration_s=round(dur, 4))
    raise RuntimeError('record construction failed')


def write_record(path, rec, Fmeas, Ftrue, rng):
    x = rec['x']; n = len(x)
    # velocity column: smoothed derivative / ~125.4 stored as float32 (quirk of the measured files)
    d = [0.0] * n
    for i in range(1, n - 1):
        d[i] = (x[i + 1] - x[i - 1]) / (2 * DT)
    c = [0.0]
    for a in d:
        c.append(c[-1] + a)
    vcol = []
    for i in range(n):
        h = min(15, i, n - 1 - i)
        vcol.append(f32((c[i + h + 1] - c[i - h]) / (2 * h + 1) / VEL_COLUMN_FACTOR))
    rows = []
    for i in range(n):
        t = i // FS if i % FS == 0 else i / FS
        Ft = Ftrue[i]
        f1 = quant(32.0 + 1000.0 * max(-Ft, 0.0) / 2.03 + rng.gauss(0, 1.2), Q_F1, OFF_F1)
        f2 = quant(33.0 + 1000.0 * max(Ft, 0.0) / 1.82 + rng.gauss(0, 1.2), Q_F2, OFF_F2)
        rows.append([t, x[i], Fmeas[i], vcol[i], rec['a1'][i], rec['a2'][i], f1, f2])
    obj = {'data': rows}
    for k, v in HEADER:
        obj[k] = v
    with open(path, 'w') as f:
        json.dump(obj, f)


def rms_diff(Fa, Fb):
    return math.sqrt(sum((a - b) ** 2 for a, b in zip(Fa, Fb)) / len(Fa))


def ratio_of(recs, bases, shape, A, P, noise):
    s = 0.0; n = 0
    for r, fb in zip(recs, bases):
        F = simulate(r, shape, A, P, v=r['v'])
        s += sum((a - b) ** 2 for a, b in zip(F, fb)); n += len(F)
    return math.sqrt(s / n) / noise


def solve_amplitude(recs, bases, shape, P, noise, target, amax=None):
    lo, hi = 0.0, amax or AMAX[shape]
    rhi = ratio_of(recs, bases, shape, hi, P, noise)
    if rhi < target:
        return None, rhi
    rlo = 0.0
    A = hi * 0.5
    for it in range(60):
        # regula falsi on sqrt-ish scale, safeguarded by bisection
        A = lo + (hi - lo) * (target - rlo) / (rhi - rlo) if it % 2 == 0 else 0.5 * (lo + hi)
        A = min(max(A, lo + 1e-6 * (hi - lo)), hi - 1e-6 * (hi - lo))
        r = ratio_of(recs, bases, shape, A, P, noise)
        if abs(r - target) / target < 0.002:
            return A, r
        if r < target:
            lo, rlo = A, r
        else:
            hi, rhi = A, r
    return A, r


# ----------------------------------------------------------------------------------------------
# Trials
# ----------------------------------------------------------------------------------------------
def plan():
    rng = random.Random(MASTER_SEED)
    slots = []
    for cat in SHAPES:
        for sh in SHAPES[cat]:
            slots.append((cat, sh))
    slots += [('none', 'none')] * 6
    rng.shuffle(slots)
    trials = []
    motion_flags = []
    for k, (cat, sh) in enumerate(slots):
        need = cat in NEEDS_MOTION
        nm = []
        for r in range(2):
            if need:
                nm.append(rng.randint(3, 4))
            else:
                nm.append(rng.randint(1, 3) if rng.random() < 0.7 else 0)
        motion_flags.append(nm)
        trials.append(dict(trial='t%02d' % (k + 1), category=cat, shape=sh,
                           seed=rng.randrange(1 << 30), n_motion=nm))
    # about 1/3 of the records (20 of 60) move the actuators within the first second
    cands = [(k, r) for k in range(30) for r in range(2) if trials[k]['n_motion'][r] > 0]
    rng.shuffle(cands)
    early = set(cands[:20])
    for k in range(30):
        trials[k]['early'] = [(k, 0) in early, (k, 1) in early]
    return trials


def run_trial(tr):
    t0 = time.time()
    rng = random.Random(tr['seed'])
    cat, sh = tr['category'], tr['shape']
    noise = rng.uniform(0.02, 0.06)
    tests = {'both'} if sh == 'actuator_coupling' else {'one', 'two', 'both'}
    recs = []
    for r in range(2):
        rec = build_record(rng, tr['n_motion'][r], tr['early'][r], tests)
        rec['F0'] = quant(rng.uniform(-0.8, 1.6), Q_FORCE, OFF_FORCE)
        rec['v'] = velocity(rec['x'])
        recs.append(rec)
    bases = [simulate(r, v=r['v']) for r in recs]
    P = draw_shape_params(sh, rng) if cat != 'none' else {}
    note = ''
    if cat == 'none':
        strength = 'none'; target = 0.0; A = 0.0; ratio = 0.0
    else:
        strength = 'strong' if STRENGTH[sh] == 'S' else 'weak'
        target = rng.uniform(8.5, 11.5) if strength == 'strong' else rng.uniform(2.7, 3.8)
        A, ratio = solve_amplitude(recs, bases, sh, P, noise, target)
        if A is None and strength == 'strong':
            note = 'strong target %.2f unreachable (max %.2f at A=%g): made weak' % (target, ratio, AMAX[sh])
            strength = 'weak'; target = rng.uniform(2.7, 3.8)
            A, ratio = solve_amplitude(recs, bases, sh, P, noise, target)
        if A is None:
            note += ' weak target %.2f unreachable at A=%g (max %.2f): bracket doubled' % (target, AMAX[sh], ratio)
            A, ratio = solve_amplitude(recs, bases, sh, P, noise, target, 2.0 * AMAX[sh])
        if A is None:
            raise RuntimeError('%s %s: weak target unreachable (%.2f)' % (tr['trial'], sh, ratio))
    out = os.path.join(OUTDIR, 'cases', tr['trial'])
    os.makedirs(out, exist_ok=True)
    info = {}
    for name, rec, fb in zip(('A', 'B'), recs, bases):
        Ft = fb if cat == 'none' else simulate(rec, sh, A, P, v=rec['v'])
        Fm = [rec['F0']] + [quant(f + rng.gauss(0.0, noise), Q_FORCE, OFF_FORCE) for f in Ft[1:]]
        write_record(os.path.join(out, name + '.json'), rec, Fm, Ft, rng)
        info[name] = dict(duration_s=rec['duration_s'], n_samples=len(rec['x']),
                          n_actuator_motions=rec['n_motion'], actuators_move_in_first_second=rec['early'],
                          motion_onset_s=rec['motion_onset_s'], final_rest_s=rec['final_rest_s'],
                          F0_kip=rec['F0'], xprime_from=rec['xprime_from'],
                          rms_effect_kip=round(rms_diff(Ft, fb), 5), pieces=rec['log'])
    return dict(trial=tr['trial'], category=cat, shape=sh, strength=strength,
                target_ratio=round(target, 4), ratio=round(ratio, 4), amplitude=A,
                params=P, noise_kip=round(noise, 6), noise_kip_exact=noise, seed=tr['seed'],
                note=note, records=info), round(time.time() - t0, 1)


def main():
    t0 = time.time()
    trials = plan()
    pool()
    os.makedirs(os.path.join(OUTDIR, 'cases'), exist_ok=True)
    from multiprocessing import Pool as MPool
    with MPool(2) as mp:
        out = mp.map(run_trial, trials, chunksize=1)
    res = [r for r, _ in out]
    key = {r['trial']: r for r in res}
    with open(os.path.join(OUTDIR, 'key.json'), 'w') as f:
        json.dump(key, f, indent=1)
    for r, sec in out:
        print(r['trial'], r['strength'], r['ratio'], r['note'], sec)
    print('done in %.1f s' % (time.time() - t0))


if __name__ == '__main__':
    main()
