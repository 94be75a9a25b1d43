#!/usr/bin/env python3
"""Blind test set 25 generator (master seed 25025). Python 3 standard library only.

Regenerates /work/blind25/cases/t01..t30/{A,B}.json and /work/blind25/key.json.
Everything is deterministic from MASTER_SEED; each trial uses its own random.Random
stream so the result does not depend on the process layout (2 worker processes).

Base model (inferred from the black box, reproduced to its 8-digit CSV precision):
  * drum velocity: central differences of the displacement column (one-sided at the two
    ends), then a 15-sample centred moving average whose half width shrinks symmetrically
    at the ends (k = min(7, i, n-1-i)); dt = 1/1024 s.  The velocity column of the file is
    NOT used (it is 1/125.4 of d(disp)/dt -- quirk of the semi-active files).
  * LuGre Eqs. 1-3 with sigma1 = 0, Eq. 4 kinetic friction (Table 1/2, x' = first row,
    clip at fc_floor), Eq. 5 Stribeck, Fs/Fc chosen by v >= 0 / v < 0.
  * initial state z0 = F_measured[0] / sigma0.
  * integration: exact exponential update of the linear-in-z ODE over [t_k, t_k+1] holding
    v and g at their values at t_{k+1} (zero-order hold on the new sample).
"""
import json, math, os, random, struct, sys, glob, bisect

MASTER_SEED = 25025
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = '/work/shared/data/brfd/semiactive'
DT = 1.0 / 1024.0
FS = 1024

# ---------------------------------------------------------------- base model parameters
S0 = 15.36; S1 = 0.0; S2 = 0.5
FSF = 7.116; FSB = 3.760; FCF = 2.648; FCB = 1.253; VS = 1.3
M = [-0.14, -0.15, -15.29, -13.00, -16.66, -15.77, -0.13, -0.15]
C = [119.68, 2.10, 1.94, 123.31]
FLOOR = 0.05
KF1 = C[0] * M[0] + C[1] * M[2]; KF2 = C[0] * M[1] + C[1] * M[3]
KB1 = C[2] * M[4] + C[3] * M[6]; KB2 = C[2] * M[5] + C[3] * M[7]

# ---------------------------------------------------------------- quantisation (measured)
QF = 0.00080087997          # friction force grid (kip), zero-aligned
QX = 5.8938196e-05          # drum displacement grid (in), phase 0.48
QX_PH = 0.48
QA = 1.0 / 409600.0         # actuator position grid (in), then float32
QA1 = 0.3179; QA1_PH = 0.062    # actuator 1 force grid (lb)
QA2 = 0.3999; QA2_PH = 0.3293   # actuator 2 force grid (lb)
VEL_RATIO = 125.4


def f32(x):
    return struct.unpack('f', struct.pack('f', x))[0]


def qforce(F):
    return round(F / QF) * QF


def qdisp(x):
    return f32((math.floor(x / QX - QX_PH + 0.5) + QX_PH) * QX)


def qact(a):
    return f32(round(a / QA) * QA)


def qgrid(v, q, ph):
    return (math.floor(v / q - ph + 0.5) + ph) * q


# ---------------------------------------------------------------- base model pieces
def velocity(x):
    n = len(x)
    r = [0.0] * n
    for i in range(1, n - 1):
        r[i] = (x[i + 1] - x[i - 1]) / (2 * DT)
    r[0] = (x[1] - x[0]) / DT
    r[-1] = (x[-1] - x[-2]) / DT
    out = [0.0] * n
    for i in range(n):
        k = min(7, i, n - 1 - i)
        s = 0.0
        for j in range(i - k, i + k + 1):
            s += r[j]
        out[i] = s / (2 * k + 1)
    return out


def fc_base(v, d1, d2):
    if v >= 0:
        b = FCF + KF1 * d1 + KF2 * d2
    else:
        b = FCB + KB1 * d1 + KB2 * d2
    return b if b > FLOOR else FLOOR


def simulate(rec, eff=None):
    """Friction force of the base model (eff None) or of the base model plus one effect.
    rec: dict with x, a1, a2, F0 (F0 = first force sample, on the grid), v (velocity)."""
    x = rec['x']; v = rec['v']; n = len(x)
    x10 = rec['a1'][0]; x20 = rec['a2'][0]
    a1 = rec['a1']; a2 = rec['a2']
    et = eff['type'] if eff else None
    p = eff['p'] if eff else {}
    if et in ('act2nd', 'deadtime', 'slew', 'hertz', 'ernst', 'play'):
        a1, a2 = transform_actuators(rec, et, p)
    F = [0.0] * n
    w = rec['F0']
    F[0] = w + S2 * v[0]
    # effect states
    u = None
    if et in ('clearance', 'loadgap', 'rattle'):
        delta = p.get('delta', 0.0)
        if et == 'loadgap':
            delta = p['c'] * abs(rec['F0'])
        u = w / S0 + (delta if w > 0 else (-delta if w < 0 else 0.0))
        sdir = 0; xrev = x[0]; inside = abs(u) <= delta; ring_t = -1.0; ring_a = 0.0; ring_s = 1
        Fprev_slide = rec['F0']
    if et == 'gms':
        beta = p['beta']; alph = p['alpha']
        ws = [b * w for b in beta]
    if et == 'hesssoom':
        vf = v[0]; cf = math.exp(-DT / p['tau']) if p['tau'] > 0 else 0.0
    if et == 'buildup':
        sdir = 0; xrev = x[0]
    if et in ('logrelax', 'sls', 'eyring'):
        trest = 0.0; wh = w
    for k in range(1, n):
        vk = v[k]
        d1 = a1[k] - x10; d2 = a2[k] - x20
        fc = fc_base(vk, d1, d2)
        # ---- g(v) (Eq. 5) with velocity / direction / servo modifications
        if vk >= 0:
            fs = FSF
        else:
            fs = FSB
        if et == 'logvel':
            fc = fc * (1.0 + p['a'] * math.log(1.0 + abs(vk) / p['vstar']))
        elif et == 'flash':
            fc = fc * (1.0 - p['a'] * (fc / p['fref']) * math.sqrt(abs(vk) / p['vref']))
            if fc < FLOOR * 0.5:
                fc = FLOOR * 0.5
        if et == 'hesssoom':
            vf = vk + (vf - vk) * cf
            ex = math.exp(-(vf / VS) ** 2)
        elif et == 'bopav' and vk < 0:
            ex = math.exp(-abs(vk / p['vs_b']) ** p['delta_b'])
        else:
            ex = math.exp(-(vk / VS) ** 2)
        g = fc + (fs - fc) * ex
        if et == 'leadtrail':
            lam = p['lam'] * g / p['fref']
            g = g / (1.0 - lam) if vk >= 0 else g / (1.0 + lam)
        elif et == 'capstanpos':
            g = g * math.exp(p['kappa'] * x[k] * (1.0 if vk >= 0 else -1.0) * p['dirgain'][0 if vk >= 0 else 1])
        elif et == 'buildup':
            if abs(vk) > 0.05:
                sd = 1 if vk > 0 else -1
                if sd != sdir:
                    sdir = sd; xrev = x[k]
            s_tr = abs(x[k] - xrev) if sdir != 0 else 0.0
            kap = p['kappa'] * (1.0 if vk >= 0 else p['rho'])
            g = g * (1.0 + kap * (g / p['fref']) * (1.0 - math.exp(-s_tr / p['sc'])))
        elif et == 'bandscale' and vk < 0:
            g = g * (1.0 + p['a'])
        # ---- stiffness
        k0 = S0
        if et == 'dirstiff' and vk < 0:
            k0 = S0 * (1.0 + p['a'])
        av = abs(vk)
        if et in ('clearance', 'loadgap', 'rattle'):
            if et == 'loadgap' and av > 0.05:
                sd = 1 if vk > 0 else -1
                if sd != sdir:
                    if sdir != 0:
                        nd = p['c'] * abs(Fprev_slide)
                        su = 1 if u > 0 else -1
                        u += su * (nd - delta)
                        delta = nd
                    sdir = sd
            if et == 'rattle' and av > 0.05:
                sd = 1 if vk > 0 else -1
                if sd != sdir:
                    sdir = sd
            if abs(u) <= delta:
                u += vk * DT
                if abs(u) > delta and et == 'rattle' and ring_t < 0:
                    pass
                now_inside = abs(u) <= delta
            else:
                su = 1.0 if u > 0 else -1.0
                if vk != 0.0:
                    a = S0 * av / g
                    uss = su * delta + (g / S0 if vk > 0 else -g / S0)
                    u = uss + (u - uss) * math.exp(-a * DT)
                now_inside = abs(u) <= delta
            if et == 'rattle':
                if inside and not now_inside:
                    ring_t = 0.0; ring_a = av; ring_s = 1 if u > 0 else -1
                inside = now_inside
            du = abs(u) - delta
            wel = S0 * (du if du > 0 else 0.0) * (1 if u > 0 else -1)
            Fk = wel + S2 * vk
            if et == 'rattle' and ring_t >= 0.0:
                ring_t += DT
                om = p['omega']; ze = p['zeta']
                Fk += p['A'] * ring_a * ring_s * math.exp(-ze * om * ring_t) * math.sin(om * math.sqrt(1 - ze * ze) * ring_t)
                if ring_t * ze * om > 12:
                    ring_t = -1.0
            if av > 0.05:
                Fprev_slide = wel
            F[k] = Fk
            continue
        if et == 'gms':
            tot = 0.0
            for i in range(len(ws)):
                ki = S0 * beta[i]
                if vk != 0.0:
                    gi = alph[i] * g
                    a = ki * av / gi
                    wss = gi if vk > 0 else -gi
                    ws[i] = wss + (ws[i] - wss) * math.exp(-a * DT)
                tot += ws[i]
            F[k] = tot + S2 * vk
            continue
        if vk != 0.0:
            a = k0 * av / g
            if et == 'dahl':
                r = w * (1.0 if vk > 0 else -1.0) / g
                mm = abs(1.0 - r) ** (p['i'] - 1.0) if r != 1.0 else (0.0 if p['i'] > 1 else 50.0)
                a *= min(max(mm, 0.02), 50.0)
            elif et == 'elastoplastic':
                r = w * (1.0 if vk > 0 else -1.0) / g
                rb = p['rba']
                if r <= 0.0:
                    al = 0.0 if r < 0 else 0.0
                    al = 0.0
                elif r <= rb:
                    al = 0.0
                elif r < 1.0:
                    al = 0.5 * math.sin(math.pi * (r - (1.0 + rb) / 2.0) / (1.0 - rb)) + 0.5
                else:
                    al = 1.0
                # alpha = 0 when unloading (sgn v != sgn z): purely elastic
                al_t = (1.0 - p['s']) + p['s'] * al
                if al_t <= 0.0:
                    w = w + k0 * vk * DT
                    F[k] = w + S2 * vk
                    if et in ('logrelax', 'sls', 'eyring'):
                        pass
                    continue
                # z_dot = v - al_t*a*z  ->  w_ss = g sgn v / al_t
                wss = (g if vk > 0 else -g) / al_t
                w = wss + (w - wss) * math.exp(-a * al_t * DT)
                F[k] = w + S2 * vk
                continue
            wss = g if vk > 0 else -g
            w = wss + (w - wss) * math.exp(-a * DT)
        # ---- rest (drum at rest) effects
        if et in ('logrelax', 'sls', 'eyring'):
            if av < p['vth']:
                if trest == 0.0:
                    wh = w
                trest += DT
                if et == 'logrelax':
                    f1 = max(1.0 - p['beta'] * math.log(1.0 + trest / p['tau']), 0.02)
                    f0 = max(1.0 - p['beta'] * math.log(1.0 + (trest - DT) / p['tau']), 0.02)
                    w = w * f1 / f0
                elif et == 'sls':
                    winf = (1.0 - p['drop']) * wh
                    w = winf + (w - winf) * math.exp(-DT / p['tau'])
                else:
                    w = w - p['c'] * math.sinh(w / p['fa']) * DT
            else:
                trest = 0.0
        F[k] = w + S2 * vk
    return F


def transform_actuators(rec, et, p):
    x10 = rec['a1'][0]; x20 = rec['a2'][0]
    out = []
    for arr, x0 in ((rec['a1'], x10), (rec['a2'], x20)):
        d = [a - x0 for a in arr]
        n = len(d)
        if et == 'act2nd':        # band clamping: 2nd-order (mass-spring-damper) response
            wn = p['wn']; ze = p['zeta']
            y = 0.0; yd = 0.0; e = [0.0] * n
            h = DT / 4
            for k in range(1, n):
                for _ in range(4):   # semi-implicit Euler substeps
                    ydd = wn * wn * (d[k] - y) - 2 * ze * wn * yd
                    yd += h * ydd; y += h * yd
                e[k] = y
        elif et == 'deadtime':
            L = p['td'] / DT; e = [0.0] * n
            for k in range(n):
                t = k - L
                if t <= 0:
                    e[k] = d[0]
                else:
                    i = int(t); fr = t - i
                    e[k] = d[i] * (1 - fr) + d[min(i + 1, n - 1)] * fr
        elif et == 'slew':
            r = p['rate'] * DT; y = d[0]; e = [0.0] * n
            for k in range(n):
                dd = d[k] - y
                if dd > r: dd = r
                elif dd < -r: dd = -r
                y += dd; e[k] = y
        elif et == 'hertz':
            d0 = p['d0']; e = [0.0] * n
            for k in range(n):
                q = 1.0 - d[k] / d0
                if q < 0: q = 0.0
                e[k] = -(2 * d0 / 3) * (q ** 1.5 - 1.0)
        elif et == 'ernst':
            tab = ernst_table(p['theta'], p['kap'])
            e = [ernst_eval(tab, dk) for dk in d]
        elif et == 'play':
            r = p['r']; wgt = p['w']; y = 0.0; e = [0.0] * n
            for k in range(n):
                if d[k] - y > r: y = d[k] - r
                elif d[k] - y < -r: y = d[k] + r
                e[k] = (1 - wgt) * d[k] + wgt * y
        out.append([x0 + ek for ek in e])
    return out[0], out[1]


_ERNST = {}


def ernst_table(theta, kap):
    """Relative band tension tau(Delta) with Ernst's tension-dependent equivalent stiffness
    d tau / d(-Delta) = K / (1 + (theta/tau)^3), K chosen so the slope at Delta = 0 is kap.
    Returns h(Delta) = -(tau - 1)/kap (h'(0) = 1, h = Delta for theta = 0)."""
    key = (theta, kap)
    if key in _ERNST:
        return _ERNST[key]
    K = kap * (1 + theta ** 3)
    def f(t):
        t = max(t, 1e-4)
        return K / (1 + (theta / t) ** 3)
    hstep = 0.0005; N = 200       # +-0.1 in
    pos = [0.0]; t = 1.0          # Delta > 0 (extension): tension falls
    for _ in range(N):
        k1 = -f(t); k2 = -f(t + hstep / 2 * k1); k3 = -f(t + hstep / 2 * k2); k4 = -f(t + hstep * k3)
        t = max(t + hstep / 6 * (k1 + 2 * k2 + 2 * k3 + k4), 1e-4); pos.append(-(t - 1) / kap)
    neg = [0.0]; t = 1.0
    for _ in range(N):
        k1 = f(t); k2 = f(t + hstep / 2 * k1); k3 = f(t + hstep / 2 * k2); k4 = f(t + hstep * k3)
        t = t + hstep / 6 * (k1 + 2 * k2 + 2 * k3 + k4); neg.append(-(t - 1) / kap)
    tab = (hstep, N, pos, neg)
    _ERNST[key] = tab
    return tab


def ernst_eval(tab, d):
    hstep, N, pos, neg = tab
    arr = pos if d >= 0 else neg
    s = abs(d) / hstep
    i = int(s)
    if i >= N:
        return arr[N] + (arr[N] - arr[N - 1]) * (s - N)
    fr = s - i
    return arr[i] * (1 - fr) + arr[i + 1] * fr


# ---------------------------------------------------------------- measured-data libraries
def load_library():
    files = sorted(glob.glob(os.path.join(DATA, '*.json')))
    strokes = []; events = []; rests = []; starts = []
    for fn in files:
        d = json.load(open(fn))['data']
        name = os.path.basename(fn)
        x = [r[1] for r in d]; a1 = [r[4] for r in d]; a2 = [r[5] for r in d]
        n = len(x)
        starts.append((d[0][4], d[0][5]))
        W = 150; pk = []
        for i in range(W, n - W):
            seg = x[i - W:i + W + 1]
            if (x[i] == max(seg) or x[i] == min(seg)) and abs(x[i] - x[i - W]) > 0.02 and abs(x[i] - x[i + W]) > 0.02:
                if not pk or i - pk[-1] > W:
                    pk.append(i)
        mv = [i for i in range(n) if abs(a1[i] - a1[0]) > 0.002 or abs(a2[i] - a2[0]) > 0.002]
        cl = []
        for i in mv:
            if cl and i - cl[-1][1] < 300:
                cl[-1][1] = i
            else:
                cl.append([i, i])
        busy = [(s - 150, e + 250) for s, e in cl]
        for j in range(len(pk) - 1):
            s, e = pk[j], pk[j + 1]
            if any(not (e < bs or s > be) for bs, be in busy):
                continue
            strokes.append({'src': '%s@%.2f-%.2fs' % (name, s / FS, e / FS),
                            'dx': [x[i] - x[s] for i in range(s, e + 1)],
                            'j1': [a1[i] - a1[0] for i in range(s, e + 1)],
                            'j2': [a2[i] - a2[0] for i in range(s, e + 1)]})
        for s, e in cl:
            # start where the deviation first leaves the rest band, end after return
            s0 = s - 60; e0 = e + 100
            r1 = a1[s0 - 1]; r2 = a2[s0 - 1]
            events.append({'src': '%s@%.3f-%.3fs' % (name, s0 / FS, e0 / FS),
                           'd1': [a1[i] - r1 for i in range(s0, e0)],
                           'd2': [a2[i] - r2 for i in range(s0, e0)]})
        s = int(14.1 * FS); e = n
        rests.append({'src': '%s@14.10-15.00s' % name,
                      'dx': [x[i] - x[s] for i in range(s, e)],
                      'j1': [a1[i] - a1[0] for i in range(s, e)],
                      'j2': [a2[i] - a2[0] for i in range(s, e)]})
    return {'strokes': strokes, 'events': events, 'rests': rests, 'starts': starts}


def resample(arr, r, L):
    out = []
    n = len(arr)
    for k in range(L):
        t = k / r
        i = int(t)
        if i >= n - 1:
            out.append(arr[-1]); continue
        fr = t - i
        out.append(arr[i] * (1 - fr) + arr[i + 1] * fr)
    return out


# ---------------------------------------------------------------- record construction
def build_record(rng, lib, spec):
    """spec: early (bool), nev_min, nev_max, length target (s), rest_prob."""
    for attempt in range(200):
        rec = _try_record(rng, lib, spec)
        if rec is not None:
            return rec
    raise RuntimeError('record construction failed')


def _rest_piece(rng, lib, L):
    """rest displacement noise + actuator jitter, L samples, starting at 0 offset."""
    dx = []; j1 = []; j2 = []; srcs = []
    flip = rng.random() < 0.5
    off = 0.0
    while len(dx) < L:
        rp = rng.choice(lib['rests'])
        seq = list(zip(rp['dx'], rp['j1'], rp['j2']))
        if flip:
            seq = seq[::-1]
            base = seq[0][0]
            seq = [(a - base, b, c) for a, b, c in seq]
        flip = not flip
        srcs.append(rp['src'] + (' reversed' if not flip else ''))
        for a, b, c in seq:
            dx.append(off + a); j1.append(b); j2.append(c)
        off = dx[-1]
    return dx[:L], j1[:L], j2[:L], srcs


def _try_record(rng, lib, spec):
    T_target = spec['T']
    final_rest = rng.uniform(1.6, 3.0)
    pieces = []   # (kind, dx list, j1, j2, meta)
    x = []; j1 = []; j2 = []; runs = []; info_pieces = []
    pos = rng.uniform(-0.4, 0.4)
    # initial rest
    L0 = int(rng.uniform(0.0, 0.25 if spec['early'] else 0.9) * FS) + 20
    dxr, r1, r2, srcs = _rest_piece(rng, lib, L0)
    x += [pos + a for a in dxr]; j1 += r1; j2 += r2
    info_pieces.append({'kind': 'rest', 't0': 0.0, 'dur': L0 / FS, 'src': srcs})
    pos = x[-1]
    direction = rng.choice([-1, 1])
    while len(x) / FS < T_target - final_rest:
        nstk = rng.choice([1, 2, 2, 3, 3, 4])
        run_start = len(x)
        for s_i in range(nstk):
            st = rng.choice(lib['strokes'])
            sgn = 1 if st['dx'][-1] > 0 else -1
            amp = rng.uniform(0.35, 1.15) if rng.random() < 0.8 else rng.uniform(0.15, 0.35)
            r = rng.uniform(0.65, 1.7)
            peak = abs(st['dx'][-1])
            s = amp * 2.0 / peak if peak > 0 else 1.0
            s = min(s, 2.5)
            if s * peak / (len(st['dx']) / FS * r) > 2.6:      # keep mean speed <= 2.6 in/s
                r = s * peak / 2.6 / (len(st['dx']) / FS)
            mir = direction * sgn
            if abs(pos + direction * s * peak) > 1.35:
                direction = -direction; mir = direction * sgn
            L = int(round((len(st['dx']) - 1) * r)) + 1
            dx = resample(st['dx'], r, L); a = resample(st['j1'], r, L); b = resample(st['j2'], r, L)
            x += [pos + mir * s * v for v in dx[1:]]; j1 += a[1:]; j2 += b[1:]
            info_pieces.append({'kind': 'stroke', 't0': (len(x) - L + 1) / FS, 'dur': (L - 1) / FS,
                                'src': st['src'], 'amp_scale': round(s, 4), 'time_stretch': round(r, 4),
                                'mirrored': mir < 0, 'direction': 'forward' if direction > 0 else 'backward'})
            pos = x[-1]
            direction = -direction
        runs.append((run_start, len(x)))
        if len(x) / FS >= T_target - final_rest:
            break
        if rng.random() < spec['rest_prob']:
            Lr = int(rng.uniform(0.3, 2.4) * FS)
            dxr, r1, r2, srcs = _rest_piece(rng, lib, Lr)
            info_pieces.append({'kind': 'rest', 't0': len(x) / FS, 'dur': Lr / FS, 'src': srcs})
            x += [pos + a for a in dxr[1:]]; j1 += r1[1:]; j2 += r2[1:]
            pos = x[-1]
            if rng.random() < 0.3:
                direction = -direction   # restart in the same direction as the last stroke
    Lf = int(final_rest * FS)
    dxr, r1, r2, srcs = _rest_piece(rng, lib, Lf)
    info_pieces.append({'kind': 'rest', 't0': len(x) / FS, 'dur': Lf / FS, 'src': srcs, 'final': True})
    x += [pos + a for a in dxr]; j1 += r1; j2 += r2
    n = len(x)
    if n / FS < 6.5 or (n - 1) / FS > 25.0:
        return None
    if max(abs(v) for v in x) > 1.45:
        return None
    # actuator motion events placed in sliding runs
    nev = rng.randint(spec['nev_min'], spec['nev_max'])
    ev1 = [0.0] * n; ev2 = [0.0] * n; evinfo = []
    occupied = []
    for e_i in range(nev):
        ok = False
        for tries in range(60):
            ev = rng.choice(lib['events'])
            Le = len(ev['d1'])
            if spec['early'] and e_i == 0:
                cand = [rr for rr in runs if rr[0] < 0.45 * FS and rr[1] - rr[0] > Le + 30]
            else:
                cand = [rr for rr in runs if rr[1] - rr[0] > Le + 30]
            if not cand:
                break
            rr = rng.choice(cand)
            lo = rr[0] + 10; hi = rr[1] - Le - 10
            if spec['early'] and e_i == 0:
                hi = min(hi, int(0.55 * FS))
            elif not spec['early']:
                lo = max(lo, int(1.05 * FS))
            if hi < lo:
                continue
            s0 = rng.randint(lo, hi)
            if any(not (s0 + Le + 40 < a or s0 > b + 40) for a, b in occupied):
                continue
            sc = rng.uniform(*spec['ev_scale'])
            for i in range(Le):
                ev1[s0 + i] += sc * ev['d1'][i]; ev2[s0 + i] += sc * ev['d2'][i]
            occupied.append((s0, s0 + Le))
            evinfo.append({'t0': round(s0 / FS, 4), 'dur': round(Le / FS, 4), 'src': ev['src'], 'scale': round(sc, 4)})
            ok = True
            break
        if not ok and e_i < spec['nev_min']:
            return None
    src0 = rng.choice(lib['starts'])
    a1 = [qact(src0[0] + j1[i] + ev1[i]) for i in range(n)]
    a2 = [qact(src0[1] + j2[i] + ev2[i]) for i in range(n)]
    xs = [qdisp(v) for v in x]
    # first actuator motion (> 0.002 in from the t = 0 position)
    first = None
    for i in range(n):
        if abs(a1[i] - a1[0]) > 0.002 or abs(a2[i] - a2[0]) > 0.002:
            first = i / FS; break
    if spec['early'] and (first is None or first >= 1.0):
        return None
    if not spec['early'] and first is not None and first < 1.0:
        return None
    # final rest: no actuator motion in the final rest
    fr0 = n - Lf
    if any(abs(a1[i] - a1[0]) > 0.002 or abs(a2[i] - a2[0]) > 0.002 for i in range(fr0, n)):
        return None
    F0 = qforce(rng.uniform(-0.6, 1.1))
    rec = {'x': xs, 'a1': a1, 'a2': a2, 'F0': F0}
    rec['v'] = velocity(xs)
    rec['info'] = {'duration_s': round((n - 1) / FS, 4), 'samples': n, 'final_rest_s': round(Lf / FS, 4),
                   'first_actuator_motion_s': first, 'actuators_move_in_first_second': bool(first is not None and first < 1.0),
                   'n_actuator_events': len(evinfo), 'actuator_events': evinfo, 'pieces': info_pieces,
                   'initial_force_kip': F0, 'actuator_rest_positions_from': list(src0)}
    return rec


# ---------------------------------------------------------------- effects catalogue
# amplitude parameter 'amp' is solved for the target ratio; make_params(rng) draws the
# shape's fixed parameters; apply(p, amp) returns the effect dict for simulate().
def _sgn(rng):
    return 1 if rng.random() < 0.5 else -1


SHAPES = {
    'backlash': {
        'clearance_deadzone': dict(
            fixed=lambda rng: {},
            apply=lambda p, a: {'delta': a},
            amp0=0.01, amax=0.4),
        'load_dependent_gap': dict(
            fixed=lambda rng: {},
            apply=lambda p, a: {'c': a},
            amp0=0.003, amax=0.1),
        'reengagement_rattle': dict(
            fixed=lambda rng: {'omega': 2 * math.pi * rng.uniform(5.0, 12.0), 'zeta': rng.uniform(0.12, 0.3),
                               'delta_unit': rng.uniform(0.004, 0.01), 'A_unit': rng.uniform(0.5, 1.2)},
            apply=lambda p, a: {'delta': a * p['delta_unit'], 'A': a * p['A_unit'], 'omega': p['omega'], 'zeta': p['zeta']},
            amp0=0.5, amax=30.0),
    },
    'residual_static': {
        'log_time_relaxation': dict(
            fixed=lambda rng: {'tau': rng.uniform(0.05, 0.4), 'vth': 0.01},
            apply=lambda p, a: {'beta': a, 'tau': p['tau'], 'vth': p['vth']},
            amp0=0.03, amax=0.35),
        'sls_settling': dict(
            fixed=lambda rng: {'tau': rng.uniform(0.25, 1.2), 'vth': 0.01},
            apply=lambda p, a: {'drop': a, 'tau': p['tau'], 'vth': p['vth']},
            amp0=0.05, amax=0.95),
        'eyring_creep': dict(
            fixed=lambda rng: {'fa': rng.uniform(0.6, 1.5), 'vth': 0.01},
            apply=lambda p, a: {'c': a, 'fa': p['fa'], 'vth': p['vth']},
            amp0=0.01, amax=3.0),
    },
    'transition_shape': {
        'dahl_exponent': dict(
            fixed=lambda rng: {'side': _sgn(rng)},
            apply=lambda p, a: {'i': (1.0 + a) if p['side'] > 0 else 1.0 / (1.0 + a)},
            amp0=0.1, amax=6.0),
        'generalized_maxwell_slip': dict(
            fixed=lambda rng: {'alpha_star': _gms_alpha(rng)},
            apply=lambda p, a: {'beta': [0.25] * 4, 'alpha': [(1 - a) * 0.25 + a * s for s in p['alpha_star']]},
            amp0=0.1, amax=1.0),
        'elastoplastic_breakaway': dict(
            fixed=lambda rng: {'rba': rng.uniform(0.3, 0.75)},
            apply=lambda p, a: {'s': a, 'rba': p['rba']},
            amp0=0.1, amax=1.0),
    },
    'velocity': {
        'rate_state_log': dict(
            fixed=lambda rng: {'vstar': rng.uniform(0.1, 0.5), 'sign': _sgn(rng)},
            apply=lambda p, a: {'a': p['sign'] * a, 'vstar': p['vstar']},
            amp0=0.02, amax=0.4),
        'flash_temperature': dict(
            fixed=lambda rng: {'fref': 3.0, 'vref': 1.0},
            apply=lambda p, a: {'a': a, 'fref': p['fref'], 'vref': p['vref']},
            amp0=0.02, amax=0.45),
        'frictional_memory_lag': dict(
            fixed=lambda rng: {},
            apply=lambda p, a: {'tau': a},
            amp0=0.01, amax=0.6),
    },
    'actuator_lag': {
        'second_order_band': dict(
            fixed=lambda rng: {'zeta': rng.uniform(0.15, 0.45)},
            apply=lambda p, a: {'wn': 2 * math.pi / a, 'zeta': p['zeta']},    # a = natural period (s)
            amp0=0.05, amax=2.0),
        'transport_delay': dict(
            fixed=lambda rng: {},
            apply=lambda p, a: {'td': a},
            amp0=0.01, amax=0.5),
        'slew_rate_limit': dict(
            fixed=lambda rng: {},
            apply=lambda p, a: {'rate': 1.0 / a},                               # a = 1/rate (s/in)
            amp0=1.0, amax=200.0),
    },
    'self_energizing': {
        'leading_trailing_brake_factor': dict(
            fixed=lambda rng: {'fref': 10.0},
            apply=lambda p, a: {'lam': a, 'fref': p['fref']},
            amp0=0.05, amax=1.1),
        'capstan_wrap_with_rotation': dict(
            fixed=lambda rng: {'dirgain': [1.0, rng.uniform(0.3, 1.0)]},
            apply=lambda p, a: {'kappa': a, 'dirgain': p['dirgain']},
            amp0=0.02, amax=1.0),
        'servo_buildup_with_travel': dict(
            fixed=lambda rng: {'fref': 3.0, 'rho': rng.uniform(0.15, 0.6), 'sc': rng.uniform(0.15, 0.6)},
            apply=lambda p, a: {'kappa': a, 'fref': p['fref'], 'rho': p['rho'], 'sc': p['sc']},
            amp0=0.03, amax=2.0),
    },
    'pretension': {
        'hertzian_clamp': dict(
            fixed=lambda rng: {},
            apply=lambda p, a: {'d0': 1.0 / a},                                 # a = 1/delta0 (1/in)
            amp0=4.0, amax=400.0),
        'ernst_sagging_band': dict(
            fixed=lambda rng: {'kap': rng.uniform(9.0, 16.0)},
            apply=lambda p, a: {'theta': a, 'kap': p['kap']},
            amp0=0.2, amax=6.0),
        'hysteretic_clamp_play': dict(
            fixed=lambda rng: {'w': rng.uniform(0.6, 1.0)},
            apply=lambda p, a: {'w': p['w'], 'r': a},                           # a = play half-width (in)
            amp0=0.001, amax=0.08),
    },
    'asymmetry': {
        'bo_pavelescu_exponent_backward': dict(
            fixed=lambda rng: {'side': _sgn(rng)},
            apply=lambda p, a: {'delta_b': 2.0 * (1 + a) ** (0.5 * p['side']), 'vs_b': VS * (1 + a) ** p['side']},
            amp0=0.05, amax=4.0),
        'band_lining_backward_scale': dict(
            fixed=lambda rng: {'sign': _sgn(rng)},
            apply=lambda p, a: {'a': p['sign'] * a},
            amp0=0.02, amax=0.6),
        'directional_band_stiffness': dict(
            fixed=lambda rng: {'sign': _sgn(rng)},
            apply=lambda p, a: {'a': (a if p['sign'] > 0 else -a / (1 + a))},
            amp0=0.1, amax=6.0),
    },
}

ETYPE = {
    'clearance_deadzone': 'clearance', 'load_dependent_gap': 'loadgap', 'reengagement_rattle': 'rattle',
    'log_time_relaxation': 'logrelax', 'sls_settling': 'sls', 'eyring_creep': 'eyring',
    'dahl_exponent': 'dahl', 'generalized_maxwell_slip': 'gms', 'elastoplastic_breakaway': 'elastoplastic',
    'rate_state_log': 'logvel', 'flash_temperature': 'flash', 'frictional_memory_lag': 'hesssoom',
    'second_order_band': 'act2nd', 'transport_delay': 'deadtime', 'slew_rate_limit': 'slew',
    'leading_trailing_brake_factor': 'leadtrail', 'capstan_wrap_with_rotation': 'capstanpos',
    'servo_buildup_with_travel': 'buildup',
    'hertzian_clamp': 'hertz', 'ernst_sagging_band': 'ernst', 'hysteretic_clamp_play': 'play',
    'bo_pavelescu_exponent_backward': 'bopav', 'band_lining_backward_scale': 'bandscale',
    'directional_band_stiffness': 'dirstiff',
}


def _gms_alpha(rng):
    raw = sorted(rng.uniform(0.05, 1.0) for _ in range(4))
    s = sum(raw)
    return [r / s for r in raw]


def effect_for(shape, fixed, amp):
    for cat, shapes in SHAPES.items():
        if shape in shapes:
            return {'type': ETYPE[shape], 'p': shapes[shape]['apply'](fixed, amp)}
    raise KeyError(shape)


def rms_diff(recs, Fb, eff):
    s = 0.0; n = 0
    for rec, fb in zip(recs, Fb):
        ft = simulate(rec, eff)
        for a, b in zip(ft, fb):
            s += (a - b) ** 2
        n += len(fb)
    return math.sqrt(s / n)


def solve_amp(recs, Fb, shape, fixed, target_rms, amp0, amax):
    f = lambda a: rms_diff(recs, Fb, effect_for(shape, fixed, a)) - target_rms
    lo = 0.0; flo = -target_rms
    hi = amp0; fhi = f(hi)
    while fhi < 0:
        lo, flo = hi, fhi
        if hi >= amax:
            return None, fhi + target_rms
        hi = min(hi * 2.0, amax); fhi = f(hi)
    # Illinois regula falsi
    side = 0
    for it in range(60):
        a = hi - fhi * (hi - lo) / (fhi - flo) if fhi != flo else 0.5 * (lo + hi)
        if not (lo < a < hi):
            a = 0.5 * (lo + hi)
        fa = f(a)
        if abs(fa) < 2e-4 * target_rms:
            return a, fa + target_rms
        if fa > 0:
            hi, fhi = a, fa
            if side == 1: flo *= 0.5
            side = 1
        else:
            lo, flo = a, fa
            if side == -1: fhi *= 0.5
            side = -1
    return a, fa + target_rms


# ---------------------------------------------------------------- writing
def fmt(v):
    return repr(v)


def write_record(path, rec, Fmeas, A1, A2, vcol):
    n = len(rec['x'])
    rows = []
    for k in range(n):
        t = k if k % FS == 0 else None
        ts = str(k // FS) if t is not None else repr(k / FS)
        fm = Fmeas[k]
        fs_ = '0' if fm == 0.0 else repr(fm)
        rows.append('[%s, %s, %s, %s, %s, %s, %s, %s]' % (ts, repr(rec['x'][k]), fs_, repr(vcol[k]),
                                                          repr(rec['a1'][k]), repr(rec['a2'][k]),
                                                          repr(A1[k]), repr(A2[k])))
    s = ('{"data": [' + ', '.join(rows) + '], "dt": 0.0009765625, "sampling freq": 1024, '
         '"displacement units": "in", "time units": "s", "friction force units": "kip", "actuator force units": "lb"}')
    with open(path, 'w') as fh:
        fh.write(s)


def finish_record(rng, rec, Ftrue, noise):
    n = len(Ftrue)
    Fm = [rec['F0']] + [qforce(Ftrue[k] + rng.gauss(0.0, noise)) for k in range(1, n)]
    Fm = [0.0 if f == 0.0 else f for f in Fm]
    A1 = []; A2 = []
    for k in range(n):
        f = Ftrue[k]
        t1 = 37.0 + 490.0 * max(-f, 0.0) + rng.gauss(0.0, 6.0)
        t2 = 38.5 + 500.0 * max(f, 0.0) + rng.gauss(0.0, 6.0)
        A1.append(qgrid(max(t1, 20.0), QA1, QA1_PH)); A2.append(qgrid(max(t2, 20.0), QA2, QA2_PH))
    x = rec['x']
    vcol = []
    for k in range(n):
        j = max(0, k - 15)
        if k == 0:
            vcol.append(f32((x[1] - x[0]) / DT / VEL_RATIO))
        else:
            vcol.append(f32((x[k] - x[j]) / ((k - j) * DT) / VEL_RATIO))
    return Fm, A1, A2, vcol


# ---------------------------------------------------------------- plan and trials
def make_plan():
    rng = random.Random(MASTER_SEED)
    cats = list(SHAPES.keys())
    # strengths: 4 categories get 2 strong shapes, 4 get 1 -> 12 strong, 12 weak
    two = set(rng.sample(cats, 4))
    slots = []
    for cat in cats:
        shapes = list(SHAPES[cat].keys())
        ns = 2 if cat in two else 1
        strong = set(rng.sample(shapes, ns))
        for sh in shapes:
            slots.append((cat, sh, 'strong' if sh in strong else 'weak'))
    for i in range(6):
        slots.append(('none', 'base_model_plus_noise', 'none'))
    rng.shuffle(slots)
    # early-actuator flags: 20 of 60 records
    flags = [True] * 20 + [False] * 40
    rng.shuffle(flags)
    plan = []
    for i, (cat, sh, st) in enumerate(slots):
        plan.append({'trial': 't%02d' % (i + 1), 'category': cat, 'shape': sh, 'strength': st,
                     'seed': rng.randrange(1 << 30), 'early': [flags[2 * i], flags[2 * i + 1]]})
    return plan


_LIB = None


def get_lib():
    global _LIB
    if _LIB is None:
        _LIB = load_library()
    return _LIB


def record_spec(rng, cat, early):
    spec = {'early': early, 'T': rng.uniform(7.0, 22.0), 'rest_prob': rng.uniform(0.3, 0.8),
            'nev_min': 1 if early else 0, 'nev_max': 5, 'ev_scale': (0.75, 1.6)}
    if cat in ('actuator_lag', 'pretension'):
        spec['nev_min'] = 4; spec['nev_max'] = 8; spec['T'] = rng.uniform(7.0, 15.0)
        spec['ev_scale'] = (1.0, 2.0)
    if cat == 'residual_static':
        spec['rest_prob'] = max(spec['rest_prob'], 0.6)
    return spec


def build_trial(pl, write=True):
    lib = get_lib()
    rng = random.Random(pl['seed'])
    cat, shape, strength = pl['category'], pl['shape'], pl['strength']
    noise = rng.uniform(0.02, 0.06)
    recs = []
    for j, nm in enumerate('AB'):
        spec = record_spec(rng, cat, pl['early'][j])
        recs.append(build_record(rng, lib, spec))
    Fb = [simulate(r) for r in recs]
    key = {'category': cat, 'shape': shape, 'strength': strength, 'noise_kip': noise}
    if cat == 'none':
        Ft = Fb; key['ratio'] = 0.0; key['params'] = {}; key['target_ratio'] = 0.0
    else:
        sd = SHAPES[cat][shape]
        fixed = sd['fixed'](rng)
        target = rng.uniform(2.7, 3.8) if strength == 'weak' else rng.uniform(8.5, 11.5)
        amp, got = solve_amp(recs, Fb, shape, fixed, target * noise, sd['amp0'], sd['amax'])
        note = None
        if amp is None:
            # cannot reach strong: fall back to weak
            note = 'could not reach strong (max ratio %.2f at amp limit); made weak' % (got / noise)
            strength = 'weak'; key['strength'] = 'weak'
            target = rng.uniform(2.7, 3.8)
            amp, got = solve_amp(recs, Fb, shape, fixed, target * noise, sd['amp0'], sd['amax'])
        eff = effect_for(shape, fixed, amp)
        Ft = [simulate(r, eff) for r in recs]
        key['target_ratio'] = target
        key['ratio'] = got / noise
        key['params'] = {'amplitude': amp, 'fixed': fixed, 'effect': eff}
        if note:
            key['note'] = note
    nrng = random.Random(pl['seed'] ^ 0x5A5A5)
    key['records'] = {}
    d = os.path.join(ROOT, 'cases', pl['trial'])
    if write:
        os.makedirs(d, exist_ok=True)
    for j, nm in enumerate('AB'):
        Fm, A1, A2, vcol = finish_record(nrng, recs[j], Ft[j], noise)
        if write:
            write_record(os.path.join(d, nm + '.json'), recs[j], Fm, A1, A2, vcol)
        info = dict(recs[j]['info'])
        info['rms_effect_kip'] = math.sqrt(sum((a - b) ** 2 for a, b in zip(Ft[j], Fb[j])) / len(Fb[j]))
        key['records'][nm] = info
    return pl['trial'], key


def regenerate_truth(trial_key, pl):
    """Rebuild records (x, actuators, F0) and the noise-free true force for verify.py."""
    lib = get_lib()
    rng = random.Random(pl['seed'])
    cat = pl['category']
    rng.uniform(0.02, 0.06)
    recs = []
    for j in range(2):
        spec = record_spec(rng, cat, pl['early'][j])
        recs.append(build_record(rng, lib, spec))
    if cat == 'none':
        return recs, [simulate(r) for r in recs], None
    eff = trial_key['params']['effect']
    return recs, [simulate(r, eff) for r in recs], eff


def main():
    plan = make_plan()
    os.makedirs(os.path.join(ROOT, 'cases'), exist_ok=True)
    nproc = 2
    if nproc > 1:
        import multiprocessing as mp
        with mp.Pool(nproc) as pool:
            res = pool.map(build_trial, plan, chunksize=1)
    else:
        res = [build_trial(p) for p in plan]
    key = {}
    for (t, k), pl in zip(res, plan):
        k['seed'] = pl['seed']
        key[t] = k
    with open(os.path.join(ROOT, 'key.json'), 'w') as fh:
        json.dump(key, fh, indent=1, sort_keys=False)
    for t in sorted(key):
        k = key[t]
        print(t, k['category'], k['shape'], k['strength'], '%.2f' % k['ratio'], '%.4f' % k['noise_kip'],
              k['records']['A']['duration_s'], k['records']['B']['duration_s'], k.get('note', ''))


if __name__ == '__main__':
    main()
