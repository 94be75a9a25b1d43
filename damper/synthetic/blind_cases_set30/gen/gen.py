#!/usr/bin/env python3
"""blind30 generator: synthetic 'measured' semi-active BRFD records = base model + ONE hidden
effect (or none) + white Gaussian noise, quantised like the measured force.

Python 3 standard library only.  Master seed 30030.

Usage:  python3 gen/gen.py            (writes ../cases/t01..t30/{A,B}.json and ../key.json)
        python3 gen/gen.py --jobs 1   (no worker processes)

Layout of a record (same as /work/shared/data/brfd/semiactive/*.json):
  {"data": [[t, x_drum(in), F(kip), vel_col, x_act1(in), x_act2(in), F_act1(lb), F_act2(lb)], ...],
   "dt": 0.0009765625, "sampling freq": 1024, "displacement units": "in", "time units": "s",
   "friction force units": "kip", "actuator force units": "lb"}
The velocity column reproduces the quirk of the measured files (about 1/125 of dx/dt).
"""
import json
import math
import os
import random
import struct
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)                      # /work/blind30
DATA_DIR = '/work/shared/data/brfd/semiactive'
SOURCE_FILES = ['harmonic0.015backward.json', 'harmonic0.015forward.json',
                'harmonic0.03ea1backward.json', 'harmonic0.03ea1forward.json',
                'harmonic0.03ea2backward.json', 'harmonic0.03ea2forward.json']
MASTER_SEED = 30030
FS = 1024
DT = 1.0 / FS

# ---------------------------------------------------------------------------------------------
# Base model parameters: /work/main/configs/brfd-semiactive.yaml (--no-fit values)
# ---------------------------------------------------------------------------------------------
P = dict(
    sigma0=15.36, sigma1=0.0, sigma2=0.500,
    fs_fwd=7.116, fs_bwd=3.760, fc_fwd=2.648, fc_bwd=1.253, vs=1.300,
    slopes=[-0.14, -0.15, -15.29, -13.00, -16.66, -15.77, -0.13, -0.15],
    scaling=[119.68, 2.10, 1.94, 123.31],
    fc_floor=0.05,
)
_m = P['slopes']
_C = P['scaling']
# Eq. (4) coefficients (kip of Fc per inch of actuator travel)
K_FWD = (_C[0] * _m[0] + _C[1] * _m[2], _C[0] * _m[1] + _C[1] * _m[3])   # v >= 0
K_BWD = (_C[2] * _m[4] + _C[3] * _m[6], _C[2] * _m[5] + _C[3] * _m[7])   # v <  0

# quantisation steps seen in the measured files
Q_FORCE = 0.0008008799604     # kip (force values are integer multiples of this)
Q_DISP = 5.891974e-05         # in
Q_ACT = 2.44140625e-06        # in (0.01/4096)
Q_F1 = 0.31793998             # lb, actuator 1 load cell
Q_F2 = 0.39995                # lb, actuator 2 load cell
VEL_COL_FACTOR = 125.4        # measured velocity column ~ (dx/dt) / 125.4, lagging ~5 samples


def f32(v):
    return struct.unpack('f', struct.pack('f', v))[0]


# =============================================================================================
# Measured material: drum half-cycles, rest noise, actuator bursts
# =============================================================================================
_LIB = None


def _smooth(a, w):
    n = len(a)
    cs = [0.0]
    for v in a:
        cs.append(cs[-1] + v)
    out = []
    for i in range(n):
        lo = max(0, i - w)
        hi = min(n, i + w + 1)
        out.append((cs[hi] - cs[lo]) / (hi - lo))
    return out


def _extrema(xs, h=0.03):
    """peak/valley indices with hysteresis h (in)."""
    n = len(xs)
    ext = [0]
    mode = None
    cand = 0
    for i in range(1, n):
        if mode is None:
            if xs[i] > xs[0] + h:
                mode = 'up'; cand = i
            elif xs[i] < xs[0] - h:
                mode = 'down'; cand = i
            continue
        if mode == 'up':
            if xs[i] > xs[cand]:
                cand = i
            elif xs[i] < xs[cand] - h:
                ext.append(cand); mode = 'down'; cand = i
        else:
            if xs[i] < xs[cand]:
                cand = i
            elif xs[i] > xs[cand] + h:
                ext.append(cand); mode = 'up'; cand = i
    # end of motion: last sample still more than 3 mils away from the final resting value
    xend = sum(xs[-300:]) / 300.0
    last = max(i for i in range(n) if abs(xs[i] - xend) > 0.003)
    if last > ext[-1] + 50:
        ext.append(last)
    return ext


def load_library():
    global _LIB
    if _LIB is not None:
        return _LIB
    lib = dict(halfcycles=[], rest_x=[], rest_a=[], bursts=[], files=[])
    for name in SOURCE_FILES:
        with open(os.path.join(DATA_DIR, name)) as fh:
            d = json.load(fh)
        D = d['data']
        x = [r[1] for r in D]
        a1 = [r[4] for r in D]
        a2 = [r[5] for r in D]
        xs = _smooth(x, 25)
        E = _extrema(xs)
        fi = len(lib['files'])
        lib['files'].append(dict(name=name, x=x, a1=a1, a2=a2, E=E, x1p=a1[0], x2p=a2[0]))
        for j in range(len(E) - 1):
            lib['halfcycles'].append((fi, j))
        # drum rest noise: tail after the motion ended (detrended)
        i0 = E[-1] + 150
        tail = x[i0:]
        m = len(tail)
        tm = (m - 1) / 2.0
        xm = sum(tail) / m
        sl = sum((k - tm) * (tail[k] - xm) for k in range(m)) / sum((k - tm) ** 2 for k in range(m))
        lib['rest_x'].append([tail[k] - xm - sl * (k - tm) for k in range(m)])
        # actuator bursts (deviation from the first-row position), 0.15 s margins
        moving = []
        for ci, arr in ((1, a1), (2, a2)):
            x0 = arr[0]
            idx = [i for i in range(len(arr)) if abs(arr[i] - x0) > 0.0005]
            if not idx:
                continue
            moving.append(ci)
            grp = [[idx[0], idx[0]]]
            for i in idx[1:]:
                if i - grp[-1][1] > 200:
                    grp.append([i, i])
                else:
                    grp[-1][1] = i
            for g0, g1 in grp:
                lib['bursts'].append(dict(file=fi, act=ci, i0=max(0, g0 - 150), i1=min(len(arr), g1 + 150)))
        # actuator rest noise: samples of a non-moving actuator (or before the first burst)
        for ci, arr in ((1, a1), (2, a2)):
            x0 = arr[0]
            seg = arr[:int(3.4 * FS)]
            lib['rest_a'].append([v - x0 for v in seg])
    # merge bursts of files where both actuators move together (0.015 files): same window
    merged = []
    for b in lib['bursts']:
        f = lib['files'][b['file']]
        both = f['name'].startswith('harmonic0.015')
        if both and b['act'] == 2:
            continue
        merged.append(dict(file=b['file'], acts=(1, 2) if both else (b['act'],), i0=b['i0'], i1=b['i1']))
    lib['bursts'] = merged
    _LIB = lib
    return lib


def _interp(arr, pos):
    i = int(pos)
    if i >= len(arr) - 1:
        return arr[-1]
    if i < 0:
        return arr[0]
    fr = pos - i
    return arr[i] * (1.0 - fr) + arr[i + 1] * fr


def _noise_slice(pool, n, rng):
    """n samples of measured rest noise: random offset, mirrored tiling (no jumps)."""
    m = len(pool)
    out = []
    k = rng.randrange(m)
    step = 1 if rng.random() < 0.5 else -1
    while len(out) < n:
        out.append(pool[k])
        k += step
        if k >= m:
            k = m - 1; step = -1
        elif k < 0:
            k = 0; step = 1
    return out


# =============================================================================================
# Motion design
# =============================================================================================
X_LIMIT = 1.3       # in (travel limit)
X_SOFT = 1.22       # keep a margin for noise
V_MAX = 3.6         # in/s peak drum speed allowed after scaling/stretching


def build_motion(rng, T_target, act_moves, act_intensity=1.0, rest_bias=1.0):
    """Drum displacement and actuator positions for one record.

    act_moves: whether the electric actuators move in this record.
    act_intensity: >1 places more (and larger) actuator bursts (used to give actuator-sensitive
                   effects enough excitation; still inside re-cut/scaled measured bursts).
    rest_bias: scales the probability/length of rests between strokes.
    Returns dict(x=[...] (unquantised), rest=[bool], a1=[...], a2=[...], x1p, x2p, blocks=[...]).
    """
    lib = load_library()
    files = lib['files']
    x = []
    rest = []
    blocks = []
    motion_spans = []
    pos = rng.uniform(-0.25, 0.25)
    rpool = lib['rest_x'][rng.randrange(len(lib['rest_x']))]

    def add_rest(dur):
        n = max(1, int(round(dur * FS)))
        nz = _noise_slice(rpool, n, rng)
        for k in range(n):
            x.append(pos + nz[k])
            rest.append(True)

    def move_to(target, speed):
        # reposition stroke: half-cosine move with the given peak speed (in/s)
        nonlocal pos
        dist = target - pos
        if abs(dist) < 1e-6:
            return
        dur = max(0.4, math.pi * abs(dist) / (2.0 * speed))
        n = int(round(dur * FS))
        nz = _noise_slice(rpool, n, rng)
        i_start = len(x)
        for k in range(1, n + 1):
            x.append(pos + dist * 0.5 * (1.0 - math.cos(math.pi * k / n)) + nz[k - 1])
            rest.append(False)
        motion_spans.append((i_start, len(x)))
        blocks.append(dict(kind='reposition', t0=i_start / FS, dur=n / FS, dx=round(dist, 4)))
        pos = target

    add_rest(rng.uniform(0.3, 1.4))
    guard = 0
    while len(x) < (T_target - 0.9) * FS and guard < 200:
        guard += 1
        remaining = T_target - 0.7 - len(x) / FS
        hcs = lib['halfcycles']
        fi, j = hcs[rng.randrange(len(hcs))]
        f = files[fi]
        E = f['E']
        mmax = len(E) - 1 - j
        m = rng.randint(1, min(6, mmax))
        s = rng.uniform(0.35, 1.25) * (1 if rng.random() < 0.8 else -1)
        k = rng.uniform(0.7, 2.3)
        i0 = E[j]
        i1 = E[j + m]
        src = f['x']
        x0 = src[i0]
        # peak speed of the source block
        vmax = 0.0
        for i in range(i0 + 8, i1 - 8, 8):
            vmax = max(vmax, abs(src[i + 8] - src[i - 8]) / (16 * DT))
        if abs(s) * vmax / k > V_MAX:
            k = abs(s) * vmax / V_MAX
        dur = (i1 - i0) * DT * k
        if dur > remaining:
            # shorten to fewer half-cycles if possible
            ok = False
            for mm in range(m - 1, 0, -1):
                i1 = E[j + mm]
                dur = (i1 - i0) * DT * k
                if dur <= remaining:
                    m = mm; ok = True
                    break
            if not ok:
                if remaining < 1.2:
                    break
                continue
        # displacement range of the block relative to its start
        rel = [src[i] - x0 for i in range(i0, i1 + 1, 16)]
        lo = min(rel) * s if s > 0 else max(rel) * s
        hi = max(rel) * s if s > 0 else min(rel) * s
        lo, hi = min(lo, hi), max(lo, hi)
        if hi - lo > 2 * X_SOFT:
            continue
        if pos + lo < -X_SOFT or pos + hi > X_SOFT:
            # reposition so that the block fits, at a realistic speed (only if it all fits in time)
            target = rng.uniform(-X_SOFT - lo, X_SOFT - hi)
            spd = rng.uniform(0.4, 1.6)
            mdur = max(0.4, math.pi * abs(target - pos) / (2.0 * spd))
            rdur = rng.uniform(0.2, 1.0) if rng.random() < 0.6 * rest_bias else 0.0
            if dur + mdur + rdur > remaining:
                if remaining < 1.2:
                    break
                continue
            move_to(target, spd)
            if rdur > 0:
                add_rest(rdur)
        n = int(round((i1 - i0) * k))
        i_start = len(x)
        for q in range(n + 1):
            sp = i0 + q / k
            x.append(pos + s * (_interp(src, sp) - x0))
            rest.append(False)
        motion_spans.append((i_start, len(x)))
        blocks.append(dict(kind='recut', src=f['name'], halfcycles=[j, j + m], t0=round(i_start / FS, 3),
                           scale=round(s, 3), stretch=round(k, 3)))
        pos = x[-1]
        if rng.random() < 0.7 * rest_bias:
            rdur = min(rng.uniform(0.15, 2.2) * (0.6 + 0.4 * rest_bias), T_target - 0.7 - len(x) / FS)
            if rdur > 0.05:
                add_rest(rdur)
    # final rest to reach the target duration (at least 0.6 s)
    n_end = max(int(0.6 * FS), int(round(T_target * FS)) + 1 - len(x))
    add_rest(n_end / FS)
    N = len(x)

    # ---- actuators ------------------------------------------------------------------------
    x1p = files[0]['x1p']
    x2p = files[0]['x2p']
    pa1 = lib['rest_a'][2 * rng.randrange(len(files))]
    pa2 = lib['rest_a'][2 * rng.randrange(len(files)) + 1]
    n1 = _noise_slice(pa1, N, rng)
    n2 = _noise_slice(pa2, N, rng)
    a1 = [x1p] + [x1p + n1[i] for i in range(1, N)]
    a2 = [x2p] + [x2p + n2[i] for i in range(1, N)]
    bursts = []
    if act_moves:
        nb = rng.randint(1, 3)
        if act_intensity > 1.0:
            nb = int(round(nb * act_intensity)) + 1
        p_hold = rng.uniform(0.2, 0.8) if act_intensity <= 1.0 else min(0.95, 0.5 + 0.2 * act_intensity)
        occupied = []
        tries = 0
        while len(bursts) < nb and tries < 80:
            tries += 1
            b = lib['bursts'][rng.randrange(len(lib['bursts']))]
            f = files[b['file']]
            sa = rng.uniform(0.6, 1.4) * (1 if rng.random() < 0.75 else -1)
            if act_intensity > 1.0:
                sa = math.copysign(min(1.6, abs(sa) * (1.0 + 0.15 * act_intensity)), sa)
            ka = rng.uniform(0.7, 1.7)
            # cut the measured burst at its two extrema; optionally hold the actuator there
            prim = f['a1'] if b['acts'][0] == 1 else f['a2']
            seg = [prim[i] - prim[0] for i in range(b['i0'], b['i1'])]
            imn = b['i0'] + seg.index(min(seg))
            imx = b['i0'] + seg.index(max(seg))
            cuts = sorted([imn, imx])
            pieces = [(b['i0'], cuts[0]), (cuts[0], cuts[1]), (cuts[1], b['i1'])]
            holds = [rng.uniform(0.3, 2.5) if rng.random() < p_hold else 0.0 for _ in range(2)]
            L = int(sum((p1 - p0) * ka for p0, p1 in pieces) + sum(holds) * FS) + 4
            if L >= N - int(0.6 * FS):
                continue
            # prefer placement during drum motion (kinetic friction), like the paper's tests
            if motion_spans and rng.random() < 0.85:
                ms = motion_spans[rng.randrange(len(motion_spans))]
                c = rng.randint(ms[0], max(ms[0], ms[1] - 1))
                st = c - L // 4
            else:
                st = rng.randint(0, N - L - 1)
            st = max(int(0.2 * FS), min(st, N - L - int(0.3 * FS)))
            if st < 0 or any(not (st + L < o0 or st > o1) for o0, o1 in occupied):
                continue
            occupied.append((st, st + L))
            for ci in b['acts']:
                srcA = f['a1'] if ci == 1 else f['a2']
                base0 = srcA[0]
                dst = a1 if ci == 1 else a2
                pos_out = st
                for pi, (p0, p1) in enumerate(pieces):
                    m_ = int((p1 - p0) * ka)
                    for q in range(m_):
                        dev = _interp(srcA, p0 + q / ka) - base0
                        dst[pos_out] += sa * dev
                        pos_out += 1
                    if pi < 2 and holds[pi] > 0:
                        hv = sa * (srcA[p1] - base0)
                        for q in range(int(holds[pi] * FS)):
                            dst[pos_out] += hv
                            pos_out += 1
            bursts.append(dict(src=f['name'], acts=list(b['acts']), t0=round(st / FS, 3), dur=round(L / FS, 3),
                               scale=round(sa, 3), stretch=round(ka, 3), holds=[round(h, 3) for h in holds]))
    return dict(x=x, rest=rest, a1=a1, a2=a2, x1p=a1[0], x2p=a2[0], blocks=blocks, bursts=bursts)


# =============================================================================================
# Base model (as inferred from `hybridsim damper predict --no-fit` used as a black box)
#   v_i   : central differences of the displacement column (one-sided at the two ends),
#           then a 15-sample centred moving average (window clipped at the record ends)
#   x'_j  : actuator positions of the first row
#   Fc_i  : Eq. (4) with the direction of v_i (v >= 0 forward), floored at fc_floor
#   g_i   : Eq. (5) with Fs of that direction
#   z_0   : F_measured[0] / sigma0
#   z_i   : exact solution of dz/dt = v_i - sigma0 |v_i| z / g_i over [t_{i-1}, t_i] with the
#           inputs of sample i held over the step (zero-order hold, "next sample")
#   F_i   : sigma0 z_i + sigma1 zdot_i + sigma2 v_i      (sigma1 = 0)
# (matched to the black box to its CSV print precision, ~5e-8 kip)
# =============================================================================================
def derive_velocity(x):
    n = len(x)
    d = [0.0] * n
    d[0] = (x[1] - x[0]) / DT
    d[-1] = (x[-1] - x[-2]) / DT
    for i in range(1, n - 1):
        d[i] = (x[i + 1] - x[i - 1]) / (2.0 * DT)
    cs = [0.0]
    for a in d:
        cs.append(cs[-1] + a)
    out = []
    for i in range(n):
        lo = i - 7 if i >= 7 else 0
        hi = i + 8 if i + 8 <= n else n
        out.append((cs[hi] - cs[lo]) / (hi - lo))
    return out


def eq4_fc(v, d1, d2, h=None):
    """Fc of Eq. (4); d1, d2 = actuator travel from x' (x - x').  h: optional nonlinear map
    applied per actuator to the tightening travel (-d) (pretension shapes)."""
    fwd = v >= 0.0
    b = P['fc_fwd'] if fwd else P['fc_bwd']
    k1, k2 = K_FWD if fwd else K_BWD
    if h is None:
        c = b + k1 * d1 + k2 * d2
    else:
        c = b - k1 * h(-d1) - k2 * h(-d2)
    return c if c > P['fc_floor'] else P['fc_floor']


def g_of(v, fc, vs=None):
    fs = P['fs_fwd'] if v >= 0.0 else P['fs_bwd']
    vs = P['vs'] if vs is None else vs
    return fc + (fs - fc) * math.exp(-(v / vs) ** 2)


def prep(rec):
    """arrays shared by all simulations of one record (rec holds the columns as written)."""
    if 'v' in rec:
        return rec
    x = rec['x']
    v = derive_velocity(x)
    x1p = rec['a1'][0]
    x2p = rec['a2'][0]
    d1 = [a - x1p for a in rec['a1']]
    d2 = [a - x2p for a in rec['a2']]
    fc = [eq4_fc(v[i], d1[i], d2[i]) for i in range(len(x))]
    g = [g_of(v[i], fc[i]) for i in range(len(x))]
    rec.update(v=v, d1=d1, d2=d2, fc=fc, g=g)
    return rec


def lugre_exact(F0, v, g, sigma0=None, sigma2=None):
    s0 = P['sigma0'] if sigma0 is None else sigma0
    s2 = P['sigma2']
    z = F0 / s0
    n = len(v)
    F = [0.0] * n
    F[0] = s0 * z + (s2 if sigma2 is None else sigma2[0]) * v[0]
    for i in range(1, n):
        vi = v[i]
        a = s0 * abs(vi) / g[i]
        if a > 0.0:
            zi = vi / a
            z = zi + (z - zi) * math.exp(-a * DT)
        else:
            z += vi * DT
        F[i] = s0 * z + (s2 if sigma2 is None else sigma2[i]) * vi
    return F


def base_force(rec):
    rec = prep(rec)
    return lugre_exact(rec['F0'], rec['v'], rec['g'])


# =============================================================================================
# Effect models.  Each shape has fixed shape parameters (drawn per trial) and one amplitude
# `amp`; amp = 0 reproduces the base model.  All act on the same inputs as the base model
# (derived velocity, written actuator columns) and start from the same initial force F0.
# =============================================================================================
V_TH = 0.12   # in/s, hysteresis for reversal tracking on the derived velocity


def reversal_tracker(v, x):
    """per-sample direction state (+1/-1/0), travel since the last reversal, reversal flags."""
    n = len(v)
    dirs = [0] * n
    travel = [0.0] * n
    flags = [False] * n
    d = 0
    x_rev = x[0]
    ext = x[0]
    for i in range(n):
        if v[i] > V_TH and d <= 0:
            x_rev = ext if d != 0 else min(ext, x[i])
            d = 1; flags[i] = True; ext = x[i]
        elif v[i] < -V_TH and d >= 0:
            x_rev = ext if d != 0 else max(ext, x[i])
            d = -1; flags[i] = True; ext = x[i]
        if d == 1:
            ext = max(ext, x[i])
        elif d == -1:
            ext = min(ext, x[i])
        else:
            ext = x[i]
        dirs[i] = d
        travel[i] = max(0.0, (x[i] - x_rev) * d) if d != 0 else 0.0
    return dirs, travel, flags


def _rk4_phi(F0, v, g, phi, phi_inv, s2=None, nsub=1):
    """dz/dt = v - |v| phi(z)/g  (generalised LuGre, phi(z) = sigma0 z is the base), F = phi(z) + s2 v."""
    s2c = P['sigma2']
    n = len(v)
    z = phi_inv(F0)
    F = [0.0] * n
    F[0] = phi(z) + (s2c if s2 is None else s2[0]) * v[0]
    h = DT / nsub
    for i in range(1, n):
        vi = v[i]
        av = abs(vi) / g[i]
        for _ in range(nsub):
            k1 = vi - av * phi(z)
            k2 = vi - av * phi(z + 0.5 * h * k1)
            k3 = vi - av * phi(z + 0.5 * h * k2)
            k4 = vi - av * phi(z + h * k3)
            z += h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        F[i] = phi(z) + (s2c if s2 is None else s2[i]) * vi
    return F


def _bisect_inv(phi, F, hi=5.0):
    """inverse of an odd, non-decreasing phi (for the initial state)."""
    if F == 0.0:
        return 0.0
    s = 1.0 if F > 0 else -1.0
    lo_z, hi_z = 0.0, hi
    for _ in range(80):
        mid = 0.5 * (lo_z + hi_z)
        if phi(s * mid) * s < abs(F):
            lo_z = mid
        else:
            hi_z = mid
    return s * 0.5 * (lo_z + hi_z)


# ---------------------------------------------------------------------------------- backlash
def sim_slack_deadzone(rec, sp, amp):
    s0 = P['sigma0']
    dlt = amp

    def phi(z):
        if z > dlt:
            return s0 * (z - dlt)
        if z < -dlt:
            return s0 * (z + dlt)
        return 0.0
    inv = lambda F: (F / s0 + (dlt if F > 0 else -dlt if F < 0 else 0.0))
    return _rk4_phi(rec['F0'], rec['v'], rec['g'], phi, inv, nsub=2)


def sim_hertz_reengage(rec, sp, amp):
    s0 = P['sigma0']
    dlt = amp
    kn = sp['knee_ratio'] * dlt

    def phi(z):
        u = abs(z) - dlt
        if u <= 0.0:
            return 0.0
        f = s0 * u * math.sqrt(u / (u + kn)) if kn > 0 else s0 * u
        return f if z > 0 else -f
    inv = lambda F: _bisect_inv(phi, F)
    return _rk4_phi(rec['F0'], rec['v'], rec['g'], phi, inv, nsub=2)


def sim_load_slack(rec, sp, amp):
    """slack width set at each reversal proportional to the force carried just before it."""
    s0 = P['sigma0']
    s2 = P['sigma2']
    v = rec['v']; g = rec['g']
    kap = amp
    dirs, travel, flags = reversal_tracker(v, rec['x'])
    n = len(v)
    dl = kap * abs(rec['F0'])
    F0 = rec['F0']
    z = F0 / s0 + (dl if F0 > 0 else -dl if F0 < 0 else 0.0)
    F = [0.0] * n

    def phi(z, dl):
        if z > dl:
            return s0 * (z - dl)
        if z < -dl:
            return s0 * (z + dl)
        return 0.0
    F[0] = phi(z, dl) + s2 * v[0]
    h = DT / 2
    for i in range(1, n):
        if flags[i]:
            Fr = phi(z, dl)
            dn = kap * abs(Fr)
            # remap z so that the force is continuous
            if z > dl:
                z = z - dl + dn
            elif z < -dl:
                z = z + dl - dn
            else:
                z = z * (dn / dl) if dl > 0 else 0.0
            dl = dn
        vi = v[i]
        av = abs(vi) / g[i]
        for _ in range(2):
            k1 = vi - av * phi(z, dl)
            k2 = vi - av * phi(z + 0.5 * h * k1, dl)
            k3 = vi - av * phi(z + 0.5 * h * k2, dl)
            k4 = vi - av * phi(z + h * k3, dl)
            z += h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        F[i] = phi(z, dl) + s2 * vi
    return F


# --------------------------------------------------------------------------- residual_static
def _rest_clock(rec):
    """time since the start of the current rest (None while moving), from the motion design."""
    rest = rec['rest']
    n = len(rest)
    clk = [None] * n
    t = 0.0
    for i in range(n):
        if rest[i]:
            t = t + DT if (i > 0 and rest[i - 1]) else 0.0
            clk[i] = t
    return clk


def _sim_rest(rec, sp, amp, kind):
    s0 = P['sigma0']; s2 = P['sigma2']
    v = rec['v']; g = rec['g']
    clk = _rest_clock(rec)
    n = len(v)
    z = rec['F0'] / s0
    F = [0.0] * n
    F[0] = s0 * z + s2 * v[0]
    z_hold = z
    if kind == 'kww':
        r = 1.0 - amp; tau = sp['tau']; beta = sp['beta']
        phi = lambda t: r + (1.0 - r) * math.exp(-(t / tau) ** beta)
    elif kind == 'log':
        A = amp; tc = sp['tc']
        phi = lambda t: max(0.03, 1.0 - A * math.log1p(t / tc))
    for i in range(1, n):
        vi = v[i]
        a = s0 * abs(vi) / g[i]
        if a > 0.0:
            zi = vi / a
            z = zi + (z - zi) * math.exp(-a * DT)
        else:
            z += vi * DT
        c = clk[i]
        if c is not None and amp > 0.0:
            if c == 0.0:
                z_hold = z
            elif kind in ('kww', 'log'):
                z *= phi(c) / phi(c - DT)
            else:   # settle toward a fixed residual band force (increment of a first-order approach)
                tau = sp['tau']
                z += amp * (sp['F_res'] / s0 - z_hold) * (math.exp(-(c - DT) / tau) - math.exp(-c / tau))
        F[i] = s0 * z + s2 * vi
    return F


def sim_kww_relax(rec, sp, amp):
    return _sim_rest(rec, sp, amp, 'kww')


def sim_log_relax(rec, sp, amp):
    return _sim_rest(rec, sp, amp, 'log')


def sim_settle_offset(rec, sp, amp):
    return _sim_rest(rec, sp, amp, 'settle')


# -------------------------------------------------------------------------- transition_shape
def sim_dahl_exponent(rec, sp, amp):
    s0 = P['sigma0']; s2 = P['sigma2']
    ex = 1.0 + amp if sp['side'] > 0 else 1.0 / (1.0 + amp)
    v = rec['v']; g = rec['g']
    n = len(v)
    z = rec['F0'] / s0
    F = [0.0] * n
    F[0] = s0 * z + s2 * v[0]
    h = DT / 2

    def f(z, vi, sg, gi):
        u = 1.0 - sg * s0 * z / gi
        if u >= 0.0:
            return vi * u ** ex
        return -vi * (-u) ** ex
    for i in range(1, n):
        vi = v[i]; gi = g[i]
        sg = 1.0 if vi > 0 else (-1.0 if vi < 0 else 0.0)
        if sg == 0.0:
            F[i] = s0 * z
            continue
        for _ in range(2):
            k1 = f(z, vi, sg, gi)
            k2 = f(z + 0.5 * h * k1, vi, sg, gi)
            k3 = f(z + 0.5 * h * k2, vi, sg, gi)
            k4 = f(z + h * k3, vi, sg, gi)
            z += h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        F[i] = s0 * z + s2 * vi
    return F


def sim_elastoplastic(rec, sp, amp):
    s0 = P['sigma0']; s2 = P['sigma2']
    beta = amp
    v = rec['v']; g = rec['g']
    n = len(v)
    z = rec['F0'] / s0
    F = [0.0] * n
    F[0] = s0 * z + s2 * v[0]
    h = DT / 2

    def f(z, vi, gi):
        zss = gi / s0
        if (z > 0) == (vi > 0) and beta > 0.0:
            az = abs(z)
            zba = beta * zss
            z1 = zba + beta * (zss - zba)
            if az <= zba:
                al = 0.0
            elif az >= z1:
                al = 1.0
            else:
                al = 0.5 + 0.5 * math.sin(math.pi * (az - 0.5 * (zba + z1)) / (z1 - zba))
        else:
            al = 1.0
        return vi - al * s0 * abs(vi) * z / gi
    for i in range(1, n):
        vi = v[i]; gi = g[i]
        for _ in range(2):
            k1 = f(z, vi, gi)
            k2 = f(z + 0.5 * h * k1, vi, gi)
            k3 = f(z + 0.5 * h * k2, vi, gi)
            k4 = f(z + h * k3, vi, gi)
            z += h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        F[i] = s0 * z + s2 * vi
    return F


def sim_iwan_blend(rec, sp, amp):
    """parallel combination: (1-lam) LuGre + lam * Iwan (uniform density of Jenkins elements).
    Positive element forces are limited by the forward sliding level g_fwd(|v|), negative ones by the
    backward level g_bwd(|v|) (each direction loads its own band end), so the sliding level in either
    direction is exactly the base model's g."""
    s2 = P['sigma2']
    Fl = lugre_exact(rec['F0'], rec['v'], rec['g'])
    if amp <= 0.0:
        return Fl
    v = rec['v']
    d1 = rec['d1']; d2 = rec['d2']
    N = sp['N']
    dmax = sp['dmax']
    gref = 0.5 * (P['fc_fwd'] + P['fc_bwd'])
    d = [dmax * (j + 1) / N for j in range(N)]
    k = [gref / (N * dj) for dj in d]
    n = len(v)

    def lims(i):
        a = abs(v[i])
        gp = g_of(a, eq4_fc(a, d1[i], d2[i]))
        gm = g_of(-a - 1e-300, eq4_fc(-a - 1e-300, d1[i], d2[i]))
        return gp / N, gm / N
    F0 = rec['F0']
    lp, lm = lims(0)
    r0 = max(-1.0, min(1.0, F0 / (lp * N) if F0 >= 0 else F0 / (lm * N)))
    e = [r0 * (lp if F0 >= 0 else lm) for _ in range(N)]
    out = [0.0] * n
    out[0] = (1 - amp) * Fl[0] + amp * (sum(e) + s2 * v[0])
    for i in range(1, n):
        dx = v[i] * DT
        lp, lm = lims(i)
        tot = 0.0
        for j in range(N):
            ej = e[j] + k[j] * dx
            if ej > lp:
                ej = lp
            elif ej < -lm:
                ej = -lm
            e[j] = ej
            tot += ej
        out[i] = (1 - amp) * Fl[i] + amp * (tot + s2 * v[i])
    return out


# ---------------------------------------------------------------------------------- velocity
def _sim_fcmod(rec, fac):
    v = rec['v']; fc = rec['fc']
    g = []
    fl = P['fc_floor']
    for i in range(len(v)):
        c = fc[i] * fac(abs(v[i]))
        g.append(g_of(v[i], c if c > fl else fl))
    return lugre_exact(rec['F0'], v, g)


def sim_ratestate_log(rec, sp, amp):
    v0 = sp['v0']
    return _sim_fcmod(rec, lambda a: 1.0 + amp * math.log1p(a / v0))


def sim_grosch_bell(rec, sp, amp):
    vp = sp['vp']; w = sp['w']
    def fac(a):
        if a <= 1e-9:
            return 1.0
        return 1.0 + amp * math.exp(-(math.log(a / vp)) ** 2 / (2 * w * w))
    return _sim_fcmod(rec, fac)


def sim_hyperbolic_weakening(rec, sp, amp):
    vh = sp['vh']
    return _sim_fcmod(rec, lambda a: 1.0 - amp * a / (a + vh))


# ------------------------------------------------------------------------------ actuator_lag
def _sim_act(rec, filt, h=None):
    v = rec['v']
    e1 = filt(rec['d1'])
    e2 = filt(rec['d2'])
    g = [g_of(v[i], eq4_fc(v[i], e1[i], e2[i], h)) for i in range(len(v))]
    return lugre_exact(rec['F0'], v, g)


def sim_second_order_lag(rec, sp, amp):
    Tn = amp
    zeta = sp['zeta']
    if Tn <= 0.0:
        return lugre_exact(rec['F0'], rec['v'], rec['g'])
    w = 1.0 / Tn
    # exact zero-order-hold transition of e = y - u, e' : e'' + 2 zeta w e' + w^2 e = 0 (zeta < 1)
    wd = w * math.sqrt(1.0 - zeta * zeta)
    ex = math.exp(-zeta * w * DT)
    c = math.cos(wd * DT)
    s = math.sin(wd * DT)
    p11 = ex * (c + zeta * w / wd * s)
    p12 = ex * s / wd
    p21 = -ex * w * w / wd * s
    p22 = ex * (c - zeta * w / wd * s)

    def filt(d):
        y = d[0]; yd = 0.0
        out = [y]
        for i in range(1, len(d)):
            u = d[i]
            e = y - u
            e, yd = p11 * e + p12 * yd, p21 * e + p22 * yd
            y = u + e
            out.append(y)
        return out
    return _sim_act(rec, filt)


def sim_rate_limited(rec, sp, amp):
    if amp <= 0.0:
        return lugre_exact(rec['F0'], rec['v'], rec['g'])
    r = 1.0 / amp
    step = r * DT
    def filt(d):
        y = d[0]
        out = [y]
        for i in range(1, len(d)):
            e = d[i] - y
            if e > step:
                e = step
            elif e < -step:
                e = -step
            y += e
            out.append(y)
        return out
    return _sim_act(rec, filt)


def sim_zener_lag(rec, sp, amp):
    tau = sp['tau']
    al = 1.0 - math.exp(-DT / tau)
    def filt(d):
        y = d[0]
        out = [d[0]]
        for i in range(1, len(d)):
            y += al * (d[i] - y)
            out.append((1.0 - amp) * d[i] + amp * y)
        return out
    return _sim_act(rec, filt)


# ----------------------------------------------------------------------------- pretension
def sim_fung_exponential(rec, sp, amp):
    b = amp
    if b <= 0.0:
        return lugre_exact(rec['F0'], rec['v'], rec['g'])
    return _sim_act(rec, lambda d: d, h=lambda t: math.expm1(b * t) / b)


def sim_tanh_saturation(rec, sp, amp):
    if amp <= 0.0:
        return lugre_exact(rec['F0'], rec['v'], rec['g'])
    ds = 1.0 / amp
    return _sim_act(rec, lambda d: d, h=lambda t: ds * math.tanh(t / ds))


def sim_bilinear_slack(rec, sp, amp):
    eps = sp['eps']
    off = eps * math.log(2.0)
    def h(t):
        x = -t / eps
        sp_ = eps * (x + math.log1p(math.exp(-x))) if x > 0 else eps * math.log1p(math.exp(x))
        return t + amp * (sp_ - off)
    return _sim_act(rec, lambda d: d, h=h)


# ------------------------------------------------------------------------- self_energizing
def sim_capstan_wrap(rec, sp, amp):
    mt = sp['mu_theta0']
    den = math.expm1(mt)
    v = rec['v']; x = rec['x']; g0 = rec['g']
    g = []
    for i in range(len(v)):
        s = math.tanh(v[i] / 0.05)
        W = math.expm1(mt * (1.0 + amp * x[i] * s)) / den
        g.append(g0[i] * W)
    return lugre_exact(rec['F0'], v, g)


def sim_wedge_servo(rec, sp, amp):
    G = sp['G_ref']
    g = [gi / (1.0 - amp * gi / G) for gi in rec['g']]
    return lugre_exact(rec['F0'], rec['v'], g)


def sim_travel_buildup(rec, sp, amp):
    sb = sp['s_b']
    dirs, travel, flags = reversal_tracker(rec['v'], rec['x'])
    g = [gi * (1.0 + amp * (1.0 - math.exp(-s / sb))) for gi, s in zip(rec['g'], travel)]
    return lugre_exact(rec['F0'], rec['v'], g)


# ------------------------------------------------------------------------------ asymmetry
def sim_asym_stribeck(rec, sp, amp):
    a = amp * sp['sign']
    vsf = P['vs'] * math.exp(a)
    vsb = P['vs'] * math.exp(-a)
    v = rec['v']; fc = rec['fc']
    g = [g_of(v[i], fc[i], vsf if v[i] >= 0 else vsb) for i in range(len(v))]
    return lugre_exact(rec['F0'], v, g)


def sim_asym_band_stiffness(rec, sp, amp):
    s0 = P['sigma0']
    a = amp * sp['sign']
    kp = s0 * math.exp(a)
    km = s0 * math.exp(-a)
    phi = lambda z: kp * z if z >= 0 else km * z
    inv = lambda F: F / kp if F >= 0 else F / km
    return _rk4_phi(rec['F0'], rec['v'], rec['g'], phi, inv, nsub=1)


def sim_asym_viscous(rec, sp, amp):
    a = amp * sp['sign']
    s2 = P['sigma2']
    v = rec['v']
    sig2 = [s2 * (1.0 + a) if vi >= 0 else s2 * (1.0 - a) for vi in v]
    return lugre_exact(rec['F0'], v, rec['g'], sigma2=sig2)


# =============================================================================================
# Shape catalogue: category, simulator, amplitude bound (physically plausible), fixed shape
# parameters drawn per trial, equation and literature source (see NOTES.md for details).
# =============================================================================================
def _sign(r):
    return 1 if r.random() < 0.5 else -1


SHAPES = {
    # ---- backlash
    'slack_deadzone': dict(
        cat='backlash', sim=sim_slack_deadzone, amp_name='delta_in', amp_max=0.12,
        draw=lambda r: {},
        eq='dz/dt = v - |v| phi(z)/g,  F = phi(z) + s2 v,  phi(z) = s0 sgn(z) max(|z|-delta, 0)',
        src='classical dead-zone (slack) element: Nordin, Galic & Gutman (1997) Int. J. Adapt. Control '
            'Signal Process. 11:49-63; Tao & Kokotovic (1996) Adaptive Control of Systems with Actuator '
            'and Sensor Nonlinearities'),
    'hertz_reengage': dict(
        cat='backlash', sim=sim_hertz_reengage, amp_name='delta_in', amp_max=0.12,
        draw=lambda r: {'knee_ratio': round(r.uniform(0.5, 1.5), 4)},
        eq='phi(z) = s0 sgn(z) u sqrt(u/(u+k)),  u = max(|z|-delta,0),  k = knee_ratio*delta '
           '(gap, then Hertz-like u^1.5 re-engagement blending into the band stiffness)',
        src='gap + Hertzian contact law F ~ u^(3/2) at re-engagement: Hunt & Crossley (1975) J. Appl. '
            'Mech. 42:440-445; Johnson (1985) Contact Mechanics; Nordin et al. (1997)'),
    'load_slack': dict(
        cat='backlash', sim=sim_load_slack, amp_name='kappa_in_per_kip', amp_max=0.03,
        draw=lambda r: {},
        eq='dead-zone phi(z) with half-width delta_n = kappa |F| reset at every drum reversal (force just '
           'before the reversal), z re-mapped so F stays continuous',
        src='load-dependent lost motion of tension elements (equivalent backlash grows with tension): '
            'Kaneko, Yamashita & Tanie (1991) IEEE Trans. Robot. Autom. 7(3); Do, Tjahjowidodo, Lau & '
            'Phee (2014) Mech. Syst. Signal Process. 42'),
    # ---- residual_static
    'kww_relax': dict(
        cat='residual_static', sim=sim_kww_relax, amp_name='depth', amp_max=0.9,
        draw=lambda r: {'tau': round(r.uniform(0.25, 1.2), 4), 'beta': round(r.uniform(0.35, 0.7), 4)},
        eq='while the drum rests: z(t) = z_hold [r + (1-r) exp(-(t/tau)^beta)],  depth = 1 - r',
        src='Kohlrausch-Williams-Watts stretched-exponential stress relaxation: Williams & Watts (1970) '
            'Trans. Faraday Soc. 66:80-85'),
    'log_relax': dict(
        cat='residual_static', sim=sim_log_relax, amp_name='A', amp_max=0.35,
        draw=lambda r: {'tc': round(r.uniform(0.02, 0.1), 4)},
        eq='while the drum rests: z(t) = z_hold max(0.03, 1 - A ln(1 + t/tc))',
        src='logarithmic-in-time creep/relaxation of frictional contacts: Dieterich (1972) J. Geophys. '
            'Res. 77:3690; Baumberger & Caroli (2006) Adv. Phys. 55:279'),
    'settle_offset': dict(
        cat='residual_static', sim=sim_settle_offset, amp_name='w', amp_max=1.0,
        draw=lambda r: {'F_res': round(_sign(r) * r.uniform(0.3, 1.1), 4), 'tau': round(r.uniform(0.3, 1.2), 4)},
        eq='while the drum rests (time t since the stop): z = z_LuGre + w (F_res/s0 - z_hold)(1 - exp(-t/tau)) '
           '(held force settles toward a fixed residual band force F_res)',
        src='standard-linear-solid (Zener) settling toward a non-zero equilibrium (residual pre-load): '
            'Zener (1948) Elasticity and Anelasticity of Metals; residual static force of the BRFD: '
            'Coble et al., seed paper Fig. 14'),
    # ---- transition_shape
    'dahl_exponent': dict(
        cat='transition_shape', sim=sim_dahl_exponent, amp_name='exponent_offset', amp_max=3.0,
        draw=lambda r: {'side': _sign(r)},
        eq='dz/dt = v |u|^i sgn(u),  u = 1 - sgn(v) s0 z / g,  i = 1+a (side +1) or 1/(1+a) (side -1)',
        src='Dahl solid-friction model with shape exponent i: Dahl (1968) Aerospace Corp. TOR-0158(3107-18)-1; '
            'Dahl (1976) AIAA J. 14:1675'),
    'elastoplastic': dict(
        cat='transition_shape', sim=sim_elastoplastic, amp_name='beta', amp_max=0.9,
        draw=lambda r: {},
        eq='dz/dt = v - alpha(z,v) s0 |v| z / g,  alpha = 0 for |z| <= beta z_ss (pure elastic presliding), '
           'sinusoidal rise to 1 at beta(2-beta) z_ss, 1 beyond and while unloading;  z_ss = g/s0',
        src='single-state elasto-plastic friction model: Dupont, Hayward, Armstrong & Altpeter (2002) '
            'IEEE Trans. Autom. Control 47(5):787-792'),
    'iwan_blend': dict(
        cat='transition_shape', sim=sim_iwan_blend, amp_name='lambda', amp_max=1.0,
        draw=lambda r: {'N': 12, 'dmax': round(r.uniform(0.2, 0.45), 4)},
        eq='F = (1-lam) F_LuGre + lam (sum_j e_j + s2 v),  e_j = clip(e_j + k_j dx, -g_bwd/N, +g_fwd/N),  '
           'k_j = g_ref/(N d_j),  d_j = dmax j/N (uniform Iwan density, Masing reversals)',
        src='Iwan (1966) J. Appl. Mech. 33:893 distributed-element (parallel Jenkins) model; '
            'Al-Bender, Lampaert & Swevers (2005) IEEE TAC 50(11) (Maxwell-slip presliding)'),
    # ---- velocity
    'ratestate_log': dict(
        cat='velocity', sim=sim_ratestate_log, amp_name='A', amp_max=0.4,
        draw=lambda r: {'v0': round(r.uniform(0.05, 0.25), 4)},
        eq='Fc(v) = Fc_eq4 [1 + A ln(1 + |v|/v0)] (regularised steady-state rate-and-state law)',
        src='rate-and-state steady state mu_ss = mu0 + (a-b) ln(v/v0): Dieterich (1979) JGR 84:2161; '
            'Ruina (1983) JGR 88:10359; regularisation: Rice, Lapusta & Ranjith (2001) JMPS 49:1865'),
    'grosch_bell': dict(
        cat='velocity', sim=sim_grosch_bell, amp_name='A', amp_max=1.5,
        draw=lambda r: {'vp': round(r.uniform(0.6, 1.8), 4), 'w': round(r.uniform(0.5, 0.9), 4)},
        eq='Fc(v) = Fc_eq4 [1 + A exp(-(ln(|v|/vp))^2 / (2 w^2))] (log-normal friction peak)',
        src='bell-shaped friction-vs-log-speed master curve of polymer/rubber friction: Grosch (1963) '
            'Proc. R. Soc. Lond. A 274:21-39; Schallamach (1963) Wear 6:375'),
    'hyperbolic_weakening': dict(
        cat='velocity', sim=sim_hyperbolic_weakening, amp_name='A', amp_max=0.8,
        draw=lambda r: {'vh': round(r.uniform(0.4, 1.5), 4)},
        eq='Fc(v) = Fc_eq4 [1 - A |v|/(|v| + vh)] (saturating velocity weakening of the kinetic level)',
        src='hyperbolic/rational velocity-weakening laws for dry friction: Popp & Stelter (1990) Phil. '
            'Trans. R. Soc. A 332:89; Ibrahim (1994) Appl. Mech. Rev. 47:209'),
    # ---- actuator_lag
    'second_order_lag': dict(
        cat='actuator_lag', sim=sim_second_order_lag, amp_name='Tn_s', amp_max=0.6,
        draw=lambda r: {'zeta': round(r.uniform(0.15, 0.45), 4)},
        eq='clamping travel y: y" + 2 zeta wn y\' + wn^2 y = wn^2 (x - x\'),  wn = 1/Tn; Eq. (4) uses y',
        src='underdamped band/actuator compliance-inertia (second-order servo response): Ogata, Modern '
            'Control Engineering, 2nd-order systems; Lu et al. (2018) J. Sound Vib. 412:184 (position-'
            'controlled friction damper actuator dynamics)'),
    'rate_limited': dict(
        cat='actuator_lag', sim=sim_rate_limited, amp_name='inv_rate_s_per_in', amp_max=40.0,
        draw=lambda r: {},
        eq='dy/dt = clip((x-x\') - y, +-r dt)/dt  (slew-rate limited clamping),  r = 1/amp',
        src='rate (slew) saturation of actuators: Slotine & Li (1991) Applied Nonlinear Control; '
            'Agrawal & Yang (2004) semi-active electromagnetic friction damper (limited actuation rate)'),
    'zener_lag': dict(
        cat='actuator_lag', sim=sim_zener_lag, amp_name='phi', amp_max=1.0,
        draw=lambda r: {'tau': round(r.uniform(0.5, 2.5), 4)},
        eq='y = (1-phi)(x-x\') + phi LP1(x-x\', tau): instantaneous part + delayed viscoelastic part',
        src='standard linear solid (Zener/Poynting-Thomson) band response: Zener (1948); Findley, Lai & '
            'Onaran (1976) Creep and Relaxation of Nonlinear Viscoelastic Materials'),
    # ---- pretension
    'fung_exponential': dict(
        cat='pretension', sim=sim_fung_exponential, amp_name='beta_per_in', amp_max=40.0,
        draw=lambda r: {},
        eq='Fc = b + sum_j |c_j| H(d_j),  d_j = x\'_j - x_j (tightening travel),  H(d) = (exp(beta d)-1)/beta',
        src='exponential (J-shaped, toe region) tension-stretch law of compliant straps/tissue: Fung (1967) '
            'Am. J. Physiol. 213:1532'),
    'tanh_saturation': dict(
        cat='pretension', sim=sim_tanh_saturation, amp_name='inv_ds_per_in', amp_max=100.0,
        draw=lambda r: {},
        eq='H(d) = ds tanh(d/ds),  ds = 1/amp (clamping saturates as the lining compacts / band seats)',
        src='saturating normal-load vs approach of compacting friction linings: Greenwood & Williamson '
            '(1966) Proc. R. Soc. A 295:300 (contact stiffening) and tanh saturation laws of band tension'),
    'bilinear_slack': dict(
        cat='pretension', sim=sim_bilinear_slack, amp_name='one_minus_r', amp_max=0.95,
        draw=lambda r: {'eps': round(r.uniform(0.001, 0.003), 5)},
        eq='H(d) = d for tightening, r d for loosening (smooth knee eps): tension-only band partly '
           'unloads on extension',
        src='tension-only (slack) cable/strap element, bilinear stiffness: Irvine (1981) Cable Structures; '
            'Nordin et al. (1997) (rubber-filled gap)'),
    # ---- self_energizing
    'capstan_wrap': dict(
        cat='self_energizing', sim=sim_capstan_wrap, amp_name='kappa_per_in', amp_max=0.5,
        draw=lambda r: {'mu_theta0': round(r.uniform(0.8, 1.6), 4)},
        eq='g_eff = g (exp(mu theta0 (1 + kappa x tanh(v/0.05))) - 1)/(exp(mu theta0) - 1): wrap angle grows '
           'with drum rotation in the direction of travel',
        src='Euler-Eytelwein capstan / band-brake equation T1/T2 = exp(mu theta): Shigley\'s Mechanical '
            'Engineering Design (band brakes); Downey et al. (2016) Eng. Struct. 113:287 (BRFD)'),
    'wedge_servo': dict(
        cat='self_energizing', sim=sim_wedge_servo, amp_name='kappa', amp_max=0.6,
        draw=lambda r: {'G_ref': 10.0},
        eq='g_eff = g / (1 - kappa g / G_ref): friction feeds back into the clamping force (self-reinforcement)',
        src='self-reinforcing (wedge/servo) brakes, F = mu N0/(1 - mu k): Roberts, Schautt, Gombert et al. '
            '(2003) SAE 2003-01-3331 (electronic wedge brake); Cao et al. (2015) J. Sound Vib. 348:41 (duo-servo)'),
    'travel_buildup': dict(
        cat='self_energizing', sim=sim_travel_buildup, amp_name='kappa', amp_max=0.6,
        draw=lambda r: {'s_b': round(r.uniform(0.25, 0.8), 4)},
        eq='g_eff = g [1 + kappa (1 - exp(-s/s_b))],  s = drum travel since the last reversal',
        src='servo build-up of band/drum brakes as the band is drawn taut: Day (2014) Braking of Road '
            'Vehicles (duo-servo drum brakes); seed paper (self-energizing effect of the BRFD)'),
    # ---- asymmetry
    'asym_stribeck': dict(
        cat='asymmetry', sim=sim_asym_stribeck, amp_name='a', amp_max=1.2,
        draw=lambda r: {'sign': _sign(r)},
        eq='vs_fwd = vs exp(+a sign),  vs_bwd = vs exp(-a sign) (direction-dependent Stribeck velocity)',
        src='asymmetric LuGre/Stribeck parameters: Marton & Lantos (2007) IEEE Trans. Ind. Electron. 54:511; '
            'Armstrong-Helouvry, Dupont & Canudas de Wit (1994) Automatica 30:1083'),
    'asym_band_stiffness': dict(
        cat='asymmetry', sim=sim_asym_band_stiffness, amp_name='a', amp_max=0.9,
        draw=lambda r: {'sign': _sign(r)},
        eq='phi(z) = s0 exp(+a sign) z for z >= 0, s0 exp(-a sign) z for z < 0 (each direction loads a '
           'different band end)',
        src='direction-dependent presliding stiffness: Swevers, Al-Bender, Ganseman & Prajogo (2000) IEEE TAC '
            '45:675; seed paper Fig. 2 (taut band alternates with direction)'),
    'asym_viscous': dict(
        cat='asymmetry', sim=sim_asym_viscous, amp_name='a', amp_max=0.9,
        draw=lambda r: {'sign': _sign(r)},
        eq='s2_fwd = s2 (1 + a sign),  s2_bwd = s2 (1 - a sign) (direction-dependent viscous term)',
        src='asymmetric viscous friction coefficients: Marton & Lantos (2007); Bittencourt & Gunnarsson '
            '(2012) IFAC SYSID (direction-dependent robot-joint friction)'),
}
CATEGORIES = ['backlash', 'residual_static', 'transition_shape', 'velocity', 'actuator_lag',
              'self_energizing', 'pretension', 'asymmetry']


# =============================================================================================
# Record assembly
# =============================================================================================
def quantise_columns(motion, rng):
    """columns as they will be written (float32-rounded, on the measured quantisation grids)."""
    off = 0.205
    x = [f32((round(v / Q_DISP - off) + off) * Q_DISP) for v in motion['x']]
    a1 = [f32(round(v / Q_ACT) * Q_ACT) for v in motion['a1']]
    a2 = [f32(round(v / Q_ACT) * Q_ACT) for v in motion['a2']]
    F_init = rng.uniform(-0.5, 1.0)          # held (residual) force at t = 0
    F0 = round(F_init / Q_FORCE) * Q_FORCE
    return dict(x=x, a1=a1, a2=a2, F0=F0, rest=motion['rest'])


def velocity_column(x):
    """imitation of the measured velocity column: smoothed dx/dt / 125.4, lagging 5 samples."""
    n = len(x)
    d = [0.0] * n
    for i in range(1, n - 1):
        d[i] = (x[i + 1] - x[i - 1]) / (2.0 * DT)
    d[0] = d[1] if n > 1 else 0.0
    d[-1] = d[-2] if n > 1 else 0.0
    cs = [0.0]
    for a in d:
        cs.append(cs[-1] + a)
    out = []
    for i in range(n):
        c = max(0, i - 5)
        lo = max(0, c - 15)
        hi = min(n, c + 16)
        out.append(f32((cs[hi] - cs[lo]) / (hi - lo) / VEL_COL_FACTOR))
    return out


def actuator_force_columns(F_true, rng):
    """load-cell forces (lb): taut end ~ F/C, slack end small (fit to the measured files) + noise."""
    n = len(F_true)
    f1 = []
    f2 = []
    o1 = 0.052 * Q_F1
    o2 = 0.319 * Q_F2
    for i in range(n):
        Fp = max(F_true[i], 0.0) * 1.0
        Fm = max(-F_true[i], 0.0) * 1.0
        # slack-end reduction saturates (a slack band end cannot push)
        a = 55.0 + 470.0 * Fm - 20.0 * (1.0 - math.exp(-Fp / 4.0)) + rng.gauss(0.0, 3.0)
        b = 110.0 + 512.0 * Fp - 60.0 * (1.0 - math.exp(-Fm / 2.0)) + rng.gauss(0.0, 10.0)
        f1.append(round((a - o1) / Q_F1) * Q_F1 + o1)
        f2.append(round((b - o2) / Q_F2) * Q_F2 + o2)
    return f1, f2


def noisy_force(F_true, F0, sigma, seed):
    nr = random.Random(seed)
    out = [F0]
    for i in range(1, len(F_true)):
        out.append(round((F_true[i] + nr.gauss(0.0, sigma)) / Q_FORCE) * Q_FORCE)
    return out


def noise_sequence(n, sigma, seed):
    nr = random.Random(seed)
    return [0.0] + [nr.gauss(0.0, sigma) for _ in range(1, n)]


def _num(v):
    if v == int(v) and abs(v) < 1e15:
        return int(v)
    return v


def write_record(path, rec, F_meas, vcol, f1, f2):
    n = len(rec['x'])
    rows = []
    for i in range(n):
        rows.append([_num(i * DT), rec['x'][i], F_meas[i], vcol[i], rec['a1'][i], rec['a2'][i], f1[i], f2[i]])
    d = {"data": rows, "dt": DT, "sampling freq": FS, "displacement units": "in", "time units": "s",
         "friction force units": "kip", "actuator force units": "lb"}
    with open(path, 'w') as fh:
        json.dump(d, fh)


def rms_ratio(Ftrue_list, Fbase_list, sigma):
    s = 0.0
    n = 0
    for Ft, Fb in zip(Ftrue_list, Fbase_list):
        for a, b in zip(Ft, Fb):
            s += (a - b) ** 2
        n += len(Ft)
    return math.sqrt(s / n) / sigma


def simulate_shape(rec, shape, sp, amp):
    if shape == 'none' or amp == 0.0:
        return base_force(rec)
    return SHAPES[shape]['sim'](prep(rec), sp, amp)


def solve_amp(recs, shape, sp, sigma, target, tol=0.004):
    """amplitude with ratio(amp) = target: coarse scan of [0, amp_max] for the first crossing, then
    Illinois regula falsi inside that bracket.  Returns (amp, ratio) or (None, best ratio)."""
    info = SHAPES[shape]
    bases = [base_force(r) for r in recs]
    f = lambda a: rms_ratio([simulate_shape(r, shape, sp, a) for r in recs], bases, sigma) - target
    amax = info['amp_max']
    lo, flo = 0.0, -target
    hi = fhi = None
    best = -target
    for frac in (0.02, 0.05, 0.1, 0.2, 0.35, 0.5, 0.7, 0.85, 1.0):
        a = frac * amax
        fa = f(a)
        best = max(best, fa)
        if fa >= 0:
            hi, fhi = a, fa
            break
        lo, flo = a, fa
    if hi is None:
        return None, best + target
    side = 0
    a, fa = hi, fhi
    for it in range(60):
        if abs(fa) < tol * target:
            return a, fa + target
        a = (lo * fhi - hi * flo) / (fhi - flo)
        if it % 4 == 3:
            a = 0.5 * (lo + hi)
        fa = f(a)
        if fa < 0:
            lo, flo = a, fa
            if side == -1:
                fhi *= 0.5
            side = -1
        else:
            hi, fhi = a, fa
            if side == 1:
                flo *= 0.5
            side = 1
        if hi - lo < 1e-10 * amax:
            break
    return a, fa + target


# =============================================================================================
# Trial plan
# =============================================================================================
def plan_trials():
    master = random.Random(MASTER_SEED)
    shapes_by_cat = {c: [s for s in SHAPES if SHAPES[s]['cat'] == c] for c in CATEGORIES}
    # 12 strong / 12 weak: four categories get 2 strong + 1 weak, four get 1 strong + 2 weak
    cats = CATEGORIES[:]
    master.shuffle(cats)
    entries = []
    for ci, c in enumerate(cats):
        st = ['strong', 'strong', 'weak'] if ci < 4 else ['strong', 'weak', 'weak']
        master.shuffle(st)
        for s, strength in zip(shapes_by_cat[c], st):
            entries.append(dict(category=c, shape=s, strength=strength))
    for _ in range(6):
        entries.append(dict(category='none', shape='none', strength=None))
    master.shuffle(entries)
    for i, e in enumerate(entries):
        e['trial'] = 't%02d' % (i + 1)
        e['seed'] = master.randrange(1, 2 ** 31 - 1)
    return entries


def motion_options(category, rng, attempt):
    """records are designed so that every category could show itself, without making the design a tell:
    every record may rest, reverse and (half of them) move the actuators with a random intensity."""
    opts = []
    for _ in range(2):
        T = rng.uniform(9.0, 24.99)
        act = rng.random() < 0.5
        inten = rng.uniform(0.8, 2.2)
        rb = rng.uniform(0.6, 1.4)
        if category in ('actuator_lag', 'pretension'):
            act = True
            inten = rng.uniform(1.3, 2.0) + 0.5 * attempt
            T = min(24.99, T + 3.0 * attempt)
        if category == 'residual_static':
            rb = min(2.0, rb + 0.3 + 0.3 * attempt)
            T = min(24.99, T + 3.0 * attempt)
        if category not in ('actuator_lag', 'pretension', 'residual_static') and attempt > 0:
            T = min(24.99, T + 3.0 * attempt)
        opts.append(dict(T=T, act=act, inten=inten, rest_bias=rb))
    return opts


def build_trial(entry, log=None):
    rng = random.Random(entry['seed'])
    sigma = rng.uniform(0.02, 0.06)
    cat = entry['category']
    shape = entry['shape']
    if cat == 'none':
        target = None
        sp = {}
    else:
        target = rng.uniform(8.5, 11.5) if entry['strength'] == 'strong' else rng.uniform(2.7, 3.8)
        sp = SHAPES[shape]['draw'](rng)
    for attempt in range(6):
        mrng = random.Random(rng.randrange(1, 2 ** 31 - 1))
        opts = motion_options(cat, mrng, attempt)
        recs = []
        metas = []
        for o in opts:
            m = build_motion(mrng, o['T'], o['act'], o['inten'], o['rest_bias'])
            rec = quantise_columns(m, mrng)
            rec['noise_seed'] = mrng.randrange(1, 2 ** 31 - 1)
            rec['aux_seed'] = mrng.randrange(1, 2 ** 31 - 1)
            prep(rec)
            recs.append(rec)
            rest_iv = []
            rm = rec['rest']
            for i in range(len(rm)):
                if rm[i] and (i == 0 or not rm[i - 1]):
                    rest_iv.append([i, i + 1])
                elif rm[i]:
                    rest_iv[-1][1] = i + 1
            metas.append(dict(duration_s=round((len(rec['x']) - 1) * DT, 4), actuators_move=o['act'],
                              rest_samples=rest_iv,
                              F0_kip=rec['F0'], noise_seed=rec['noise_seed'], aux_seed=rec['aux_seed'],
                              strokes=m['blocks'], actuator_bursts=m['bursts']))
        if cat == 'none':
            amp, ratio = 0.0, 0.0
            break
        amp, ratio = solve_amp(recs, shape, sp, sigma, target)
        if amp is not None and abs(ratio - target) < 0.01 * target:
            break
        if log:
            log('  %s %s attempt %d: max ratio %.2f < target %.2f, new motion' % (entry['trial'], shape, attempt,
                                                                                 ratio, target))
    else:
        raise RuntimeError('could not reach the target ratio for %s (%s)' % (entry['trial'], shape))
    return dict(entry=entry, sigma=sigma, target=target, sp=sp, amp=amp, ratio=ratio, recs=recs, metas=metas,
                attempts=attempt + 1)


def finish_trial(res, outdir):
    entry = res['entry']
    shape = entry['shape']
    os.makedirs(os.path.join(outdir, entry['trial']), exist_ok=True)
    for name, rec in zip(('A', 'B'), res['recs']):
        Ft = simulate_shape(rec, shape, res['sp'], res['amp'])
        Fm = noisy_force(Ft, rec['F0'], res['sigma'], rec['noise_seed'])
        arng = random.Random(rec['aux_seed'])
        f1, f2 = actuator_force_columns(Ft, arng)
        vcol = velocity_column(rec['x'])
        write_record(os.path.join(outdir, entry['trial'], name + '.json'), rec, Fm, vcol, f1, f2)


def key_entry(res):
    e = res['entry']
    k = {'category': e['category'], 'shape': e['shape'], 'strength': e['strength'],
         'ratio': round(res['ratio'], 4), 'noise_kip': round(res['sigma'], 6), 'noise_sd_exact': res['sigma']}
    if e['category'] == 'none':
        k['params'] = {}
        k['ratio'] = 0.0
    else:
        info = SHAPES[e['shape']]
        p = dict(res['sp'])
        p[info['amp_name']] = res['amp']
        k['params'] = p
        k['amp'] = res['amp']
        k['amp_name'] = info['amp_name']
        k['amp_bounds'] = [0.0, info['amp_max']]
        k['ratio_target'] = round(res['target'], 4)
        k['equation'] = info['eq']
        k['source'] = info['src']
    k['seed'] = e['seed']
    k['attempts'] = res['attempts']
    k['records'] = {'A': res['metas'][0], 'B': res['metas'][1]}
    return k


def _work(entry):
    t0 = time.time()
    res = build_trial(entry, log=lambda s: print(s, flush=True))
    finish_trial(res, os.path.join(ROOT, 'cases'))
    k = key_entry(res)
    print('%s %-16s %-20s %-6s ratio %6.3f sigma %.4f amp %.5g  (%.1f s)' % (
        entry['trial'], entry['category'], entry['shape'], entry['strength'] or '-', res['ratio'],
        res['sigma'], res['amp'], time.time() - t0), flush=True)
    return entry['trial'], k


def main(argv):
    jobs = 2
    only = None
    if '--jobs' in argv:
        jobs = int(argv[argv.index('--jobs') + 1])
    if '--only' in argv:
        only = argv[argv.index('--only') + 1].split(',')
    t0 = time.time()
    load_library()
    entries = plan_trials()
    if only:
        entries = [e for e in entries if e['trial'] in only]
    os.makedirs(os.path.join(ROOT, 'cases'), exist_ok=True)
    if jobs > 1:
        import multiprocessing as mp
        with mp.Pool(jobs) as pool:
            results = pool.map(_work, entries, chunksize=1)
    else:
        results = [_work(e) for e in entries]
    key = {t: k for t, k in sorted(results)}
    if only:
        kp = os.path.join(ROOT, 'key.json')
        old = json.load(open(kp)) if os.path.exists(kp) else {}
        old.update(key)
        key = dict(sorted(old.items()))
    with open(os.path.join(ROOT, 'key.json'), 'w') as fh:
        json.dump(key, fh, indent=1)
    print('gen.py done in %.1f s' % (time.time() - t0))


if __name__ == '__main__':
    main(sys.argv[1:])
