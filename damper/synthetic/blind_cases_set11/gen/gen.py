#!/usr/bin/env python3
"""Blind hidden-effect test set "blind11" for a BRFD friction-damper model-discrepancy tool.

Python 3 standard library only.  Usage:

    python3 gen/gen.py --seed 11011 --out DIR        # writes DIR/cases/tNN/{A,B}.json and DIR/key.json

Every record re-uses the drum displacement and electric-actuator positions of the six measured
semi-active tests (/work/shared/data/brfd/semiactive), cut at drum reversals, mirrored, stopped
mid-stroke with a smooth deceleration, or two pieces concatenated; a 0.25 s hold is put in front
(so the drum starts exactly at rest) and a >= 1.6 s hold at the end.  The force column is the
semi-active LuGre model of the seed paper (Eqs. 1-5, parameters of configs/brfd-semiactive.yaml)
plus, for effect trials, one hidden physical effect, plus white Gaussian noise.

Conventions of the base model (chosen to replay exactly what `damper predict --no-fit` does on a
record, see verify.py):
  * drum velocity is derived from the displacement column (the velocity column of the semi-active
    files is ~1/125.4 of the true in/s velocity): central differences (one-sided at the ends),
    then a 15-sample centred moving average whose window shrinks symmetrically at the ends;
  * z(0) = F(0)/sigma0 (the record starts at rest, v(0) = 0);
  * z is advanced from sample k-1 to k with the inputs of sample k held over the step (exact
    exponential solution of the linear-in-z LuGre ODE);
  * F_k = sigma0 z_k + sigma1 zdot_k + sigma2 v_k, sigma1 = 0.
"""
import argparse
import json
import math
import os
import random
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
DATA_DIR = '/work/shared/data/brfd/semiactive'
CONFIG = '/work/main/configs/brfd-semiactive.yaml'
TESTS = ['harmonic0.015backward', 'harmonic0.015forward', 'harmonic0.03ea1backward',
         'harmonic0.03ea1forward', 'harmonic0.03ea2backward', 'harmonic0.03ea2forward']
DT = 0.0009765625
FS_HZ = 1024
VEL_COLUMN_FACTOR = 125.4      # measured velocity column = true in/s velocity / ~125.4 (README quirk)
XQ = 5.8650970458984375e-05    # displacement quantization step of the measured files (in)
START_HOLD_S = 0.25
V_DIR = 0.06                   # in/s: direction tracker threshold (reversal detection)
V_REST = 0.08                  # in/s: rest gating scale, w = exp(-(v/V_REST)^4)


# ----------------------------------------------------------------------------- config
def _num(s):
    s = s.strip()
    if s.startswith('['):
        return [float(t) for t in s.strip('[]').split(',') if t.strip()]
    try:
        return float(s)
    except ValueError:
        return s


def load_config(path=CONFIG):
    """Minimal YAML-subset reader for configs/brfd-semiactive.yaml (section: key: value)."""
    out, sec = {}, None
    for line in open(path):
        line = line.split('#', 1)[0].rstrip()
        if not line.strip():
            continue
        ind = len(line) - len(line.lstrip())
        key, _, val = line.strip().partition(':')
        if ind == 0:
            sec = key
            if val.strip():
                out[key] = _num(val)
            else:
                out[key] = {}
        elif isinstance(out.get(sec), dict):
            out[sec][key] = _num(val)
    L, S = out['lugre'], out['semiactive']
    m, C = S['slopes_kip_per_in'], S['scaling']
    return dict(s0=L['sigma0_kip_per_in'], s1=L['sigma1_kip_s_per_in'], s2=L['sigma2_kip_s_per_in'],
                fsf=L['fs_fwd_kip'], fsb=L['fs_bwd_kip'], fcf=L['fc_fwd_kip'], fcb=L['fc_bwd_kip'],
                vs=L['vs_in_per_s'], floor=S['fc_floor_kip'],
                kf1=C[0] * m[0] + C[1] * m[2], kf2=C[0] * m[1] + C[1] * m[3],
                kb1=C[2] * m[4] + C[3] * m[6], kb2=C[2] * m[5] + C[3] * m[7])


P = None  # model parameters, set in main / load


def params():
    global P
    if P is None:
        P = load_config()
    return P


# ----------------------------------------------------------------------------- signals
def derive_velocity(x, dt=DT, half=7):
    """Central differences (one-sided at the ends) + centred moving average of 2*half+1 samples,
    window shrinking symmetrically at the ends (zero phase)."""
    n = len(x)
    if n < 2:
        return [0.0] * n
    raw = [0.0] * n
    raw[0] = (x[1] - x[0]) / dt
    raw[-1] = (x[-1] - x[-2]) / dt
    for i in range(1, n - 1):
        raw[i] = (x[i + 1] - x[i - 1]) / (2 * dt)
    cs = [0.0]
    for r in raw:
        cs.append(cs[-1] + r)
    v = [0.0] * n
    for i in range(n):
        h = min(half, i, n - 1 - i)
        v[i] = (cs[i + h + 1] - cs[i - h]) / (2 * h + 1)
    return v


_SRC = {}


def source(name):
    """Measured test -> dict of columns + reversal indices."""
    if name in _SRC:
        return _SRC[name]
    D = json.load(open(os.path.join(DATA_DIR, name + '.json')))['data']
    cols = list(zip(*D))
    s = dict(name=name, t=list(cols[0]), x=list(cols[1]), F=list(cols[2]), vcol=list(cols[3]),
             a1=list(cols[4]), a2=list(cols[5]), f1=list(cols[6]), f2=list(cols[7]))
    v = derive_velocity(s['x'])
    s['v'] = v
    n = len(v)
    rev = []
    for i in range(1, n):
        if (v[i - 1] > 0) != (v[i] > 0) and abs(s['x'][i]) > 0.05:
            lo, hi = max(0, i - 40), min(n, i + 40)
            seg = s['x'][lo:hi]
            j = lo + (seg.index(max(seg)) if s['x'][i] > 0 else seg.index(min(seg)))
            if not rev or j - rev[-1] > 300:
                rev.append(j)
    s['rev'] = rev
    # actuator motion window (samples where either actuator is > 2 mil away from its t=0 position)
    mv = [i for i in range(n) if abs(s['a1'][i] - s['a1'][0]) > 0.002 or abs(s['a2'][i] - s['a2'][0]) > 0.002]
    s['act_window'] = (mv[0], mv[-1]) if mv else None
    _SRC[name] = s
    return s


# ----------------------------------------------------------------------------- record design
def build_inputs(design):
    """design -> dict(rec=columns of the record, warm=columns of the warm-up history or None, z0...)."""
    pieces = design['pieces']
    mir = -1.0 if design.get('mirror') else 1.0
    cols = {k: [] for k in ('x', 'a1', 'a2', 'vcol', 'f1', 'f2')}
    synth = []  # True where the sample is synthetic (hold / deceleration)

    def add(k_x, a1, a2, vc, f1, f2, syn):
        cols['x'].append(k_x); cols['a1'].append(a1); cols['a2'].append(a2)
        cols['vcol'].append(vc); cols['f1'].append(f1); cols['f2'].append(f2); synth.append(syn)

    first = pieces[0]
    s0 = source(first['test'])
    m0 = mir * (-1.0 if first.get('mirror') else 1.0)
    i0 = first['i0']
    # start hold
    for _ in range(int(round(START_HOLD_S / DT))):
        add(m0 * s0['x'][i0], s0['a1'][i0], s0['a2'][i0], 0.0, s0['f1'][i0], s0['f2'][i0], True)
    for k, pc in enumerate(pieces):
        s = source(pc['test'])
        m = mir * (-1.0 if pc.get('mirror') else 1.0)
        dx = da1 = da2 = 0.0
        if k > 0:
            dx = cols['x'][-1] - m * s['x'][pc['i0']]
            da1 = cols['a1'][-1] - s['a1'][pc['i0']]
            da2 = cols['a2'][-1] - s['a2'][pc['i0']]
        start = pc['i0'] + (1 if k > 0 else 0)
        for i in range(start, pc['i1'] + 1):
            add(m * s['x'][i] + dx, s['a1'][i] + da1, s['a2'][i] + da2, m * s['vcol'][i],
                s['f1'][i], s['f2'][i], False)
    # smooth mid-stroke stop
    if design.get('decel_s'):
        Td = design['decel_s']
        last = pieces[-1]
        s = source(last['test'])
        m = mir * (-1.0 if last.get('mirror') else 1.0)
        vm = m * s['v'][last['i1']]
        xm = cols['x'][-1]
        nd = int(round(Td / DT))
        for j in range(1, nd + 1):
            t = j * DT
            xx = xm + vm * (t / 2 + Td / (2 * math.pi) * math.sin(math.pi * t / Td))
            xx = xm + round((xx - xm) / XQ) * XQ
            add(xx, cols['a1'][-1], cols['a2'][-1], None, cols['f1'][-1], cols['f2'][-1], True)
    # end hold
    for _ in range(int(round(design['end_hold_s'] / DT))):
        add(cols['x'][-1], cols['a1'][-1], cols['a2'][-1], 0.0, cols['f1'][-1], cols['f2'][-1], True)
    v = derive_velocity(cols['x'])
    cols['v'] = v
    cols['vcol'] = [v[i] / VEL_COLUMN_FACTOR if c is None else c for i, c in enumerate(cols['vcol'])]
    cols['xp1'], cols['xp2'] = cols['a1'][0], cols['a2'][0]
    # warm-up history: the measured test from its start to the first cut point
    warm = None
    if i0 > 0:
        wx = [m0 * s0['x'][i] for i in range(0, i0 + 1)]
        warm = dict(x=wx, a1=s0['a1'][:i0 + 1], a2=s0['a2'][:i0 + 1], v=derive_velocity(wx),
                    xp1=s0['a1'][0], xp2=s0['a2'][0])
    z0 = m0 * s0['F'][0] / params()['s0']
    return dict(rec=cols, warm=warm, z0=z0, synth=synth)


# ----------------------------------------------------------------------------- small helpers
def expm(A, terms=30):
    """Matrix exponential of a small square matrix (scaling and squaring + Taylor)."""
    n = len(A)
    nrm = max(sum(abs(a) for a in row) for row in A)
    k = 0
    while nrm > 0.5:
        nrm /= 2
        k += 1
    As = [[a / (2 ** k) for a in row] for row in A]
    E = [[float(i == j) for j in range(n)] for i in range(n)]
    T = [row[:] for row in E]
    for t in range(1, terms):
        T = [[sum(T[i][l] * As[l][j] for l in range(n)) / t for j in range(n)] for i in range(n)]
        E = [[E[i][j] + T[i][j] for j in range(n)] for i in range(n)]
    for _ in range(k):
        E = [[sum(E[i][l] * E[l][j] for l in range(n)) for j in range(n)] for i in range(n)]
    return E


def second_order_zoh(wn, zeta, dt=DT):
    """ZOH discretisation of y'' = wn^2 (u - y) - 2 zeta wn y'  ->  (Phi, Gamma)."""
    M = [[0.0, 1.0, 0.0], [-wn * wn, -2 * zeta * wn, wn * wn], [0.0, 0.0, 0.0]]
    E = expm([[a * dt for a in row] for row in M])
    return [[E[0][0], E[0][1]], [E[1][0], E[1][1]]], [E[0][2], E[1][2]]


def lugre_exact(z, v, g, s0, dt=DT):
    """z' = v - s0 |v| z / g with v, g held: exact solution over dt."""
    if v == 0.0:
        return z
    a = s0 * abs(v) / g
    zs = v / a
    return zs + (z - zs) * math.exp(-a * dt)


# ----------------------------------------------------------------------------- the model
SHAPES = {
    # category: [(shape, p_max, extras sampler)]
    'backlash': ['play_gap_release', 'reversal_capacity_dropout', 'reversal_release_time'],
    'residual_static': ['rest_relax_fraction', 'rest_log_creep', 'rest_settle_level_2nd'],
    'actuator_lag': ['act_transport_delay', 'act_second_order', 'act_loaded_asym_lag'],
    'asymmetry': ['dir_stiffness', 'dir_gain', 'bwd_quadratic_drag'],
    'velocity': ['sqrt_viscous', 'frictional_memory', 'stribeck_exponent'],
    'pretension': ['clamp_gain', 'clamp_offset', 'travel_tension_loss'],
    'self_energizing': ['wrap_position_capstan', 'servo_force_feedback', 'wrap_travel_saturating'],
    'transition_shape': ['bristle_exponent', 'elastoplastic_blend', 'maxwell_slip_two'],
}

P_MAX = {
    'play_gap_release': 0.4, 'reversal_capacity_dropout': 0.97, 'reversal_release_time': 0.95,
    'rest_relax_fraction': 1.0, 'rest_log_creep': 0.6, 'rest_settle_level_2nd': 1.0,
    'act_transport_delay': 1.0, 'act_second_order': 1.0, 'act_loaded_asym_lag': 2.0,
    'dir_stiffness': 6.0, 'dir_gain': 3.0, 'bwd_quadratic_drag': 4.0,
    'sqrt_viscous': 4.0, 'frictional_memory': 2.0, 'stribeck_exponent': 1.7,
    'clamp_gain': 2.0, 'clamp_offset': 4.0, 'travel_tension_loss': 0.9,
    'wrap_position_capstan': 2.0, 'servo_force_feedback': 1.3, 'wrap_travel_saturating': 3.0,
    'bristle_exponent': 3.0, 'elastoplastic_blend': 1.0, 'maxwell_slip_two': 0.97,
}


def sample_extras(shape, rng):
    r = lambda a, b: round(rng.uniform(a, b), 4)
    if shape == 'play_gap_release':
        return dict(release_length_in=r(0.03, 0.06))
    if shape == 'reversal_capacity_dropout':
        return dict(length_in=r(0.06, 0.12))
    if shape == 'reversal_release_time':
        return dict(tau_s=r(0.10, 0.22), onset_s=0.015)
    if shape == 'rest_relax_fraction':
        return dict(tau_s=r(0.3, 0.7))
    if shape == 'rest_log_creep':
        return dict(theta_s=r(0.03, 0.10))
    if shape == 'rest_settle_level_2nd':
        return dict(level_kip=r(-0.6, 0.9), f_hz=r(0.6, 1.0), zeta=r(0.3, 0.45))
    if shape == 'act_second_order':
        return dict(zeta=r(0.25, 0.35))
    if shape == 'act_loaded_asym_lag':
        return dict(unload_ratio=r(0.15, 0.35))
    if shape == 'clamp_offset':
        return dict(sign=rng.choice([-1.0, 1.0]))
    if shape == 'travel_tension_loss':
        return dict(scale_in=r(5.0, 10.0))
    if shape == 'servo_force_feedback':
        return dict(f_ref_kip=10.0)
    if shape == 'wrap_travel_saturating':
        return dict(length_in=r(0.4, 0.8))
    if shape == 'elastoplastic_blend':
        return dict(breakaway_frac=r(0.45, 0.75))
    return {}


def init_state(shape, p, ex, z0, x0, a10, a20):
    Pm = params()
    st = dict(z=z0, dir=(1 if z0 >= 0 else -1), d=1e3, trev=1e3, trest=0.0, zstop=z0, zr=0.0,
              s=0.0, X=x0, y1=a10, y2=a20, yd1=0.0, yd2=0.0, vl=0.0, l1=a10, l2=a20)
    if shape == 'play_gap_release':
        st['xb'] = x0 - p * (1 if z0 >= 0 else -1)
    if shape == 'dir_stiffness':
        st['Fb'] = Pm['s0'] * z0
    if shape == 'maxwell_slip_two':
        k1, k2 = Pm['s0'] * (1 + p) / 2, Pm['s0'] * (1 - p) / 2
        st['z1'], st['z2'] = Pm['s0'] * z0 / 2 / k1, Pm['s0'] * z0 / 2 / k2
    if shape == 'act_transport_delay':
        st['h1'], st['h2'] = [a10], [a20]
    return st


def simulate(shape, p, ex, seq, st):
    """Run the (effect) model over one input sequence; st is the state AT sample 0 (mutated).
    Returns the force list."""
    Pm = params()
    s0, s2, vs, floor = Pm['s0'], Pm['s2'], Pm['vs'], Pm['floor']
    fsf, fsb, fcf, fcb = Pm['fsf'], Pm['fsb'], Pm['fcf'], Pm['fcb']
    kf1, kf2, kb1, kb2 = Pm['kf1'], Pm['kf2'], Pm['kb1'], Pm['kb2']
    V, X, A1, A2 = seq['v'], seq['x'], seq['a1'], seq['a2']
    xp1, xp2 = seq['xp1'], seq['xp2']
    dt = DT
    n = len(V)
    F = [0.0] * n
    exp = math.exp
    # per-shape constants
    if shape == 'act_second_order':
        wn = 1.0 / p if p > 0 else None
        if wn:
            Phi, Gam = second_order_zoh(wn, ex['zeta'])
    if shape == 'act_transport_delay':
        nd = p / dt
    if shape == 'rest_settle_level_2nd':
        wr = 2 * math.pi * ex['f_hz']
        zl = ex['level_kip'] / s0
    if shape == 'dir_stiffness':
        sf, sb = s0 * (1 + p), s0 / (1 + p)
    if shape == 'maxwell_slip_two':
        k1, k2 = s0 * (1 + p) / 2, s0 * (1 - p) / 2
    if shape == 'elastoplastic_blend':
        beta = ex['breakaway_frac']
    nexp = 1.0 + p if shape == 'bristle_exponent' else 1.0
    delta = 2.0 - p if shape == 'stribeck_exponent' else 2.0

    z = st['z']
    for i in range(n):
        v = V[i]
        vb = v
        if i > 0:
            av = abs(v)
            # ---------------- trackers
            st['s'] += av * dt
            st['d'] += av * dt
            st['trev'] += dt
            if v > V_DIR and st['dir'] < 0:
                st['dir'] = 1; st['d'] = 0.0; st['trev'] = 0.0
            elif v < -V_DIR and st['dir'] > 0:
                st['dir'] = -1; st['d'] = 0.0; st['trev'] = 0.0
            w = exp(-(v / V_REST) ** 4)
            # ---------------- actuator positions seen by the clamp
            u1, u2 = A1[i], A2[i]
            if shape == 'act_transport_delay':
                h1, h2 = st['h1'], st['h2']
                h1.append(u1); h2.append(u2)
                pos = len(h1) - 1 - nd
                if pos <= 0:
                    u1, u2 = h1[0], h2[0]
                else:
                    j = int(pos); fr = pos - j
                    u1 = h1[j] + fr * (h1[min(j + 1, len(h1) - 1)] - h1[j])
                    u2 = h2[j] + fr * (h2[min(j + 1, len(h2) - 1)] - h2[j])
            elif shape == 'act_second_order' and wn:
                y1, yd1, y2, yd2 = st['y1'], st['yd1'], st['y2'], st['yd2']
                st['y1'] = Phi[0][0] * y1 + Phi[0][1] * yd1 + Gam[0] * u1
                st['yd1'] = Phi[1][0] * y1 + Phi[1][1] * yd1 + Gam[1] * u1
                st['y2'] = Phi[0][0] * y2 + Phi[0][1] * yd2 + Gam[0] * u2
                st['yd2'] = Phi[1][0] * y2 + Phi[1][1] * yd2 + Gam[1] * u2
                u1, u2 = st['y1'], st['y2']
            elif shape == 'act_loaded_asym_lag' and p > 0:
                # first-order lag, slow (tau = p) while retracting = tightening the band against
                # its load, fast (tau = unload_ratio * p) while extending = releasing
                for key_, u_ in (('y1', u1), ('y2', u2)):
                    e_ = u_ - st[key_]
                    tau_ = p if e_ < 0 else ex['unload_ratio'] * p
                    st[key_] += e_ * (1 - exp(-dt / tau_))
                u1, u2 = st['y1'], st['y2']
            # ---------------- band / drum slip velocity (play operator)
            if shape == 'play_gap_release':
                st['X'] += v * dt
                xb = min(max(st['xb'], st['X'] - p), st['X'] + p)
                vb = (xb - st['xb']) / dt
                st['xb'] = xb
            # ---------------- kinetic / static friction, Eq. (4)-(5)
            if vb >= 0:
                Fc = fcf + kf1 * (u1 - xp1) + kf2 * (u2 - xp2); Fs = fsf
            else:
                Fc = fcb + kb1 * (u1 - xp1) + kb2 * (u2 - xp2); Fs = fsb
            if Fc < floor:
                Fc = floor
            if shape == 'clamp_gain':
                Fc *= (1 + p); Fs *= (1 + p)
            elif shape == 'clamp_offset':
                Fc = max(Fc + ex['sign'] * p, floor); Fs = max(Fs + ex['sign'] * p, floor)
            elif shape == 'travel_tension_loss':
                k = 1 - p * (1 - exp(-st['s'] / ex['scale_in']))
                Fc *= k; Fs *= k
            elif shape == 'dir_gain':
                k = (1 + p) if vb >= 0 else 1 / (1 + p)
                Fc *= k; Fs *= k
            vst = vb
            if shape == 'frictional_memory':
                if p > 0:
                    st['vl'] += (v - st['vl']) * (1 - exp(-dt / p))
                else:
                    st['vl'] = v
                vst = st['vl']
            if delta == 2.0:
                g = Fc + (Fs - Fc) * exp(-(vst / vs) ** 2)
            else:
                g = Fc + (Fs - Fc) * exp(-abs(vst / vs) ** delta)
            if shape == 'reversal_capacity_dropout':
                g *= 1 - p * exp(-(st['d'] / ex['length_in']) ** 2)
            elif shape == 'wrap_position_capstan':
                g *= exp(p * (1 if v >= 0 else -1) * X[i])
            elif shape == 'servo_force_feedback':
                g *= 1 + p * abs(s0 * z) / ex['f_ref_kip']
            elif shape == 'wrap_travel_saturating':
                g *= 1 + p * (1 - exp(-st['d'] / ex['length_in']))
            if g < 1e-3:
                g = 1e-3
            # ---------------- bristle state
            if shape == 'dir_stiffness':
                if v != 0.0:
                    sd = sf if v >= 0 else sb
                    Fs_ = g if v > 0 else -g
                    st['Fb'] = Fs_ + (st['Fb'] - Fs_) * exp(-sd * av / g * dt)
            elif shape == 'maxwell_slip_two':
                st['z1'] = lugre_exact(st['z1'], v, g / 2, k1)
                st['z2'] = lugre_exact(st['z2'], v, g / 2, k2)
            elif shape == 'bristle_exponent' and p > 0:
                def f(zz):
                    r_ = s0 * zz / g
                    return v - av * (abs(r_) ** nexp) * (1 if r_ >= 0 else -1)
                # adaptive sub-stepping: local rate |v| n |r|^(n-1) s0/g kept below 0.4/h
                rr = max(1.0, abs(s0 * z / g))
                rate = av * nexp * rr ** (nexp - 1) * s0 / g
                ns = max(4, int(math.ceil(rate * dt / 0.4)))
                h = dt / ns
                for _ in range(ns):
                    q1 = f(z); q2 = f(z + h / 2 * q1); q3 = f(z + h / 2 * q2); q4 = f(z + h * q3)
                    z += h / 6 * (q1 + 2 * q2 + 2 * q3 + q4)
            elif shape == 'elastoplastic_blend' and p > 0:
                zm = g / s0; zb = beta * zm
                def f(zz):
                    if v == 0.0:
                        return 0.0
                    if (zz >= 0) != (v >= 0):
                        aep = 0.0
                    else:
                        az = abs(zz)
                        if az <= zb:
                            aep = 0.0
                        elif az >= zm:
                            aep = 1.0
                        else:
                            aep = 0.5 * math.sin(math.pi * (az - (zm + zb) / 2) / (zm - zb)) + 0.5
                    al = 1 - p * (1 - aep)
                    return v - al * av * s0 * zz / g
                h = dt / 4
                for _ in range(4):
                    q1 = f(z); q2 = f(z + h / 2 * q1); q3 = f(z + h / 2 * q2); q4 = f(z + h * q3)
                    z += h / 6 * (q1 + 2 * q2 + 2 * q3 + q4)
            else:
                z = lugre_exact(z, vb, g, s0)
            if shape == 'play_gap_release' and vb == 0.0 and av > 0.05 and p > 0:
                z *= exp(-av * dt / ex['release_length_in'])
            # ---------------- behaviour at rest
            if shape in ('rest_relax_fraction', 'rest_log_creep', 'rest_settle_level_2nd'):
                if w < 0.5:
                    st['zstop'] = z; st['trest'] = 0.0; st['zr'] = 0.0
                else:
                    st['trest'] += dt
                    zs = st['zstop']
                    if shape == 'rest_relax_fraction':
                        zt = (1 - p) * zs
                        z = zt + (z - zt) * exp(-w * dt / ex['tau_s'])
                    elif shape == 'rest_log_creep':
                        z2 = z - w * p * zs * dt / (ex['theta_s'] + st['trest'])
                        z = z2 if (z2 >= 0) == (zs >= 0) else 0.0
                    else:
                        zt = zs + p * (zl - zs)
                        st['zr'] += dt * w * (wr * wr * (zt - z) - 2 * ex['zeta'] * wr * st['zr'])
                        z += dt * w * st['zr']
        # ---------------- output force
        if shape == 'dir_stiffness':
            Fo = st['Fb'] + s2 * v
        elif shape == 'maxwell_slip_two':
            Fo = k1 * st['z1'] + k2 * st['z2'] + s2 * v
        else:
            Fo = s0 * z + s2 * vb
        if shape == 'reversal_release_time':
            tr = st['trev']
            Fo -= s0 * z * p * (1 - exp(-tr / ex['onset_s'])) * exp(-tr / ex['tau_s'])
        elif shape == 'sqrt_viscous':
            Fo += p * math.copysign(math.sqrt(abs(v)), v)
        elif shape == 'bwd_quadratic_drag':
            if v < 0:
                Fo -= p * v * v
        F[i] = Fo
    st['z'] = z
    return F


def run_record(shape, p, ex, inp):
    """Simulate warm-up history (if any) then the record; returns record force (noise-free)."""
    if inp['warm'] is not None:
        w = inp['warm']
        st = init_state(shape, p, ex, inp['z0'], w['x'][0], w['a1'][0], w['a2'][0])
        simulate(shape, p, ex, w, st)
    else:
        r = inp['rec']
        st = init_state(shape, p, ex, inp['z0'], r['x'][0], r['a1'][0], r['a2'][0])
    return simulate(shape, p, ex, inp['rec'], st)


def base_replay(inp, F0):
    """What the base model (--no-fit) predicts on the record: z0 = F(0)/sigma0."""
    r = inp['rec']
    z0 = F0 / params()['s0']
    st = init_state('none', 0.0, {}, z0, r['x'][0], r['a1'][0], r['a2'][0])
    return simulate('none', 0.0, {}, r, st)


# ----------------------------------------------------------------------------- trial design
def design_record(rng, tests, end_kind, need_actuators=False):
    """Random record design using only the given source tests."""
    for _attempt in range(200):
        t1 = rng.choice(tests)
        s1 = source(t1)
        R, N = s1['rev'], len(s1['x'])
        mirror = rng.random() < 0.35
        concat = len(tests) > 1 and rng.random() < 0.45
        start_zero = rng.random() < 0.4
        i_start = 0 if start_zero else rng.randint(1, 7)      # reversal index
        a0 = 0 if start_zero else R[i_start]
        pieces = []
        decel = None
        if concat:
            lo_j = i_start + 2 if not start_zero else 2
            j = rng.randint(lo_j, max(lo_j, 8))
            pieces.append(dict(test=t1, i0=a0, i1=R[j]))
            t2 = rng.choice([t for t in tests if t != t1])
            s2 = source(t2)
            R2, N2 = s2['rev'], len(s2['x'])
            mir2 = rng.random() < 0.3
            sign_end = 1 if s1['x'][R[j]] > 0 else -1
            cand = [k for k in range(2, 10)
                    if (1 if s2['x'][R2[k]] > 0 else -1) * (-1 if mir2 else 1) == sign_end]
            k = rng.choice(cand)
            if end_kind == 'rampdown':
                pieces.append(dict(test=t2, i0=R2[k], i1=N2 - 1, mirror=mir2))
            elif end_kind == 'reversal':
                l = rng.randint(k + 2, min(k + 6, len(R2) - 1))
                pieces.append(dict(test=t2, i0=R2[k], i1=R2[l], mirror=mir2))
            else:
                l = rng.randint(k + 1, min(k + 5, len(R2) - 2))
                m = int(R2[l] + rng.uniform(0.3, 0.7) * (R2[l + 1] - R2[l]))
                pieces.append(dict(test=t2, i0=R2[k], i1=m, mirror=mir2))
                decel = round(rng.uniform(0.3, 0.5), 3)
        else:
            if end_kind == 'rampdown':
                pieces.append(dict(test=t1, i0=a0, i1=N - 1))
            elif end_kind == 'reversal':
                lo = (i_start + 4) if not start_zero else 4
                l = rng.randint(lo, len(R) - 1)
                pieces.append(dict(test=t1, i0=a0, i1=R[l]))
            else:
                lo = (i_start + 3) if not start_zero else 3
                l = rng.randint(lo, len(R) - 2)
                m = int(R[l] + rng.uniform(0.3, 0.7) * (R[l + 1] - R[l]))
                pieces.append(dict(test=t1, i0=a0, i1=m))
                decel = round(rng.uniform(0.3, 0.5), 3)
        dur = sum(pc['i1'] - pc['i0'] for pc in pieces) * DT
        if dur < 4.0 or dur > 21.0:
            continue
        if need_actuators:
            act = 0
            for pc in pieces:
                s = source(pc['test'])
                for i in range(pc['i0'], pc['i1'] + 1, 4):
                    if abs(s['a1'][i] - s['a1'][0]) > 0.002 or abs(s['a2'][i] - s['a2'][0]) > 0.002:
                        act += 4
            if act * DT < 2.0:
                continue
        d = dict(pieces=pieces, mirror=mirror, decel_s=decel,
                 end_hold_s=round(rng.uniform(1.6, 2.6), 3), end_kind=end_kind)
        return d
    raise RuntimeError('no design found')


def describe(design, inp):
    pcs = []
    for pc in design['pieces']:
        s = source(pc['test'])
        pcs.append(dict(test=pc['test'] + '.json', from_s=round(s['t'][pc['i0']], 6),
                        to_s=round(s['t'][pc['i1']], 6), mirrored_piece=bool(pc.get('mirror'))))
    n = len(inp['rec']['x'])
    return dict(pieces=pcs, mirror_whole=bool(design['mirror']), start_hold_s=START_HOLD_S,
                decel_stop_s=design['decel_s'], end_hold_s=design['end_hold_s'],
                end=design['end_kind'], duration_s=round((n - 1) * DT, 6),
                x1_initial_in=inp['rec']['xp1'], x2_initial_in=inp['rec']['xp2'],
                warmup_from_test_start=inp['warm'] is not None)


def rms(a):
    return math.sqrt(sum(t * t for t in a) / len(a)) if a else 0.0


def effect_ratio(shape, p, ex, inps, noise):
    d = []
    Fs = []
    for inp in inps:
        Fe = run_record(shape, p, ex, inp)
        Fb = base_replay(inp, Fe[0])
        d.extend(a - b for a, b in zip(Fe, Fb))
        Fs.append(Fe)
    return rms(d) / noise, Fs


def calibrate(shape, ex, inps, noise, target, pmax):
    """Find p with effect RMS / noise == target (monotone search on [0, pmax])."""
    lo, rlo = 0.0, 0.0
    hi = pmax
    rhi, Fhi = effect_ratio(shape, hi, ex, inps, noise)
    if rhi < target:
        return None, rhi, Fhi
    best = (abs(rhi / target - 1), hi, rhi, Fhi)
    p = pmax * 0.1
    for it in range(40):
        r, Fs_ = effect_ratio(shape, p, ex, inps, noise)
        if abs(r / target - 1) < best[0]:
            best = (abs(r / target - 1), p, r, Fs_)
        if abs(r / target - 1) < 0.004:
            break
        if r < target:
            lo, rlo = p, r
        else:
            hi, rhi = p, r
        # log-log interpolation inside the bracket, bisection fallback
        if lo > 0 and rlo > 0 and rhi > rlo:
            k = math.log(rhi / rlo) / math.log(hi / lo) if hi > lo else 1.0
            pn = lo * (target / rlo) ** (1.0 / k) if k > 0 else 0.5 * (lo + hi)
        elif rhi > 0:
            pn = hi * (target / rhi)
        else:
            pn = 0.5 * (lo + hi)
        if not (lo < pn < hi) or it % 5 == 4:
            pn = 0.5 * (lo + hi) if lo > 0 else min(0.5 * (lo + hi), pn if lo < pn < hi else 0.5 * hi)
        p = pn
    return best[1], best[2], best[3]


def plan(seed):
    rng = random.Random('plan-%d' % seed)
    cats = list(SHAPES)
    # 12 weak + 12 strong: four categories get 2 strong/1 weak, four get 1 strong/2 weak
    strong2 = set(rng.sample(cats, 4))
    trials = []
    for c in cats:
        st = ['strong', 'strong', 'weak'] if c in strong2 else ['strong', 'weak', 'weak']
        rng.shuffle(st)
        for shape, s in zip(SHAPES[c], st):
            trials.append(dict(category=c, shape=shape, strength=s))
    for _ in range(6):
        trials.append(dict(category='none', shape='none', strength='none'))
    rng.shuffle(trials)
    for k, t in enumerate(trials):
        t['tid'] = 't%02d' % (k + 1)
    return trials


def make_trial(args):
    seed, t = args
    import time
    t_start = time.time()
    rng = random.Random('trial-%d-%s' % (seed, t['tid']))
    shape = t['shape']
    ex = sample_extras(shape, rng)
    ends = ['rampdown', 'reversal', 'mid']
    for attempt in range(12):
        pool = TESTS[:]
        rng.shuffle(pool)
        nA = rng.choice([1, 1, 2])
        nB = rng.choice([1, 1, 2])
        tA, tB = pool[:nA], pool[nA:nA + nB]
        eA, eB = rng.sample(ends, 2)
        need_act = t['category'] == 'actuator_lag'
        dA = design_record(rng, tA, eA, need_act)
        dB = design_record(rng, tB, eB, need_act)
        inps = [build_inputs(dA), build_inputs(dB)]
        noise = round(rng.uniform(0.02, 0.06), 4)
        if shape == 'none':
            Fs = [run_record('none', 0.0, {}, inp) for inp in inps]
            p, ratio, target = 0.0, 0.0, 0.0
            break
        target = rng.uniform(2.7, 3.8) if t['strength'] == 'weak' else rng.uniform(8.5, 11.5)
        # lower the noise (within 0.02..0.06) if the effect cannot reach the target otherwise
        p, ratio, Fs = calibrate(shape, ex, inps, noise, target, P_MAX[shape])
        if p is None:
            rmax = ratio
            need = noise * rmax / target
            if need >= 0.02:
                noise = round(max(0.02, need * 0.9), 4)
                p, ratio, Fs = calibrate(shape, ex, inps, noise, target, P_MAX[shape])
        if p is not None and abs(ratio / target - 1) < 0.02:
            break
        print('  %s %s: retry design (ratio %.2f target %.2f)' % (t['tid'], shape, ratio, target),
              file=sys.stderr)
    else:
        raise RuntimeError('calibration failed for %s' % t)
    nrng = random.Random('noise-%d-%s' % (seed, t['tid']))
    out = {}
    for lab, d, inp, Fe in zip('AB', (dA, dB), inps, Fs):
        noisy = [f + nrng.gauss(0.0, noise) for f in Fe]
        out[lab] = dict(design=d, inp=inp, F=Fe, Fn=noisy)
    key = dict(category=t['category'], shape=shape, strength=t['strength'], noise_kip=noise,
               achieved_ratio=round(ratio, 4), p=p, extras=dict(ex, target_ratio=round(target, 4)),
               inputs={lab: describe(out[lab]['design'], out[lab]['inp']) for lab in 'AB'})
    print('  %s %s done in %.0f s (ratio %.3f target %.3f)' % (t['tid'], shape, time.time() - t_start, ratio, target),
          file=sys.stderr)
    return t['tid'], key, out


def record_json(inp, F):
    r = inp['rec']
    n = len(F)
    rows = []
    for i in range(n):
        t = i * DT
        rows.append([int(t) if t.is_integer() else t, r['x'][i], F[i], r['vcol'][i], r['a1'][i], r['a2'][i],
                     r['f1'][i], r['f2'][i]])
    return {"data": rows, "dt": DT, "sampling freq": FS_HZ, "displacement units": "in",
            "time units": "s", "friction force units": "kip", "actuator force units": "lb"}


def write_trial(outdir, tid, out, noisy=True):
    d = os.path.join(outdir, 'cases', tid)
    os.makedirs(d, exist_ok=True)
    for lab in 'AB':
        with open(os.path.join(d, lab + '.json'), 'w') as fh:
            json.dump(record_json(out[lab]['inp'], out[lab]['Fn'] if noisy else out[lab]['F']), fh)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--seed', type=int, default=11011)
    ap.add_argument('--out', required=True)
    ap.add_argument('--jobs', type=int, default=min(8, os.cpu_count() or 1))
    ap.add_argument('--only', default='', help='comma list of trial ids (debug)')
    a = ap.parse_args()
    params()
    for t in TESTS:
        source(t)
    trials = plan(a.seed)
    if a.only:
        trials = [t for t in trials if t['tid'] in a.only.split(',')]
    jobs = [(a.seed, t) for t in trials]
    if a.jobs > 1:
        import multiprocessing as mp
        with mp.Pool(a.jobs) as pool:
            res = pool.map(make_trial, jobs, chunksize=1)
    else:
        res = [make_trial(j) for j in jobs]
    key = {}
    for tid, k, out in res:
        write_trial(a.out, tid, out)
        key[tid] = k
        print('%s %-16s %-28s %-6s noise=%.4f ratio=%.3f p=%.5g' % (
            tid, k['category'], k['shape'], k['strength'], k['noise_kip'], k['achieved_ratio'], k['p']))
    key = dict(sorted(key.items()))
    with open(os.path.join(a.out, 'key.json'), 'w') as fh:
        json.dump(key, fh, indent=1)


if __name__ == '__main__':
    main()
