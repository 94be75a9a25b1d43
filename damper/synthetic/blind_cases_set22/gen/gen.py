#!/usr/bin/env python3
"""Blind test set generator (master seed 22022). Python 3 stdlib only.
Regenerates /work/blind22/cases/tXX/{A,B}.json and key.json deterministically.
Base model (inferred from the black box, see NOTES.md): drum velocity = central differences of the
displacement column + centred 15-sample moving average; z0 = F_meas[0]/sigma0; each step i->i+1 integrates
LuGre exactly with the inputs (v, x1, x2) of sample i+1 held constant; F = sigma0 z + sigma2 v."""
import json, math, os, random, struct, sys
from multiprocessing import Pool

SEED = 22022
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SRC = '/work/shared/data/brfd/semiactive'
DT = 1.0 / 1024
S0, S1, S2 = 15.36, 0.0, 0.500
FSF, FSB, FCF, FCB, VS = 7.116, 3.760, 2.648, 1.253, 1.300
M = [-0.14, -0.15, -15.29, -13.00, -16.66, -15.77, -0.13, -0.15]
C = [119.68, 2.10, 1.94, 123.31]
FLOOR = 0.05
K1F, K2F = C[0]*M[0] + C[1]*M[2], C[0]*M[1] + C[1]*M[3]
K1B, K2B = C[2]*M[4] + C[3]*M[6], C[2]*M[5] + C[3]*M[7]
QF = 0.00080087996174084          # force lattice (kip), offset ~0
QD, OD = 5.886506440592083e-05, 4.993961670809096e-05   # displacement lattice (in)
QA = 2.384185791015625e-06         # actuator position step (in)
QL1, QL2 = 0.3179418, 0.3998960    # actuator force steps (lb)
HEAD = ['dt', 'sampling freq', 'displacement units', 'time units', 'friction force units', 'actuator force units']

def f32(x): return struct.unpack('f', struct.pack('f', x))[0]
def qforce(F): return round(F / QF) * QF
def qdisp(x): return round((x - OD) / QD) * QD + OD

def velocity(x):
    n = len(x)
    vc = [(x[min(i+1, n-1)] - x[max(i-1, 0)]) / ((min(i+1, n-1) - max(i-1, 0)) * DT) for i in range(n)]
    cs = [0.0]
    for a in vc: cs.append(cs[-1] + a)
    return [(cs[min(n-1, i+7)+1] - cs[max(0, i-7)]) / (min(n-1, i+7) - max(0, i-7) + 1) for i in range(n)]

# ---------------------------------------------------------------- sources
def load_sources():
    strokes, motions = [], []
    for fn in sorted(os.listdir(SRC)):
        d = json.load(open(os.path.join(SRC, fn)))['data']
        x = [r[1] for r in d]; v = velocity(x); n = len(x)
        # reversals: sign changes of v with hysteresis 0.05 in/s
        rev = []; s = 0
        for i in range(n):
            if s >= 0 and v[i] < -0.05:
                if s > 0: rev.append(max(range(max(0, (rev[-1] if rev else 0)), i), key=lambda k: x[k]))
                s = -1
            elif s <= 0 and v[i] > 0.05:
                if s < 0: rev.append(min(range(max(0, (rev[-1] if rev else 0)), i), key=lambda k: x[k]))
                s = 1
        for a, b in zip(rev, rev[1:]):
            tr = x[b] - x[a]
            if abs(tr) > 1.5:
                strokes.append([(x[k] - x[a]) / tr for k in range(a, b + 1)])
        p1, p2 = d[0][4], d[0][5]
        act = [abs(r[4]-p1) > 0.001 or abs(r[5]-p2) > 0.001 for r in d]
        i = 0
        while i < n:
            if act[i]:
                j = i
                while j < n and (any(act[j:j+60])): j += 1
                a, b = max(0, i-30), min(n, j+30)
                d1 = [d[k][4]-p1 for k in range(a, b)]; d2 = [d[k][5]-p2 for k in range(a, b)]
                L = len(d1); T = 40
                for k in range(L):
                    w = 1.0
                    if k < T: w = 0.5 - 0.5*math.cos(math.pi*k/T)
                    if k > L-1-T: w = 0.5 - 0.5*math.cos(math.pi*(L-1-k)/T)
                    d1[k] *= w; d2[k] *= w
                both = max(abs(u) for u in d1) > 0.005 and max(abs(u) for u in d2) > 0.005
                motions.append({'src': fn, 't0': a*DT, 'd1': d1, 'd2': d2, 'both': both})
                i = j
            i += 1
    return strokes, motions

def resample(seq, m):
    L = len(seq); out = []
    for k in range(m):
        u = k*(L-1)/(m-1); i = min(int(u), L-2); f = u-i
        out.append(seq[i]*(1-f) + seq[i+1]*f)
    return out

# ---------------------------------------------------------------- records
def build_record(rng, SRCS, want_motion, early, need_both, F0, need_act=False):
    strokes, motions = SRCS
    P1, P2 = 0.6549999713897705, 0.8559008240699768
    for attempt in range(200):
        Ltot = rng.uniform(6.5, 13.0) if rng.random() < 0.8 else rng.uniform(13.0, 19.0)
        fin = rng.uniform(1.6, 2.6)
        pos = rng.uniform(-0.3, 0.3)
        X = []; D1 = []; D2 = []; REST = []; info = {'pieces': []}
        n0 = int((rng.uniform(0.1, 0.25) if early else rng.uniform(0.15, 0.9)) / DT)
        X += [pos]*n0; D1 += [0.0]*n0; D2 += [0.0]*n0; REST += [True]*n0
        info['pieces'].append(['rest', round(n0*DT, 4)])
        nmot = 0; first = True
        mot_pool = [m for m in motions if m['both']] if need_both else motions
        target_mot = (rng.randint(2, 4) if need_act else rng.randint(1, 3)) if want_motion else 0
        if need_act: Ltot = rng.uniform(6.5, 11.0)
        while len(X)*DT < Ltot - fin:
            u = rng.choice(strokes)
            travel = rng.uniform(0.5, 2.3)
            if pos > 0.4: sg = -1
            elif pos < -0.4: sg = 1
            else: sg = rng.choice([-1, 1])
            if abs(pos + sg*travel) > 1.25: travel = max(0.3, 1.25 - abs(pos))
            tf = rng.uniform(0.65, 1.5)
            m = max(64, int(len(u)*tf*travel**0.3 / 1.23))
            if early and first and m < 600: m = 600 + rng.randint(0, 300)
            seg = resample(u, m)
            st = len(X)
            X += [pos + sg*travel*s for s in seg]; REST += [False]*m
            d1 = [0.0]*m; d2 = [0.0]*m
            if early and first:
                host = m > 500
            else:
                host = nmot < target_mot and st*DT > 1.05 and m > 400 and rng.random() < (0.9 if need_act else 0.7)
            if host:
                mo = rng.choice(mot_pool)
                Lm = int(m*rng.uniform(0.55, 0.9)); sc = rng.uniform(0.7, 1.5)*rng.choice([-1, 1])
                r1 = resample(mo['d1'], Lm); r2 = resample(mo['d2'], Lm)
                off = rng.randint(20, min(150, m-Lm-1)) if early and first else rng.randint(20, m-Lm-1)
                for k in range(Lm):
                    d1[off+k] = sc*r1[k]; d2[off+k] = sc*r2[k]
                nmot += 1
                info['pieces'].append(['stroke+act', round(sg*travel, 4), round(m*DT, 4), mo['src'], round(mo['t0'], 3), round(abs(sc), 3)])
            else:
                info['pieces'].append(['stroke', round(sg*travel, 4), round(m*DT, 4)])
            D1 += d1; D2 += d2
            pos = X[-1]; first = False
            if rng.random() < 0.4 and len(X)*DT < Ltot - fin - 0.5:
                nr = int(rng.uniform(0.2, 1.3)/DT)
                X += [pos]*nr; D1 += [0.0]*nr; D2 += [0.0]*nr; REST += [True]*nr
                info['pieces'].append(['rest', round(nr*DT, 4)])
        nf = int(fin/DT)
        X += [pos]*nf; D1 += [0.0]*nf; D2 += [0.0]*nf; REST += [True]*nf
        info['pieces'].append(['rest', round(nf*DT, 4)])
        n = len(X)
        if not (6.5 <= (n-1)*DT <= 25): continue
        if want_motion and nmot == 0: continue
        # quantise: displacement with light jitter (not within 24 samples of the ends)
        xq = [qdisp(X[i] + (rng.gauss(0, 0.35*QD) if 24 <= i < n-24 else 0.0)) for i in range(n)]
        x1 = [f32(P1 + round(D1[i]/QA)*QA) for i in range(n)]
        x2 = [f32(P2 + round(D2[i]/QA)*QA) for i in range(n)]
        x1[0] = P1; x2[0] = P2
        fm = None
        for i in range(n):
            if abs(x1[i]-P1) > 0.002 or abs(x2[i]-P2) > 0.002: fm = i*DT; break
        if early and (fm is None or fm >= 1.0): continue
        if (not early) and fm is not None and fm < 1.0: continue
        runs = []; i = 0
        while i < n:
            if REST[i]:
                j = i
                while j < n and REST[j]: j += 1
                runs.append([i, j]); i = j
            else: i += 1
        info['rest_runs'] = runs
        info['first_motion_s'] = fm; info['n_act_motions'] = nmot
        info['length_s'] = round((n-1)*DT, 4); info['final_rest_s'] = round(nf*DT, 4)
        return {'x': xq, 'x1': x1, 'x2': x2, 'rest': REST, 'F0': F0, 'p1': P1, 'p2': P2}, info
    raise RuntimeError('record construction failed')

# ---------------------------------------------------------------- model (+ effects)
def fc_law(v, x1, x2, p1, p2, eff=None, P=None):
    d1, d2 = x1 - p1, x2 - p2
    if eff == 'PT2':  # slack-side saturation of extension
        a = P['a']
        if a > 0:
            if d1 > 0: d1 = math.tanh(a*d1)/a
            if d2 > 0: d2 = math.tanh(a*d2)/a
    if v >= 0: b, D = FCF, K1F*d1 + K2F*d2
    else: b, D = FCB, K1B*d1 + K2B*d2
    if eff == 'PT1':  # power-law clamping: Fc = b (1 + D/b)^n
        n = 1.0 + P['sgn']*P['a']
        f = b*max(1.0 + D/b, 1e-3)**n
    elif eff == 'PT3':  # actuator cross-coupling term
        f = b + D + P['a']*P['dirsign'][0 if v >= 0 else 1]*d1*d2
    else:
        f = b + D
    return max(f, FLOOR)

def simulate(rec, eff=None, P=None):
    x = rec['x']; X1 = rec['x1']; X2 = rec['x2']; REST = rec['rest']
    V = velocity(x); n = len(x); p1, p2 = rec['p1'], rec['p2']
    a_ = P['a'] if P else 0.0
    z = rec['F0']/S0
    F = [0.0]*n
    F[0] = S0*z + S2*V[0]
    y1, y2 = p1, p2; yd1 = yd2 = 0.0              # actuator-lag states
    vl = 0.0                                     # lagged velocity (TS2)
    psi = math.log(1.0)                          # rate-state memory (V3)
    Xs = x[0]; pp = x[0]                         # integrated drum position, play interface (BL1)
    dirn = 0; trav = 10.0; prev_trav = 0.0; lost = 0.0   # reversal bookkeeping
    trest = 0.0; zstop = None; add = 0.0; Fstop = 0.0; slip_since = 0.0; aged = 0.0
    hist1 = [p1]; hist2 = [p2]
    if eff == 'AL2': nd = a_/DT
    if eff == 'BL1': pp = x[0] - a_*(1 if rec['F0'] >= 0 else -1)   # start in contact on the loaded side
    for j in range(1, n):
        v = V[j]; x1 = X1[j]; x2 = X2[j]
        # reversal detection on the smoothed velocity
        rev = False
        if v > 0.02 and dirn <= 0:
            rev = dirn != 0; dirn = 1
        elif v < -0.02 and dirn >= 0:
            rev = dirn != 0; dirn = -1
        if rev: prev_trav = trav; trav = 0.0
        trav += abs(v)*DT
        # ---- actuator lag
        if eff == 'AL1':
            tr = P['tau_ratio']
            tau1 = a_*(tr if x1 < y1 else 1.0); tau2 = a_*(tr if x2 < y2 else 1.0)
            y1 += (x1-y1)*(1-math.exp(-DT/tau1)) if tau1 > 0 else (x1-y1)
            y2 += (x2-y2)*(1-math.exp(-DT/tau2)) if tau2 > 0 else (x2-y2)
            x1, x2 = y1, y2
        elif eff == 'AL2':
            hist1.append(x1); hist2.append(x2)
            u = j - nd
            if u <= 0: x1, x2 = p1, p2
            else:
                i0 = int(u); f = u - i0
                x1 = hist1[i0]*(1-f) + hist1[min(i0+1, j)]*f
                x2 = hist2[i0]*(1-f) + hist2[min(i0+1, j)]*f
        elif eff == 'AL3':
            if a_ > 0:
                wn = 1.0/a_; ze = P['zeta']; ns = max(1, int(DT*wn/0.05)+1); h = DT/ns
                for _ in range(ns):
                    yd1 += h*(wn*wn*(x1-y1) - 2*ze*wn*yd1); y1 += h*yd1
                    yd2 += h*(wn*wn*(x2-y2) - 2*ze*wn*yd2); y2 += h*yd2
                x1, x2 = y1, y2
        fc = fc_law(v, x1, x2, p1, p2, eff, P)
        fs = FSF if v >= 0 else FSB
        vs = VS
        if eff == 'AS1' and (v >= 0) == (P['dir'] > 0): vs = VS*math.exp(P['sgn']*a_)
        if eff == 'V2':
            vw = P['vw']
            if abs(v) > vw: fc = fc*(1 - a_*(1 - vw/abs(v)))
        elif eff == 'V3':
            lv = math.log(1 + abs(v)/P['vstar'])
            psi += (lv - psi)*(1 - math.exp(-(abs(v) + 0.01)*DT/P['Dc']))
            fc = fc*(1 + P['sgn']*a_*psi)
        if eff == 'TS1':
            ex = math.exp(-abs(v/vs)**(2.0 - a_))
        elif eff == 'TS2':
            vl += (v - vl)*(1 - math.exp(-DT/a_)) if a_ > 0 else (v - vl)
            ex = math.exp(-(vl/vs)**2)
        else:
            ex = math.exp(-(v/vs)**2)
        g = fc + (fs - fc)*ex
        if eff == 'SE1':
            g *= math.exp(a_*x[j]*(1 if v >= 0 else -1))
        elif eff == 'SE2':
            if v >= 0 and z > 0: g /= (1 - a_*min(S0*z/P['Fref'], 0.95))
        elif eff == 'SE3':
            if (v >= 0) == (P['dir'] > 0): g *= 1 + a_*(1 - math.exp(-trav/P['lam']))
        k = S0
        if eff == 'AS3' and (v >= 0) == (P['dir'] > 0): k = S0*math.exp(P['sgn']*a_)
        ve = v
        collapse = False
        if eff == 'BL1':
            Xs += v*DT
            pn = min(max(pp, Xs - a_), Xs + a_)
            ve = (pn - pp)/DT
            # contact lost once the drum is more than 3 mil inside the dead band
            collapse = a_ > 0 and abs(Xs - pn) < a_ - min(0.003, 0.5*a_)
            pp = pn
        elif eff == 'BL3':
            if rev: lost = a_*prev_trav
            if lost > 0:
                lost -= abs(v)*DT; ve = 0.0; collapse = True
        # ---- integrate one step (inputs of sample j held), exact for linear-in-z LuGre
        if eff == 'TS3':
            w = min(a_, 1.0); zb = P['zba'] + max(a_ - 1.0, 0.0)*(0.95 - P['zba'])
            def dz(zz):
                zss = g/S0
                if zz*ve <= 0: al = 1.0
                else:
                    r = abs(zz)/zss
                    if r <= zb: ad = 0.0
                    elif r >= 1: ad = 1.0
                    else: ad = 0.5 + 0.5*math.sin(math.pi*((r - zb)/(1 - zb) - 0.5))
                    al = (1 - w) + w*ad
                return ve - al*S0*abs(ve)/g*zz
            k1 = dz(z); k2 = dz(z + DT/2*k1); k3 = dz(z + DT/2*k2); k4 = dz(z + DT*k3)
            z += DT/6*(k1 + 2*k2 + 2*k3 + k4)
        elif collapse:
            z *= math.exp(-abs(v)*DT/P['lu'])   # band spring unloads over travel lu inside the free play
        else:
            ar = k*abs(ve)/g
            if ar > 0:
                e = math.exp(-ar*DT)
                z = z*e + (ve/ar)*(1 - e)*(k/S0)
            else:
                z += ve*DT*(k/S0)
        # ---- rest effects
        if eff == 'RS1':
            if REST[j]:
                if zstop is None: zstop = z; trest = 0.0
                trest += DT
                z = zstop*((1 - a_) + a_*math.exp(-trest/P['tau']))
            else:
                zstop = None
        Fz = S0*z
        if eff == 'BL2':
            Fz *= 1 - a_*math.exp(-trav/P['lam'])
        out = Fz + S2*ve
        if eff == 'V1':
            out += a_*(1 if v >= 0 else -1)*abs(v)**P['n']
        elif eff == 'AS2':
            if (v >= 0) == (P['dir'] > 0): out += a_*v
        elif eff == 'RS2':
            if REST[j]:
                if zstop is None: zstop = 1; trest = 0.0; Fstop = 1.0 if Fz >= 0 else -1.0
                trest += DT; aged = a_*Fstop*math.log(1 + trest/P['theta']); slip_since = 0.0
                out += aged
            else:
                zstop = None
                slip_since += abs(v)*DT
                out += aged*math.exp(-slip_since/P['Dc'])
        elif eff == 'RS3':
            if REST[j]:
                if zstop is None: zstop = 1; trest = 0.0; Fstop = 1.0 if Fz >= 0 else -1.0
                trest += DT
                out += a_*Fstop*math.exp(-trest/P['tau'])*math.sin(2*math.pi*P['f']*trest)
            else:
                zstop = None
        F[j] = out
    return F

# ---------------------------------------------------------------- effects catalogue
def draw_params(shape, rng):
    P = {'a': 0.0}
    if shape == 'AL1': P.update(tau_ratio=rng.uniform(0.15, 0.4), amax=30.0)
    elif shape == 'AL2': P.update(amax=3.0)
    elif shape == 'AL3': P.update(zeta=rng.uniform(0.12, 0.3), amax=2.0)
    elif shape == 'PT1': P.update(sgn=rng.choice([-1, 1]), amax=None)
    elif shape == 'PT2': P.update(amax=3000.0)
    elif shape == 'PT3': P.update(dirsign=[rng.choice([-1, 1]), rng.choice([-1, 1])], amax=1e6)
    elif shape == 'TS1': P.update(amax=1.6)
    elif shape == 'TS2': P.update(amax=1.5)
    elif shape == 'TS3': P.update(zba=rng.uniform(0.3, 0.6), amax=2.0)
    elif shape == 'V1': P.update(n=rng.uniform(0.3, 0.6), amax=10.0)
    elif shape == 'V2': P.update(vw=rng.uniform(1.0, 1.8), amax=0.9)
    elif shape == 'V3': P.update(vstar=rng.uniform(0.3, 1.0), Dc=rng.uniform(0.1, 0.4), sgn=rng.choice([-1, 1]), amax=3.0)
    elif shape == 'SE1': P.update(amax=3.0)
    elif shape == 'SE2': P.update(Fref=10.0, amax=0.95)
    elif shape == 'SE3': P.update(dir=rng.choice([-1, 1]), lam=rng.uniform(0.3, 0.8), amax=5.0)
    elif shape == 'AS1': P.update(dir=rng.choice([-1, 1]), sgn=rng.choice([-1, 1]), amax=3.0)
    elif shape == 'AS2': P.update(dir=rng.choice([-1, 1]), amax=10.0)
    elif shape == 'AS3': P.update(dir=rng.choice([-1, 1]), sgn=rng.choice([-1, 1]), amax=4.0)
    elif shape == 'BL1': P.update(lu=rng.uniform(0.01, 0.03), amax=0.6)
    elif shape == 'BL2': P.update(lam=rng.uniform(0.03, 0.12), amax=1.0)
    elif shape == 'BL3': P.update(lu=rng.uniform(0.01, 0.03), amax=0.5)
    elif shape == 'RS1': P.update(tau=rng.uniform(0.3, 1.2), amax=1.0)
    elif shape == 'RS2': P.update(theta=rng.uniform(0.05, 0.3), Dc=rng.uniform(0.02, 0.1), amax=20.0)
    elif shape == 'RS3': P.update(tau=rng.uniform(0.25, 0.7), f=rng.uniform(2.0, 6.0), amax=20.0)
    if shape == 'PT1': P['amax'] = 3.0 if P['sgn'] > 0 else 0.97
    return P

CATS = {
    'backlash': ['BL1', 'BL2', 'BL3'], 'residual_static': ['RS1', 'RS2', 'RS3'],
    'transition_shape': ['TS1', 'TS2', 'TS3'], 'velocity': ['V1', 'V2', 'V3'],
    'actuator_lag': ['AL1', 'AL2', 'AL3'], 'self_energizing': ['SE1', 'SE2', 'SE3'],
    'pretension': ['PT1', 'PT2', 'PT3'], 'asymmetry': ['AS1', 'AS2', 'AS3'],
}
SHAPE_NAMES = {
    'BL1': 'free play with force collapse (play operator, dead band 2*delta)',
    'BL2': 'soft engagement: force recovery with travel since reversal',
    'BL3': 'amplitude-proportional lost motion (band stretch recovery)',
    'RS1': 'viscoelastic relaxation of held force at rest',
    'RS2': 'logarithmic static aging at rest (rate-and-state), erased by slip',
    'RS3': 'damped ring-down of held force after stopping (rig compliance)',
    'TS1': 'Stribeck exponent different from 2 (generalised Stribeck)',
    'TS2': 'frictional lag in the Stribeck velocity (Hess-Soom)',
    'TS3': 'elasto-plastic presliding (Dupont breakaway displacement)',
    'V1': 'power-law viscous term',
    'V2': 'flash-heating high-speed weakening of kinetic friction',
    'V3': 'rate-and-state steady-state log velocity dependence with slip memory',
    'AL1': 'asymmetric first-order clamping lag (tighten fast/release slow)',
    'AL2': 'pure transport delay of the clamping',
    'AL3': 'underdamped second-order band tension response',
    'PT1': 'power-law clamping law (Fc ~ N^n)',
    'PT2': 'slack-side saturation of actuator extension',
    'PT3': 'actuator cross-coupling term in the clamping law',
    'SE1': 'capstan-type amplification growing with drum position in direction of travel',
    'SE2': 'load-feedback servo amplification in the forward direction',
    'SE3': 'direction-selective amplification growing with travel since reversal',
    'AS1': 'direction-dependent Stribeck velocity',
    'AS2': 'direction-dependent viscous coefficient',
    'AS3': 'direction-dependent bristle (band) stiffness',
}
NEED_ACT = {'AL1', 'AL2', 'AL3', 'PT1', 'PT2', 'PT3'}
NEED_BOTH = {'PT3'}

def ratio_of(recs, shape, P, a, Fb, noise):
    Q = dict(P); Q['a'] = a
    s = 0.0; m = 0
    for r, fb in zip(recs, Fb):
        ft = simulate(r, shape, Q)
        s += sum((u - w)**2 for u, w in zip(ft, fb)); m += len(fb)
    return math.sqrt(s/m)/noise

def solve(recs, shape, P, Fb, noise, target):
    lo, hi = 0.0, P['amax']
    rhi = ratio_of(recs, shape, P, hi, Fb, noise)
    if rhi < target: return None, rhi
    rlo = 0.0
    a = hi*0.5
    for it in range(40):
        # Illinois-style regula falsi in sqrt space for robustness
        a = lo + (hi - lo)*(target - rlo)/(rhi - rlo) if it % 2 == 0 else 0.5*(lo + hi)
        r = ratio_of(recs, shape, P, a, Fb, noise)
        if abs(r/target - 1) < 0.004: return a, r
        if r < target: lo, rlo = a, r
        else: hi, rhi = a, r
    return a, r

def rows_of(rec, Fmeas, rng):
    n = len(rec['x']); V = velocity(rec['x']); rows = []
    for i in range(n):
        t = i/1024
        if t == int(t): t = int(t)
        F = Fmeas[i]
        a1 = 35.0 + 560.0*max(-F, 0.0) + rng.gauss(0, 1.2)
        a2 = 45.0 + 560.0*max(F, 0.0) + rng.gauss(0, 1.2)
        rows.append([t, rec['x'][i], F, f32(V[i]/125.5 + rng.gauss(0, 2e-5)), rec['x1'][i], rec['x2'][i],
                     round(a1/QL1)*QL1, round(a2/QL2)*QL2])
    return rows

def write_json(path, rows):
    obj = {'data': rows, 'dt': 0.0009765625, 'sampling freq': 1024, 'displacement units': 'in',
           'time units': 's', 'friction force units': 'kip', 'actuator force units': 'lb'}
    with open(path, 'w') as f: json.dump(obj, f)

def make_trial(job):
    slot, tid, cat, shape, strength = job
    import time; T0 = time.time()
    rng = random.Random(SEED*1000 + slot)
    SRCS = load_sources()
    noise = rng.uniform(0.02, 0.06)
    need_act = shape in NEED_ACT
    early_flags = job_early[tid]
    recs = []; infos = []
    for ri, nm in enumerate('AB'):
        want = need_act or early_flags[ri] or rng.random() < 0.5
        F0 = qforce(rng.uniform(-0.5, 0.9))
        r, info = build_record(rng, SRCS, want, early_flags[ri], shape in NEED_BOTH, F0, need_act)
        recs.append(r); infos.append(info)
    Fb = [simulate(r) for r in recs]
    entry = {'category': cat, 'shape': shape if shape else 'none', 'shape_desc': SHAPE_NAMES.get(shape, 'base model + noise'),
             'strength': strength, 'noise_kip': noise}
    if shape:
        P = draw_params(shape, rng)
        target = rng.uniform(2.7, 3.8) if strength == 'weak' else rng.uniform(8.5, 11.5)
        a, r = solve(recs, shape, P, Fb, noise, target)
        if a is None and strength == 'strong':
            entry['note'] = 'strong target %.2f not reachable (max ratio %.2f); made weak' % (target, r)
            strength = entry['strength'] = 'weak'
            target = rng.uniform(2.7, 3.8)
            a, r = solve(recs, shape, P, Fb, noise, target)
        if a is None:
            a = P['amax']; entry['note'] = entry.get('note', '') + '; weak target not reachable, used max amplitude (ratio %.2f)' % r
        P['a'] = a; P.pop('amax', None)
        Ft = [simulate(rr, shape, P) for rr in recs]
        entry.update(target_ratio=target, ratio=r, params=P)
    else:
        Ft = Fb; entry.update(ratio=0.0, params={})
    entry['records'] = {}
    for ri, nm in enumerate('AB'):
        nrng = random.Random(SEED*1000 + slot*10 + ri + 7)
        Fm = [recs[ri]['F0']] + [qforce(f + nrng.gauss(0, noise)) for f in Ft[ri][1:]]
        rows = rows_of(recs[ri], Fm, nrng)
        os.makedirs(os.path.join(ROOT, 'cases', tid), exist_ok=True)
        write_json(os.path.join(ROOT, 'cases', tid, nm + '.json'), rows)
        infos[ri]['early_actuator_motion'] = early_flags[ri]
        infos[ri]['F0_kip'] = recs[ri]['F0']
        entry['records'][nm] = infos[ri]
    print(tid, shape, strength, round(entry['ratio'], 2), '%.1fs' % (time.time() - T0), entry.get('note', ''), flush=True)
    return tid, entry

job_early = {}

def plan():
    rng = random.Random(SEED)
    slots = []
    for cat, shapes in CATS.items():
        for s in shapes: slots.append([cat, s])
    rng.shuffle(slots)
    # shapes whose physical range cannot reach the strong band on these records are weak by design
    limited = {'AL1', 'AL2', 'PT2', 'V2', 'TS1'}
    free = [k for k, s in enumerate(slots) if s[1] not in limited]
    strong = set(rng.sample(free, 12))
    for k, s in enumerate(slots): s.append('strong' if k in strong else 'weak')
    slots += [['none', None, 'none'] for _ in range(6)]
    rng.shuffle(slots)
    tids = ['t%02d' % (i+1) for i in range(30)]
    # early actuator motion in ~1/3 of the 60 records (20), only where the record has motions
    flags = [True]*20 + [False]*40; rng.shuffle(flags)
    for i, t in enumerate(tids): job_early[t] = [flags[2*i], flags[2*i+1]]
    return [(i, tids[i], s[0], s[1], s[2]) for i, s in enumerate(slots)]

def main():
    jobs = plan()
    with Pool(2) as pool:
        res = pool.map(make_trial, jobs, chunksize=1)
    key = {tid: e for tid, e in sorted(res)}
    json.dump(key, open(os.path.join(ROOT, 'key.json'), 'w'), indent=1)
    for tid, e in sorted(res):
        print(tid, e['category'], e['shape'], e['strength'], round(e['ratio'], 2), e.get('note', ''))

if __name__ == '__main__':
    main()
