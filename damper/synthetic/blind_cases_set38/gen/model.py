"""Replica of the base model of `hybridsim damper predict --no-fit` with
/work/main/configs/brfd-semiactive.yaml (inferred from the black box's CSV output), plus the
hidden-effect variants used by blind set 38. Standard library only."""
import math

FS = 1024
DT = 1.0 / FS

BASE = {
    "sigma0": 15.36, "sigma1": 0.0, "sigma2": 0.5,
    "fs_fwd": 7.116, "fs_bwd": 3.760, "fc_fwd": 2.648, "fc_bwd": 1.253, "vs": 1.300,
    "m": [-0.14, -0.15, -15.29, -13.00, -16.66, -15.77, -0.13, -0.15],
    "C": [119.68, 2.10, 1.94, 123.31],
    "floor": 0.05,
}


def drum_velocity(x):
    """Black box's drum velocity: central-difference gradient (one-sided at the two ends,
    like numpy.gradient), then a centred 15-sample moving average whose window shrinks at
    the record ends."""
    n = len(x)
    g = [0.0] * n
    g[0] = (x[1] - x[0]) * FS
    g[-1] = (x[-1] - x[-2]) * FS
    for i in range(1, n - 1):
        g[i] = (x[i + 1] - x[i - 1]) * (FS / 2.0)
    pre = [0.0]
    s = 0.0
    for val in g:
        s += val
        pre.append(s)
    v = [0.0] * n
    for i in range(n):
        lo = max(0, i - 7)
        hi = min(n, i + 8)
        v[i] = (pre[hi] - pre[lo]) / (hi - lo)
    return v


def drum_velocity_direct(x):
    n = len(x)
    g = [0.0] * n
    g[0] = (x[1] - x[0]) * FS
    g[-1] = (x[-1] - x[-2]) * FS
    for i in range(1, n - 1):
        g[i] = (x[i + 1] - x[i - 1]) * (FS / 2.0)
    v = [0.0] * n
    for i in range(n):
        lo = max(0, i - 7)
        hi = min(n, i + 8)
        v[i] = sum(g[lo:hi]) / (hi - lo)
    return v


def eq4(v, x1, x2, x1p, x2p, P=BASE):
    m, C = P["m"], P["C"]
    if v >= 0:
        f = P["fc_fwd"] + (C[0] * m[0] + C[1] * m[2]) * (x1 - x1p) + (C[0] * m[1] + C[1] * m[3]) * (x2 - x2p)
    else:
        f = P["fc_bwd"] + (C[2] * m[4] + C[3] * m[6]) * (x1 - x1p) + (C[2] * m[5] + C[3] * m[7]) * (x2 - x2p)
    return f


def base_predict(x, x1, x2, F0, P=BASE, return_fc=False):
    """LuGre Eqs. (1)-(3) with Eq. (4)-(5); z(0) = F0/sigma0 (first force sample); each step
    i-1 -> i integrates Eq. (1) exactly with v, g frozen at sample i (exponential update);
    F_i = sigma0 z_i + sigma1 zdot_i + sigma2 v_i."""
    n = len(x)
    v = drum_velocity(x)
    s0, s1, s2 = P["sigma0"], P["sigma1"], P["sigma2"]
    vs = P["vs"]
    x1p, x2p = x1[0], x2[0]
    z = F0 / s0
    out = [0.0] * n
    fcs = [0.0] * n
    for i in range(n):
        vi = v[i]
        fc = eq4(vi, x1[i], x2[i], x1p, x2p, P)
        if fc < P["floor"]:
            fc = P["floor"]
        fs = P["fs_fwd"] if vi >= 0 else P["fs_bwd"]
        g = fc + (fs - fc) * math.exp(-(vi / vs) ** 2)
        if i > 0 and vi != 0.0:
            zs = g / s0 if vi > 0 else -g / s0
            z = zs + (z - zs) * math.exp(-s0 * abs(vi) * DT / g)
        zd = vi - s0 * abs(vi) * z / g
        out[i] = s0 * z + s1 * zd + s2 * vi
        fcs[i] = fc
    if return_fc:
        return out, fcs, v
    return out


# ----------------------------------------------------------------------------------------
# Hidden-effect simulator. Written in the force state Fz = sigma0*z, stepping exactly like
# base_predict (exponential update with coefficients frozen at sample i), so that every
# effect reduces to the base model when its amplitude is zero.
# ----------------------------------------------------------------------------------------

REST_WIN = 192          # samples (187.5 ms): rest detector window
REST_TOL = 0.0015       # in: drum displacement range inside the window below which = at rest


def rest_clock(x):
    """t_r[i] = time (s) since the rest detector switched on (None while moving). The detector
    is on when max-min of the displacement column over the last 192 samples is < 1.5 mils;
    rest periods count only after the drum has moved at least once in the record."""
    n = len(x)
    out = [None] * n
    moved = False
    on_since = None
    from collections import deque
    dmax, dmin = deque(), deque()
    for i in range(n):
        while dmax and x[dmax[-1]] <= x[i]:
            dmax.pop()
        dmax.append(i)
        while dmin and x[dmin[-1]] >= x[i]:
            dmin.pop()
        dmin.append(i)
        lo = i - REST_WIN + 1
        while dmax[0] < lo:
            dmax.popleft()
        while dmin[0] < lo:
            dmin.popleft()
        rest = i >= REST_WIN - 1 and (x[dmax[0]] - x[dmin[0]]) < REST_TOL
        if not rest:
            if i >= REST_WIN - 1:
                moved = True
            on_since = None
        else:
            if moved:
                if on_since is None:
                    on_since = i
                out[i] = (i - on_since) * DT
    return out


def actuator_effective(xa, kind, p):
    """Effective (clamping) actuator position seen by the band, from the measured one."""
    n = len(xa)
    x0 = xa[0]
    out = [x0] * n
    if kind == "rate_limit":
        r = 1.0 / p["amp"] if p["amp"] > 0 else float("inf")
        step = r * DT
        e = x0
        for i in range(1, n):
            d = xa[i] - e
            if d > step:
                d = step
            elif d < -step:
                d = -step
            e += d
            out[i] = e
    elif kind == "linkage_play":
        h = p["amp"]
        e = x0
        for i in range(1, n):
            if xa[i] - e > h:
                e = xa[i] - h
            elif xa[i] - e < -h:
                e = xa[i] + h
            out[i] = e
    elif kind == "sls_creep":
        c, tau = p["amp"], p["tau_s"]
        a = 1.0 - math.exp(-DT / tau)
        y = 0.0
        for i in range(1, n):
            d = xa[i] - x0
            y += (d - y) * a
            out[i] = x0 + (1.0 - c) * d + c * y
    else:
        return list(xa)
    return out


def simulate(x, x1, x2, F0, shape=None, p=None, P=BASE):
    """Truth force for one record: base model with one hidden effect `shape` (params p)."""
    if shape is None or shape == "none":
        return base_predict(x, x1, x2, F0, P)
    n = len(x)
    v = drum_velocity(x)
    s0, s2 = P["sigma0"], P["sigma2"]
    vs = P["vs"]
    m, C = P["m"], P["C"]
    kf1 = C[0] * m[0] + C[1] * m[2]
    kf2 = C[0] * m[1] + C[1] * m[3]
    kb1 = C[2] * m[4] + C[3] * m[6]
    kb2 = C[2] * m[5] + C[3] * m[7]
    bf, bb = P["fc_fwd"], P["fc_bwd"]
    floor = P["floor"]
    x1p, x2p = x1[0], x2[0]
    amp = p["amp"] if p else 0.0

    # actuator lag: effective positions
    if shape in ("rate_limit", "linkage_play", "sls_creep"):
        x1e = actuator_effective(x1, shape, p)
        x2e = actuator_effective(x2, shape, p)
    else:
        x1e, x2e = x1, x2

    tr = rest_clock(x) if shape in ("sls_relax", "log_relax", "powerlaw_creep_up") else None

    # direction-dependent constants
    s0f = s0b = s0
    vsf = vsb = vs
    s2f = s2b = s2
    if shape == "stribeck_velocity_dir":
        r = math.exp(p["sign"] * amp)
        if p["dir"] == "bwd":
            vsb = vs * r
        else:
            vsf = vs * r
    elif shape == "stiffness_dir":
        r = math.exp(p["sign"] * amp)
        if p["dir"] == "bwd":
            s0b = s0 * r
        else:
            s0f = s0 * r
    elif shape == "viscous_dir":
        if p["dir"] == "bwd":
            s2b = s2 + amp
        else:
            s2f = s2 + amp

    Fz = F0
    FA = FB = 0.0
    if shape == "gms2":
        w = p["w"]
        FA = w * F0
        FB = (1.0 - w) * F0
        eA = math.exp(amp)
        eB = math.exp(-amp)
    out = [0.0] * n
    out[0] = F0 + (s2f if v[0] >= 0 else s2b) * v[0]
    Fprev = out[0]
    # backlash state
    slack = False
    rho_out = 1.0  # backlash: fraction of the viscous term transmitted (rho while slack/re-engaging)
    gap = 0.0
    s_eng = None  # travel since re-engagement (B2), None when fully engaged
    # rest state
    Fon = None
    # frictional lag state
    sL = abs(v[0])
    # travel since reversal (S3)
    trav = 0.0
    sgn_prev = 1 if v[0] >= 0 else -1
    if shape == "frictional_lag":
        aL = 1.0 - math.exp(-DT / amp) if amp > 0 else 1.0

    for i in range(1, n):
        vi = v[i]
        fwd = vi >= 0
        av = abs(vi)
        # ---- kinetic level Fc (Eq. 4, possibly modified)
        d1 = x1e[i] - x1p
        d2 = x2e[i] - x2p
        if fwd:
            b = bf
            lin = kf1 * d1 + kf2 * d2
        else:
            b = bb
            lin = kb1 * d1 + kb2 * d2
        if shape == "power_clamp":
            pe = 1.0 + amp
            base_ = 1.0 + lin / (pe * b)
            fc = b * (base_ ** pe) if base_ > 0 else 0.0
        elif shape == "tanh_saturation":
            fc = b + (math.tanh(lin * amp) / amp if amp > 0 else lin)
        elif shape == "actuator_coupling":
            fc = b + lin + p["sign"] * amp * d1 * d2
        else:
            fc = b + lin
        if fc < floor:
            fc = floor
        if shape == "ratestate_log":
            M = 1.0 + amp * math.log(max(av, p["v_min"]) / p["v_ref"])
            if M < 0.3:
                M = 0.3
            fc = max(fc * M, floor)
        elif shape == "grosch_hump":
            if av > 0:
                lz = math.log(av / p["v_p"])
                M = 1.0 + amp * math.exp(-lz * lz / (2.0 * p["width"] ** 2))
            else:
                M = 1.0
            fc = max(fc * M, floor)
        elif shape == "thermal_weakening":
            q = (av / p["v_w"]) ** p["n"]
            M = 1.0 - amp * q / (1.0 + q)
            fc = max(fc * M, floor)
        fs = P["fs_fwd"] if fwd else P["fs_bwd"]
        vsd = vsf if fwd else vsb
        # ---- Stribeck speed (frictional lag uses a lagged speed)
        if shape == "frictional_lag":
            sL += (av - sL) * aL
            sp = sL
        else:
            sp = av
        g = fc + (fs - fc) * math.exp(-(sp / vsd) ** 2)
        # ---- self-energizing multipliers
        if shape == "servo_feedback":
            g *= 1.0 + amp * abs(Fprev)
        elif shape == "capstan_wrap":
            g *= math.exp(amp * x[i] * (1.0 if fwd else -1.0))
        elif shape == "progressive_wrap":
            sg = 1 if fwd else -1
            if sg != sgn_prev:
                trav = 0.0
            sgn_prev = sg
            trav += av * DT
            g *= 1.0 + amp * (1.0 - math.exp(-trav / p["lam_in"]))
        s0d = s0f if fwd else s0b
        # ---- bristle (band) force update
        if shape == "gms2":
            if vi != 0.0:
                sg = 1.0 if vi > 0 else -1.0
                kA = s0 * eA * av * DT / g
                kB = s0 * eB * av * DT / g
                FA = sg * w * g + (FA - sg * w * g) * math.exp(-kA)
                FB = sg * (1.0 - w) * g + (FB - sg * (1.0 - w) * g) * math.exp(-kB)
            Fz = FA + FB
        elif shape in ("deadzone_hard", "deadzone_hertz", "soft_stage"):
            delta = amp
            if slack:
                gap += vi * DT
                if abs(gap) >= delta:
                    slack = False
                    s_eng = 0.0
                rho = 0.0 if shape != "soft_stage" else p["kappa"]
            if not slack:
                if shape == "deadzone_hertz" and s_eng is not None:
                    s_eng += av * DT
                    lam = p["lam_ratio"] * delta
                    rho = min(1.0, math.sqrt(s_eng / lam)) if lam > 0 else 1.0
                    if rho >= 1.0:
                        s_eng = None
                else:
                    rho = 1.0
            if vi != 0.0 and rho > 0.0:
                zs = g if vi > 0 else -g
                Fn = zs + (Fz - zs) * math.exp(-rho * s0 * av * DT / g)
            else:
                Fn = Fz
            if (not slack) and delta > 0 and Fz != 0.0 and (Fn > 0) != (Fz > 0) and Fn != 0.0:
                # unloading crossed zero: the band goes slack
                slack = True
                gap = 0.0
                Fn = 0.0 if shape != "soft_stage" else Fn
                s_eng = None
            Fz = Fn
            rho_out = 0.0 if (slack and shape != "soft_stage") else rho
            if slack and shape == "soft_stage":
                rho_out = p["kappa"]
        elif shape == "elastoplastic":
            if vi != 0.0:
                zss = g
                az = abs(Fz)
                if (Fz >= 0) == (vi > 0):
                    zba = p["phi"] * zss
                    if az <= zba:
                        aep = 0.0
                    elif az >= zss:
                        aep = 1.0
                    else:
                        aep = 0.5 * math.sin(math.pi * (az - 0.5 * (zss + zba)) / (zss - zba)) + 0.5
                else:
                    aep = 0.0
                al = 1.0 - amp * (1.0 - aep)
                if al > 1e-12:
                    zs = (g if vi > 0 else -g) / al
                    Fz = zs + (Fz - zs) * math.exp(-al * s0 * av * DT / g)
                else:
                    Fz = Fz + s0 * vi * DT
        else:
            if vi != 0.0:
                zs = g if vi > 0 else -g
                Fz = zs + (Fz - zs) * math.exp(-s0d * av * DT / g)
        # ---- held-force evolution at rest
        if tr is not None:
            t = tr[i]
            if t is None:
                Fon = None
            else:
                if Fon is None:
                    Fon = Fz
                else:
                    if shape == "sls_relax":
                        tau = p["tau_s"]
                        r1 = (1 - amp) + amp * math.exp(-t / tau)
                        r0 = (1 - amp) + amp * math.exp(-(t - DT) / tau)
                    elif shape == "log_relax":
                        tau = p["tau_s"]
                        r1 = max(0.0, 1 - amp * math.log(1 + t / tau))
                        r0 = max(0.0, 1 - amp * math.log(1 + (t - DT) / tau))
                    else:
                        r1 = 1 + amp * (t / p["t0_s"]) ** p["n"]
                        r0 = 1 + amp * ((t - DT) / p["t0_s"]) ** p["n"]
                    Fz += Fon * (r1 - r0)
        F = Fz + rho_out * (s2f if fwd else s2b) * vi
        out[i] = F
        Fprev = F
    return out
