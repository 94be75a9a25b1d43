#!/usr/bin/env python3
"""Blind test-set generator for a BRFD model-discrepancy tool (blind12).

Python 3 standard library only.  Usage:

    python3 gen/gen.py --seed 12012 --out /work/blind12

writes OUT/cases/t01..t30/{A.json,B.json} and OUT/key.json.  Deterministic per seed.

Base model: semi-active LuGre model of the seed paper (Eqs. 1-5, Tables 1-2) with the
parameters of /work/runs/brfd-semiactive.yaml, reproducing the numerical conventions of
`hybridsim damper predict --no-fit` (found by experiment against its CSV output):
  * drum velocity = central differences of the displacement (one-sided at the two ends),
    then a 15-sample centred moving average whose window shrinks symmetrically at the
    ends (half-width min(7, i, n-1-i)), evaluated as a difference of running prefix sums
    (this reproduces the tool's last-digit rounding, e.g. -3e-14 where the exact value is 0);
  * z(0) = F_measured(0)/sigma0, no state update on sample 0;
  * for i >= 1 the bristle ODE is integrated exactly over dt with v, g held at sample i:
    z <- z_ss + (z - z_ss) exp(-a dt), a = sigma0 |v|/g, z_ss = v/a (no update if v == 0);
  * F_i = sigma0 z_i + sigma1 zdot_i + sigma2 v_i;
  * Fc of Eq. (4) uses the direction v >= 0 (forward) / v < 0, x' = first-row actuator
    positions, and is clipped below at fc_floor.
"""
import argparse
import json
import math
import os
import random
import sys
import time

DT = 1.0 / 1024.0
SRC_DIR = '/work/shared/data/brfd/semiactive'
SOURCES = ['harmonic0.03ea1forward', 'harmonic0.03ea1backward',
           'harmonic0.03ea2forward', 'harmonic0.03ea2backward',
           'harmonic0.015forward', 'harmonic0.015backward']
# Velocity-column quirk of the measured semi-active files: the column is ~1/125 of
# d(displacement)/dt.  Our records keep the quirk (column = derived velocity / 125.4).
VEL_QUIRK = 125.4

# Parameters of /work/runs/brfd-semiactive.yaml (hard-coded; verify.py checks them
# against the yaml text).
P = dict(s0=15.36, s1=0.0, s2=0.500, fsf=7.116, fsb=3.760, fcf=2.648, fcb=1.253,
         vs=1.300,
         m=[-0.14, -0.15, -15.29, -13.00, -16.66, -15.77, -0.13, -0.15],
         C=[119.68, 2.10, 1.94, 123.31], floor=0.05)
_m, _C = P['m'], P['C']
KF1 = _C[0] * _m[0] + _C[1] * _m[2]   # forward, d Fc / d x1
KF2 = _C[0] * _m[1] + _C[1] * _m[3]   # forward, d Fc / d x2
KB1 = _C[2] * _m[4] + _C[3] * _m[6]   # backward
KB2 = _C[2] * _m[5] + _C[3] * _m[7]

CATEGORIES = ['backlash', 'residual_static', 'actuator_lag', 'asymmetry', 'velocity',
              'pretension', 'self_energizing', 'transition_shape']
SHAPES = {
    'backlash': ['clearance_deadzone', 'driveline_play', 'engagement_dip'],
    'residual_static': ['rest_relaxation', 'travel_residual', 'log_creep'],
    'actuator_lag': ['first_order_lag', 'dead_time', 'second_order'],
    'asymmetry': ['kinetic_direction_scaling', 'stiffness_asymmetry', 'one_sided_breakaway'],
    'velocity': ['log_strengthening', 'power_viscous', 'thermal_weakening'],
    'pretension': ['travel_loss', 'thermal_tension', 'anchor_slip_step'],
    'self_energizing': ['capstan_wrap', 'tension_feedback', 'taut_band_spring'],
    'transition_shape': ['stribeck_exponent', 'dahl_shape', 'frictional_lag'],
}
WEAK = (2.7, 3.8)
STRONG = (8.5, 11.5)
NOISE = (0.02, 0.06)


# ----------------------------------------------------------------------------- utils
def r9(v):
    """Round to 9 significant digits (what is written to the file is what is simulated)."""
    return float('%.9g' % v)


def smooth01(u):
    """C1 smooth step 0 -> 1 on [0, 1]."""
    if u <= 0.0:
        return 0.0
    if u >= 1.0:
        return 1.0
    return 0.5 - 0.5 * math.cos(math.pi * u)


def derive_velocity(x, half=7):
    """Drum velocity: central differences + centred 15-sample moving average (shrinking
    symmetric window at the ends) -- the convention of `damper predict`."""
    n = len(x)
    cd = [0.0] * n
    cd[0] = (x[1] - x[0]) / DT
    cd[-1] = (x[-1] - x[-2]) / DT
    for i in range(1, n - 1):
        cd[i] = (x[i + 1] - x[i - 1]) / (2 * DT)
    # moving average through a running prefix sum (reproduces the tool's rounding:
    # e.g. -3.0e-14 instead of 0 at some samples, which decides the Fc direction there)
    C = [0.0] * (n + 1)
    acc = 0.0
    for k in range(n):
        acc += cd[k]
        C[k + 1] = acc
    v = [0.0] * n
    for i in range(n):
        h = min(half, i, n - 1 - i)
        v[i] = (C[i + h + 1] - C[i - h]) / (2 * h + 1)
    return v


def kinetic(v, a1, a2, x1p, x2p):
    """Eq. (4) per sample, clipped at fc_floor; returns Fc and Fs arrays."""
    fc = [0.0] * len(v)
    fs = [0.0] * len(v)
    fl = P['floor']
    for i, vi in enumerate(v):
        if vi >= 0:
            c = P['fcf'] + KF1 * (a1[i] - x1p) + KF2 * (a2[i] - x2p)
            fs[i] = P['fsf']
        else:
            c = P['fcb'] + KB1 * (a1[i] - x1p) + KB2 * (a2[i] - x2p)
            fs[i] = P['fsb']
        fc[i] = c if c > fl else fl
    return fc, fs


def stribeck(v, fc, fs, vs=None, expo=2.0, vstr=None):
    vs = P['vs'] if vs is None else vs
    vv = v if vstr is None else vstr
    if expo == 2.0:
        return [c + (s - c) * math.exp(-(w / vs) ** 2) for c, s, w in zip(fc, fs, vv)]
    return [c + (s - c) * math.exp(-abs(w / vs) ** expo) for c, s, w in zip(fc, fs, vv)]


def lugre_core(v, g, F0, k_pos=None, k_neg=None, dead=0.0, decay=None, creep=None,
               dahl=1.0, feedback=None):
    """Exact-exponential LuGre integration (base convention) with optional modifications.
    k_pos/k_neg: bristle stiffness for z > 0 / z <= 0 (default sigma0)
    dead:       half-width of a dead zone in the bristle spring (in)
    decay:      per-sample multiplicative factor on z after the update
    creep:      (p, tau_c): log-time growth of the held force at rest
    dahl:       exponent alpha of the approach to sliding (1 = LuGre)
    feedback:   (kind, p, tau, ref): slow state multiplying g
    """
    s0, s1, s2 = P['s0'], P['s1'], P['s2']
    kp = s0 if k_pos is None else k_pos
    kn = s0 if k_neg is None else k_neg
    n = len(v)
    out = [0.0] * n
    # initial state reproducing F0 (with sigma1 = 0 the first output is s0 z0 + s2 v0
    # in the base; we keep the spring force equal to F0)
    if F0 > 0:
        z = F0 / kp + dead
    elif F0 < 0:
        z = F0 / kn - dead
    else:
        z = 0.0
    t_rest = 0.0
    fb_state = 0.0
    if feedback is not None:
        fb_kind, fb_p, fb_tau, fb_ref = feedback
        fb_alpha = 1.0 - math.exp(-DT / fb_tau)
    exp = math.exp
    for i in range(n):
        vi = v[i]
        gi = g[i]
        if feedback is not None:
            gi = gi * (1.0 + fb_p * fb_state / fb_ref)
            if gi < 0.02:
                gi = 0.02
        if i > 0 and vi != 0.0:
            av = abs(vi)
            if dead == 0.0:
                k = kp if z > 0 else kn
                a = k * av / gi
                if dahl != 1.0:
                    u = (1.0 if vi > 0 else -1.0) * k * z / gi
                    q = abs(1.0 - u)
                    q = min(max(q, 1e-4), 1e4)
                    a *= q ** (dahl - 1.0)
                zss = vi / a if dahl == 1.0 else (gi / k if vi > 0 else -gi / k)
                z = zss + (z - zss) * exp(-a * DT)
            else:
                z = _dead_step(z, vi, gi, kp, kn, dead)
        if decay is not None:
            z *= decay[i]
        if creep is not None:
            if abs(vi) < 1e-3:
                t_rest += DT
                sgn = 1.0 if z > 0 else (-1.0 if z < 0 else 0.0)
                k = kp if z > 0 else kn
                z += sgn * creep[0] * DT / (k * (creep[1] + t_rest))
            else:
                t_rest = 0.0
        # spring force
        if dead == 0.0:
            fspr = (kp if z > 0 else kn) * z
        else:
            if z > dead:
                fspr = kp * (z - dead)
            elif z < -dead:
                fspr = kn * (z + dead)
            else:
                fspr = 0.0
        if s1 != 0.0:
            zd = vi - abs(vi) * fspr / gi
            F = fspr + s1 * zd + s2 * vi
        else:
            F = fspr + s2 * vi
        out[i] = F
        if feedback is not None:
            drive = abs(F) * abs(vi) if fb_kind == 'power' else abs(F)
            fb_state += fb_alpha * (drive - fb_state)
    return out


def _dead_step(z, vi, gi, kp, kn, c):
    """One exact step of dz/dt = v - |v| f(z)/g with a dead zone |z| <= c in f."""
    tl = DT
    av = abs(vi)
    for _ in range(4):
        if tl <= 0:
            break
        if z > c or (z == c and vi > 0):
            a = kp * av / gi
            zss = c + vi / a
            znew = zss + (z - zss) * math.exp(-a * tl)
            if znew >= c:
                return znew
            # reaches the boundary
            tb = math.log((z - zss) / (c - zss)) / a
            z = c
            tl -= tb
            if vi > 0:
                return z
            z = c - 1e-15
        elif z < -c or (z == -c and vi < 0):
            a = kn * av / gi
            zss = -c + vi / a
            znew = zss + (z - zss) * math.exp(-a * tl)
            if znew <= -c:
                return znew
            tb = math.log((z - zss) / (-c - zss)) / a
            z = -c
            tl -= tb
            if vi < 0:
                return z
            z = -c + 1e-15
        else:
            znew = z + vi * tl
            if -c <= znew <= c:
                return znew
            if znew > c:
                tl -= (c - z) / vi
                z = c
            else:
                tl -= (-c - z) / vi
                z = -c
    return z


def base_model(x, a1, a2, F0, v=None):
    """Noise-free base model; returns (v, F, fc)."""
    if v is None:
        v = derive_velocity(x)
    fc, fs = kinetic(v, a1, a2, a1[0], a2[0])
    g = stribeck(v, fc, fs)
    return v, lugre_core(v, g, F0), fc


def replay_file(path):
    """Replay a record file through the base model the way `damper predict --no-fit`
    does (z0 from the file's first force sample).  Returns (F_pred, F_meas, v, fc)."""
    d = json.load(open(path))['data']
    x = [r[1] for r in d]
    a1 = [r[4] for r in d]
    a2 = [r[5] for r in d]
    Fm = [r[2] for r in d]
    v, F, fc = base_model(x, a1, a2, Fm[0])
    return F, Fm, v, fc


def nrmse_line(Fp, Fm):
    n = len(Fm)
    rmse = math.sqrt(sum((a - b) ** 2 for a, b in zip(Fp, Fm)) / n)
    mu = sum(Fm) / n
    sd = math.sqrt(sum((a - mu) ** 2 for a in Fm) / n)
    rng = max(Fm) - min(Fm)
    return 'nrmse=%.4g rmse_kip=%.4g nrmse_range=%.4g' % (rmse / sd if sd > 0 else float('nan'),
                                                         rmse, rmse / rng if rng > 0 else float('nan'))


# ----------------------------------------------------------------------------- sources
_SRC = {}


def load_sources():
    for name in SOURCES:
        d = json.load(open(os.path.join(SRC_DIR, name + '.json')))['data']
        cols = list(zip(*d))
        s = dict(name=name, x=list(cols[1]), F=list(cols[2]), a1=list(cols[4]),
                 a2=list(cols[5]), f1=list(cols[6]), f2=list(cols[7]))
        n = len(d)
        act = [i for i in range(n) if abs(s['a1'][i] - s['a1'][0]) > 0.002
               or abs(s['a2'][i] - s['a2'][0]) > 0.002]
        s['act0'] = act[0] * DT
        s['act1'] = act[-1] * DT
        s['T'] = (n - 1) * DT
        # local extrema of the displacement (turning points) with |x| > 0.4
        xs = s['x']
        ext = []
        w = 60
        for i in range(w, n - w):
            xi = xs[i]
            if abs(xi) > 0.1:
                seg = xs[i - w:i + w + 1]
                if (xi > 0 and xi == max(seg)) or (xi < 0 and xi == min(seg)):
                    if not ext or i - ext[-1] > 2 * w:
                        ext.append(i)
        s['ext_all'] = [i * DT for i in ext]
        s['ext'] = [i * DT for i in ext if abs(xs[i]) > 0.4]
        _SRC[name] = s
    return _SRC


def sample(src, key, ts):
    arr = src[key]
    u = ts / DT
    i = int(math.floor(u))
    if i < 0:
        return arr[0]
    if i >= len(arr) - 1:
        return arr[-1]
    f = u - i
    return arr[i] + f * (arr[i + 1] - arr[i])


def take_piece(src, ts, te, r, mirror):
    """Samples of a source between source times ts and te, time-scaled by r (source
    seconds per record second) and optionally mirrored (drum direction reversed,
    actuator roles swapped about their nominal initial positions)."""
    n = int((te - ts) / (r * DT)) + 1
    out = {k: [] for k in ('x', 'a1', 'a2', 'f1', 'f2', 'F')}
    c1, c2 = 0.655, 0.8559
    for k in range(n):
        t = ts + k * r * DT
        x = sample(src, 'x', t)
        a1 = sample(src, 'a1', t)
        a2 = sample(src, 'a2', t)
        f1 = sample(src, 'f1', t)
        f2 = sample(src, 'f2', t)
        F = sample(src, 'F', t)
        if mirror:
            x, F = -x, -F
            a1, a2 = c1 + (a2 - c2), c2 + (a1 - c1)
            f1, f2 = f2, f1
        out['x'].append(x)
        out['a1'].append(a1)
        out['a2'].append(a2)
        out['f1'].append(f1)
        out['f2'].append(f2)
        out['F'].append(F)
    return out


# ----------------------------------------------------------------------------- records
END_KINDS = ['natural', 'brake', 'turnaround', 'post_reversal', 'return']


class Rec:
    def __init__(self):
        self.x, self.a1, self.a2, self.f1, self.f2 = [], [], [], [], []

    def hold(self, T):
        n = int(round(T / DT))
        for k in ('x', 'a1', 'a2', 'f1', 'f2'):
            arr = getattr(self, k)
            arr.extend([arr[-1]] * n)

    def n(self):
        return len(self.x)


def _find_time(src, lo, hi, cond, rng):
    """Random time in [lo, hi] (source s) where cond(src, t) holds (nearest after a random
    start, wrapping)."""
    cands = [k * 0.01 for k in range(int(lo * 100), int(hi * 100) + 1)]
    start = rng.randrange(len(cands))
    for j in range(len(cands)):
        t = cands[(start + j) % len(cands)]
        if cond(src, t):
            return t
    return cands[start]


def _start_time(src, rng):
    """Start of a cut: a turning point of the source (drum momentarily at rest) in the
    ramp-up before the first actuator motion."""
    c = [t for t in src['ext_all'] if 0.5 <= t <= src['act0'] - 0.4]
    return rng.choice(c)


def choose_cut(src, end_kind, lo, hi, rng):
    """Source time where the piece is cut for a given way of ending."""
    if end_kind == 'brake' or end_kind == 'return':
        # mid-stroke: near a zero crossing of x (fast sliding)
        def cond(s, t):
            return abs(sample(s, 'x', t)) < 0.15 and abs(sample(s, 'x', t + 0.05) -
                                                        sample(s, 'x', t - 0.05)) > 0.15
        return _find_time(src, lo, hi, cond, rng), 0.0
    ext = [t for t in src['ext'] if lo <= t <= hi]
    if not ext:
        ext = src['ext']
    t = rng.choice(ext)
    if end_kind == 'turnaround':
        return t, 0.0
    dtp = rng.uniform(0.03, 0.15)
    return t + dtp, dtp


def append_piece(rec, pc, T_in, rel_act):
    """Append a piece: displacement and actuator positions continue from the record's
    current (held) values; the displacement change fades in over T_in seconds."""
    x0r = rec.x[-1]
    a10r, a20r = rec.a1[-1], rec.a2[-1]
    xs0, a1s0, a2s0 = pc['x'][0], pc['a1'][0], pc['a2'][0]
    f10r, f20r = rec.f1[-1], rec.f2[-1]
    nin = max(1, int(T_in / DT))
    for k in range(len(pc['x'])):
        w = smooth01(k / nin)
        rec.x.append(x0r + w * (pc['x'][k] - xs0))
        if rel_act:
            rec.a1.append(a10r + (pc['a1'][k] - a1s0))
            rec.a2.append(a20r + (pc['a2'][k] - a2s0))
        else:
            rec.a1.append(pc['a1'][k])
            rec.a2.append(pc['a2'][k])
        wf = smooth01(k / 205.0)
        rec.f1.append((1 - wf) * f10r + wf * pc['f1'][k])
        rec.f2.append((1 - wf) * f20r + wf * pc['f2'][k])


def end_motion(rec, end_kind, rng, info):
    """Bring the drum to rest according to end_kind (actuators held from here)."""
    if end_kind == 'natural':
        # the source has decayed to (almost) rest: blend into a constant
        nb = int(0.25 / DT)
        xh = sum(rec.x[-64:]) / 64.0
        for k in ('a1', 'a2'):
            arr = getattr(rec, k)
            hv = sum(arr[-64:]) / 64.0
            for j in range(nb):
                w = smooth01((j + 1) / nb)
                arr[-nb + j] = (1 - w) * arr[-nb + j] + w * hv
        for j in range(nb):
            w = smooth01((j + 1) / nb)
            rec.x[-nb + j] = (1 - w) * rec.x[-nb + j] + w * xh
        info['brake_s'] = 0.25
        return
    ve = (rec.x[-1] - rec.x[-9]) / (8 * DT)
    if end_kind in ('turnaround',):
        Tb = rng.uniform(0.03, 0.06)
    elif end_kind == 'post_reversal':
        Tb = rng.uniform(0.04, 0.10)
    else:
        Tb = rng.uniform(0.08, 0.30)
    info['brake_s'] = round(Tb, 4)
    nb = int(Tb / DT)
    xe = rec.x[-1]
    for j in range(1, nb + 1):
        u = j / nb
        rec.x.append(xe + ve * Tb * 0.5 * (u + math.sin(math.pi * u) / math.pi))
        for k in ('a1', 'a2', 'f1', 'f2'):
            arr = getattr(rec, k)
            arr.append(arr[-1])
    if end_kind == 'return':
        rec.hold(rng.uniform(0.1, 0.5))
        Tr = rng.uniform(0.8, 2.0)
        xs = rec.x[-1]
        xt = xs * rng.uniform(-0.4, 0.3)
        info['return_s'] = round(Tr, 3)
        info['return_to_in'] = round(xt, 4)
        nr = int(Tr / DT)
        for j in range(1, nr + 1):
            rec.x.append(xs + (xt - xs) * smooth01(j / nr))
            for k in ('a1', 'a2', 'f1', 'f2'):
                arr = getattr(rec, k)
                arr.append(arr[-1])


def build_record(rng, srcs, end_kind):
    """One record from the source names srcs (1 or 2 sources)."""
    info = {'sources': list(srcs), 'end': end_kind}
    r = 1.0 if rng.random() < 0.6 else round(rng.uniform(0.75, 1.35), 3)
    mirror = rng.random() < 0.3
    info['time_scale'] = r
    info['mirrored'] = mirror
    s1 = _SRC[srcs[0]]
    rec = Rec()
    if len(srcs) == 1 and end_kind == 'natural':
        body = 'whole'
        ts = 0.0
        te = s1['T']
    elif len(srcs) == 1:
        body = 'cut'
        ts = _start_time(s1, rng) if rng.random() < 0.7 else 0.0
        te, dtp = choose_cut(s1, end_kind, s1['act0'] + 2.3, 13.6, rng)
    else:
        body = 'joined'
        ts = _start_time(s1, rng) if rng.random() < 0.6 else 0.0
        # piece 1 is cut at a turning point; piece 2 starts at a turning point of the same
        # sign and similar amplitude, so the join needs only a small offset
        te, dtp = choose_cut(s1, 'turnaround', s1['act0'] + 1.5, s1['act1'] + 1.0, rng)
    info['body'] = body
    pc = take_piece(s1, ts, te, r, mirror)
    # initial force: measured force of the source at the start of the piece
    F0 = sorted(pc['F'][:11])[5]
    F0 = max(-2.5, min(3.5, F0))
    info['F_init_kip'] = round(F0, 6)
    # start hold
    rec.x.append(pc['x'][0])
    rec.a1.append(pc['a1'][0])
    rec.a2.append(pc['a2'][0])
    rec.f1.append(pc['f1'][0])
    rec.f2.append(pc['f2'][0])
    T_h0 = rng.uniform(0.2, 0.6)
    rec.hold(T_h0 - DT)
    T_in = 0.1 if ts < 0.2 else rng.uniform(0.05, 0.15)
    append_piece(rec, pc, T_in, rel_act=False)
    pieces = [dict(src=s1['name'], t0=ts, t1=round(te, 4))]
    if body == 'joined':
        end_motion(rec, 'turnaround', rng, {})
        rec.hold(rng.uniform(0.3, 1.0))
        s2 = _SRC[srcs[1]]
        xh = rec.x[-1] * (-1 if mirror else 1)
        # start piece 2 at a turning point (before actuation) close to the held position
        cands = [t for t in s2['ext_all'] if 1.0 <= t <= s2['act0'] - 0.2]
        ts2 = min(cands, key=lambda t: abs(sample(s2, 'x', t) - xh))
        if end_kind == 'natural':
            te2 = s2['T']
        else:
            te2, dtp = choose_cut(s2, end_kind, s2['act0'] + 1.5, 13.6, rng)
        pc2 = take_piece(s2, ts2, te2, r, mirror)
        append_piece(rec, pc2, rng.uniform(0.05, 0.15), rel_act=True)
        pieces.append(dict(src=s2['name'], t0=ts2, t1=round(te2, 4)))
    info['pieces'] = pieces
    end_motion(rec, end_kind, rng, info)
    T_rest = rng.uniform(1.7, 3.0)
    rec.hold(T_rest)
    info['start_hold_s'] = round(T_h0, 3)
    info['end_rest_s'] = round(T_rest, 3)
    # quantize what is written == what is simulated
    rec.x = [r9(v) for v in rec.x]
    rec.a1 = [r9(v) for v in rec.a1]
    rec.a2 = [r9(v) for v in rec.a2]
    rec.f1 = [round(v, 6) for v in rec.f1]
    rec.f2 = [round(v, 6) for v in rec.f2]
    # force the final rest to be exactly constant
    nrest = int(round(T_rest / DT))
    for k in ('x', 'a1', 'a2', 'f1', 'f2'):
        arr = getattr(rec, k)
        c = arr[-1]
        for j in range(len(arr) - nrest - 1, len(arr)):
            arr[j] = c
    rec.F0 = round(F0, 8)
    rec.v = derive_velocity(rec.x)
    rec.t = [i * DT for i in range(rec.n())]
    info['duration_s'] = round((rec.n() - 1) * DT, 4)
    rec.info = info
    return rec


def write_record(path, rec, F):
    rows = []
    for i in range(rec.n()):
        t = rec.t[i]
        t = int(t) if t == int(t) else t
        rows.append([t, rec.x[i], round(F[i], 8), r9(rec.v[i] / VEL_QUIRK), rec.a1[i],
                     rec.a2[i], rec.f1[i], rec.f2[i]])
    obj = {"data": rows, "dt": DT, "sampling freq": 1024, "displacement units": "in",
           "time units": "s", "friction force units": "kip", "actuator force units": "lb"}
    with open(path, 'w') as f:
        json.dump(obj, f, separators=(', ', ': '))


# ----------------------------------------------------------------------------- effects
def _play(x, h, y0):
    y = [0.0] * len(x)
    yp = y0
    for i, xi in enumerate(x):
        if xi - yp > h:
            yp = xi - h
        elif yp - xi > h:
            yp = xi + h
        y[i] = yp
    return y


def _reversal_travel(x, d0, eps=0.002):
    """Travel since the last turning point (position-based detector, threshold eps)."""
    n = len(x)
    s = [0.0] * n
    d = d0 if d0 != 0 else 1
    ext = x[0]
    turn = None
    for i, xi in enumerate(x):
        if d > 0:
            if xi > ext:
                ext = xi
            elif ext - xi > eps:
                d = -1
                turn = ext
                ext = xi
        else:
            if xi < ext:
                ext = xi
            elif xi - ext > eps:
                d = 1
                turn = ext
                ext = xi
        s[i] = 1e9 if turn is None else abs(xi - turn)
    return s


def _lag1(a, tau):
    al = 1.0 - math.exp(-DT / tau)
    y = a[0]
    out = []
    for ai in a:
        y += al * (ai - y)
        out.append(y)
    return out


def _delay(a, T):
    m = T / DT
    out = []
    for i in range(len(a)):
        u = i - m
        if u <= 0:
            out.append(a[0])
        else:
            j = int(u)
            f = u - j
            out.append(a[j] + f * (a[min(j + 1, len(a) - 1)] - a[j]))
    return out


def _second_order(a, tn, zeta):
    wn = 1.0 / tn
    ns = max(1, int(math.ceil(wn * DT / 0.02)))
    h = DT / ns
    y, yd = a[0], 0.0
    out = []
    for ai in a:
        for _ in range(ns):
            ydd = wn * wn * (ai - y) - 2 * zeta * wn * yd
            yd += h * ydd
            y += h * yd
        out.append(y)
    return out


def _cum_travel(x):
    S = [0.0] * len(x)
    acc = 0.0
    for i in range(1, len(x)):
        acc += abs(x[i] - x[i - 1])
        S[i] = acc
    return S


def effect_force(rec, shape, p, q):
    """Force of base model + effect (noise-free).  p = amplitude (p = 0 gives the base
    model exactly), q = dict of extra shape parameters (for anchor_slip_step the
    record-specific step time is q['t_step'][rec.tag])."""
    x, a1, a2, v, F0 = rec.x, rec.a1, rec.a2, rec.v, rec.F0
    x1p, x2p = a1[0], a2[0]
    n = len(x)
    if p == 0.0 or shape == 'none':
        fc, fs = kinetic(v, a1, a2, x1p, x2p)
        return lugre_core(v, stribeck(v, fc, fs), F0)
    # ---- backlash
    if shape == 'clearance_deadzone':
        fc, fs = kinetic(v, a1, a2, x1p, x2p)
        return lugre_core(v, stribeck(v, fc, fs), F0, dead=p / 2.0)
    if shape == 'driveline_play':
        h = p / 2.0
        # contact on the side of the initial force: y = x - h sgn(F0)
        y0 = x[0] - h * (1 if F0 >= 0 else -1)
        y = _play(x, h, y0)
        vy = derive_velocity(y)
        fc, fs = kinetic(vy, a1, a2, x1p, x2p)
        g = stribeck(vy, fc, fs)
        ell = q['relax_len_in']
        dec = [1.0] * n
        for i in range(1, n):
            if y[i] == y[i - 1] and x[i] != x[i - 1]:
                dec[i] = math.exp(-abs(x[i] - x[i - 1]) / ell)
        return lugre_core(vy, g, F0, decay=dec)
    if shape == 'engagement_dip':
        fc, fs = kinetic(v, a1, a2, x1p, x2p)
        F = lugre_core(v, stribeck(v, fc, fs), F0)
        s = _reversal_travel(x, 1 if F0 >= 0 else -1)
        lam = q['lambda_in']
        out = []
        for Fi, si in zip(F, s):
            u = si / lam
            psi = u * u * math.exp(2.0 * (1.0 - u)) if u < 40 else 0.0
            out.append(Fi * (1.0 - p * psi))
        return out
    # ---- residual static
    if shape == 'rest_relaxation':
        fc, fs = kinetic(v, a1, a2, x1p, x2p)
        vr = q['v_r']
        dec = [math.exp(-DT * p * math.exp(-(vi / vr) ** 2)) for vi in v]
        return lugre_core(v, stribeck(v, fc, fs), F0, decay=dec)
    if shape == 'travel_residual':
        fc, fs = kinetic(v, a1, a2, x1p, x2p)
        F = lugre_core(v, stribeck(v, fc, fs), F0)
        S = _cum_travel(x)
        al = 1.0 - math.exp(-DT / q['tau_e'])
        e = 0.0
        out = []
        for i in range(n):
            e += al * (abs(v[i]) - e)
            R = math.exp(-(e / q['e_r']) ** 2)
            out.append(F[i] + p * (1.0 - math.exp(-S[i] / q['S0'])) * R)
        return out
    if shape == 'log_creep':
        fc, fs = kinetic(v, a1, a2, x1p, x2p)
        return lugre_core(v, stribeck(v, fc, fs), F0, creep=(p, q['tau_c']))
    # ---- actuator lag: the band sees lagged actuator positions
    if shape in ('first_order_lag', 'dead_time', 'second_order'):
        if shape == 'first_order_lag':
            b1, b2 = _lag1(a1, p), _lag1(a2, p)
        elif shape == 'dead_time':
            b1, b2 = _delay(a1, p), _delay(a2, p)
        else:
            b1, b2 = _second_order(a1, p, q['zeta']), _second_order(a2, p, q['zeta'])
        fc, fs = kinetic(v, b1, b2, x1p, x2p)
        return lugre_core(v, stribeck(v, fc, fs), F0)
    # ---- asymmetry
    if shape == 'kinetic_direction_scaling':
        fc, fs = kinetic(v, a1, a2, x1p, x2p)
        fc = [max(P['floor'], c * (1.0 + p if vi >= 0 else 1.0 - p)) for c, vi in zip(fc, v)]
        return lugre_core(v, stribeck(v, fc, fs), F0)
    if shape == 'stiffness_asymmetry':
        fc, fs = kinetic(v, a1, a2, x1p, x2p)
        kstiff, ksoft = P['s0'] * (1.0 + p), P['s0'] / (1.0 + p)
        if q['stiff_side'] > 0:
            kp, kn = kstiff, ksoft
        else:
            kp, kn = ksoft, kstiff
        return lugre_core(v, stribeck(v, fc, fs), F0, k_pos=kp, k_neg=kn)
    if shape == 'one_sided_breakaway':
        fc, fs = kinetic(v, a1, a2, x1p, x2p)
        g = stribeck(v, fc, fs)
        d, vb = q['direction'], q['v_b']
        g = [gi + (p * math.exp(-(vi / vb) ** 2) if (vi >= 0) == (d > 0) else 0.0)
             for gi, vi in zip(g, v)]
        return lugre_core(v, g, F0)
    # ---- velocity
    if shape == 'log_strengthening':
        fc, fs = kinetic(v, a1, a2, x1p, x2p)
        g = stribeck(v, fc, fs)
        g = [gi * (1.0 + p * math.log(1.0 + abs(vi) / q['v_ref'])) for gi, vi in zip(g, v)]
        return lugre_core(v, g, F0)
    if shape == 'power_viscous':
        fc, fs = kinetic(v, a1, a2, x1p, x2p)
        F = lugre_core(v, stribeck(v, fc, fs), F0)
        al, sg = q['alpha'], q['sign']
        return [Fi + sg * p * math.copysign(abs(vi) ** al, vi) for Fi, vi in zip(F, v)]
    if shape == 'thermal_weakening':
        fc, fs = kinetic(v, a1, a2, x1p, x2p)
        vh = q['v_h']
        fc = [max(P['floor'], c * (1.0 - p * (vi / vh) ** 2 / (1.0 + (vi / vh) ** 2)))
              for c, vi in zip(fc, v)]
        return lugre_core(v, stribeck(v, fc, fs), F0)
    # ---- pretension (clamping level: scales Fs and Fc together)
    if shape in ('travel_loss', 'anchor_slip_step', 'capstan_wrap'):
        fc, fs = kinetic(v, a1, a2, x1p, x2p)
        g = stribeck(v, fc, fs)
        if shape == 'travel_loss':
            S = _cum_travel(x)
            k = [1.0 - p * (1.0 - math.exp(-Si / q['S0'])) for Si in S]
        elif shape == 'anchor_slip_step':
            ts, w = q['t_step'][rec.tag], q['width_s']
            sg = q['sign']
            k = [1.0 + sg * p / (1.0 + math.exp(-max(-60.0, min(60.0, (t - ts) / w))))
                 for t in rec.t]
        else:  # capstan_wrap: Euler-Eytelwein gain on the wrap-angle change
            xr = x[0]
            k = [math.exp(max(-3.0, min(3.0, p * (1 if vi >= 0 else -1) * (xi - xr))))
                 for xi, vi in zip(x, v)]
        g = [max(0.02, gi * ki) for gi, ki in zip(g, k)]
        return lugre_core(v, g, F0)
    if shape == 'thermal_tension':
        fc, fs = kinetic(v, a1, a2, x1p, x2p)
        return lugre_core(v, stribeck(v, fc, fs), F0,
                          feedback=('power', p, q['tau_c'], 5.0))
    # ---- self-energizing
    if shape == 'tension_feedback':
        fc, fs = kinetic(v, a1, a2, x1p, x2p)
        return lugre_core(v, stribeck(v, fc, fs), F0,
                          feedback=('force', p, q['tau_b'], 3.0))
    if shape == 'taut_band_spring':
        fc, fs = kinetic(v, a1, a2, x1p, x2p)
        F = lugre_core(v, stribeck(v, fc, fs), F0)
        xr, rho = x[0], q['rho']
        if q['stiff_side'] > 0:
            kf, kb = p, p * rho
        else:
            kf, kb = p * rho, p
        return [Fi + (kf * (xi - xr) if xi > xr else kb * (xi - xr)) for Fi, xi in zip(F, x)]
    # ---- transition shape
    if shape == 'stribeck_exponent':
        fc, fs = kinetic(v, a1, a2, x1p, x2p)
        ex = 2.0 * (1.0 + p) if q['sign'] > 0 else 2.0 / (1.0 + p)
        return lugre_core(v, stribeck(v, fc, fs, expo=ex), F0)
    if shape == 'dahl_shape':
        fc, fs = kinetic(v, a1, a2, x1p, x2p)
        al = 1.0 + p if q['sign'] > 0 else 1.0 / (1.0 + p)
        return lugre_core(v, stribeck(v, fc, fs), F0, dahl=al)
    if shape == 'frictional_lag':
        fc, fs = kinetic(v, a1, a2, x1p, x2p)
        vl = _lag1(v, p)
        return lugre_core(v, stribeck(v, fc, fs, vstr=vl), F0)
    raise ValueError(shape)


P_MAX = {
    'clearance_deadzone': 0.8, 'driveline_play': 0.8, 'engagement_dip': 0.98,
    'rest_relaxation': 30.0, 'travel_residual': 5.0, 'log_creep': 3.0,
    'first_order_lag': 3.0, 'dead_time': 1.5, 'second_order': 1.0,
    'kinetic_direction_scaling': 0.7, 'stiffness_asymmetry': 4.0, 'one_sided_breakaway': 20.0,
    'log_strengthening': 2.0, 'power_viscous': 3.0, 'thermal_weakening': 0.9,
    'travel_loss': 0.8, 'thermal_tension': 3.0, 'anchor_slip_step': 0.8,
    'capstan_wrap': 1.5, 'tension_feedback': 1.5, 'taut_band_spring': 5.0,
    'stribeck_exponent': 4.0, 'dahl_shape': 4.0, 'frictional_lag': 0.8,
}


def draw_extras(shape, rng, recs):
    q = {}
    if shape == 'driveline_play':
        q['relax_len_in'] = round(rng.uniform(0.01, 0.03), 4)
    elif shape == 'engagement_dip':
        q['lambda_in'] = round(rng.uniform(0.08, 0.20), 4)
    elif shape == 'rest_relaxation':
        q['v_r'] = round(rng.uniform(0.02, 0.10), 4)
    elif shape == 'travel_residual':
        q['S0'] = round(rng.uniform(3.0, 15.0), 3)
        q['tau_e'] = 0.25
        q['e_r'] = 0.05
        q['sign'] = 1 if rng.random() < 0.7 else -1
    elif shape == 'log_creep':
        q['tau_c'] = round(rng.uniform(0.02, 0.2), 4)
    elif shape == 'second_order':
        q['zeta'] = round(rng.uniform(0.15, 0.45), 3)
    elif shape == 'kinetic_direction_scaling':
        q['sign'] = rng.choice([1, -1])
    elif shape == 'stiffness_asymmetry':
        q['stiff_side'] = rng.choice([1, -1])
    elif shape == 'one_sided_breakaway':
        q['direction'] = rng.choice([1, -1])
        q['v_b'] = round(rng.uniform(0.5, 1.2), 4)
    elif shape == 'log_strengthening':
        q['v_ref'] = round(rng.uniform(0.1, 0.8), 4)
    elif shape == 'power_viscous':
        q['alpha'] = round(rng.uniform(0.3, 0.7) if rng.random() < 0.5 else rng.uniform(1.5, 2.2), 3)
        q['sign'] = rng.choice([1, -1])
    elif shape == 'thermal_weakening':
        q['v_h'] = round(rng.uniform(0.8, 2.5), 4)
    elif shape == 'travel_loss':
        q['S0'] = round(rng.uniform(4.0, 15.0), 3)
    elif shape == 'thermal_tension':
        q['tau_c'] = round(rng.uniform(3.0, 10.0), 3)
        q['power_ref_kip_in_per_s'] = 5.0
    elif shape == 'anchor_slip_step':
        q['sign'] = -1 if rng.random() < 0.7 else 1
        q['width_s'] = round(rng.uniform(0.05, 0.3), 4)
        q['t_step'] = {}
        for rec in recs:
            # inside the moving part of the record
            T = rec.t[-1]
            q['t_step'][rec.tag] = round(rng.uniform(0.25, 0.65) * T, 4)
    elif shape == 'tension_feedback':
        q['tau_b'] = round(rng.uniform(0.1, 0.5), 4)
        q['force_ref_kip'] = 3.0
    elif shape == 'taut_band_spring':
        q['rho'] = round(rng.uniform(0.3, 1.0), 4)
        q['stiff_side'] = rng.choice([1, -1])
    elif shape == 'stribeck_exponent':
        q['sign'] = rng.choice([1, -1])
    elif shape == 'dahl_shape':
        q['sign'] = rng.choice([1, -1])
    return q


def _eff(rec, shape, p, q):
    if shape == 'travel_residual':
        p = p * q['sign']
    if shape == 'kinetic_direction_scaling':
        p = p * q['sign']
    return effect_force(rec, shape, p, q)


def ratio_of(recs, bases, shape, p, q, sd):
    s2 = 0.0
    n = 0
    for rec, Fb in zip(recs, bases):
        Fe = _eff(rec, shape, p, q)
        s2 += sum((a - b) ** 2 for a, b in zip(Fe, Fb))
        n += len(Fb)
    return math.sqrt(s2 / n) / sd


def calibrate(recs, bases, shape, q, sd, target, tol=0.001):
    """Smallest-bracket amplitude p with ratio(p) = target.  Returns (p, ratio, evals)
    or (None, max_ratio, evals) when target is not reachable below P_MAX."""
    pmax = P_MAX[shape]
    f = lambda p: ratio_of(recs, bases, shape, p, q, sd)
    ev = 0
    p = pmax / 32.0
    r = f(p); ev += 1
    lo = hi = None
    if r < target:
        lo = (p, r)
        while True:
            p2 = min(pmax, p * 2.0)
            r2 = f(p2); ev += 1
            if r2 >= target:
                hi = (p2, r2)
                break
            lo = (p2, r2)
            if p2 >= pmax:
                return None, r2, ev
            p = p2
    else:
        hi = (p, r)
        while True:
            p2 = p / 2.0
            r2 = f(p2); ev += 1
            if r2 < target:
                lo = (p2, r2)
                break
            hi = (p2, r2)
            p = p2
            if p < pmax * 1e-7:
                return None, r2, ev
    # Illinois regula falsi in log p / log r
    (pa, ra), (pb, rb) = lo, hi
    side = 0
    best = hi
    for _ in range(30):
        la, lb = math.log(pa), math.log(pb)
        fa = math.log(max(ra, 1e-12)) - math.log(target)
        fb = math.log(rb) - math.log(target)
        if side == -1:
            fa *= 0.5
        elif side == 1:
            fb *= 0.5
        lp = lb - fb * (lb - la) / (fb - fa) if fb != fa else 0.5 * (la + lb)
        if not (min(la, lb) < lp < max(la, lb)):
            lp = 0.5 * (la + lb)
        pc = math.exp(lp)
        rc = f(pc); ev += 1
        if abs(rc / target - 1.0) < tol:
            return pc, rc, ev
        if rc < target:
            pa, ra = pc, rc
            side = 1
        else:
            pb, rb = pc, rc
            side = -1
        best = (pc, rc)
    return best[0], best[1], ev


# ----------------------------------------------------------------------------- main
def plan(rng):
    """Trial plan: categories/shapes/strengths and record sources & endings."""
    trials = []
    for cat in CATEGORIES:
        for shp in SHAPES[cat]:
            trials.append(dict(category=cat, shape=shp))
    strengths = ['weak'] * 12 + ['strong'] * 12
    rng.shuffle(strengths)
    for tr, s in zip(trials, strengths):
        tr['strength'] = s
    for _ in range(6):
        trials.append(dict(category='none', shape='none', strength='none'))
    rng.shuffle(trials)
    for k, tr in enumerate(trials):
        tr['id'] = 't%02d' % (k + 1)
        srcs = SOURCES[:]
        rng.shuffle(srcs)
        kinds = END_KINDS[:]
        rng.shuffle(kinds)
        eA, eB = kinds[0], kinds[1]
        nA = 2 if rng.random() < 0.3 else 1
        nB = 2 if rng.random() < 0.3 else 1
        tr['srcA'] = srcs[:nA]
        tr['srcB'] = srcs[nA:nA + nB]
        tr['endA'], tr['endB'] = eA, eB
    return trials


def generate(seed, out, noise_free_none=False, only=None, log=sys.stderr, write=True):
    t0 = time.time()
    load_sources()
    rng = random.Random(seed)
    trials = plan(rng)
    key = {}
    made = {}
    for tr in trials:
        tid = tr['id']
        trng = random.Random('%d-%s' % (seed, tid))
        recA = build_record(trng, tr['srcA'], tr['endA'])
        recB = build_record(trng, tr['srcB'], tr['endB'])
        recA.tag, recB.tag = 'A', 'B'
        recs = [recA, recB]
        shape = tr['shape']
        if only is not None and tid not in only:
            # keep the RNG stream identical: draw what would be drawn
            pass
        bases = [effect_force(r, 'none', 0.0, {}) for r in recs]
        entry = dict(category=tr['category'], shape=shape, strength=tr['strength'])
        if shape == 'none':
            sd = round(trng.uniform(*NOISE), 5)
            p, target, achieved, q, ev = 0.0, 0.0, 0.0, {}, 0
            forces = bases
        else:
            for attempt in range(8):
                sd = round(trng.uniform(*NOISE), 5)
                target = round(trng.uniform(*(WEAK if tr['strength'] == 'weak' else STRONG)), 4)
                q = draw_extras(shape, trng, recs)
                if only is not None and tid not in only:
                    p = None
                    break
                p, achieved, ev = calibrate(recs, bases, shape, q, sd, target)
                if p is not None:
                    break
                print('  %s %s: target %.2f unreachable (max %.2f), redraw' %
                      (tid, shape, target, achieved), file=log)
            if p is None and (only is None or tid in only):
                raise RuntimeError('calibration failed for %s %s' % (tid, shape))
            if p is not None:
                forces = [_eff(r, shape, p, q) for r in recs]
                entry['calibration_evals'] = ev
        entry.update(p=p, noise_kip=sd, target_ratio=target,
                     achieved_ratio=round(achieved, 4) if p is not None else None)
        # signed amplitude actually applied for shapes with a sign parameter
        if shape in ('travel_residual', 'kinetic_direction_scaling') and p is not None:
            entry['p_signed'] = p * q['sign']
        entry['params'] = q
        entry['records'] = {'A': recA.info, 'B': recB.info}
        key[tid] = entry
        if only is not None and tid not in only:
            continue
        # noise
        nrng = random.Random('%d-%s-noise' % (seed, tid))
        noisy = []
        for rec, F in zip(recs, forces):
            if noise_free_none and shape == 'none':
                noisy.append(list(F))
            else:
                noisy.append([Fi + nrng.gauss(0.0, sd) for Fi in F])
        made[tid] = (recs, forces, noisy)
        if write:
            d = os.path.join(out, 'cases', tid)
            os.makedirs(d, exist_ok=True)
            for rec, Fn, tag in zip(recs, noisy, 'AB'):
                write_record(os.path.join(d, tag + '.json'), rec, Fn)
        print('%s %-16s %-26s %-6s p=%-10.4g sd=%.4f target=%.3f got=%s  (%.1fs)' %
              (tid, tr['category'], shape, tr['strength'], p if p is not None else float('nan'),
               sd, target, entry['achieved_ratio'], time.time() - t0), file=log)
    if write:
        with open(os.path.join(out, 'key.json'), 'w') as f:
            json.dump(key, f, indent=1, sort_keys=True)
    return key, made


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--seed', type=int, default=12012)
    ap.add_argument('--out', default='/work/blind12')
    a = ap.parse_args()
    t0 = time.time()
    generate(a.seed, a.out)
    print('done in %.1f s' % (time.time() - t0), file=sys.stderr)


if __name__ == '__main__':
    main()
