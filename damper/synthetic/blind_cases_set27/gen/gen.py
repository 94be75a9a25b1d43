#!/usr/bin/env python3
"""Blind test set generator for the BRFD model-discrepancy tool (master seed 27027).

Deterministic: `python3 gen/gen.py` regenerates cases/t01..t30, key.json.
Python 3 standard library only.  Uses at most 2 processes.

Base model (inferred from the black box, see NOTES.md):
  * drum velocity v = central differences of the displacement column (one-sided at the two
    ends), then a 15-sample centred moving average whose half-width shrinks to fit at the ends;
    the file's velocity column (1/125.4 of in/s, the known quirk) is ignored.
  * x'_1, x'_2 = actuator positions of row 0; z(0) = F_measured(0)/sigma0.
  * F_i = sigma0 z_i + sigma2 v_i  (sigma1 = 0);
    z_{i+1} = zs + (z_i - zs) exp(-a dt), a = sigma0 |v_{i+1}| / g_{i+1}, zs = v_{i+1}/a
    (exact exponential step with the velocity and actuator positions of the NEW sample);
    g = Fc + (Fs_dir - Fc) exp(-(v/vs)^2), Fc = max(Eq.4, 0.05), direction by v >= 0.
"""
import json, math, os, random, sys, struct, shutil

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
DATA = '/work/shared/data/brfd/semiactive'
FILES = ['harmonic0.015backward.json', 'harmonic0.015forward.json',
         'harmonic0.03ea1backward.json', 'harmonic0.03ea1forward.json',
         'harmonic0.03ea2backward.json', 'harmonic0.03ea2forward.json']
MASTER_SEED = 27027
DT = 1.0 / 1024
HEADER_TAIL = {"dt": 0.0009765625, "sampling freq": 1024, "displacement units": "in",
               "time units": "s", "friction force units": "kip", "actuator force units": "lb"}

# ---------------- base model parameters (config /work/runs/brfd-semiactive.yaml) -------------
S0, S2 = 15.36, 0.5
FS = (7.116, 3.760)          # fwd, bwd
BB = (2.648, 1.253)          # b fwd, b bwd
VS = 1.3
M = [-0.14, -0.15, -15.29, -13.00, -16.66, -15.77, -0.13, -0.15]
C = [119.68, 2.10, 1.94, 123.31]
K1F = C[0] * M[0] + C[1] * M[2]; K2F = C[0] * M[1] + C[1] * M[3]
K1B = C[2] * M[4] + C[3] * M[6]; K2B = C[2] * M[5] + C[3] * M[7]
FLOOR = 0.05

# ---------------- quantisation grids (fitted on the measured files) --------------------------
QX = 5.89421674e-05; OX = 0.66308 * QX         # displacement (in), float32 values
QF = 0.000800879963                              # friction force (kip), zero offset
QA = 1.0 / 409600                                # actuator positions (in), float32 values
QVEL = 125.385                                   # velocity column = (in/s)/125.385, lagged 7 samples
VLAG = 7


def f32(x):
    return struct.unpack('f', struct.pack('f', x))[0]


def qx(x):
    return f32(OX + QX * round((x - OX) / QX))


def qf(F):
    return round(F / QF) * QF


# ---------------- velocity reconstruction exactly as the black box ---------------------------
def smooth_velocity(x):
    n = len(x)
    d = [0.0] * n
    for i in range(1, n - 1):
        d[i] = (x[i + 1] - x[i - 1]) / (2 * DT)
    d[0] = (x[1] - x[0]) / DT
    d[-1] = (x[-1] - x[-2]) / DT
    cs = [0.0]
    for e in d:
        cs.append(cs[-1] + e)
    out = []
    for i in range(n):
        k = min(7, i, n - 1 - i)
        out.append((cs[i + k + 1] - cs[i - k]) / (2 * k + 1))
    return out


def base_sim(x, a1, a2, F0meas, v=None):
    """Exact replica of `hybridsim damper predict --no-fit` with the config above."""
    if v is None:
        v = smooth_velocity(x)
    n = len(x)
    x1p, x2p = a1[0], a2[0]
    z = F0meas / S0
    F = [0.0] * n
    ex = math.exp
    for i in range(n):
        F[i] = S0 * z + S2 * v[i]
        if i == n - 1:
            break
        j = i + 1
        vj = v[j]
        if vj >= 0:
            fc = BB[0] + K1F * (a1[j] - x1p) + K2F * (a2[j] - x2p); fs = FS[0]
        else:
            fc = BB[1] + K1B * (a1[j] - x1p) + K2B * (a2[j] - x2p); fs = FS[1]
        if fc < FLOOR:
            fc = FLOOR
        g = fc + (fs - fc) * ex(-(vj / VS) ** 2)
        a = S0 * abs(vj) / g
        if a > 0:
            zs = vj / a
            z = zs + (z - zs) * ex(-a * DT)
    return F


# ---------------- effect shapes ----------------------------------------------------------------
# name: (category, amplitude max, amplitude meaning)
SHAPES = {
    'play_input':      ('backlash', 0.35, 'half gap delta (in) of a play operator on the drum input'),
    'travel_dip':      ('backlash', 1.0, 'depth c of the post-reversal force dip'),
    'smooth_deadzone': ('backlash', 4.0, 'dead-zone width dF (kip) around zero bristle force'),
    'relax_exp':       ('residual_static', 8.0, 'relaxation rate 1/tau (1/s) of the held force'),
    'log_creep':       ('residual_static', 0.6, 'log-creep coefficient c'),
    'thermal_drift':   ('residual_static', 2.0, 'thermal drift coefficient c (per unit heat)'),
    'sigma1_attn':     ('transition_shape', 12.0, 'micro-damping sigma1 (kip s/in)'),
    'dahl_exponent':   ('transition_shape', 3.0, 'exponent offset |alpha-1| (or 1/alpha-1)'),
    'elastoplastic':   ('transition_shape', 0.95, 'elastic fraction beta = z_ba/z_ss'),
    'log_rate':        ('velocity', 0.6, '|c| of g(1 + c ln(1+|v|/v0))'),
    'frictional_lag':  ('velocity', 0.6, 'frictional memory time tau_L (s)'),
    'flash_heating':   ('velocity', 3.0, 'weakening coefficient c per unit flash heat'),
    'lag_first':       ('actuator_lag', 3.0, 'time constant tau (s)'),
    'lag_second':      ('actuator_lag', 0.5, '1/omega_n (s)'),
    'lag_delay':       ('actuator_lag', 0.6, 'dead time T_d (s)'),
    'capstan_load':    ('self_energizing', 1.5, 'load servo gain kappa'),
    'wrap_position':   ('self_energizing', 1.5, 'wrap gain kappa (1/in)'),
    'wrap_travel':     ('self_energizing', 1.5, 'stroke wrap build-up kappa'),
    'gain_quadratic':  ('pretension', 3.0, 'tension-dependent gain c'),
    'bilinear_tension': ('pretension', 0.95, 'bilinear slope change a'),
    'coupling':        ('pretension', 60000.0, '|c| of c*(x1-x1\')*(x2-x2\') (kip/in^2)'),
    'vs_dir':          ('asymmetry', 2.0, 'log ratio of one direction\'s Stribeck velocity'),
    'visc_dir':        ('asymmetry', 2.0, 'log ratio of one direction\'s viscous coefficient'),
    'band_stiffness':  ('asymmetry', 1.5, 'log ratio of one band\'s bristle stiffness'),
}
CATEGORIES = ['backlash', 'residual_static', 'transition_shape', 'velocity', 'actuator_lag',
              'self_energizing', 'pretension', 'asymmetry']
NEEDS_MOTION = {'actuator_lag', 'pretension'}


def draw_fixed(shape, rng):
    """Fixed (non-amplitude) parameters of a shape."""
    p = {}
    if shape == 'travel_dip':
        p['lam_in'] = rng.uniform(0.04, 0.12)
    elif shape == 'log_creep':
        p['theta_s'] = rng.uniform(0.03, 0.15)
    elif shape == 'thermal_drift':
        p['tau_th_s'] = rng.uniform(2.0, 6.0); p['E0_kip_in'] = 10.0
    elif shape == 'sigma1_attn':
        p['vd_in_s'] = rng.uniform(0.2, 0.6)
    elif shape == 'dahl_exponent':
        p['side'] = rng.choice(['above', 'below'])
    elif shape == 'log_rate':
        p['sign'] = rng.choice([1, -1]); p['v0_in_s'] = rng.uniform(0.1, 0.5)
    elif shape == 'flash_heating':
        p['tau_th_s'] = rng.uniform(0.05, 0.3); p['P0_kip_in_s'] = 5.0
    elif shape == 'lag_second':
        p['zeta'] = rng.uniform(0.2, 0.5)
    elif shape == 'capstan_load':
        p['rho_bwd'] = rng.uniform(0.0, 0.6)
    elif shape == 'wrap_travel':
        p['lam_in'] = rng.uniform(0.3, 1.0); p['rho_bwd'] = rng.uniform(0.0, 0.5)
    elif shape == 'bilinear_tension':
        p['side'] = rng.choice(['extension_softens', 'retraction_stiffens'])
    elif shape == 'coupling':
        p['sign'] = rng.choice([1, -1])
    elif shape in ('vs_dir', 'visc_dir'):
        p['dir'] = rng.choice(['fwd', 'bwd']); p['sign'] = rng.choice([1, -1])
    elif shape == 'band_stiffness':
        p['band'] = rng.choice(['z>0 (band of actuator 2)', 'z<0 (band of actuator 1)'])
        p['sign'] = rng.choice([1, -1])
    return p


def amp_max(shape, fp):
    m = SHAPES[shape][1]
    if shape == 'log_rate' and fp['sign'] < 0:
        m = 0.25
    if shape == 'bilinear_tension' and fp['side'] == 'retraction_stiffens':
        m = 4.0
    if shape in ('vs_dir', 'visc_dir', 'band_stiffness') and fp['sign'] < 0:
        m = min(m, 1.2)
    return m


def play(x, d):
    out = [x[0]] * len(x)
    y = x[0]
    for i, xi in enumerate(x):
        if xi - y > d:
            y = xi - d
        elif y - xi > d:
            y = xi + d
        out[i] = y
    return out


def travel_since_reversal(x, h=0.002):
    s = [0.0] * len(x)
    dirn = 0; ext = x[0]; xr = x[0]
    for i, xi in enumerate(x):
        if dirn >= 0:
            if xi > ext:
                ext = xi
            if xi < ext - h:
                dirn = -1; xr = ext; ext = xi
        if dirn < 0:
            if xi < ext:
                ext = xi
            if xi > ext + h:
                dirn = 1; xr = ext; ext = xi
        if dirn == 0 and abs(xi - x[0]) > h:
            dirn = 1 if xi > x[0] else -1; ext = xi
        s[i] = abs(xi - xr)
    return s


def rest_flags(v, vr=0.02, hold=102):
    r = [False] * len(v); cnt = 0
    for i, vi in enumerate(v):
        cnt = cnt + 1 if abs(vi) < vr else 0
        r[i] = cnt > hold
    return r


def true_sim(R, shape, amp, fp, F0):
    """Clean 'true' friction force: base model + one effect of amplitude amp (amp=0 -> base)."""
    x, a1, a2 = R['x'], R['a1'], R['a2']
    n = len(x)
    x1p, x2p = a1[0], a2[0]
    v = R['v']
    if shape == 'play_input' and amp > 0:
        xe = play(x, amp); v = smooth_velocity(xe)
    A1, A2 = a1, a2
    if shape in ('lag_first', 'lag_second', 'lag_delay') and amp > 0:
        A1 = lag_filter(a1, shape, amp, fp); A2 = lag_filter(a2, shape, amp, fp)
    s_tr = R['s'] if shape in ('travel_dip', 'wrap_travel') else None
    rest = R['rest'] if shape in ('relax_exp', 'log_creep', 'thermal_drift') else None
    xc = x[0]
    z = F0 / S0
    F = [0.0] * n
    ex = math.exp
    vfilt = abs(v[0]); heat = 0.0; tr = 0.0; zstop = None; Tstop = 0.0
    if shape == 'frictional_lag' and amp > 0:
        kf = 1.0 - ex(-DT / amp)
    if shape == 'flash_heating':
        kh = 1.0 - ex(-DT / fp['tau_th_s'])
    if shape == 'band_stiffness':
        zsel = 1 if fp['band'].startswith('z>0') else -1
        s0alt = S0 * ex(fp['sign'] * amp)
    if shape == 'dahl_exponent':
        alpha = 1.0 + amp if fp['side'] == 'above' else 1.0 / (1.0 + amp)
    if shape in ('vs_dir', 'visc_dir'):
        dsel = 1 if fp['dir'] == 'fwd' else -1
        kdir = ex(fp['sign'] * amp)
    for i in range(n):
        vi = v[i]
        # ---- output
        s0i = S0
        if shape == 'band_stiffness' and z * zsel > 0:
            s0i = s0alt
        s2i = S2
        if shape == 'visc_dir' and (1 if vi >= 0 else -1) == dsel:
            s2i = S2 * kdir
        if shape == 'travel_dip':
            u = s_tr[i] / fp['lam_in']
            Fi = s0i * z * (1.0 - amp * u * ex(1.0 - u)) + s2i * vi
        elif shape == 'smooth_deadzone' and amp > 0:
            zd = amp / S0
            Fi = S0 * z * z * z / (z * z + zd * zd) + s2i * vi
        else:
            Fi = s0i * z + s2i * vi
        if shape == 'sigma1_attn':
            gi = gfun(shape, amp, fp, vi, A1[i] - x1p, A2[i] - x2p, z, x[i], xc, None, vfilt, heat)
            Fi += amp * ex(-(vi / fp['vd_in_s']) ** 2) * (vi - S0 * abs(vi) / gi * z)
        F[i] = Fi
        if i == n - 1:
            break
        # ---- states driven by the output sample i
        if shape == 'flash_heating':
            heat += (abs(Fi * vi) / fp['P0_kip_in_s'] - heat) * kh
        if shape == 'thermal_drift':
            heat += DT * (abs(Fi * vi) / fp['E0_kip_in'] - heat / fp['tau_th_s'])
        # ---- z update to sample j
        j = i + 1
        vj = v[j]
        if shape == 'frictional_lag':
            vfilt = vfilt + (abs(vj) - vfilt) * kf if amp > 0 else abs(vj)
        g = gfun(shape, amp, fp, vj, A1[j] - x1p, A2[j] - x2p, z, x[j], xc,
                 s_tr[j] if s_tr is not None else None, vfilt, heat)
        s0j = S0
        if shape == 'band_stiffness' and z * zsel > 0:
            s0j = s0alt
        a = s0j * abs(vj) / g
        if shape == 'dahl_exponent' and amp > 0 and vj != 0:
            u = (1 if vj >= 0 else -1) * s0j * z / g
            w = abs(1.0 - u)
            fac = w ** (alpha - 1.0) if w > 1e-9 else (0.0 if alpha > 1 else 50.0)
            a *= min(fac, 50.0)
        if shape == 'elastoplastic' and amp > 0 and vj != 0:
            # single-state elasto-plastic (Dupont et al. 2002): no slip below z_ba = beta*z_ss,
            # sine ramp to full slip over a width min(z_ss - z_ba, z_ba); unloading tends to
            # purely elastic as beta grows (alpha_unload = 1 - beta)
            zss = g / s0j; zba = amp * zss
            sz = z * (1 if vj >= 0 else -1)
            if sz < 0:
                al = 1.0 - amp
            elif sz <= zba:
                al = 0.0
            else:
                w = min(zss - zba, zba)
                if sz >= zba + w:
                    al = 1.0
                else:
                    al = 0.5 * math.sin(math.pi * ((sz - zba) / w - 0.5)) + 0.5
            a *= al
        if a > 0:
            zs = vj / a
            z = zs + (z - zs) * ex(-a * DT)
        else:
            z += vj * DT
        # ---- rest effects
        if rest is not None:
            if shape == 'relax_exp':
                if rest[j]:
                    z *= ex(-amp * DT)
            else:
                if rest[j]:
                    if zstop is None:
                        zstop = z; tr = 0.0; Tstop = heat
                    tr += DT
                    if shape == 'log_creep':
                        fac = 1.0 - amp * math.log(1.0 + tr / fp['theta_s'])
                    else:
                        fac = 1.0 - amp * max(0.0, Tstop - heat)
                    z = zstop * max(0.0, fac)
                else:
                    zstop = None
    return F


def gfun(shape, amp, fp, vj, d1, d2, z, xj, xc, sj, vfilt, heat):
    fwd = vj >= 0
    if fwd:
        b = BB[0]; L = K1F * d1 + K2F * d2; fs = FS[0]
    else:
        b = BB[1]; L = K1B * d1 + K2B * d2; fs = FS[1]
    if shape == 'gain_quadratic':
        L = L * math.exp(amp * L / b)
    elif shape == 'bilinear_tension':
        if fp['side'] == 'extension_softens':
            if L < 0:
                L *= (1.0 - amp)
        elif L > 0:
            L *= (1.0 + amp)
    elif shape == 'coupling':
        L += fp['sign'] * amp * d1 * d2
    fc = b + L
    if fc < FLOOR:
        fc = FLOOR
    if shape == 'capstan_load':
        k = amp if fwd else -fp['rho_bwd'] * amp
        fc *= math.exp(k * S0 * abs(z) / fs)
    elif shape == 'wrap_position':
        fc *= math.exp(amp * (1 if fwd else -1) * (xj - xc))
    elif shape == 'wrap_travel':
        k = amp if fwd else fp['rho_bwd'] * amp
        fc *= 1.0 + k * (1.0 - math.exp(-sj / fp['lam_in']))
    vsx = VS
    if shape == 'vs_dir' and (1 if fwd else -1) == (1 if fp['dir'] == 'fwd' else -1):
        vsx = VS * math.exp(fp['sign'] * amp)
    vst = vfilt if shape == 'frictional_lag' else vj
    g = fc + (fs - fc) * math.exp(-(vst / vsx) ** 2)
    if shape == 'log_rate':
        g *= 1.0 + fp['sign'] * amp * math.log(1.0 + abs(vj) / fp['v0_in_s'])
    elif shape == 'flash_heating':
        g /= 1.0 + amp * heat
    return max(g, 0.02)


def lag_filter(a, shape, amp, fp):
    n = len(a)
    out = [a[0]] * n
    if shape == 'lag_first':
        k = 1.0 - math.exp(-DT / amp); y = a[0]
        for i in range(n):
            y += (a[i] - y) * k; out[i] = y
    elif shape == 'lag_second':
        wn = 1.0 / amp; ze = fp['zeta']; y = a[0]; yd = 0.0
        sub = max(1, int(math.ceil(wn * DT / 0.1))); h = DT / sub
        for i in range(n):
            for _ in range(sub):
                yd += h * (wn * wn * (a[i] - y) - 2 * ze * wn * yd)
                y += h * yd
            out[i] = y
    elif shape == 'lag_delay':
        dn = amp / DT
        for i in range(n):
            tpos = i - dn
            if tpos <= 0:
                out[i] = a[0]
            else:
                k = int(tpos); fr = tpos - k
                out[i] = a[k] + (a[min(k + 1, n - 1)] - a[k]) * fr
    return out


# ---------------- measured pieces ------------------------------------------------------------
_LIB = None


def library():
    global _LIB
    if _LIB is not None:
        return _LIB
    strokes, motions, heads = [], [], {}
    grids = {}
    for fn in FILES:
        d = json.load(open(os.path.join(DATA, fn)))['data']
        n = len(d)
        x = [r[1] for r in d]; a1 = [r[4] for r in d]; a2 = [r[5] for r in d]
        heads[fn] = (a1[0], a2[0])
        mov = [i for i in range(n) if abs(a1[i] - a1[0]) > 0.002 or abs(a2[i] - a2[0]) > 0.002]
        segs = []; s = mov[0]; p = mov[0]
        for i in mov[1:]:
            if i > p + 200:
                segs.append((s, p)); s = i
            p = i
        segs.append((s, p))
        for (s, e) in segs:
            lo, hi = s - 150, e + 150
            motions.append({'file': fn, 't0': lo * DT, 'core': (e - s) * DT,
                            'd1': [a1[k] - a1[lo] for k in range(lo, hi + 1)],
                            'd2': [a2[k] - a2[lo] for k in range(lo, hi + 1)],
                            'both': '0.015' in fn})
        sm = []
        cs = [0.0]
        for e_ in x:
            cs.append(cs[-1] + e_)
        for i in range(n):
            lo_, hi_ = max(0, i - 20), min(n - 1, i + 20)
            sm.append((cs[hi_ + 1] - cs[lo_]) / (hi_ - lo_ + 1))
        pk = [i for i in range(1024, 13 * 1024) if (sm[i] >= sm[i - 1] and sm[i] > sm[i + 1])
              or (sm[i] <= sm[i - 1] and sm[i] < sm[i + 1])]
        pk2 = []
        for i in pk:
            if not pk2 or i - pk2[-1] > 400:
                pk2.append(i)
        for k in range(len(pk2) - 1):
            s, e = pk2[k], pk2[k + 1]
            if abs(x[e] - x[s]) < 1.0:
                continue
            if any(not (e + 100 < ms or s - 100 > me) for (ms, me) in segs):
                continue
            strokes.append({'file': fn, 't0': s * DT, 'x': [x[i] - x[s] for i in range(s, e + 1)],
                            'd1': [a1[i] - a1[s] for i in range(s, e + 1)],
                            'd2': [a2[i] - a2[s] for i in range(s, e + 1)]})
        for c, key in ((6, 'f1'), (7, 'f2')):
            vals = sorted(set(r[c] for r in d))
            q = min(vals[i + 1] - vals[i] for i in range(len(vals) - 1) if vals[i + 1] - vals[i] > 0.2)
            if key not in grids:
                ds = [vals[i + 1] - vals[i] for i in range(len(vals) - 1)]
                sm_ = [t for t in ds if t < 1.5 * q]
                qq = sum(sm_) / len(sm_)
                grids[key] = (qq, vals[0] - qq * math.floor(vals[0] / qq))
    _LIB = {'strokes': strokes, 'motions': motions, 'heads': heads, 'grids': grids}
    return _LIB


def resample(seq, stretch):
    """Linear interpolation of seq onto a grid stretched in time by `stretch`."""
    m = len(seq) - 1
    n2 = int(round(m * stretch))
    out = []
    for k in range(n2 + 1):
        tpos = k / stretch
        i = min(int(tpos), m - 1); fr = tpos - i
        out.append(seq[i] + (seq[i + 1] - seq[i]) * fr)
    return out


def build_record(rng, with_motion, early, motion_both, many=False):
    """Drum strokes cut from the measured tests (scaled, mirrored, time-stretched, joined),
    rests between them, actuator motions cut from measured tests placed in sliding strokes."""
    lib = library()
    head_file = rng.choice(FILES)
    x1p, x2p = lib['heads'][head_file]
    target = rng.uniform(6.5, 19.0)
    final_rest = rng.uniform(1.55, 2.2)
    xs, d1s, d2s = [], [], []
    info = {'head_file': head_file, 'pieces': [], 'motions': []}
    pos = rng.uniform(-0.3, 0.3)
    r0 = rng.uniform(0.1, 0.3) if early else rng.uniform(0.3, 1.2)

    def add_rest(dur):
        nn = int(round(dur / DT))
        for _ in range(nn):
            xs.append(pos + rng.gauss(0, 0.45 * QX)); d1s.append(rng.gauss(0, 0.5 * QA))
            d2s.append(rng.gauss(0, 0.5 * QA))
        info['pieces'].append(('rest', round(dur, 3)))
    add_rest(r0)
    lastdir = rng.choice([1, -1])
    nmot_target = (rng.choice([4, 5, 6]) if many else rng.choice([1, 2, 3])) if with_motion else 0
    nmot = 0
    first = True
    placed = []
    while (len(xs) * DT < target - final_rest - 0.6 or (with_motion and nmot == 0)
           or (many and with_motion and nmot < nmot_target and len(xs) * DT < 19.5)):
        st = rng.choice(lib['strokes'])
        t_here = len(xs) * DT
        want_motion = with_motion and nmot < nmot_target and (
            (early and first) or (t_here + 0.05 >= 1.1 and rng.random() < (0.9 if many else 0.6)))
        if early and first:
            want_motion = True
        stretch = rng.uniform(1.2, 1.6) if want_motion else rng.uniform(0.75, 1.6)
        scale = rng.uniform(0.35, 1.05)
        # direction: alternate mostly, keep the drum within about +-1.2 in
        dirn = -lastdir if rng.random() < 0.8 else lastdir
        travel = 2.0 * scale
        if abs(pos + dirn * travel) > 1.25:
            dirn = -dirn
        if abs(pos + dirn * travel) > 1.25:
            scale = max(0.25, (1.2 - abs(pos)) / 2.0 + 0.0) if abs(pos) < 1.2 else 0.25
            dirn = -1 if pos > 0 else 1
            travel = 2.0 * scale
        src = st['x']; sgn = 1 if src[-1] > src[0] else -1
        shape_x = resample([dirn * sgn * scale * u for u in src], stretch)
        sd1 = resample(st['d1'], stretch); sd2 = resample(st['d2'], stretch)
        i0 = len(xs)
        for k in range(1, len(shape_x)):
            xs.append(pos + shape_x[k]); d1s.append(sd1[k]); d2s.append(sd2[k])
        info['pieces'].append(('stroke', st['file'], round(st['t0'], 4), round(scale, 4),
                               round(stretch, 4), dirn))
        pos = xs[-1]
        lastdir = dirn
        dur = (len(xs) - i0) * DT
        if want_motion:
            cands = [m for m in lib['motions'] if (m['both'] or not motion_both)]
            mo = rng.choice(cands)
            slack = dur - mo['core'] - 0.1
            off = rng.uniform(0.03, max(0.04, min(slack, 0.12 if early and first else slack)))
            kstart = i0 + int(round(off / DT)) - 150
            placed.append((kstart, mo))
            info['motions'].append({'source_file': mo['file'], 'source_window_start_s': round(mo['t0'], 4),
                                    'placed_core_start_s': round((kstart + 150) * DT, 4),
                                    'stroke_start_s': round(i0 * DT, 4), 'stroke_end_s': round(len(xs) * DT, 4)})
            nmot += 1
        first = False
        if rng.random() < 0.45:
            add_rest(rng.uniform(0.25, 1.5))
    final_rest = max(final_rest, 6.6 - len(xs) * DT)
    add_rest(final_rest)
    n = len(xs)
    for kstart, mo in placed:
        for k in range(len(mo['d1'])):
            idx = kstart + k
            if 0 <= idx < n:
                d1s[idx] += mo['d1'][k]; d2s[idx] += mo['d2'][k]
    x = [qx(u) for u in xs]
    x[1] = x[0]   # zero velocity at row 0: the black box's F(0) = sigma0 z(0) then equals the written F(0)
    a1 = [f32(QA * round((x1p + u) / QA)) for u in d1s]
    a2 = [f32(QA * round((x2p + u) / QA)) for u in d2s]
    a1[0] = x1p; a2[0] = x2p
    v = smooth_velocity(x)
    info['duration_s'] = round((n - 1) * DT, 4)
    return {'x': x, 'a1': a1, 'a2': a2, 'v': v, 's': travel_since_reversal(x), 'rest': rest_flags(v),
            'info': info}


def first_motion_time(a1, a2, thr=0.002):
    for i in range(len(a1)):
        if abs(a1[i] - a1[0]) > thr or abs(a2[i] - a2[0]) > thr:
            return i * DT
    return None


def num(u):
    if u == int(u):
        return int(u)
    return u


def write_record(path, R, Fmeas, rng):
    lib = library()
    n = len(R['x'])
    (q1, o1), (q2, o2) = lib['grids']['f1'], lib['grids']['f2']
    # velocity column: the quirk (1/125.385 of in/s, lagging ~7 samples)
    v = R['v']
    vcol = [v[max(0, i - VLAG)] / QVEL + rng.gauss(0, 2e-6) for i in range(n)]
    rows = []
    for i in range(n):
        F = R['Ftrue'][i]
        f1 = 1000 * (max(F, 0) / C[0] + max(-F, 0) / C[2]) + 3.0 + rng.gauss(0, 0.6)
        f2 = 1000 * (max(F, 0) / C[1] + max(-F, 0) / C[3]) + 3.0 + rng.gauss(0, 3.0)
        f1 = o1 + q1 * round((f1 - o1) / q1); f2 = o2 + q2 * round((f2 - o2) / q2)
        rows.append([num(i * DT), num(R['x'][i]), num(Fmeas[i]), num(vcol[i]), num(R['a1'][i]),
                     num(R['a2'][i]), num(f1), num(f2)])
    obj = {'data': rows}
    obj.update(HEADER_TAIL)
    with open(path, 'w') as fh:
        json.dump(obj, fh)


def rms_ratio(Ftrue_list, Fbase_list, noise):
    s = 0.0; c = 0
    for Ft, Fb in zip(Ftrue_list, Fbase_list):
        for a, b in zip(Ft, Fb):
            s += (a - b) ** 2; c += 1
    return math.sqrt(s / c) / noise


def make_trial_records(tid, spec):
    """Records, noise and base predictions of one trial (amplitude-independent)."""
    rng = random.Random(MASTER_SEED * 1000 + spec['slot'])
    noise = rng.uniform(0.02, 0.06)
    recs = []
    for r in range(2):
        R = build_record(rng, spec['motion'][r], spec['early'][r], spec['shape'] == 'coupling',
                         spec['category'] in NEEDS_MOTION)
        # initial residual force; the first sample is written noise-free so that the true and
        # the base model start from the same state (the black box sets z(0) = F(0)/sigma0)
        R['F0'] = qf(rng.uniform(-0.5, 1.0))
        n = len(R['x'])
        R['noise'] = [rng.gauss(0, noise) for _ in range(n)]
        R['noise'][0] = 0.0
        R['F0meas'] = R['F0']
        R['Fbase'] = base_sim(R['x'], R['a1'], R['a2'], R['F0meas'], R['v'])
        R['wseed'] = rng.randrange(1 << 30)
        recs.append(R)
    return noise, recs


def solve_trial(args):
    tid, spec = args
    noise, recs = make_trial_records(tid, spec)
    shape = spec['shape']
    out = {'trial': tid, 'noise_kip': noise}
    if shape == 'none':
        for R in recs:
            R['Ftrue'] = R['Fbase']
        out.update(amp=0.0, ratio=rms_ratio([R['Ftrue'][1:] for R in recs],
                                            [R['Fbase'][1:] for R in recs], noise), fp={})
    else:
        fp = spec['fp']
        def ratio(a):
            return rms_ratio([true_sim(R, shape, a, fp, R['F0']) for R in recs],
                             [R['Fbase'] for R in recs], noise)
        amax = amp_max(shape, fp)
        rmax = ratio(amax)
        target = spec['target']
        if rmax < target:
            out['note'] = 'target %.2f not reachable (max %.2f at amp %.4g)' % (target, rmax, amax)
            a = amax; r = rmax
        else:
            lo, rlo = 0.0, ratio(0.0)
            hi, rhi = amax, rmax
            a, r = hi, rhi
            for it in range(60):
                # Illinois-type regula falsi in amplitude, guarded by bisection
                am = lo + (target - rlo) * (hi - lo) / (rhi - rlo) if rhi != rlo else 0.5 * (lo + hi)
                if not (lo + 0.02 * (hi - lo) < am < hi - 0.02 * (hi - lo)) or it % 3 == 2:
                    am = 0.5 * (lo + hi)
                rm = ratio(am)
                a, r = am, rm
                if abs(rm - target) < 0.002 * target:
                    break
                if rm < target:
                    lo, rlo = am, rm
                else:
                    hi, rhi = am, rm
        out.update(amp=a, ratio=r, fp=fp, ratio_max=rmax)
        for R in recs:
            R['Ftrue'] = true_sim(R, shape, a, fp, R['F0'])
    # write
    d = os.path.join(ROOT, 'cases', tid)
    os.makedirs(d, exist_ok=True)
    recinfo = []
    for r, R in enumerate(recs):
        n = len(R['x'])
        Fm = [R['F0meas']] + [qf(R['Ftrue'][i] + R['noise'][i]) for i in range(1, n)]
        write_record(os.path.join(d, 'AB'[r] + '.json'), R, Fm, random.Random(R['wseed']))
        info = dict(R['info'])
        info['F0_true_kip'] = R['F0']; info['F0_measured_kip'] = R['F0meas']
        info['first_actuator_motion_s'] = first_motion_time(R['a1'], R['a2'])
        info['actuators_move_within_first_second'] = spec['early'][r]
        info['rms_effect_kip'] = math.sqrt(sum((a - b) ** 2 for a, b in zip(R['Ftrue'], R['Fbase'])) / n)
        recinfo.append(info)
    out['records'] = {'A': recinfo[0], 'B': recinfo[1]}
    return out


def plan():
    rng = random.Random(MASTER_SEED)
    slots = []
    for cat in CATEGORIES:
        for sh in [s for s in SHAPES if SHAPES[s][0] == cat]:
            slots.append({'category': cat, 'shape': sh})
    for k in range(6):
        slots.append({'category': 'none', 'shape': 'none'})
    for k, s in enumerate(slots):
        s['slot'] = k
        s['fp'] = draw_fixed(s['shape'], rng) if s['shape'] != 'none' else {}
    # actuator motions per record; exactly 20 of 60 records move within the first second
    for s in slots:
        need = s['category'] in NEEDS_MOTION
        s['motion'] = [need or rng.random() < 0.45 for _ in range(2)]
    recs = [(s, r) for s in slots for r in range(2) if s['motion'][r]]
    rng.shuffle(recs)
    early = set((s['slot'], r) for s, r in recs[:20])
    for s in slots:
        s['early'] = [(s['slot'], r) in early for r in range(2)]
    order = list(range(30))
    rng.shuffle(order)
    trials = {}
    for k, s in enumerate(slots):
        trials['t%02d' % (order[k] + 1)] = s
    return trials


def feasibility(args):
    tid, spec = args
    noise, recs = make_trial_records(tid, spec)
    amax = amp_max(spec['shape'], spec['fp'])
    return rms_ratio([true_sim(R, spec['shape'], amax, spec['fp'], R['F0']) for R in recs],
                     [R['Fbase'] for R in recs], noise)


def assign_strengths(trials, rmax):
    """12 weak, 12 strong; strong only where the maximum amplitude reaches ratio >= 8.7."""
    rng = random.Random(MASTER_SEED + 1)
    eff = sorted(t for t in trials if trials[t]['shape'] != 'none')
    capable = [t for t in eff if rmax[t] >= 8.7]
    # mix strengths inside every category (one strong where possible, one weak), then fill
    strong, weak = set(), set()
    for cat in CATEGORIES:
        ts = [t for t in eff if trials[t]['category'] == cat]
        rng.shuffle(ts)
        cap = [t for t in ts if t in capable]
        if cap:
            strong.add(cap[0])
            rest = [t for t in ts if t != cap[0]]
            weak.add(rest[0])
    pool = [t for t in capable if t not in strong and t not in weak]
    rng.shuffle(pool)
    strong.update(pool[:12 - len(strong)])
    for t in eff:
        s = trials[t]
        if t in strong:
            s['strength'] = 'strong'; s['target'] = rng.uniform(8.5, 11.5)
        else:
            s['strength'] = 'weak'
            s['target'] = rng.uniform(2.7, min(3.8, 0.98 * rmax[t])) if rmax[t] > 2.75 else 2.7
    for t in trials:
        if trials[t]['shape'] == 'none':
            trials[t]['strength'] = 'none'; trials[t]['target'] = 0.0


def main():
    trials = plan()
    if os.path.isdir(os.path.join(ROOT, 'cases')):
        shutil.rmtree(os.path.join(ROOT, 'cases'))
    procs = int(os.environ.get('GEN_PROCS', '2'))
    if procs > 1:
        import multiprocessing as mp
        pool = mp.Pool(min(procs, 2)); pmap = lambda f, it: pool.map(f, it, chunksize=1)
    else:
        pool = None; pmap = lambda f, it: list(map(f, it))
    eff = sorted((t, s) for t, s in trials.items() if s['shape'] != 'none')
    rmax = dict(zip([t for t, _ in eff], pmap(feasibility, eff)))
    assign_strengths(trials, rmax)
    jobs = sorted(trials.items())
    res = pmap(solve_trial, jobs)
    if pool is not None:
        pool.close(); pool.join()
    key = {}
    for (tid, spec), out in zip(jobs, res):
        ent = {'category': spec['category'], 'shape': spec['shape'], 'strength': spec['strength'],
               'target_ratio': spec['target'], 'ratio': out['ratio'], 'noise_kip': out['noise_kip'],
               'params': dict(out['fp'], amplitude=out['amp'],
                              amplitude_meaning=SHAPES[spec['shape']][2] if spec['shape'] != 'none' else ''),
               'records': out['records'], 'slot': spec['slot']}
        if 'ratio_max' in out:
            ent['ratio_at_max_amplitude'] = out['ratio_max']
        if 'note' in out:
            ent['note'] = out['note']
        key[tid] = ent
        print(tid, spec['category'], spec['shape'], spec['strength'], 'target %.2f ratio %.3f amp %.4g' %
              (spec['target'], out['ratio'], out['amp']), out.get('note', ''), flush=True)
    with open(os.path.join(ROOT, 'key.json'), 'w') as fh:
        json.dump(key, fh, indent=1)


if __name__ == '__main__':
    main()
