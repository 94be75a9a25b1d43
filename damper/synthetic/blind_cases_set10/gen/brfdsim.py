"""Semi-active BRFD model (LuGre Eqs. 1-3 of the seed paper with the kinetic friction of
Eq. 4 fed into the Stribeck function, Eq. 5) plus hidden-effect variants.

Python 3 standard library only.

Numerical conventions (chosen so that the plain base model reproduces
`hybridsim damper predict --no-fit` on the same input file to ~1e-6 kip):
  * drum velocity v is derived from the displacement column (the file's velocity column is
    not in in/s, see the data README): central difference (one-sided at the two ends),
    then a centred moving average of 15 samples whose window shrinks symmetrically at the
    record ends;
  * step k-1 -> k holds the inputs (v, actuator positions) at their sample-k values and
    advances the bristle state exactly (LuGre is linear in z for frozen v) or, for the
    state-nonlinear variants, with RK4 sub-steps;
  * z(0) = F_file(0) / sigma0.
"""
import math
import re

DT = 1.0 / 1024.0


# --------------------------------------------------------------------------- parameters
def load_config(path):
    txt = open(path).read()

    def num(key):
        m = re.search(r'^\s*' + key + r'\s*:\s*([-+0-9.eE]+)', txt, re.M)
        return float(m.group(1))

    def lst(key):
        m = re.search(r'^\s*' + key + r'\s*:\s*\[([^\]]*)\]', txt, re.M)
        return [float(a) for a in m.group(1).split(',')]

    P = dict(s0=num('sigma0_kip_per_in'), s1=num('sigma1_kip_s_per_in'),
             s2=num('sigma2_kip_s_per_in'), fsf=num('fs_fwd_kip'), fsb=num('fs_bwd_kip'),
             fcf=num('fc_fwd_kip'), fcb=num('fc_bwd_kip'), vs=num('vs_in_per_s'),
             floor=num('fc_floor_kip'))
    m = lst('slopes_kip_per_in')
    C = lst('scaling')
    # Eq. (4): m11 m12 m21 m22 m31 m32 m41 m42 ; C1..C4
    P['kf1'] = C[0] * m[0] + C[1] * m[2]
    P['kf2'] = C[0] * m[1] + C[1] * m[3]
    P['kb1'] = C[2] * m[4] + C[3] * m[6]
    P['kb2'] = C[2] * m[5] + C[3] * m[7]
    if abs(P['s1']) > 0:
        raise SystemExit('this generator assumes sigma1 = 0 (as in the config)')
    return P


def drum_velocity(x):
    n = len(x)
    d = [0.0] * n
    d[0] = (x[1] - x[0]) / DT
    d[-1] = (x[-1] - x[-2]) / DT
    for i in range(1, n - 1):
        d[i] = (x[i + 1] - x[i - 1]) / (2 * DT)
    v = [0.0] * n
    for i in range(n):
        k = min(7, i, n - 1 - i)
        v[i] = sum(d[i - k:i + k + 1]) / (2 * k + 1)
    return v


# --------------------------------------------------------------------------- helpers
def first_order(u, tau):
    if tau <= 0:
        return list(u)
    a = math.exp(-DT / tau)
    y = [u[0]] * len(u)
    for i in range(1, len(u)):
        y[i] = u[i] + (y[i - 1] - u[i]) * a
    return y


def delayed(u, d):
    if d <= 0:
        return list(u)
    ds = d / DT
    n = len(u)
    y = [0.0] * n
    for i in range(n):
        t = i - ds
        if t <= 0:
            y[i] = u[0]
        else:
            j = int(t)
            f = t - j
            y[i] = u[j] * (1 - f) + u[min(j + 1, n - 1)] * f
    return y


def second_order(u, tn, zeta):
    """y'' = wn^2 (u - y) - 2 zeta wn y', wn = 1/tn; RK4, 4 sub-steps, u held."""
    if tn <= 0:
        return list(u)
    wn = 1.0 / tn
    y, yd = u[0], 0.0
    out = [y]
    h = DT / 4
    for i in range(1, len(u)):
        uu = u[i]
        for _ in range(4):
            def f(a, b):
                return b, wn * wn * (uu - a) - 2 * zeta * wn * b
            k1 = f(y, yd)
            k2 = f(y + h / 2 * k1[0], yd + h / 2 * k1[1])
            k3 = f(y + h / 2 * k2[0], yd + h / 2 * k2[1])
            k4 = f(y + h * k3[0], yd + h * k3[1])
            y += h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
            yd += h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
        out.append(y)
    return out


REST_V = 0.05    # in/s: |v| below this counts as "drum at rest"
REST_ON = 0.10   # s: rest effects start after this long at rest
REST_W = 0.05    # s: smooth onset of the rest effects


def rest_time(v):
    tr = [0.0] * len(v)
    for i in range(1, len(v)):
        tr[i] = tr[i - 1] + DT if abs(v[i]) < REST_V else 0.0
    return tr


def travel_since_reversal(x, v, vh=0.05):
    n = len(x)
    s = [1e9] * n
    dirn = 0
    ext = x[0]
    rev = None
    for i in range(n):
        vi = v[i]
        if dirn >= 0 and vi < -vh:
            if dirn == 1:
                rev = ext
            dirn = -1
            ext = x[i]
        elif dirn <= 0 and vi > vh:
            if dirn == -1:
                rev = ext
            dirn = 1
            ext = x[i]
        if dirn == 1 and x[i] > ext:
            ext = x[i]
        elif dirn == -1 and x[i] < ext:
            ext = x[i]
        if rev is not None:
            s[i] = abs(x[i] - rev)
    return s


# --------------------------------------------------------------------------- simulation
NONLINEAR = {'bl_deadzone', 'bl_soft', 'as_stiff', 'ts_dahl', 'ts_elastoplastic', 'se_servo'}


def simulate(P, rec, shape='none', p=0.0, ex=None, return_z=False):
    """rec: dict x, v, x1, x2, z0 (base bristle state at t=0), S0 (wear distance at t=0).
    Returns (force list, info dict)."""
    ex = ex or {}
    x, v = rec['x'], rec['v']
    n = len(x)
    s0, s2, vs = P['s0'], P['s2'], P['vs']
    x10, x20 = rec['x1'][0], rec['x2'][0]
    info = {}

    # ---- effective actuator positions (band clamping following the commands)
    x1e, x2e = rec['x1'], rec['x2']
    if shape == 'al_first':
        x1e, x2e = first_order(x1e, p), first_order(x2e, p)
    elif shape == 'al_delay':
        x1e, x2e = delayed(x1e, p), delayed(x2e, p)
    elif shape == 'al_second':
        x1e, x2e = second_order(x1e, p, ex['zeta']), second_order(x2e, p, ex['zeta'])

    # ---- auxiliary signals
    if shape == 've_memory':
        u = first_order([abs(a) for a in v], p)
    if shape == 'pt_wear':
        S = [0.0] * n
        acc = rec.get('S0', 0.0)
        for i in range(n):
            if i > 0:
                acc += abs(v[i]) * DT
            S[i] = acc
        info['S_end'] = acc
    if shape.startswith('rs_'):
        tr = rest_time(v)
        w = [0.0 if t < REST_ON else 1.0 - math.exp(-(t - REST_ON) / REST_W) for t in tr]
    if shape == 'bl_dip':
        trav = travel_since_reversal(x, v)

    # ---- Stribeck function g(v) with the semi-active Fc of Eq. 4 (per sample)
    fl = P['floor']
    g = [0.0] * n
    for i in range(n):
        vi = v[i]
        fwd = vi >= 0
        if fwd:
            c = P['fcf'] + P['kf1'] * (x1e[i] - x10) + P['kf2'] * (x2e[i] - x20)
            fs = P['fsf']
        else:
            c = P['fcb'] + P['kb1'] * (x1e[i] - x10) + P['kb2'] * (x2e[i] - x20)
            fs = P['fsb']
        if shape == 'pt_offset':
            c += p * ex['sign']
            fs += p * ex['sign']
        if c < fl:
            c = fl
        if shape == 've_stribeck':
            st = (1 - p) * math.exp(-(vi / vs) ** 2) + p * math.exp(-(abs(vi) / ex['vs2']) ** ex['delta'])
        elif shape == 've_memory':
            st = math.exp(-(u[i] / vs) ** 2)
        else:
            st = math.exp(-(vi / vs) ** 2)
        gi = c + (fs - c) * st
        if shape == 'pt_gain':
            gi *= (1 + p) if ex['sign'] > 0 else 1.0 / (1 + p)
        elif shape == 'pt_wear':
            gi *= 1 - p * (1 - math.exp(-S[i] / ex['Sw']))
        elif shape == 'as_gain':
            if fwd == (ex['dir'] > 0):
                gi *= (1 + p) if ex['sign'] > 0 else 1.0 / (1 + p)
        elif shape == 'as_tanh':
            gi *= 1 + ex['sign'] * p * math.tanh(vi / ex['va'])
        elif shape == 've_power':
            pass
        elif shape == 'se_angle':
            gi *= 1 + p * abs(x[i]) ** ex['beta']
        elif shape == 'se_capstan':
            gi *= math.exp(p * x[i] * (1 if fwd else -1))
        if shape == 've_power' and ex.get('inside'):
            gi += p * abs(vi) ** ex['alpha']
        if gi < fl:
            gi = fl
        g[i] = gi

    # ---- bristle state
    F0el = s0 * rec['z0']
    F = [0.0] * n
    zs = [0.0] * n if return_z else None

    if shape == 'ts_multi':
        ks, ws = ex['k'], ex['w']
        zb = rec['z0']
        zm = [wj * F0el / (s0 * kj) for kj, wj in zip(ks, ws)]
        for i in range(n):
            vi = v[i]
            av = abs(vi)
            if i > 0 and av > 0:
                a = s0 * av / g[i]
                zss = vi / a
                zb = zss + (zb - zss) * math.exp(-a * DT)
                for j in range(3):
                    aj = s0 * ks[j] * av / (ws[j] * g[i])
                    zssj = vi / aj
                    zm[j] = zssj + (zm[j] - zssj) * math.exp(-aj * DT)
            fm = s0 * sum(kj * zj for kj, zj in zip(ks, zm))
            F[i] = (1 - p) * s0 * zb + p * fm + s2 * vi
        return F, info

    if shape not in NONLINEAR:
        z = rec['z0']
        zon = None
        for i in range(n):
            vi = v[i]
            if i > 0:
                a = s0 * abs(vi) / g[i]
                b = vi
                if shape == 'rs_relax' and w[i] > 0:
                    a += w[i] * p
                elif shape == 'rs_settle':
                    if w[i] > 0:
                        if zon is None:
                            zon = z
                        k = w[i] / ex['tau']
                        a += k
                        b += k * (zon + ex['sign'] * p / s0)
                    else:
                        zon = None
                if a > 0:
                    zss = b / a
                    z = zss + (z - zss) * math.exp(-a * DT)
            if return_z:
                zs[i] = z
            fel = s0 * z
            if shape == 'bl_dip':
                fel *= 1 - p * math.exp(-trav[i] / ex['sr'])
            elif shape == 'rs_creep':
                if tr[i] > REST_ON:
                    fel *= 1 + p * math.log(1 + (tr[i] - REST_ON) / ex['t0'])
            F[i] = fel + s2 * vi
            if shape == 've_power' and not ex.get('inside'):
                F[i] += p * math.copysign(abs(vi) ** ex['alpha'], vi)
        if return_z:
            info['z'] = zs
        return F, info

    # ---- state-nonlinear variants: dz/dt = f(z), RK4 with held inputs
    zb0 = rec['z0']
    if shape == 'bl_deadzone':
        d = p

        def fel(z):
            az = abs(z)
            return math.copysign(s0 * (az - d), z) if az > d else 0.0
        z = zb0 + math.copysign(d, zb0)
    elif shape == 'bl_soft':
        zsft = p

        def fel(z):
            az = abs(z)
            if zsft <= 0:
                return s0 * z
            if az < zsft:
                return math.copysign(s0 * az * az / (2 * zsft), z)
            return math.copysign(s0 * (az - zsft / 2), z)
        fz = abs(F0el) / s0
        if zsft > 0 and fz < zsft / 2:
            z = math.copysign(math.sqrt(2 * zsft * fz), zb0)
        else:
            z = math.copysign(fz + zsft / 2, zb0)
    elif shape == 'as_stiff':
        kfac = (1 + p) if ex['stiffer'] else 1.0 / (1 + p)
        side = ex['side']

        def fel(z):
            return s0 * z * (kfac if (z >= 0) == (side > 0) else 1.0)
        z = F0el / (s0 * (kfac if (zb0 >= 0) == (side > 0) else 1.0))
    else:
        def fel(z):
            return s0 * z
        z = zb0

    if shape == 'ts_dahl':
        alpha = (1 + p) if ex['soft'] else 1.0 / (1 + p)

        def deriv(z, vi, gi):
            uu = 1 - math.copysign(1, vi) * s0 * z / gi
            return vi * math.copysign(abs(uu) ** alpha, uu)
    elif shape == 'ts_elastoplastic':
        beta = p

        def deriv(z, vi, gi):
            zss = gi / s0
            if (z >= 0) != (vi >= 0) or beta <= 0:
                al = 1.0
            else:
                zba = beta * zss
                az = abs(z)
                if az <= zba:
                    al = 0.0
                elif az >= zss:
                    al = 1.0
                else:
                    al = 0.5 * math.sin(math.pi * (az - 0.5 * (zss + zba)) / (zss - zba)) + 0.5
            return vi - al * abs(vi) * s0 * z / gi
    elif shape == 'se_servo':
        fr = ex['Fr']

        def deriv(z, vi, gi):
            ge = gi * (1 + p * abs(s0 * z) / fr)
            return vi - abs(vi) * s0 * z / ge
    else:
        def deriv(z, vi, gi):
            return vi - abs(vi) * fel(z) / gi

    nsub = 2
    h = DT / nsub
    for i in range(n):
        vi = v[i]
        if i > 0 and vi != 0:
            gi = g[i]
            for _ in range(nsub):
                k1 = deriv(z, vi, gi)
                k2 = deriv(z + h / 2 * k1, vi, gi)
                k3 = deriv(z + h / 2 * k2, vi, gi)
                k4 = deriv(z + h * k3, vi, gi)
                z += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        F[i] = fel(z) + s2 * vi
    return F, info
