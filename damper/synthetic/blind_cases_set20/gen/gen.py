#!/usr/bin/env python3
"""Blind test set 'blind20' for the BRFD semi-active model-discrepancy tool.

Regenerates /work/blind20/cases/tNN/{A,B}.json and /work/blind20/key.json deterministically
(master seed 20020). Python 3 standard library only.

    python3 gen.py [--out DIR]      (DIR defaults to the parent of this folder)

Base model (reproduced from the black box, see NOTES.md): LuGre Eqs. (1)-(3) with the kinetic
friction of Eq. (4) in the Stribeck function Eq. (5), parameters of /work/runs/brfd-semiactive.yaml,
drum velocity from the displacement column (central differences + 15-sample centred moving
average, shrinking at the ends), z(0) = F_file(0)/sigma0, exact exponential update of z over
each sample with v, x1, x2 of the new sample.
"""
import json, math, os, random, struct, sys, time

MASTER_SEED = 20020
HERE = os.path.dirname(os.path.abspath(__file__))
SRC = '/work/shared/data/brfd/semiactive'
SRC_FILES = ['harmonic0.015backward', 'harmonic0.015forward', 'harmonic0.03ea1backward',
             'harmonic0.03ea1forward', 'harmonic0.03ea2backward', 'harmonic0.03ea2forward']
FS_HZ = 1024
DT = 1.0 / FS_HZ

# ---------------------------------------------------------------- base model (config yaml)
S0, S1, S2 = 15.36, 0.0, 0.500
FSF, FSB, FCF, FCB, VS = 7.116, 3.760, 2.648, 1.253, 1.300
FLOOR = 0.05
MSL = [-0.14, -0.15, -15.29, -13.00, -16.66, -15.77, -0.13, -0.15]
CSC = [119.68, 2.10, 1.94, 123.31]
KF1 = CSC[0] * MSL[0] + CSC[1] * MSL[2]
KF2 = CSC[0] * MSL[1] + CSC[1] * MSL[3]
KB1 = CSC[2] * MSL[4] + CSC[3] * MSL[6]
KB2 = CSC[2] * MSL[5] + CSC[3] * MSL[7]

# ---------------------------------------------------------------- quantisation (from the measured files)
QX, OX = 5.8919197963814276e-05, -1.010582974538261      # drum displacement (in)
QF, OF = 0.0008007880207900535, -4.399987915996794       # friction force (kip)
QA1, OA1 = 2.443804044880738e-06, 0.6246849628457438     # actuator 1 position (in), float32
QA2, OA2 = 2.443795410339293e-06, 0.8255176065537769     # actuator 2 position (in), float32
QL1, OL1 = 0.31801611777623917, 24.419641328662124       # actuator 1 force (lb)
QL2, OL2 = 0.3999722969910918, 27.622662997867792        # actuator 2 force (lb)


def f32(x):
    return struct.unpack('f', struct.pack('f', x))[0]


def quant(x, q, o):
    return o + q * round((x - o) / q)


def sgn(x):
    return 1.0 if x > 0 else (-1.0 if x < 0 else 0.0)


# ---------------------------------------------------------------- helpers
def drum_velocity(x):
    """Exactly what the black box does: central differences (one-sided at the ends) followed by a
    15-sample centred moving average whose window shrinks symmetrically at the ends."""
    n = len(x)
    d = [0.0] * n
    d[0] = (x[1] - x[0]) / DT
    d[-1] = (x[-1] - x[-2]) / DT
    for i in range(1, n - 1):
        d[i] = (x[i + 1] - x[i - 1]) / (2 * DT)
    cs = [0.0]
    for a in d:
        cs.append(cs[-1] + a)
    v = [0.0] * n
    for i in range(n):
        h = min(7, i, n - 1 - i)
        v[i] = (cs[i + h + 1] - cs[i - h]) / (2 * h + 1)
    return v


def moving_average(a, h):
    n = len(a)
    cs = [0.0]
    for q in a:
        cs.append(cs[-1] + q)
    out = [0.0] * n
    for i in range(n):
        lo, hi = max(0, i - h), min(n, i + h + 1)
        out[i] = (cs[hi] - cs[lo]) / (hi - lo)
    return out


def interp(a, u):
    n = len(a)
    if u <= 0:
        return a[0]
    if u >= n - 1:
        return a[-1]
    i = int(u)
    f = u - i
    return a[i] * (1 - f) + a[i + 1] * f


# ---------------------------------------------------------------- measured sources
class Source:
    def __init__(self, name):
        d = json.load(open(os.path.join(SRC, name + '.json')))['data']
        self.name = name
        self.x = [r[1] for r in d]
        self.d1 = [r[4] - d[0][4] for r in d]
        self.d2 = [r[5] - d[0][5] for r in d]
        n = len(self.x)
        xs = moving_average(self.x, 25)
        ext = []
        for i in range(1, n - 1):
            if (xs[i] > xs[i - 1] and xs[i] >= xs[i + 1]) or (xs[i] < xs[i - 1] and xs[i] <= xs[i + 1]):
                if abs(xs[i]) > 0.1:
                    typ = 1 if xs[i] > 0 else -1
                    if ext and ext[-1][1] == typ:      # keep the larger of two same-type extrema
                        if abs(xs[i]) > abs(xs[ext[-1][0]]):
                            ext[-1] = (i, typ)
                    else:
                        ext.append((i, typ))
        self.ext = ext                                 # [(index, +1 max / -1 min)]
        # rest jitter (last 0.7 s, where drum and actuators are nearly still): high-pass part only
        # (minus a 0.1 s centred moving average), so that tiled pieces add no drift or steps
        i0 = n - 700
        self.rx, self.r1, self.r2 = [], [], []
        for src, dst in ((self.x, self.rx), (self.d1, self.r1), (self.d2, self.r2)):
            seg = src[i0 - 60:]
            sm = moving_average(seg, 50)
            dst += [a - b for a, b in zip(seg[60:], sm[60:])]
        # actuator events
        act = [max(abs(a), abs(b)) > 0.002 for a, b in zip(self.d1, self.d2)]
        spans = []
        i = 0
        while i < n:
            if act[i]:
                j = i
                while j < n and act[j]:
                    j += 1
                if spans and i - spans[-1][1] < 150:
                    spans[-1] = (spans[-1][0], j)
                else:
                    spans.append((i, j))
                i = j
            else:
                i += 1
        self.events = []
        for a, b in spans:
            a, b = max(0, a - 80), min(n - 1, b + 80)
            if b - a < 300:
                continue
            e1 = [self.d1[k] - (self.d1[a] + (self.d1[b] - self.d1[a]) * (k - a) / (b - a)) for k in range(a, b + 1)]
            e2 = [self.d2[k] - (self.d2[a] + (self.d2[b] - self.d2[a]) * (k - a) / (b - a)) for k in range(a, b + 1)]
            self.events.append((e1, e2, a))


# ---------------------------------------------------------------- record construction
class Builder:
    def __init__(self, rng, srcs):
        self.rng = rng
        self.srcs = srcs
        self.X, self.D1, self.D2 = [], [], []
        self.log = []
        self.rx = []
        self.r1 = []
        self.r2 = []
        for s in srcs:
            self.rx += s.rx
            self.r1 += s.r1
            self.r2 += s.r2

    def t(self):
        return len(self.X) * DT

    def rest(self, dur, value=None, kind='rest', dev=None):
        rng = self.rng
        n = int(round(dur * FS_HZ))
        xv = self.X[-1] if value is None else value
        if dev is not None:
            e1, e2 = dev
        else:
            e1 = self.D1[-1] if self.D1 else 0.0
            e2 = self.D2[-1] if self.D2 else 0.0
        off = rng.randrange(len(self.rx))
        L = len(self.rx)
        r0x = self.rx[off % L]
        r01, r02 = self.r1[off % L], self.r2[off % L]
        for j in range(n):
            k = (off + j) % L
            self.X.append(xv + self.rx[k] - r0x)
            self.D1.append(e1 + self.r1[k] - r01)
            self.D2.append(e2 + self.r2[k] - r02)
        self.log.append({'kind': kind, 't0': round((len(self.X) - n) * DT, 4), 'dur_s': round(n * DT, 4)})

    def piece(self, s, i0, i1, kind, need_type=None, amp_max=1.2):
        """Append source s samples i0..i1 (time-stretched, scaled, maybe mirrored)."""
        rng = self.rng
        st = rng.uniform(0.75, 1.5)
        sa = rng.uniform(0.35, amp_max)
        # peak drum speed limit ~4.5 in/s (source peak ~3.5 in/s)
        sa = min(sa, 4.5 / 3.6 * st)
        mir = 1.0
        if need_type is not None:
            st_type = [e[1] for e in s.ext if e[0] == i0][0]
            mir = 1.0 if st_type == need_type else -1.0
        elif rng.random() < 0.5:
            mir = -1.0
        asc = rng.uniform(0.6, 2.0) * (1.0 if rng.random() < 0.75 else -1.0)
        m = int(round((i1 - i0) * st))
        xs, a1, a2 = [], [], []
        for j in range(m + 1):
            u = i0 + j / st
            xs.append(mir * sa * interp(s.x, u))
            p1, p2 = interp(s.d1, u), interp(s.d2, u)
            if mir < 0:
                p1, p2 = p2, p1
            a1.append(asc * p1)
            a2.append(asc * p2)
        # continuity with what is already there: decaying offsets
        if self.X:
            dx = self.X[-1] - xs[0]
            # length of the first half cycle: to the next extremum of the source
            nxt = [e[0] for e in s.ext if e[0] > i0]
            L1 = int(round(((nxt[0] if nxt else i1) - i0) * st))
            L1 = max(1, min(L1, m))
            for j in range(L1 + 1):
                xs[j] += dx * 0.5 * (1 + math.cos(math.pi * j / L1))
            d1o, d2o = self.D1[-1] - a1[0], self.D2[-1] - a2[0]
            L2 = min(m, 205)
            for j in range(L2 + 1):
                w = 0.5 * (1 + math.cos(math.pi * j / L2))
                a1[j] += d1o * w
                a2[j] += d2o * w
            xs, a1, a2 = xs[1:], a1[1:], a2[1:]
        t0 = self.t()
        self.X += xs
        self.D1 += a1
        self.D2 += a2
        self.log.append({'kind': kind, 'src': s.name, 'src_t0': round(i0 * DT, 3), 'src_t1': round(i1 * DT, 3),
                         't0': round(t0, 4), 'dur_s': round(len(xs) * DT, 4), 'time_stretch': round(st, 4),
                         'amp_scale': round(sa, 4), 'mirrored': mir < 0, 'act_scale': round(asc, 4)})


def build_record(rng, srcs, early):
    """Drum displacement and actuator deviations for one record, from pieces of the measured tests."""
    B = Builder(rng, srcs)
    T_target = rng.uniform(6.5, 25.0)
    r_final = rng.uniform(1.5, 3.5)
    r0 = rng.uniform(0.3, 1.5)
    n_mid_rest = 0
    s = rng.choice(srcs)
    tmp = Builder(rng, srcs)
    if rng.random() < 0.35:
        # measured start: ramp-up from rest, up to extremum k
        k = rng.randint(1, 3)
        tmp.piece(s, 0, s.ext[k][0], 'start_piece')
    else:
        k0 = rng.randint(1, len(s.ext) - 3)
        k = k0 + rng.randint(1, min(3, len(s.ext) - 1 - k0))
        tmp.piece(s, s.ext[k0][0], s.ext[k][0], 'piece')
    B.rest(r0, value=tmp.X[0], kind='initial_rest', dev=(tmp.D1[0], tmp.D2[0]))
    B.X += tmp.X[1:]
    B.D1 += tmp.D1[1:]
    B.D2 += tmp.D2[1:]
    tmp.log[0]['t0'] = round(B.log[0]['dur_s'], 4)
    B.log += tmp.log
    last_type = s.ext[k][1] * (-1 if tmp.log[0]['mirrored'] else 1)
    ended_with_end_piece = False
    while B.t() + r_final < T_target:
        if n_mid_rest < 2 and rng.random() < 0.3:
            d = rng.uniform(0.5, 2.5)
            if B.t() + d + r_final + 2.0 < 25.0:
                B.rest(d, kind='mid_rest')
                n_mid_rest += 1
        s = rng.choice(srcs)
        remaining = 25.0 - r_final - B.t()
        if rng.random() < 0.3 and B.t() + r_final + 3.0 > T_target:
            # measured end: from one of the last extrema through the ramp-down and rest
            k = rng.randint(len(s.ext) - 4, len(s.ext) - 2)
            i0 = s.ext[k][0]
            i1 = len(s.x) - 1
            if (i1 - i0) * DT * 1.5 < remaining:
                B.piece(s, i0, i1, 'end_piece', need_type=last_type)
                ended_with_end_piece = True
                break
        k = rng.randint(0, len(s.ext) - 2)
        h = rng.randint(1, 4)
        h = min(h, len(s.ext) - 1 - k)
        while h > 0 and (s.ext[k + h][0] - s.ext[k][0]) * DT * 1.5 > remaining:
            h -= 1
        if h == 0:
            break
        B.piece(s, s.ext[k][0], s.ext[k + h][0], 'piece', need_type=last_type)
        mir = B.log[-1]['mirrored']
        last_type = s.ext[k + h][1] * (-1 if mir else 1)
    B.rest(r_final, kind='final_rest')
    n = len(B.X)
    # ---- actuator events placed in time ("rearranged")
    evlib = [(s, e) for s in srcs for e in s.events]
    D1, D2 = B.D1, B.D2
    if not early:
        # no actuator motion in the first second: taper the coupled deviations in
        for k in range(min(n, int(1.6 * FS_HZ))):
            w = 0.0 if k < 1.1 * FS_HZ else 0.5 - 0.5 * math.cos(math.pi * (k - 1.1 * FS_HZ) / (0.5 * FS_HZ))
            D1[k] *= w
            D2[k] *= w
    T = n * DT
    n_ev = rng.randint(2, 2 + int(T / 2.5))
    placements = []
    if early:
        placements.append(rng.uniform(0.05, 0.6))
    for _ in range(n_ev):
        placements.append(rng.uniform(1.2, max(1.3, T - 3.0)))
    events_info = []
    for tp in placements:
        s, (e1, e2, ea) = rng.choice(evlib)
        st = rng.uniform(0.7, 1.5)
        sc = rng.uniform(0.8, 2.4) * (1.0 if rng.random() < 0.7 else -1.0)
        swap = rng.random() < 0.5
        k0 = int(round(tp * FS_HZ))
        m = int(round((len(e1) - 1) * st))
        for j in range(m + 1):
            k = k0 + j
            if k >= n:
                break
            p1, p2 = interp(e1, j / st), interp(e2, j / st)
            if swap:
                p1, p2 = p2, p1
            D1[k] += sc * p1
            D2[k] += sc * p2
        events_info.append({'t0': round(tp, 3), 'dur_s': round(m * DT, 3), 'src': s.name,
                            'src_t0': round(ea * DT, 3), 'scale': round(sc, 3), 'swapped': swap,
                            'time_stretch': round(st, 3)})
    # travel measured from the t = 0 position, limited to about +-0.075 in (soft clip beyond 0.05)
    for D in (D1, D2):
        d0 = D[0]
        for k in range(n):
            D[k] -= d0
        for k in range(n):
            a = abs(D[k])
            if a > 0.05:
                D[k] = math.copysign(0.05 + 0.025 * math.tanh((a - 0.05) / 0.025), D[k])
    return B.X, D1, D2, B.log, events_info


# ---------------------------------------------------------------- model machinery
class Rec:
    """Quantised record inputs plus everything the base model / effects need."""

    def __init__(self, x, a1, a2, F0file):
        self.n = n = len(x)
        self.x, self.x1, self.x2 = x, a1, a2
        self.x1p, self.x2p = a1[0], a2[0]
        self.F0 = F0file
        self.v = v = drum_velocity(x)
        self.pos = [vk >= 0 for vk in v]
        self.E = [math.exp(-(vk / VS) ** 2) for vk in v]
        self.fclin = self.fc_lin(a1, a2)
        self.fc = [max(f, FLOOR) for f in self.fclin]
        self.fs = [FSF if p else FSB for p in self.pos]
        self.g = [fc + (fs - fc) * e for fc, fs, e in zip(self.fc, self.fs, self.E)]
        self.Fbase = lugre(self, self.g)
        # rest detection (|v| averaged over 0.1 s below 0.01 in/s during the last 0.05 s)
        vsm = moving_average(v, 50)
        cnt = 50
        self.rest = [False] * n
        self.trest = [0.0] * n
        dl = sgn(F0file) or 1.0
        self.dlast = [0.0] * n
        for k in range(n):
            if abs(vsm[k]) < 0.01:
                cnt += 1
            else:
                cnt = 0
            if abs(vsm[k]) > 0.05:
                dl = sgn(vsm[k])
            self.dlast[k] = dl
            if cnt >= 51:
                self.rest[k] = True
                self.trest[k] = (cnt - 51) * DT
        # travel since the last drum reversal: s = distance back from the running extreme once it
        # exceeds 0.4 mil (quantisation jitter), reversal confirmed after 3 mil; before the first
        # reversal s is 'large' (the record starts as if the last slip was in the direction of F0)
        eps_s, eps_c = 4e-4, 3e-3
        self.srev = [0.0] * n
        dirn = sgn(F0file) or 1.0
        ext, xrev = x[0], None
        for k in range(n):
            xk = x[k]
            if dirn > 0:
                if xk > ext:
                    ext = xk
                d = ext - xk
            else:
                if xk < ext:
                    ext = xk
                d = xk - ext
            if d > eps_c:
                xrev, dirn, ext = ext, -dirn, xk
                d = 0.0
            if d > eps_s:
                self.srev[k] = d
            else:
                self.srev[k] = abs(xk - xrev) if xrev is not None else 1e3

    def fc_lin(self, a1, a2):
        out = []
        for p, y1, y2 in zip(self.pos, a1, a2):
            d1, d2 = y1 - self.x1p, y2 - self.x2p
            out.append(FCF + KF1 * d1 + KF2 * d2 if p else FCB + KB1 * d1 + KB2 * d2)
        return out

    def g_from_fc(self, fc, E=None):
        E = self.E if E is None else E
        return [f + (fs - f) * e for f, fs, e in zip(fc, self.fs, E)]


def lugre(rec, g, s0=S0):
    v, n = rec.v, rec.n
    z = rec.F0 / s0
    F = [0.0] * n
    F[0] = s0 * z + S2 * v[0]
    a = s0 * DT
    exp = math.exp
    for k in range(1, n):
        vk = v[k]
        if vk > 0:
            zs = g[k] / s0
            z = zs + (z - zs) * exp(-a * vk / g[k])
        elif vk < 0:
            zs = -g[k] / s0
            z = zs + (z - zs) * exp(a * vk / g[k])
        F[k] = s0 * z + S2 * vk
    return F


# ---------------------------------------------------------------- the 24 effect shapes
def _z_step(z, vk, gk):
    if vk > 0:
        zs = gk / S0
        return zs + (z - zs) * math.exp(-S0 * vk / gk * DT)
    if vk < 0:
        zs = -gk / S0
        return zs + (z - zs) * math.exp(S0 * vk / gk * DT)
    return z


def eff_B1(rec, p, q):
    """rigid link with a dead zone (total lost motion 2r) between drum and band/interface: in
    contact the interface moves with the drum (base LuGre); when the transmitted force would change
    sign the link separates, F = 0 exactly while the drum crosses the gap (the interface relaxes,
    sigma0 z + sigma2 v_i = 0), and contact on the other side re-engages with an impact."""
    r = p
    v, g, n, x = rec.v, rec.g, rec.n, rec.x
    z = rec.F0 / S0
    side = sgn(rec.F0) or 1.0
    y = x[0] - r * side
    contact = True
    F = [rec.Fbase[0]] + [0.0] * (n - 1)
    for k in range(1, n):
        vk, gk, xk = v[k], g[k], x[k]
        if not contact:
            u = xk - y
            if u >= r:
                contact, side = True, 1.0
            elif u <= -r:
                contact, side = True, -1.0
        if contact:
            z = _z_step(z, vk, gk)
            Fk = S0 * z + S2 * vk
            y = xk - r * side
            if Fk * side < 0 and r > 0:
                contact = False
                Fk = 0.0
        else:
            lam = S0 / S2 * (1.0 + S0 * abs(z) / gk)
            zn = z * math.exp(-lam * DT)
            y += -S0 / S2 * 0.5 * (z + zn) * DT
            z = zn
            Fk = 0.0
        F[k] = Fk
    return F


def eff_B2(rec, p, q):
    """loss of band tension while neither band end is taut: friction capacity and viscous term
    scaled by e(s) = 1 - (1 - e_min) exp(-s/l), s = drum travel since the last reversal, l = p."""
    ell = p
    emin = q['e_min']
    if ell <= 0:
        return rec.Fbase
    v, n = rec.v, rec.n
    e = [1.0 - (1.0 - emin) * math.exp(-s / ell) for s in rec.srev]
    g = [gk * ek for gk, ek in zip(rec.g, e)]
    z = rec.F0 / S0
    F = [rec.Fbase[0]] + [0.0] * (n - 1)
    for k in range(1, n):
        z = _z_step(z, v[k], g[k])
        F[k] = S0 * z + S2 * e[k] * v[k]
    return F


def eff_B3(rec, p, q):
    """three-stage (unload - near-zero backlash - re-tension): the base unloading runs until the
    transmitted force crosses zero; from there the force is taken up as 1 - exp(-s/l), s = drum
    travel since that zero crossing, l = p."""
    ell = p
    v, g, n, x = rec.v, rec.g, rec.n, rec.x
    z = rec.F0 / S0
    F = [rec.Fbase[0]] + [0.0] * (n - 1)
    Fo = rec.Fbase[0]
    s = 1e9
    for k in range(1, n):
        vk = v[k]
        z = _z_step(z, vk, g[k])
        FL = S0 * z + S2 * vk
        if FL * Fo < 0:
            s = 0.0
        else:
            s += abs(x[k] - x[k - 1])
        Fo = FL
        e = 1.0 - math.exp(-s / ell) if ell > 0 else 1.0
        F[k] = FL * e
    return F


def _rest_effect(rec, offset_fn):
    v, g, n = rec.v, rec.g, rec.n
    z = rec.F0 / S0
    F = [0.0] * n
    Fh, Oprev, was = 0.0, 0.0, False
    for k in range(n):
        vk = v[k]
        if k > 0 and vk != 0:
            zt = g[k] / S0 if vk > 0 else -g[k] / S0
            z = zt + (z - zt) * math.exp(-S0 * abs(vk) / g[k] * DT)
        if rec.rest[k]:
            if not was:
                Fh, Oprev = S0 * z, 0.0
                was = True
            O = offset_fn(rec.trest[k], Fh, rec.dlast[k])
            z += (O - Oprev) / S0
            Oprev = O
        else:
            was = False
        F[k] = S0 * z + S2 * vk
    return F


def eff_R1(rec, p, q):
    """standard-linear-solid relaxation at rest: held force relaxes toward (1-p)*F_hold, tau."""
    tau = q['tau_s']
    return _rest_effect(rec, lambda t, Fh, d: -p * Fh * (1 - math.exp(-t / tau)))


def eff_R2(rec, p, q):
    """logarithmic-time creep relaxation at rest: |F| drops by p*ln(1+t/tau0) (not past zero)."""
    t0 = q['tau0_s']
    return _rest_effect(rec, lambda t, Fh, d: -sgn(Fh) * min(abs(Fh), p * math.log(1 + t / t0)))


def eff_R3(rec, p, q):
    """residual band tension at rest: settles by +p kip in the direction of the last slip."""
    tau = q['tau_s']
    return _rest_effect(rec, lambda t, Fh, d: p * d * (1 - math.exp(-t / tau)))


def _rk4_lugre(rec, rhs):
    """RK4 with v, g held over the sample, sub-stepped so that |v|/|z_ss| * h <= 0.1."""
    v, g, n = rec.v, rec.g, rec.n
    z = rec.F0 / S0
    F = [rec.Fbase[0]] + [0.0] * (n - 1)
    for k in range(1, n):
        vk = v[k]
        if vk != 0:
            zs = g[k] / S0 if vk > 0 else -g[k] / S0
            m = max(1, int(math.ceil(abs(vk) / abs(zs) * DT / 0.1)))
            h = DT / m
            for _ in range(m):
                k1 = rhs(z, vk, zs)
                k2 = rhs(z + 0.5 * h * k1, vk, zs)
                k3 = rhs(z + 0.5 * h * k2, vk, zs)
                k4 = rhs(z + h * k3, vk, zs)
                z = z + h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        F[k] = S0 * z + S2 * vk
    return F


def eff_T1(rec, p, q):
    """Dahl exponent: dz/dt = v*|1 - z/zs|^alpha*sgn(1 - z/zs), alpha = 1+p or 1/(1+p).
    With u = 1 - z/zs: du/dt = -(|v|/|zs|) |u|^alpha sgn(u), solved exactly over each sample."""
    al = 1.0 + p if q['rounder'] else 1.0 / (1.0 + p)
    v, g, n = rec.v, rec.g, rec.n
    z = rec.F0 / S0
    F = [rec.Fbase[0]] + [0.0] * (n - 1)
    for k in range(1, n):
        vk = v[k]
        if vk != 0:
            zs = g[k] / S0 if vk > 0 else -g[k] / S0
            c = abs(vk) / abs(zs) * DT
            u = 1.0 - z / zs
            au = abs(u)
            if au > 0:
                if al == 1.0:
                    au = au * math.exp(-c)
                elif al > 1.0:
                    au = (au ** (1.0 - al) + (al - 1.0) * c) ** (-1.0 / (al - 1.0))
                else:
                    w = au ** (1.0 - al) - (1.0 - al) * c
                    au = w ** (1.0 / (1.0 - al)) if w > 0 else 0.0
                u = au if u > 0 else -au
            z = zs * (1.0 - u)
        F[k] = S0 * z + S2 * vk
    return F


def eff_T2(rec, p, q):
    """generalized Maxwell-slip / Iwan: 4 parallel LuGre elements, equal shares of g, stiffness
    shares spread by exp(p*u_i); total sliding level unchanged."""
    us = [-1.0, -1.0 / 3, 1.0 / 3, 1.0]
    lam = [math.exp(p * u) for u in us]
    m = sum(lam) / 4.0
    lam = [l / m for l in lam]
    v, g, n = rec.v, rec.g, rec.n
    zi = [rec.F0 / S0] * 4
    F = [rec.Fbase[0]] + [0.0] * (n - 1)
    for k in range(1, n):
        vk = v[k]
        if vk != 0:
            sv = 1.0 if vk > 0 else -1.0
            for i in range(4):
                zs = sv * g[k] / (S0 * lam[i])
                zi[i] = zs + (zi[i] - zs) * math.exp(-S0 * lam[i] * abs(vk) / g[k] * DT)
        F[k] = S0 * 0.25 * sum(l * z for l, z in zip(lam, zi)) + S2 * vk
    return F


def eff_T3(rec, p, q):
    """elasto-plastic presliding (Dupont et al.): pure elastic for |z| < p*zss on loading, smooth
    transition (Dupont's half-sine) to LuGre slip by min(2p, 1)*zss; unloading as LuGre."""
    def rhs(z, vk, zs):
        zb = p * abs(zs)
        w = min(zb, abs(zs) - zb)
        az = abs(z)
        if z * vk > 0 and zb > 0:
            if az < zb:
                al = 0.0
            elif az < zb + w:
                al = 0.5 - 0.5 * math.cos(math.pi * (az - zb) / w)
            else:
                al = 1.0
        else:
            al = 1.0
        return vk * (1.0 - al * z / zs)
    return _rk4_lugre(rec, rhs)


def eff_V1(rec, p, q):
    """generalized Stribeck exponent delta = 2*exp(-p) (< 2: slower, longer Stribeck decay)."""
    d = 2.0 * math.exp(-p)
    E = [math.exp(-abs(vk / VS) ** d) for vk in rec.v]
    return lugre(rec, rec.g_from_fc(rec.fc, E))


def eff_V2(rec, p, q):
    """frictional lag: the Stribeck curve sees the velocity through a first-order lag tau_L = p."""
    tau = p
    c = 1.0 - math.exp(-DT / tau) if tau > 0 else 1.0
    vf = rec.v[0]
    E = []
    for vk in rec.v:
        vf += (vk - vf) * c
        E.append(math.exp(-(vf / VS) ** 2))
    return lugre(rec, rec.g_from_fc(rec.fc, E))


def eff_V3(rec, p, q):
    """rate-and-state (Ruina slip law, regularised): Fc*(1 + a ln(1+|v|/v*) + theta),
    dtheta/dt = -(|v|/Dc)(theta + b ln(1+|v|/v*)), a = p, b = beta*p."""
    a, b, vst, Dc = p, q['beta'] * p, q['vstar'], q['Dc']
    th = 0.0
    fc = []
    for vk, f in zip(rec.v, rec.fc):
        av = abs(vk)
        L = math.log(1.0 + av / vst)
        tss = -b * L
        th = tss + (th - tss) * math.exp(-av * DT / Dc)
        m = max(0.05, 1.0 + a * L + th)
        fc.append(max(FLOOR, f * m))
    return lugre(rec, rec.g_from_fc(fc))


def _act_eff(rec, y1, y2):
    fl = rec.fc_lin(y1, y2)
    return lugre(rec, rec.g_from_fc([max(f, FLOOR) for f in fl]))


def eff_A1(rec, p, q):
    """pure transport delay tau_d = p of the band clamping behind the actuator positions."""
    nd = p / DT
    y1 = [interp(rec.x1, k - nd) for k in range(rec.n)]
    y2 = [interp(rec.x2, k - nd) for k in range(rec.n)]
    return _act_eff(rec, y1, y2)


def eff_A2(rec, p, q):
    """first-order lag, time constant p."""
    c = 1.0 - math.exp(-DT / p) if p > 0 else 1.0
    y1, y2 = [], []
    e1, e2 = rec.x1[0], rec.x2[0]
    for a, b in zip(rec.x1, rec.x2):
        e1 += (a - e1) * c
        e2 += (b - e2) * c
        y1.append(e1)
        y2.append(e2)
    return _act_eff(rec, y1, y2)


def eff_A3(rec, p, q):
    """second-order servo: y'' = wn^2 (x - y) - 2 zeta wn y', wn = 1/p."""
    if p <= 0:
        return rec.Fbase
    wn, ze = 1.0 / p, q['zeta']
    out = []
    for xs in (rec.x1, rec.x2):
        y, yd = xs[0], 0.0
        ys = []
        for xk in xs:
            def f(y_, yd_):
                return yd_, wn * wn * (xk - y_) - 2 * ze * wn * yd_
            a1, b1 = f(y, yd)
            a2, b2 = f(y + 0.5 * DT * a1, yd + 0.5 * DT * b1)
            a3, b3 = f(y + 0.5 * DT * a2, yd + 0.5 * DT * b2)
            a4, b4 = f(y + DT * a3, yd + DT * b3)
            y += DT / 6 * (a1 + 2 * a2 + 2 * a3 + a4)
            yd += DT / 6 * (b1 + 2 * b2 + 2 * b3 + b4)
            ys.append(y)
        ys[0] = xs[0]
        out.append(ys)
    return _act_eff(rec, out[0], out[1])


def eff_S1(rec, p, q):
    """capstan with wrap angle growing with drum rotation: g*exp(p*sgn(v)*x)."""
    g = [gk * math.exp(p * (1.0 if pk else -1.0) * xk) for gk, pk, xk in zip(rec.g, rec.pos, rec.x)]
    return lugre(rec, g)


def eff_S2(rec, p, q):
    """leading/trailing shoe factor: g/(1 - p g/10) energizing direction, g/(1 + p g/10) other."""
    ed = q['energizing_forward']
    g = []
    for gk, pk in zip(rec.g, rec.pos):
        if pk == ed:
            g.append(gk / max(0.05, 1.0 - p * gk / 10.0))
        else:
            g.append(gk / (1.0 + p * gk / 10.0))
    return lugre(rec, g)


def eff_S3(rec, p, q):
    """servo build-up with travel since the last reversal: g*(1 + p(1 - exp(-s/l)))."""
    ell = q['ell_in']
    g = [gk * (1.0 + p * (1.0 - math.exp(-s / ell))) for gk, s in zip(rec.g, rec.srev)]
    return lugre(rec, g)


def eff_P1(rec, p, q):
    """power-law (Hertz-type, stiffening) clamping: Fc = b*(Fc_lin/b)^n, n = 1+p."""
    nn = 1.0 + p
    fc = []
    for f, pk in zip(rec.fclin, rec.pos):
        b = FCF if pk else FCB
        fc.append(max(FLOOR, b * (f / b) ** nn) if f > 0 else FLOOR)
    return lugre(rec, rec.g_from_fc(fc))


def eff_P2(rec, p, q):
    """Archard wear of the lining: clamping lost in proportion to the friction work done in the
    record: g*(1 - p*W/100 kip-in), floored at 0.2."""
    W = 0.0
    g = []
    for gk, vk in zip(rec.g, rec.v):
        W += gk * abs(vk) * DT
        g.append(gk * max(0.2, 1.0 - p * W / 100.0))
    return lugre(rec, g)


def eff_P3(rec, p, q):
    """thermal loosening (fade): lining temperature state T' = g|v|/10 - T/tau_th, g*(1 - p T)."""
    tau = q['tau_th_s']
    c = math.exp(-DT / tau)
    T = 0.0
    g = []
    for gk, vk in zip(rec.g, rec.v):
        T = T * c + gk * abs(vk) * DT / 10.0
        g.append(gk * max(0.2, 1.0 - p * T))
    return lugre(rec, g)


def eff_Y1(rec, p, q):
    """the two bands differ in compliance: sigma0/(1+p) while the force is in the 'soft' band's
    direction (bilinear bristle spring; force-form of Eq. 1, exact per sample incl. zero crossing)."""
    sd = 1.0 if q['soft_forward'] else -1.0
    s0s = S0 / (1.0 + p)
    v, g, n = rec.v, rec.g, rec.n
    Ff = rec.F0
    F = [rec.Fbase[0]] + [0.0] * (n - 1)
    for k in range(1, n):
        vk = v[k]
        if vk != 0:
            Fss = g[k] if vk > 0 else -g[k]
            s0 = s0s if (Ff * sd > 0 or (Ff == 0 and vk * sd > 0)) else S0
            lam = s0 * abs(vk) / g[k]
            Fn = Fss + (Ff - Fss) * math.exp(-lam * DT)
            if Ff * Fn < 0:
                ts = math.log((Ff - Fss) / (-Fss)) / lam
                s1 = S0 if s0 == s0s else s0s
                lam1 = s1 * abs(vk) / g[k]
                Fn = Fss * (1.0 - math.exp(-lam1 * (DT - ts)))
            Ff = Fn
        F[k] = Ff + S2 * vk
    return F


def eff_Y2(rec, p, q):
    """extra viscous friction p*sigma2*v in one sliding direction only."""
    fwd = q['forward']
    return [F + (p * S2 * vk if ((vk >= 0) == fwd) else 0.0) for F, vk in zip(rec.Fbase, rec.v)]


def eff_Y3(rec, p, q):
    """direction-dependent Stribeck velocity: vs*(1+p)^(+-1) in one direction."""
    fwd = q['forward']
    vsd = VS * ((1.0 + p) if q['up'] else 1.0 / (1.0 + p))
    E = [math.exp(-(vk / (vsd if ((vk >= 0) == fwd) else VS)) ** 2) for vk in rec.v]
    return lugre(rec, rec.g_from_fc(rec.fc, E))


# category -> [(shape name, function, p0, pmax, p meaning, source, param drawer)]
def _q_none(r):
    return {}


SHAPES = {
    'backlash': [
        ('deadzone_rigid_link', eff_B1, 0.02, 0.6, 'r: half-width (in) of the dead zone (lost motion 2r) between drum and band', _q_none),
        ('tension_loss_after_reversal', eff_B2, 0.05, 1.5, 'l: drum travel (in) over which the band tension recovers after a reversal',
         lambda r: {'e_min': round(r.uniform(0.03, 0.15), 4)}),
        ('three_stage_takeup', eff_B3, 0.05, 1.5, 'l: travel constant (in) of the 1-exp(-s/l) re-tension after each force zero-crossing', _q_none),
    ],
    'residual_static': [
        ('sls_relaxation', eff_R1, 0.2, 0.95, 'fraction of the held force relaxed at rest (exp, time constant tau_s)',
         lambda r: {'tau_s': round(r.uniform(0.25, 1.2), 4)}),
        ('log_creep_relaxation', eff_R2, 0.2, 4.0, 'kip per unit ln(1+t/tau0) of held-force decay at rest',
         lambda r: {'tau0_s': round(r.uniform(0.02, 0.1), 4)}),
        ('residual_band_tension', eff_R3, 0.3, 5.0, 'kip of extra residual force settling at rest in the last slip direction',
         lambda r: {'tau_s': round(r.uniform(0.15, 0.8), 4)}),
    ],
    'transition_shape': [
        ('dahl_exponent', eff_T1, 0.2, 2.5, 'alpha-1 (rounder) or 1/alpha-1 (sharper) of the Dahl exponent',
         lambda r: {'rounder': r.random() < 0.5}),
        ('maxwell_slip_spread', eff_T2, 0.5, 4.0, 'log-spread of element stiffness shares (4 Maxwell-slip elements)', _q_none),
        ('elastoplastic_presliding', eff_T3, 0.1, 0.95, 'z_ba/z_ss: purely elastic fraction of the bristle range', _q_none),
    ],
    'velocity': [
        ('stribeck_exponent', eff_V1, 0.3, 2.5, 'ln(2/delta), delta = Stribeck exponent (2 in the model)', _q_none),
        ('frictional_lag', eff_V2, 0.05, 1.5, 'tau_L (s): lag of the velocity seen by the Stribeck curve', _q_none),
        ('rate_state_ruina', eff_V3, 0.05, 1.2, 'a: direct-effect coefficient (b = beta*a) of rate-and-state friction on Fc',
         lambda r: {'beta': round(r.uniform(1.4, 2.2), 4), 'vstar': round(r.uniform(0.2, 0.8), 4),
                    'Dc': round(r.uniform(0.05, 0.3), 4)}),
    ],
    'actuator_lag': [
        ('transport_delay', eff_A1, 0.05, 1.2, 'tau_d (s): pure delay of the clamping behind the actuator positions', _q_none),
        ('first_order_lag', eff_A2, 0.05, 2.5, 'tau (s): first-order lag time constant', _q_none),
        ('second_order_servo', eff_A3, 0.05, 1.2, '1/omega_n (s) of an underdamped second-order clamping response',
         lambda r: {'zeta': round(r.uniform(0.2, 0.45), 4)}),
    ],
    'self_energizing': [
        ('capstan_wrap_angle', eff_S1, 0.1, 1.5, 'mu/R (1/in): capstan exponent per inch of drum travel, g*exp(p*sgn(v)*x)', _q_none),
        ('shoe_factor_feedback', eff_S2, 0.1, 1.0, 'p in g/(1 -+ p g/10 kip): load feedback of the self-energizing (leading) band',
         lambda r: {'energizing_forward': r.random() < 0.5}),
        ('servo_buildup_travel', eff_S3, 0.1, 2.5, 'fractional friction build-up with travel since reversal, g*(1+p(1-exp(-s/l)))',
         lambda r: {'ell_in': round(r.uniform(0.15, 0.6), 4)}),
    ],
    'pretension': [
        ('power_law_clamping', eff_P1, 0.2, 4.0, 'n-1: exponent n of the stiffening clamp law Fc = b (Fc_lin/b)^n', _q_none),
        ('archard_wear_loosening', eff_P2, 0.1, 4.0, 'fraction of clamping lost per 100 kip-in of friction work', _q_none),
        ('thermal_fade', eff_P3, 0.05, 4.0, 'fraction of clamping lost per unit lining temperature state (T in 10 kip-in units)',
         lambda r: {'tau_th_s': round(r.uniform(2.0, 8.0), 4)}),
    ],
    'asymmetry': [
        ('directional_band_stiffness', eff_Y1, 0.3, 10.0, 'sigma0 -> sigma0/(1+p) while the force is in the soft band direction',
         lambda r: {'soft_forward': r.random() < 0.5}),
        ('directional_viscous', eff_Y2, 1.0, 8.0, 'extra viscous coefficient p*sigma2 in one sliding direction',
         lambda r: {'forward': r.random() < 0.5}),
        ('directional_stribeck_velocity', eff_Y3, 0.2, 9.0, 'v_s -> v_s*(1+p)^(+-1) in one sliding direction',
         lambda r: {'forward': r.random() < 0.5, 'up': r.random() < 0.5}),
    ],
}

SOURCES = {
    'deadzone_rigid_link': 'Dead-zone backlash model with rigid engagement / impact (Nordin & Gutman 2002, Automatica 38(10):1633-1649; Nordin, Galic & Gutman 1997, Int. J. Adapt. Control Signal Process. 11(1):49-63) between the drum and the LuGre interface',
    'tension_loss_after_reversal': 'Band tension (normal force) lost while neither band end is taut after a reversal (seed paper, backlash description; band-brake friction proportional to band tension, Euler-Eytelwein), recovering with drum travel',
    'three_stage_takeup': 'Three-stage dynamic friction model with a near-zero-force backlash stage between unloading and re-tensioned sliding (Cao, Downey, Laflamme, Taylor & Ricles 2015, J. Sound Vib. 348:41-56, cited by the seed paper)',
    'sls_relaxation': 'Standard linear solid (Zener 1948, Elasticity and Anelasticity of Metals) stress relaxation of the tensioned band/lining at rest',
    'log_creep_relaxation': 'Logarithmic-time creep/relaxation of frictional contacts at rest (Baumberger & Caroli 2006, Adv. Phys. 55:279-348; Dieterich 1972, J. Geophys. Res. 77:3690)',
    'residual_band_tension': 'Residual static force persisting between drum and bands after excitation (seed paper: Coble et al., model error modes, Fig. 14), first-order settling in the last slip direction',
    'dahl_exponent': 'Dahl model shape exponent i (Dahl 1976, AIAA J. 14(12):1675-1682): dF/dx = sigma|1 - F/Fc sgn v|^i sgn(...)',
    'maxwell_slip_spread': 'Distributed-element / generalized Maxwell-slip friction (Iwan 1966, J. Appl. Mech. 33:893-900; Al-Bender, Lampaert & Swevers 2005, IEEE TAC 50(11):1883-1887)',
    'elastoplastic_presliding': 'Single-state elasto-plastic friction model with a purely elastic presliding region (Dupont, Hayward, Armstrong & Altpeter 2002, IEEE TAC 47(5):787-792)',
    'stribeck_exponent': 'Generalized Stribeck curve exp(-|v/vs|^delta) (Armstrong-Helouvry, Dupont & Canudas de Wit 1994, Automatica 30(7):1083-1138)',
    'frictional_lag': 'Frictional lag / memory: friction responds to a lagged velocity (Hess & Soom 1990, J. Tribol. 112(1):147-152; Armstrong-Helouvry et al. 1994 seven-parameter model)',
    'rate_state_ruina': 'Rate-and-state friction, Dieterich 1979 (J. Geophys. Res. 84(B5):2161-2168) with the Ruina 1983 slip evolution law (J. Geophys. Res. 88(B12):10359-10370)',
    'transport_delay': 'Pure actuator time delay (Horiuchi, Inoue, Konno & Namita 1999, Earthquake Eng. Struct. Dyn. 28(10):1121-1141)',
    'first_order_lag': 'First-order filter between command and effective damper input (Spencer, Dyke, Sain & Carlson 1997, J. Eng. Mech. 123(3):230-238)',
    'second_order_servo': 'Second-order (underdamped) servo-actuator dynamics (actuator dynamics / control-structure interaction, Dyke, Spencer, Quast & Sain 1995, J. Eng. Mech. 121(2):322-338)',
    'capstan_wrap_angle': 'Euler-Eytelwein capstan equation T1/T2 = exp(mu theta) for band brakes (e.g. Budynas & Nisbett, Shigley\'s Mechanical Engineering Design, band-type brakes) with the wrap angle changing with drum rotation (self-energizing description of the seed paper)',
    'shoe_factor_feedback': 'Brake (shoe) factor of self-energizing leading / de-energizing trailing brakes, C* = mu/(1 -+ mu h/a) (Limpert 1999, Brake Design and Safety, SAE), duo-servo friction damper of Cao et al. 2015',
    'servo_buildup_travel': 'Servo (self-energizing) action that develops as the band/shoe is dragged after a reversal (duo-servo brakes: Limpert 1999; Day 2014, Braking of Road Vehicles)',
    'power_law_clamping': 'Hertz-type power-law contact load vs interference, N ~ delta^n (Johnson 1985, Contact Mechanics), applied to the actuator-set clamping of Eq. 4',
    'archard_wear_loosening': 'Archard 1953 wear law (J. Appl. Phys. 24(8):981-988): wear ~ load x sliding distance, i.e. friction work, loosening the band clamp',
    'thermal_fade': 'Thermal brake fade: friction/clamp loss with lining temperature, first-order heating by friction power and Newton cooling (Limpert 1999; Day 2014)',
    'directional_band_stiffness': 'Direction-dependent LuGre parameters (Canudas de Wit, Olsson, Astrom & Lischinsky 1995, IEEE TAC 40(3):419-425; seed paper: forward loads band 2, backward band 1), here the bristle/band stiffness',
    'directional_viscous': 'Direction-dependent viscous friction coefficient (asymmetric friction parameter sets, Marton & Lantos 2007, IEEE Trans. Ind. Electron. 54(1):511-521)',
    'directional_stribeck_velocity': 'Direction-dependent Stribeck velocity (asymmetric friction parameter sets, Marton & Lantos 2007; Armstrong-Helouvry 1991, Control of Machines with Friction)',
}


# ---------------------------------------------------------------- trial generation
def rms_ratio(recs, Fts, sd):
    s, n = 0.0, 0
    for r, Ft in zip(recs, Fts):
        for a, b in zip(Ft, r.Fbase):
            s += (a - b) ** 2
        n += r.n
    return math.sqrt(s / n) / sd


def solve_p(fn, recs, q, sd, target, p0, pmax):
    def R(p):
        return rms_ratio(recs, [fn(r, p, q) for r in recs], sd)
    lo, rlo = 0.0, 0.0
    p = p0
    hi = rhi = None
    evals = 0
    while True:
        r = R(p)
        evals += 1
        if abs(r / target - 1) < 0.003:
            return p, r, evals
        if r >= target:
            hi, rhi = p, r
            break
        lo, rlo = p, r
        if p >= pmax:
            return None, r, evals
        fac = (target / r) ** 1.2 if r > 0 else 4.0
        p = min(pmax, p * min(8.0, max(1.5, fac)))
    for _ in range(30):
        if rlo > 0 and lo > 0:
            p = math.exp(math.log(lo) + (math.log(target) - math.log(rlo)) *
                         (math.log(hi) - math.log(lo)) / (math.log(rhi) - math.log(rlo)))
        else:
            p = hi * target / rhi
        w = hi - lo
        p = min(max(p, lo + 0.05 * w), hi - 0.05 * w)
        r = R(p)
        evals += 1
        if abs(r / target - 1) < 0.003:
            return p, r, evals
        if r > target:
            hi, rhi = p, r
        else:
            lo, rlo = p, r
    return p, r, evals


def make_records(rng, srcs, sd, early_flags):
    """Two records: inputs (quantised), F_file(0) and Rec objects."""
    out = []
    for name, early in zip('AB', early_flags):
        X, D1, D2, log, evs = build_record(rng, srcs, early)
        n = len(X)
        b1 = 0.655 + rng.uniform(-0.002, 0.002)
        b2 = 0.8559 + rng.uniform(-0.002, 0.002)
        x = [quant(a, QX, OX) for a in X]
        a1 = [f32(quant(b1 + d, QA1, OA1)) for d in D1]
        a2 = [f32(quant(b2 + d, QA2, OA2)) for d in D2]
        F0true = rng.uniform(-1.5, 3.5)
        n0 = rng.gauss(0.0, 1.0)
        F0file = quant(F0true + sd * n0, QF, OF)
        kv = rng.uniform(125.35, 125.55)
        ct1, ct2 = rng.uniform(1.85, 2.1), rng.uniform(1.85, 2.1)
        cs1, cs2 = rng.uniform(110, 130), rng.uniform(110, 130)
        sl1, sl2 = rng.uniform(25, 45), rng.uniform(25, 45)
        rec = Rec(x, a1, a2, F0file)
        first_motion = None
        for k in range(n):
            if abs(a1[k] - a1[0]) > 0.002 or abs(a2[k] - a2[0]) > 0.002:
                first_motion = k * DT
                break
        out.append({'name': name, 'rec': rec, 'log': log, 'events': evs, 'kv': kv,
                    'act_force': (ct1, ct2, cs1, cs2, sl1, sl2), 'F0true': F0true,
                    'first_act_motion_s': first_motion})
    return out


def write_record(path, R, Ffile, rng):
    rec = R['rec']
    n = rec.n
    x = rec.x
    d = [0.0] * n
    d[0] = (x[1] - x[0]) / DT
    d[-1] = (x[-1] - x[-2]) / DT
    for i in range(1, n - 1):
        d[i] = (x[i + 1] - x[i - 1]) / (2 * DT)
    vm = moving_average(d, 15)
    ct1, ct2, cs1, cs2, sl1, sl2 = R['act_force']
    rows = []
    for k in range(n):
        t = k * DT
        t = int(t) if k % FS_HZ == 0 else t
        F = Ffile[k]
        Fp, Fm = max(F, 0.0), max(-F, 0.0)
        l1 = sl1 + 1000.0 * Fm / ct1 + 1000.0 * Fp / cs1 + rng.gauss(0, 2.0)
        l2 = sl2 + 1000.0 * Fp / ct2 + 1000.0 * Fm / cs2 + rng.gauss(0, 2.0)
        rows.append([t, x[k], F, f32(vm[k] / R['kv']), rec.x1[k], rec.x2[k],
                     quant(l1, QL1, OL1), quant(l2, QL2, OL2)])
    doc = {'data': rows, 'dt': DT, 'sampling freq': FS_HZ, 'displacement units': 'in',
           'time units': 's', 'friction force units': 'kip', 'actuator force units': 'lb'}
    with open(path, 'w') as fh:
        json.dump(doc, fh)


def plan(master):
    cats = list(SHAPES.keys())
    pattern_strong2 = master.sample(cats, 4)          # these get 2 strong, the others 1 strong
    effect = []
    for c in cats:
        ns = 2 if c in pattern_strong2 else 1
        st = ['strong'] * ns + ['weak'] * (3 - ns)
        master.shuffle(st)
        for i in range(3):
            effect.append((c, i, st[i]))
    slots = effect + [('none', None, None)] * 6
    master.shuffle(slots)
    return slots


def generate(out_dir, verbose=True, write=True):
    t_start = time.time()
    srcs = [Source(nm) for nm in SRC_FILES]
    master = random.Random(MASTER_SEED)
    slots = plan(master)
    seeds = [master.randrange(2 ** 31) for _ in slots]
    # early actuator motion: exactly 20 of the 60 records, spread by the master seed
    early_all = [True] * 20 + [False] * 40
    master.shuffle(early_all)
    key = {}
    results = {}
    for ti, ((cat, si, strength), seed) in enumerate(zip(slots, seeds)):
        tid = 't%02d' % (ti + 1)
        trng = random.Random(seed)
        sd = trng.uniform(0.02, 0.06)
        if cat == 'none':
            shape, fn, p0, pmax, pmean, qdraw = 'none', None, 0, 0, 'none', _q_none
            target = 0.0
        else:
            shape, fn, p0, pmax, pmean, qdraw = SHAPES[cat][si]
            target = trng.uniform(2.7, 3.8) if strength == 'weak' else trng.uniform(8.5, 11.5)
        q = qdraw(trng)
        early = early_all[2 * ti: 2 * ti + 2]
        attempt = 0
        while True:
            rrng = random.Random(seed * 31 + 7 + attempt)
            Rs = make_records(rrng, srcs, sd, early)
            recs = [R['rec'] for R in Rs]
            if fn is None:
                p, ratio, evals = 0.0, 0.0, 0
                Fts = [r.Fbase for r in recs]
                break
            pmax_eff = pmax
            if shape == 'shoe_factor_feedback':
                ef = q['energizing_forward']
                gmax = max(max(gk for gk, pk in zip(r.g, r.pos) if pk == ef) for r in recs)
                pmax_eff = min(pmax, 0.75 * 10.0 / gmax)
            p, ratio, evals = solve_p(fn, recs, q, sd, target, p0, pmax_eff)
            if p is not None:
                Fts = [fn(r, p, q) for r in recs]
                ratio = rms_ratio(recs, Fts, sd)
                break
            attempt += 1
            if attempt > 12:
                raise RuntimeError('%s %s: target %.2f not reachable' % (tid, shape, target))
        nrng = random.Random(seed * 31 + 1000003)
        files = {}
        info = {}
        for R, Ft in zip(Rs, Fts):
            rec = R['rec']
            Ffile = [rec.F0] + [quant(Ft[k] + nrng.gauss(0.0, sd), QF, OF) for k in range(1, rec.n)]
            files[R['name']] = (R, Ffile)
            info[R['name']] = {'duration_s': round((rec.n - 1) * DT, 4), 'n_samples': rec.n,
                               'F_init_kip': round(rec.F0, 6),
                               'actuators_move_in_first_second': R['first_act_motion_s'] is not None and R['first_act_motion_s'] < 1.0,
                               'first_actuator_motion_s': R['first_act_motion_s'],
                               'x1_initial_in': rec.x1p, 'x2_initial_in': rec.x2p,
                               'pieces': R['log'], 'actuator_events': R['events'],
                               'velocity_column_factor': round(R['kv'], 4)}
        if write:
            d = os.path.join(out_dir, 'cases', tid)
            os.makedirs(d, exist_ok=True)
            for nm, (R, Ffile) in files.items():
                write_record(os.path.join(d, nm + '.json'), R, Ffile, random.Random(seed * 31 + 99 + ord(nm)))
        key[tid] = {'category': cat, 'shape': shape, 'strength': strength if cat != 'none' else 'none',
                    'p': p, 'p_meaning': pmean, 'noise_kip': sd, 'ratio': ratio, 'target_ratio': target,
                    'params': q, 'source': SOURCES.get(shape, 'none: exact base model + noise'),
                    'record_attempts': attempt + 1, 'solver_evals': evals, 'records': info}
        results[tid] = {'recs': [files[n][0]['rec'] for n in 'AB'], 'truth': Fts,
                        'Ffile': [files[n][1] for n in 'AB']}
        if verbose:
            print('%s %-16s %-30s %-6s sd=%.4f target=%6.3f ratio=%6.3f p=%.5g evals=%d att=%d  (%.1fs)' % (
                tid, cat, shape, strength or '', sd, target, ratio, p, evals, attempt + 1, time.time() - t_start),
                flush=True)
    if write:
        with open(os.path.join(out_dir, 'key.json'), 'w') as fh:
            json.dump(key, fh, indent=1, sort_keys=True)
    return key, results


if __name__ == '__main__':
    out = os.path.dirname(HERE)
    if '--out' in sys.argv:
        out = sys.argv[sys.argv.index('--out') + 1]
    t0 = time.time()
    generate(out)
    print('gen.py done in %.1f s' % (time.time() - t0))
