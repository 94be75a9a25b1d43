"""Base model: semi-active LuGre model of the seed paper (Eqs. 1-5), plus the hidden effects.

Base (paper, Eqs. 1-5), units kip, in, s:
  zdot = v - sigma0 |v| z / g(v)                                  (1)
  g(v) = Fc(x1,x2,v) + (Fs - Fc(x1,x2,v)) exp(-(v/vs)^2)          (2),(5)
  F    = sigma0 z + sigma1 zdot + sigma2 v                        (3)
  Fc   = b_dir + K_dir1 (x1 - x1') + K_dir2 (x2 - x2')            (4)
         K_fwd1 = C1 m11 + C2 m21, K_fwd2 = C1 m12 + C2 m22  (v >= 0)
         K_bwd1 = C3 m31 + C4 m41, K_bwd2 = C3 m32 + C4 m42  (v <  0)
  Fc is clipped below at fc_floor.  Backward values (b, Fs) are magnitudes; g > 0 always.
Drum velocity: central differences of the displacement (one-sided at the ends) + 15-sample
centred moving average whose window shrinks symmetrically at the ends.
"""
import math

DT = 1.0 / 1024.0


def read_config(path):
    """Tiny parser for the few keys of configs/brfd-semiactive.yaml we need."""
    P = {}
    with open(path) as fh:
        for line in fh:
            s = line.split('#', 1)[0].strip()
            if ':' not in s:
                continue
            k, v = s.split(':', 1)
            k = k.strip(); v = v.strip()
            if not v:
                continue
            if v.startswith('['):
                P[k] = [float(a) for a in v.strip('[]').split(',')]
            else:
                try:
                    P[k] = float(v)
                except ValueError:
                    P[k] = v
    m = P['slopes_kip_per_in']; C = P['scaling']
    return dict(sigma0=P['sigma0_kip_per_in'], sigma1=P['sigma1_kip_s_per_in'],
                sigma2=P['sigma2_kip_s_per_in'], fs_f=P['fs_fwd_kip'], fs_b=P['fs_bwd_kip'],
                fc_f=P['fc_fwd_kip'], fc_b=P['fc_bwd_kip'], vs=P['vs_in_per_s'],
                K_f1=C[0] * m[0] + C[1] * m[2], K_f2=C[0] * m[1] + C[1] * m[3],
                K_b1=C[2] * m[4] + C[3] * m[6], K_b2=C[2] * m[5] + C[3] * m[7],
                floor=P['fc_floor_kip'])


def drum_velocity(x, w=15):
    n = len(x)
    c = [0.0] * n
    for i in range(1, n - 1):
        c[i] = (x[i + 1] - x[i - 1]) / (2 * DT)
    c[0] = (x[1] - x[0]) / DT
    c[-1] = (x[-1] - x[-2]) / DT
    ps = [0.0]
    for a in c:
        ps.append(ps[-1] + a)
    h = w // 2
    out = []
    for i in range(n):
        k = min(h, i, n - 1 - i)
        out.append((ps[i + k + 1] - ps[i - k]) / (2 * k + 1))
    return out


def base_fc(P, v, d1, d2):
    if v >= 0:
        fc = P['fc_f'] + P['K_f1'] * d1 + P['K_f2'] * d2
        fs = P['fs_f']
    else:
        fc = P['fc_b'] + P['K_b1'] * d1 + P['K_b2'] * d2
        fs = P['fs_b']
    if fc < P['floor']:
        fc = P['floor']
    return fc, fs


# ----------------------------------------------------------------------------------------
# Simulation with (optionally) one hidden effect.
# inp: dict x (in), v (in/s, drum_velocity(x)), a1, a2 (in), x10, x20 (in), F_init (kip)
# eff: None or dict(cat=..., shape=..., p={...})
# Returns the noise-free "true" force (kip), one value per sample.
# ----------------------------------------------------------------------------------------

def _sgn(a):
    return 1.0 if a > 0 else (-1.0 if a < 0 else 0.0)


def _actuator_paths(inp, eff):
    """Effective actuator displacement from x' (d1, d2) as seen by the bands."""
    a1, a2 = inp['a1'], inp['a2']
    x10, x20 = inp['x10'], inp['x20']
    n = len(a1)
    d1 = [a - x10 for a in a1]
    d2 = [a - x20 for a in a2]
    if not eff or eff['cat'] != 'actuator_lag':
        return d1, d2
    p = eff['p']; sh = eff['shape']
    out = []
    for d in (d1, d2):
        if sh == 'first_order':
            tau = p['tau_s']; y = d[0]; o = []
            al = 1.0 - math.exp(-DT / tau)
            for i in range(n):
                y += al * (d[i] - y); o.append(y)
        elif sh == 'delay':
            k = int(round(p['delay_s'] / DT))
            o = [d[max(0, i - k)] for i in range(n)]
        elif sh == 'second_order':
            wn = 2 * math.pi * p['fn_hz']; ze = p['zeta']
            y = d[0]; yd = 0.0; o = []
            h = DT / 4
            for i in range(n):
                u = d[i]
                for _ in range(4):   # semi-implicit Euler, 4 substeps
                    ydd = wn * wn * (u - y) - 2 * ze * wn * yd
                    yd += h * ydd
                    y += h * yd
                o.append(y)
        else:
            raise ValueError(sh)
        out.append(o)
    return out[0], out[1]


def simulate(P, inp, eff=None):
    x = inp['x']; v = inp['v']; n = len(v)
    d1, d2 = _actuator_paths(inp, eff)
    s0, s2, vs = P['sigma0'], P['sigma2'], P['vs']
    cat = eff['cat'] if eff else 'none'
    sh = eff['shape'] if eff else ''
    p = eff['p'] if eff else {}
    F_init = inp['F_init']

    # ---- effect-specific state ----
    s_travel = 0.0          # cumulative drum travel (in)
    theta = 0.0             # thermal state (kip*in)
    vL = v[0]               # lagged velocity (frictional memory)
    spd = abs(v[0])         # smoothed speed for rest detection
    resting = False; t_rest = 0.0; z_ref = 0.0
    F_prev = F_init

    def g_of(i, vv):
        """Steady-state friction level g(v) incl. effects acting on the friction level."""
        dd1, dd2 = d1[i], d2[i]
        if cat == 'pretension' and sh == 'pretension_loss':
            u = p['u_max_in'] * (1.0 - math.exp(-s_travel / p['s0_in']))
            dd1 += u; dd2 += u
        if vv >= 0:
            b, K1, K2, fs = P['fc_f'], P['K_f1'], P['K_f2'], P['fs_f']
        else:
            b, K1, K2, fs = P['fc_b'], P['K_b1'], P['K_b2'], P['fs_b']
        t1 = K1 * dd1; t2 = K2 * dd2
        if cat == 'pretension':
            if sh == 'hardening':
                h = p['h']; t1 *= (1.0 - h * dd1 / 0.03); t2 *= (1.0 - h * dd2 / 0.03)
            elif sh == 'gain':
                t1 *= p['k']; t2 *= p['k']
        fc = b + t1 + t2
        if fc < P['floor']:
            fc = P['floor']
        if cat == 'pretension' and sh == 'static_follows':
            fs = fs + p['lam'] * (fs / b) * (fc - b)
        vsd = vs
        if cat == 'asymmetry' and sh == 'velocity_dir' and vv < 0:
            vsd = vs * p['vs_mult']
        ve = vv
        if cat == 'velocity' and sh == 'frictional_memory':
            ve = vL
        r = abs(ve) / vsd
        if cat == 'velocity' and sh == 'stribeck_exponent':
            st = math.exp(-(r ** p['delta']))
        elif cat == 'velocity' and sh == 'lorentzian':
            st = (1 - p['alpha']) * math.exp(-r * r) + p['alpha'] / (1.0 + r * r)
        else:
            st = math.exp(-r * r)
        g = fc + (fs - fc) * st
        if cat == 'velocity' and sh == 'log_strengthening':
            g *= 1.0 + p['a'] * math.log(1.0 + abs(vv) / p['v0'])
        if cat == 'self_energizing':
            if sh == 'capstan_position':
                g *= math.exp(p['kappa'] * x[i] * _sgn(vv if vv != 0 else 1.0))
            elif sh == 'band_stretch':
                g *= 1.0 + p['kappa'] * abs(x[i])
            elif sh == 'thermal':
                g *= 1.0 + p['beta'] * theta
        return g

    def sig2(vv):
        if cat == 'asymmetry' and sh == 'velocity_dir' and vv < 0:
            return s2 * p['s2_mult']
        return s2

    # ---- representation of the elastic state ----
    out = [0.0] * n
    if cat == 'backlash' and sh == 'deadzone':
        zb = p['gap_in'] / 2.0
        z = _sgn(F_init) * (zb + abs(F_init) / s0)
    elif cat == 'backlash' and sh == 'smooth':
        zb = p['gap_in'] / 2.0
        e_t = F_init / s0; z = e_t
        for _ in range(60):
            fz = z - zb * math.tanh(z / zb) - e_t
            dfz = 1 - zb * (1 - math.tanh(z / zb) ** 2) / zb
            z -= fz / max(dfz, 1e-3)
    elif cat == 'asymmetry' and sh == 'stiffness_dir':
        kb = s0 * p['k_ratio']
        z = F_init / (s0 if F_init >= 0 else kb)
    elif cat == 'transition_shape' and sh == 'gms':
        z = F_init / s0
        al = p['alphas']; dl = p['deltas']
        kj = [a * p['g_ref'] / d for a, d in zip(al, dl)]
        # initial element deflections: load the stiffest first, consistent with F_init
        zj = []
        rem = F_init
        for a, k in zip(al, kj):
            f = max(-a * p['g_ref'], min(a * p['g_ref'], rem))
            zj.append(f / k); rem -= f
        zj = [zz * 1.0 for zz in zj]
    else:
        z = F_init / s0

    def elastic(zz):
        if cat == 'backlash' and sh == 'deadzone':
            return _sgn(zz) * max(abs(zz) - zb, 0.0)
        if cat == 'backlash' and sh == 'smooth':
            return zz - zb * math.tanh(zz / zb)
        return zz

    def force(i, vv, zz):
        if cat == 'backlash':
            e = elastic(zz)
            if sh == 'deadzone':
                chi = min(1.0, abs(e) / 0.01)
            else:
                chi = math.tanh(zz / zb) ** 2
            return s0 * e + s2 * vv * chi
        if cat == 'asymmetry' and sh == 'stiffness_dir':
            k = s0 if zz >= 0 else kb
            return k * zz + s2 * vv
        if cat == 'asymmetry' and sh == 'velocity_dir':
            return s0 * zz + sig2(vv) * vv
        if cat == 'transition_shape' and sh == 'gms':
            m = p['mix']
            return (1 - m) * s0 * zz + m * sum(k * q for k, q in zip(kj, zj)) + s2 * vv
        return s0 * zz + s2 * vv

    out[0] = force(0, v[0], z)
    F_prev = out[0]
    nsub = p.get('nsub', 1) if eff else 1
    for i in range(1, n):
        vv = v[i]
        # states updated with the new sample's velocity (same convention as the base model)
        s_travel += abs(x[i] - x[i - 1])
        if cat == 'self_energizing' and sh == 'thermal':
            theta += DT * (abs(F_prev * vv) - theta / p['tau_th_s'])
        if cat == 'velocity' and sh == 'frictional_memory':
            vL += (vv - vL) * (1.0 - math.exp(-DT / p['tau_s']))
        g = g_of(i, vv)
        if cat == 'backlash' or (cat == 'transition_shape' and sh in ('elastoplastic', 'dahl_exponent')) \
                or (cat == 'asymmetry' and sh == 'stiffness_dir'):
            # general ODE, RK4 with substeps (v, g held over the sample, as in the base step)
            h = DT / nsub
            def f(zz):
                if cat == 'backlash':
                    return vv - s0 * abs(vv) * elastic(zz) / g
                if cat == 'asymmetry':
                    k = s0 if zz >= 0 else kb
                    return vv - abs(vv) * k * zz / g
                zss = g / s0
                if sh == 'elastoplastic':
                    if vv == 0:
                        return 0.0
                    zba = p['beta'] * zss
                    az = abs(zz)
                    if _sgn(zz) != _sgn(vv):
                        a = p.get('alpha_opp', 0.0)
                    elif az <= zba:
                        a = 0.0
                    elif az >= zss:
                        a = 1.0
                    else:
                        a = 0.5 * math.sin(math.pi * (az - 0.5 * (zss + zba)) / (zss - zba)) + 0.5
                    return vv * (1.0 - a * zz * _sgn(vv) / zss)
                # dahl_exponent
                u = 1.0 - zz * _sgn(vv) / zss
                return vv * _sgn(u) * abs(u) ** p['i']
            for _ in range(nsub):
                k1 = f(z); k2 = f(z + h / 2 * k1); k3 = f(z + h / 2 * k2); k4 = f(z + h * k3)
                z += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        else:
            a = s0 * abs(vv) / g
            if a > 0:
                zs = vv / a
                z = zs + (z - zs) * math.exp(-a * DT)
            if cat == 'transition_shape' and sh == 'gms':
                dx = vv * DT
                for j in range(len(zj)):
                    q = zj[j] + dx
                    lim = al[j] * g / kj[j]
                    if q > lim:
                        q = lim
                    elif q < -lim:
                        q = -lim
                    zj[j] = q
        if cat == 'residual_static':
            spd += (abs(vv) - spd) * (1.0 - math.exp(-DT / 0.05))
            now_rest = spd < p.get('v_rest', 0.03)
            if now_rest and not resting:
                resting = True; t_rest = 0.0; z_ref = z
            elif not now_rest:
                resting = False
            if resting:
                if sh == 'exp_relax':
                    z += -(z - p['rho'] * z_ref) * (1.0 - math.exp(-DT / p['tau_s']))
                elif sh == 'log_relax':
                    z += -p['c'] * z_ref * DT / (p['t0_s'] + t_rest)
                t_rest += DT
        out[i] = force(i, vv, z)
        F_prev = out[i]
    return out
