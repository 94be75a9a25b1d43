"""Base BRFD semi-active LuGre model (as inferred from the black box) plus the effect shapes.

Base (verified against `hybridsim damper predict --no-fit` to ~5e-8 kip, i.e. CSV rounding):
  v_i  = central difference of the displacement column (one-sided at the two ends),
         then a zero-phase centred moving average of 15 samples whose half-width shrinks
         symmetrically at the record ends (h = min(7, i, n-1-i)).
  Fc_i = Eq. (4) with x'_1, x'_2 = actuator columns at row 0, clipped at 0.05 kip.
  g_i  = Fc_i + (Fs_dir - Fc_i) exp(-(v_i/vs)^2), direction by v_i >= 0.
  z_0  = F_measured[0] / sigma0;  z_i from z_{i-1} by the exact solution of
         dz/dt = v_i - sigma0 |v_i| z / g_i over one step dt (v_i, g_i held);
  F_i  = sigma0 z_i + sigma2 v_i   (sigma1 = 0).
"""
import math

DT = 1.0 / 1024
P = dict(s0=15.36, s1=0.0, s2=0.5, fsf=7.116, fsb=3.76, fcf=2.648, fcb=1.253, vs=1.3, floor=0.05)
M = [-0.14, -0.15, -15.29, -13.00, -16.66, -15.77, -0.13, -0.15]
C = [119.68, 2.10, 1.94, 123.31]
KF1 = C[0] * M[0] + C[1] * M[2]
KF2 = C[0] * M[1] + C[1] * M[3]
KB1 = C[2] * M[4] + C[3] * M[6]
KB2 = C[2] * M[5] + C[3] * M[7]


def velocity(x):
    n = len(x)
    r = [0.0] * n
    for i in range(n):
        if i == 0:
            r[i] = (x[1] - x[0]) / DT
        elif i == n - 1:
            r[i] = (x[-1] - x[-2]) / DT
        else:
            r[i] = (x[i + 1] - x[i - 1]) / (2 * DT)
    cs = [0.0]
    for a in r:
        cs.append(cs[-1] + a)
    out = [0.0] * n
    for i in range(n):
        h = min(7, i, n - 1 - i)
        out[i] = (cs[i + h + 1] - cs[i - h]) / (2 * h + 1)
    return out


def lin_clamp(d1, d2, fwd):
    """Eq. (4) increment L (kip) for actuator increments d1, d2 (in)."""
    return (KF1 * d1 + KF2 * d2) if fwd else (KB1 * d1 + KB2 * d2)


def simulate(x, x1, x2, f0, shape=None, a=0.0):
    """Return force list. shape=None or a=0 -> exact base model."""
    s0, s2, vs, floor = P['s0'], P['s2'], P['vs'], P['floor']
    v = velocity(x)
    n = len(x)
    x10, x20 = x1[0], x2[0]
    if a == 0.0:
        shape = None
    sh = shape
    z = f0 / s0
    F = [0.0] * n
    # effect states
    e_gap = 0.0; vl = v[0]; y = 0.0; trest = 0.0; lastdir = 0; srev = 0.0; sprev = 0.0
    trev = -1e9; xrev = x[0]; rdir = 0; Fprev = f0
    z1 = z2 = 0.0
    xe1, xe2 = x10, x20; ve1 = ve2 = 0.0; xs1, xs2 = x10, x20
    if sh == 'gms2':
        c1, c2 = 0.5 * (1 + a), 0.5 * (1 - a)
        z1 = 0.5 * f0 / (s0 * c1); z2 = 0.5 * f0 / (s0 * c2)
    gapmode = False; side = 1 if f0 >= 0 else -1
    if sh == 'play_gap':
        e_gap = (a / 2) if f0 >= 0 else -(a / 2)
    nd = int(round(a / DT)) if sh == 'delay' else 0
    for i in range(n):
        vi = v[i]
        fwd = vi >= 0
        d = 1 if fwd else -1
        # ---------------- actuator positions seen by the clamping law
        p1, p2 = x1[i], x2[i]
        if sh == 'delay':
            j = max(0, i - nd); p1, p2 = x1[j], x2[j]
        elif sh == 'second_order' and i > 0:
            w = 1.0 / a; zeta = 0.25
            ve1 += DT * (w * w * (x1[i] - xe1) - 2 * zeta * w * ve1); xe1 += DT * ve1
            ve2 += DT * (w * w * (x2[i] - xe2) - 2 * zeta * w * ve2); xe2 += DT * ve2
            p1, p2 = xe1, xe2
        elif sh == 'zener' and i > 0:
            k = 1 - math.exp(-DT / 0.8)
            xs1 += (x1[i] - xs1) * k; xs2 += (x2[i] - xs2) * k
            p1 = (1 - a) * x1[i] + a * xs1; p2 = (1 - a) * x2[i] + a * xs2
        d1, d2 = p1 - x10, p2 - x20
        L = lin_clamp(d1, d2, fwd)
        b = P['fcf'] if fwd else P['fcb']
        if sh == 'stiffening':
            L = L * (1 + a * abs(L))
        elif sh == 'powerlaw':
            r = max(1 + L / b, 1e-3)
            L = b * (r ** (1 - a) - 1)
        elif sh == 'coupling':
            L = L + a * (d1 / 0.015) * (d2 / 0.015)
        fc = max(b + L, floor)
        fs = P['fsf'] if fwd else P['fsb']
        # ---------------- reversal bookkeeping (travel since the last reversal)
        if abs(vi) > 0.05:
            if rdir != 0 and d != rdir:
                sprev = srev; srev = 0.0; trev = i * DT
            if d != rdir:
                xrev = x[i]
            rdir = d
        if i > 0:
            srev += abs(vi) * DT
        # ---------------- kinetic / Stribeck modifications
        vsd = vs
        vg = vi
        if sh == 'rate_strength':
            fc = fc * (1 + a * math.log(1 + abs(vi) / 0.5))
        elif sh == 'flash_weaken':
            fc = fc * (1 - a * max(0.0, 1 - 1.2 / abs(vi))) if abs(vi) > 1.2 else fc
        elif sh == 'memory':
            if i > 0:
                vl += (vi - vl) * (1 - math.exp(-DT / a))
            vg = vl
        elif sh == 'vs_asym' and not fwd:
            vsd = vs * (1 + a)
        g = fc + (fs - fc) * math.exp(-(vg / vsd) ** 2)
        if sh == 'outward_wrap':
            g *= 1 + a * max(0.0, x[i] * d)
        elif sh == 'capstan_travel':
            g *= 1 + a * (1 - math.exp(-srev / 0.4))
        elif sh == 'servo':
            g /= max(1 - a * abs(Fprev) / fs, 0.2)
        # ---------------- bristle state
        if i > 0:
            vin = vi
            if sh == 'play_gap' and gapmode:
                h = a / 2
                e_gap += vi * DT
                if e_gap >= h:
                    vin = (e_gap - h) / DT; e_gap = h; gapmode = False; side = 1
                elif e_gap <= -h:
                    vin = (e_gap + h) / DT; e_gap = -h; gapmode = False; side = -1
                else:
                    vin = 0.0
            kap = 1.0
            if sh == 'sigma_asym' and not fwd:
                kap = 1 - a
            if sh == 'gms2':
                for kidx in (1, 2):
                    ck = c1 if kidx == 1 else c2
                    zk = z1 if kidx == 1 else z2
                    rate = ck * s0 * abs(vi) / (0.5 * g)
                    if rate > 0:
                        zsat = vi / rate; zk = zsat + (zk - zsat) * math.exp(-rate * DT)
                    else:
                        zk += vi * DT
                    if kidx == 1: z1 = zk
                    else: z2 = zk
            else:
                rate = kap * s0 * abs(vin) / g
                if sh == 'elastoplastic' and rate > 0:
                    zss = g / s0
                    if z * vin > 0:
                        zb = 0.5 * a * zss; zm = a * zss; az = abs(z)
                        if az <= zb: alpha = 0.0
                        elif az >= zm: alpha = 1.0
                        else: alpha = 0.5 * math.sin(math.pi * ((az - (zm + zb) / 2) / (zm - zb))) + 0.5
                        rate *= alpha
                elif sh == 'dahl_exp' and rate > 0:
                    u = abs(s0 * z / g)
                    rate *= max(u, 1e-6) ** a
                if rate > 0:
                    zsat = kap * vin / rate
                    z = zsat + (z - zsat) * math.exp(-rate * DT)
                else:
                    z += kap * vin * DT
                if sh == 'play_gap' and not gapmode and z * side < 0:
                    z = 0.0; gapmode = True
            wr = math.exp(-(vi / 0.05) ** 2)
            if sh == 'maxwell_relax':
                y += DT * ((z - y) * wr / 0.6 - y * (1 - wr) / 0.05)
            elif sh == 'log_relax':
                trest += DT * (wr - (1 - wr) * trest / 0.05)
            elif sh == 'spring_settle':
                zeq = 2.0 * x[i] / s0
                z += (zeq - z) * (1 - math.exp(-DT * a * wr / 0.3))
        # ---------------- output
        if sh == 'gms2':
            Fi = s0 * (c1 * z1 + c2 * z2) + s2 * vi
        else:
            s2d = s2 * (1 + a) if (sh == 'visc_asym' and not fwd) else s2
            vo = vin if (sh == 'play_gap' and i > 0) else vi
            Fi = s0 * z + s2d * vo
        if sh == 'maxwell_relax':
            Fi -= a * s0 * y
        elif sh == 'log_relax':
            Fi *= 1 - a * math.log(1 + max(trest, 0.0) / 0.05)
        elif sh == 'stored_collapse' and rdir != 0:
            depth = a * min(1.0, sprev / 1.0)
            Fi *= 1 - depth * math.exp(-srev / 0.15)
        elif sh == 'impact_ring' and rdir != 0:
            tt = i * DT - trev
            if tt >= 0:
                Fi += -a * rdir * math.exp(-tt / 0.12) * math.cos(2 * math.pi * 6.0 * tt)
        F[i] = Fi
        Fprev = Fi
    return F
