"""blind36 -- base model (black-box replica) and the 24 hidden-effect shapes.

Python 3 standard library only.  Units: kip, in, s.  Sampling 1024 Hz.

The base model is the semi-active LuGre model of the paper (Eqs. 1-5) with the parameters of
configs/brfd-semiactive.yaml, computed the way `hybridsim damper predict --no-fit` computes it
(inferred by black-box comparison, see NOTES.md):
  * drum velocity v_i: central differences of the displacement column (one-sided at the two ends),
    then a centred 15-sample moving average whose window is clipped to the record at its ends;
  * x'_1, x'_2 = actuator positions of the first row; Fc from Eq. 4 with the sign of v_i
    (v >= 0 forward), floored at 0.05 kip; g from Eq. 5;
  * initial state sigma0*z_0 = measured force of the first row;
  * step i-1 -> i: z is advanced over dt with v_i, g_i held constant, solved exactly
    (z_ss + (z - z_ss) exp(-sigma0 |v_i| dt / g_i)); output F_i = sigma0 z_i + sigma2 v_i (sigma1 = 0).
Everything below is written for the elastic force E = sigma0 z.
"""
import math

FS = 1024
DT = 1.0 / FS

# ---- base parameters (configs/brfd-semiactive.yaml) ----
SIG0 = 15.36
SIG1 = 0.0
SIG2 = 0.500
FS_F = 7.116
FS_B = 3.760
FC_F = 2.648
FC_B = 1.253
VS = 1.300
SLOPES = [-0.14, -0.15, -15.29, -13.00, -16.66, -15.77, -0.13, -0.15]
SCAL = [119.68, 2.10, 1.94, 123.31]
FC_FLOOR = 0.05
KF1 = SCAL[0] * SLOPES[0] + SCAL[1] * SLOPES[2]
KF2 = SCAL[0] * SLOPES[1] + SCAL[1] * SLOPES[3]
KB1 = SCAL[2] * SLOPES[4] + SCAL[3] * SLOPES[6]
KB2 = SCAL[2] * SLOPES[5] + SCAL[3] * SLOPES[7]
VEL_HALF = 7            # 15-sample centred moving average
REST_V = 0.06           # in/s: |v| below this counts as "drum at rest" (noise at rest < 0.035)

exp = math.exp
log = math.log


# ----------------------------------------------------------------------------------------------
# black-box replica
# ----------------------------------------------------------------------------------------------
def derive_velocity(x):
    n = len(x)
    d = [0.0] * n
    d[0] = (x[1] - x[0]) / DT
    d[n - 1] = (x[n - 1] - x[n - 2]) / DT
    for i in range(1, n - 1):
        d[i] = (x[i + 1] - x[i - 1]) / (2 * DT)
    cs = [0.0] * (n + 1)
    s = 0.0
    for i in range(n):
        s += d[i]
        cs[i + 1] = s
    v = [0.0] * n
    h = VEL_HALF
    for i in range(n):
        a = i - h if i - h > 0 else 0
        b = i + h + 1 if i + h + 1 < n else n
        v[i] = (cs[b] - cs[a]) / (b - a)
    return v


def eq4_deltas(a1, a2, x1p, x2p):
    """linear actuator contributions of Eq. 4 (kip), forward and backward."""
    df = [KF1 * (p - x1p) + KF2 * (q - x2p) for p, q in zip(a1, a2)]
    db = [KB1 * (p - x1p) + KB2 * (q - x2p) for p, q in zip(a1, a2)]
    return df, db


def fc_arrays(df, db, law=None):
    if law is None:
        fcf = [FC_F + d if FC_F + d > FC_FLOOR else FC_FLOOR for d in df]
        fcb = [FC_B + d if FC_B + d > FC_FLOOR else FC_FLOOR for d in db]
    else:
        fcf = [max(FC_FLOOR, FC_F + law(d)) for d in df]
        fcb = [max(FC_FLOOR, FC_B + law(d)) for d in db]
    return fcf, fcb


def g_array(v, fcf, fcb, vs_f=VS, vs_b=VS):
    g = [0.0] * len(v)
    for i, vi in enumerate(v):
        if vi >= 0:
            fc = fcf[i]
            r = vi / vs_f
            g[i] = fc + (FS_F - fc) * exp(-r * r)
        else:
            fc = fcb[i]
            r = vi / vs_b
            g[i] = fc + (FS_B - fc) * exp(-r * r)
    return g


def lugre(v, g, E0, sig_f=SIG0, sig_b=SIG0):
    """base LuGre in elastic-force form; sig_f/sig_b allow a direction-dependent stiffness."""
    n = len(v)
    out = [0.0] * n
    E = E0
    out[0] = E0 + SIG2 * v[0]
    for i in range(1, n):
        vi = v[i]
        if vi > 0:
            gi = g[i]
            E = gi + (E - gi) * exp(-sig_f * vi * DT / gi)
        elif vi < 0:
            gi = g[i]
            E = -gi + (E + gi) * exp(sig_b * vi * DT / gi)
        out[i] = E + SIG2 * vi
    return out


class Rec:
    """one record as the black box sees it (recorded columns) plus cached derived arrays."""

    def __init__(self, x, a1, a2, E0):
        self.x = x
        self.a1 = a1
        self.a2 = a2
        self.x1p = a1[0]
        self.x2p = a2[0]
        self.E0 = E0
        self.n = len(x)
        self.v = derive_velocity(x)
        self.df, self.db = eq4_deltas(a1, a2, self.x1p, self.x2p)
        self.fcf, self.fcb = fc_arrays(self.df, self.db)
        self.g = g_array(self.v, self.fcf, self.fcb)
        self._X = None
        self._trav = None

    def base(self):
        return lugre(self.v, self.g, self.E0)

    @property
    def X(self):
        """displacement re-integrated from the derived velocity (smooth, no sensor noise)."""
        if self._X is None:
            X = [0.0] * self.n
            s = self.x[0]
            X[0] = s
            for i in range(1, self.n):
                s += self.v[i] * DT
                X[i] = s
            self._X = X
        return self._X

    @property
    def travel(self):
        """travel since the last drum reversal (reversal = retreat of 0.005 in from the extreme)."""
        if self._trav is None:
            X = self.X
            h = 0.005
            out = [0.0] * self.n
            d = 0
            ext = X[0]
            rev = X[0]
            for i in range(self.n):
                xi = X[i]
                if d == 0:
                    if xi > X[0] + h:
                        d = 1
                        ext = xi
                    elif xi < X[0] - h:
                        d = -1
                        ext = xi
                elif d == 1:
                    if xi > ext:
                        ext = xi
                    elif xi < ext - h:
                        d = -1
                        rev = ext
                        ext = xi
                else:
                    if xi < ext:
                        ext = xi
                    elif xi > ext + h:
                        d = 1
                        rev = ext
                        ext = xi
                out[i] = abs(xi - rev)
            self._trav = out
        return self._trav


# ----------------------------------------------------------------------------------------------
# shapes.  Each: f(p, rec, fx) -> F_true list.  p = strength parameter (p = 0 gives the base model
# exactly), fx = fixed per-trial parameters.
# ----------------------------------------------------------------------------------------------

# ---------------- backlash ----------------
def _deadzone_core(p_delta, R, snap=None):
    """LuGre acting on a band coordinate u with a slack dead zone of half-width delta:
    E = sigma0 * D(u), D(u) = sign(u) max(|u| - delta, 0);  du/dt = v - sigma0 |v| D(u) / g.
    snap = (K, tau_d, f_r): at each exit from the dead zone (band snaps taut at speed v) a damped
    ring  s K |v| exp(-t/tau_d) sin(2 pi f_r t)  is added to the force."""
    v, g = R.v, R.g
    n = R.n
    dl = p_delta
    E0 = R.E0
    if E0 > 0:
        u = E0 / SIG0 + dl
    elif E0 < 0:
        u = E0 / SIG0 - dl
    else:
        u = 0.0
    out = [0.0] * n
    out[0] = E0 + SIG2 * v[0]
    events = []
    for i in range(1, n):
        vi = v[i]
        if vi != 0.0:
            gi = g[i]
            a = SIG0 * abs(vi) / gi
            s = 1.0 if vi > 0 else -1.0
            wss = s * gi / SIG0
            rem = DT
            for _ in range(4):
                if u > dl or u < -dl:
                    sg = 1.0 if u > 0 else -1.0
                    w = u - sg * dl
                    if s == sg:  # loading: never re-enters the zone
                        u = sg * dl + wss + (w - wss) * exp(-a * rem)
                        break
                    r = wss / (wss - w)
                    tc = -log(r) / a if r > 0 else 0.0
                    if tc >= rem:
                        u = sg * dl + wss + (w - wss) * exp(-a * rem)
                        break
                    u = sg * dl
                    rem -= tc
                    # now inside the zone, moving inward (falls through to zone branch)
                    te = 2 * dl / abs(vi)
                    if te >= rem:
                        u += vi * rem
                        break
                    rem -= te
                    u = s * dl + wss * (1.0 - exp(-a * rem))
                    if snap is not None and dl > 0:
                        events.append((i * DT - rem, abs(vi), s))
                    break
                else:
                    te = (s * dl - u) / vi
                    if te >= rem:
                        u += vi * rem
                        break
                    rem -= te
                    u = s * dl + wss * (1.0 - exp(-a * rem))
                    if snap is not None and dl > 0 and te > 0:
                        events.append((i * DT - rem, abs(vi), s))
                    break
        if u > dl:
            E = SIG0 * (u - dl)
        elif u < -dl:
            E = SIG0 * (u + dl)
        else:
            E = 0.0
        out[i] = E + SIG2 * vi
    if snap is not None and events:
        K, tau_d, f_r = snap
        w_r = 2 * math.pi * f_r
        L = int(6 * tau_d * FS) + 2
        for (t0, sp, s) in events:
            i0 = int(t0 * FS) + 1
            amp = s * K * sp
            for i in range(i0, min(n, i0 + L)):
                t = i * DT - t0
                out[i] += amp * exp(-t / tau_d) * math.sin(w_r * t)
    return out


def sh_slack_deadzone(p, R, fx):
    return _deadzone_core(p, R)


def sh_slack_snap(p, R, fx):
    return _deadzone_core(fx['delta_per_p'] * p, R,
                          snap=(fx['K_per_p'] * p, fx['tau_d'], fx['f_ring']))


def sh_sag_softened(p, R, fx):
    """Ernst sag-softened band stiffness: dE/dt = sigma0 kappa(E) (v - |v| E / g),
    kappa(E) = 1 / (1 + (E* / (|E| + E_p))^3)."""
    v, g = R.v, R.g
    n = R.n
    Es = p
    Ep = fx['E_p']
    out = [0.0] * n
    E = R.E0
    out[0] = E + SIG2 * v[0]
    h = DT
    for i in range(1, n):
        vi = v[i]
        if vi != 0.0 and Es > 0:
            gi = g[i]
            av = abs(vi)

            def f(e):
                q = Es / (abs(e) + Ep)
                return SIG0 * (vi - av * e / gi) / (1.0 + q * q * q)
            k1 = f(E)
            k2 = f(E + 0.5 * h * k1)
            k3 = f(E + 0.5 * h * k2)
            k4 = f(E + h * k3)
            E += h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        elif vi != 0.0:
            gi = g[i]
            ss = gi if vi > 0 else -gi
            E = ss + (E - ss) * exp(-SIG0 * abs(vi) * DT / gi)
        out[i] = E + SIG2 * vi
    return out


# ---------------- residual_static ----------------
def _rest_core(R, mode, p, fx):
    v, g = R.v, R.g
    n = R.n
    out = [0.0] * n
    E = R.E0
    out[0] = E + SIG2 * v[0]
    resting = True
    t_r = 0.0
    E_start = E
    tau = fx.get('tau', 1.0)
    t_c = fx.get('t_c', 0.1)
    Fb = fx.get('F_bias', 0.0)
    decay = exp(-DT / tau)
    prev_f = 1.0
    Rd = 0.0
    for i in range(1, n):
        vi = v[i]
        if vi > 0:
            gi = g[i]
            E = gi + (E - gi) * exp(-SIG0 * vi * DT / gi)
        elif vi < 0:
            gi = g[i]
            E = -gi + (E + gi) * exp(SIG0 * vi * DT / gi)
        if abs(vi) < REST_V:
            if not resting:
                resting = True
                t_r = 0.0
                E_start = E
                prev_f = 1.0
                Rd = 0.0
            t_r += DT
            if mode == 'prony':
                # relaxed deficit Rd(t) -> p E_start with time constant tau (Rd = 0 at rest start)
                dR = (p * E_start - Rd) * (1.0 - decay)
                Rd += dR
                E -= dR
            elif mode == 'log':
                f = 1.0 - p * log(1.0 + t_r / t_c)
                if f < 0.0:
                    f = 0.0
                E = E * f / prev_f if prev_f > 0 else 0.0
                prev_f = f
            else:  # settle toward a bias level
                E = Fb + (E - Fb) * exp(-p * DT)
        else:
            resting = False
        out[i] = E + SIG2 * vi
    return out


def sh_prony_relaxation(p, R, fx):
    return _rest_core(R, 'prony', p, fx)


def sh_log_creep(p, R, fx):
    return _rest_core(R, 'log', p, fx)


def sh_settle_to_bias(p, R, fx):
    return _rest_core(R, 'settle', p, fx)


# ---------------- transition_shape ----------------
def sh_elastoplastic_blend(p, R, fx):
    """F = (1-w) E_lugre + w E_ep + sigma2 v.  E_ep: Dupont et al. (2002) elastoplastic model,
    dE/dt = sigma0 (v - alpha(E, v) |v| E / g); alpha = 0 when unloading or |E| <= b_a g,
    sinusoidal from 0 to 1 between b_a g and g, 1 beyond."""
    v, g = R.v, R.g
    n = R.n
    w = p
    ba = fx['breakaway_frac']
    base = lugre(v, g, R.E0)
    out = [0.0] * n
    Ee = R.E0
    out[0] = base[0]
    nsub = 4
    h = DT / nsub
    pi = math.pi
    for i in range(1, n):
        vi = v[i]
        if vi != 0.0:
            gi = g[i]
            av = abs(vi)
            eba = ba * gi
            for _ in range(nsub):
                if (Ee > 0) != (vi > 0) or abs(Ee) <= eba:
                    al = 0.0
                elif abs(Ee) >= gi:
                    al = 1.0
                else:
                    al = 0.5 * math.sin(pi * (abs(Ee) - 0.5 * (gi + eba)) / (gi - eba)) + 0.5
                if al == 0.0:
                    Ee += SIG0 * vi * h
                else:
                    a = al * SIG0 * av / gi
                    ss = vi / (al * av / gi) if al > 0 else 0.0
                    Ee = ss + (Ee - ss) * exp(-a * h)
        out[i] = (1 - w) * (base[i] - SIG2 * vi) + w * Ee + SIG2 * vi
    return out


def sh_iwan_masing_blend(p, R, fx):
    """F = (1-w) E_lugre + w E_iwan + sigma2 v.  E_iwan: Iwan (1966) parallel bank of N Jenkins
    elements (stiffness K/N each) with a uniform density of slip strengths phi_j g(t),
    phi_j = 2 j / (N (N+1)), sum phi_j = 1 (so the sliding level is g)."""
    v, g = R.v, R.g
    n = R.n
    w = p
    N = fx['N']
    K = fx['K_over_sigma0'] * SIG0
    ke = K / N
    phi = [2.0 * (j + 1) / (N * (N + 1)) for j in range(N)]
    base = lugre(v, g, R.E0)
    # initial state: virgin loading to E0 (g at t=0)
    g0 = g[0]
    E0 = R.E0
    sgn = 1.0 if E0 >= 0 else -1.0
    target = min(abs(E0), 0.999 * g0)
    lo, hi = 0.0, 10.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        F = sum(min(ke * mid, ph * g0) for ph in phi)
        if F < target:
            lo = mid
        else:
            hi = mid
    d = [sgn * min(lo, ph * g0 / ke) for ph in phi]
    out = [0.0] * n
    out[0] = base[0]
    for i in range(1, n):
        vi = v[i]
        gi = g[i]
        step = vi * DT
        tot = 0.0
        for j in range(N):
            lim = phi[j] * gi / ke
            dj = d[j] + step
            if dj > lim:
                dj = lim
            elif dj < -lim:
                dj = -lim
            d[j] = dj
            tot += dj
        Ei = ke * tot
        out[i] = (1 - w) * (base[i] - SIG2 * vi) + w * Ei + SIG2 * vi
    return out


def sh_dahl_exponent(p, R, fx):
    """Dahl (1968/1976) power-law generalisation of the bristle law:
    dE/dx = sigma0 sgn(1 - sE/g) |1 - sE/g|^alpha,  alpha = 1 - p  (alpha = 1 is the base LuGre).
    alpha < 1: softer start after a reversal (slope 2^alpha sigma0 instead of 2 sigma0) and the
    sliding level g is reached after a FINITE travel (no exponential tail); same sliding level.
    Solved exactly per step (v, g constant): (1-u)^(1-alpha) decreases linearly in a t."""
    v, g = R.v, R.g
    n = R.n
    al = 1.0 - p
    q = 1.0 - al
    out = [0.0] * n
    E = R.E0
    out[0] = E + SIG2 * v[0]
    for i in range(1, n):
        vi = v[i]
        if vi != 0.0:
            gi = g[i]
            s = 1.0 if vi > 0 else -1.0
            a = SIG0 * abs(vi) / gi
            u = s * E / gi
            if q <= 0.0:
                u = 1.0 + (u - 1.0) * exp(-a * DT)
            else:
                dlt = 1.0 - u
                if dlt != 0.0:
                    y = abs(dlt) ** q - q * a * DT
                    m = y ** (1.0 / q) if y > 0.0 else 0.0
                    u = 1.0 - m if dlt > 0 else 1.0 + m
            E = s * u * gi
        out[i] = E + SIG2 * vi
    return out


# ---------------- velocity ----------------
def _g_mod(R, fn):
    return [fn(gi, vi) for gi, vi in zip(R.g, R.v)]


def sh_rate_state_log(p, R, fx):
    """steady-state rate-and-state law: g' = g (1 + c ln((|v| + v0) / v_ref)), c = sign * p."""
    c = fx['sign'] * p
    v0 = fx['v0']
    vr = fx['v_ref']

    def fn(gi, vi):
        r = gi * (1.0 + c * log((abs(vi) + v0) / vr))
        return r if r > FC_FLOOR else FC_FLOOR
    return lugre(R.v, _g_mod(R, fn), R.E0)


def sh_grosch_bell(p, R, fx):
    """Grosch (1963) bell-shaped friction vs log speed: g' = g (1 + A exp(-(log10(|v|/v_p))^2 / (2 w^2)))."""
    A = p
    vp = fx['v_peak']
    w2 = 2.0 * fx['width_decades'] ** 2
    l10 = math.log(10.0)

    def fn(gi, vi):
        av = abs(vi)
        if av < 1e-9:
            return gi
        q = log(av / vp) / l10
        return gi * (1.0 + A * exp(-q * q / w2))
    return lugre(R.v, _g_mod(R, fn), R.E0)


def sh_power_law_thirdbody(p, R, fx):
    """shear-thinning third-body layer: g' = g + c |v|^n (n < 1)."""
    c = p
    ne = fx['n']
    return lugre(R.v, _g_mod(R, lambda gi, vi: gi + c * abs(vi) ** ne), R.E0)


# ---------------- actuator_lag ----------------
def _run_with_actuators(R, b1, b2):
    df, db = eq4_deltas(b1, b2, R.x1p, R.x2p)
    fcf, fcb = fc_arrays(df, db)
    return lugre(R.v, g_array(R.v, fcf, fcb), R.E0)


def sh_zener_partial_lag(p, R, fx):
    """standard-linear-solid (Zener) path from actuator travel to band clamping:
    x~ = alpha x + (1 - alpha) y,  tau dy/dt = x - y."""
    tau = p
    al = fx['alpha_instant']
    if tau <= 0:
        return R.base()
    k = exp(-DT / tau)
    res = []
    for a, x0 in ((R.a1, R.x1p), (R.a2, R.x2p)):
        y = 0.0
        o = [0.0] * R.n
        for i in range(R.n):
            xi = a[i] - x0
            y = xi + (y - xi) * k
            o[i] = x0 + al * xi + (1 - al) * y
        res.append(o)
    return _run_with_actuators(R, res[0], res[1])


def sh_second_order_resonant(p, R, fx):
    """underdamped band/actuator coupling: y'' + 2 zeta w y' + w^2 y = w^2 x, w = 2 pi / T_n,
    T_n = p; exact zero-order-hold discretisation."""
    Tn = p
    if Tn <= 0:
        return R.base()
    z = fx['zeta']
    w = 2 * math.pi / Tn
    wd = w * math.sqrt(1 - z * z)
    ex = exp(-z * w * DT)
    c = math.cos(wd * DT)
    s = math.sin(wd * DT)
    res = []
    for a, x0 in ((R.a1, R.x1p), (R.a2, R.x2p)):
        y = 0.0
        yd = 0.0
        o = [0.0] * R.n
        for i in range(R.n):
            xi = a[i] - x0
            e0 = y - xi
            e = ex * (e0 * c + (yd + z * w * e0) / wd * s)
            yd = ex * (yd * c - (w * w * e0 + z * w * yd) / wd * s)
            y = xi + e
            o[i] = x0 + y
        res.append(o)
    return _run_with_actuators(R, res[0], res[1])


def sh_leadscrew_play(p, R, fx):
    """lost motion (play operator, half-width eps) between actuator travel and band end."""
    eps = p
    res = []
    for a, x0 in ((R.a1, R.x1p), (R.a2, R.x2p)):
        y = 0.0
        o = [0.0] * R.n
        for i in range(R.n):
            xi = a[i] - x0
            if xi - y > eps:
                y = xi - eps
            elif y - xi > eps:
                y = xi + eps
            o[i] = x0 + y
        res.append(o)
    return _run_with_actuators(R, res[0], res[1])


# ---------------- self_energizing ----------------
def sh_capstan_wrap_growth(p, R, fx):
    """Euler-Eytelwein band brake whose tight-side wrap grows with drum rotation:
    g' = g (exp(mu theta0 + s beta x) - 1) / (exp(mu theta0) - 1), s = direction of sliding."""
    b = p
    mt = fx['mu_theta0']
    den = exp(mt) - 1.0
    x = R.x
    gm = [0.0] * R.n
    for i, (gi, vi) in enumerate(zip(R.g, R.v)):
        s = 1.0 if vi >= 0 else -1.0
        gm[i] = gi * (exp(mt + s * b * x[i]) - 1.0) / den
    return lugre(R.v, gm, R.E0)


def sh_servo_takeup_travel(p, R, fx):
    """servo (self-energizing) take-up that builds with travel since the last reversal:
    g' = g (1 + A (1 - exp(-s_rev / l)))."""
    A = p
    ell = fx['ell']
    tr = R.travel
    gm = [gi * (1.0 + A * (1.0 - exp(-t / ell))) for gi, t in zip(R.g, tr)]
    return lugre(R.v, gm, R.E0)


def sh_tension_feedback_lag(p, R, fx):
    """friction force fed back into the tight-band tension through a first-order lag:
    tau dy/dt = kappa E - y,  g' = g + max(0, s y)."""
    kap = p
    tau = fx['tau']
    k = exp(-DT / tau)
    v, g = R.v, R.g
    n = R.n
    out = [0.0] * n
    E = R.E0
    y = kap * E
    out[0] = E + SIG2 * v[0]
    for i in range(1, n):
        vi = v[i]
        if vi > 0:
            gi = g[i] + (y if y > 0 else 0.0)
            E = gi + (E - gi) * exp(-SIG0 * vi * DT / gi)
        elif vi < 0:
            gi = g[i] + (-y if y < 0 else 0.0)
            E = -gi + (E + gi) * exp(SIG0 * vi * DT / gi)
        t = kap * E
        y = t + (y - t) * k
        out[i] = E + SIG2 * vi
    return out


# ---------------- pretension ----------------
def _run_law(R, law):
    fcf, fcb = fc_arrays(R.df, R.db, law)
    return lugre(R.v, g_array(R.v, fcf, fcb), R.E0)


def sh_fung_exponential(p, R, fx):
    """exponential (Fung-type strain-stiffening) band law: dFc = (exp(beta D) - 1) / beta."""
    b = p
    if b <= 0:
        return R.base()
    return _run_law(R, lambda d: (exp(b * d) - 1.0) / b)


def sh_tanh_saturation(p, R, fx):
    """saturating clamping: dFc = D_s tanh(D / D_s), 1/D_s = p."""
    gm = p
    if gm <= 0:
        return R.base()
    return _run_law(R, lambda d: math.tanh(gm * d) / gm)


def sh_bilinear_tension_only(p, R, fx):
    """bilinear (kinked) law about the set point x': retraction (D > 0, band tightened) with slope
    (1 + p) times Eq. 4's, extension (D < 0, band slackened) with slope (1 - p) times Eq. 4's."""
    up = 1.0 + p
    dn = 1.0 - p
    return _run_law(R, lambda d: up * d if d >= 0 else dn * d)


# ---------------- asymmetry ----------------
def sh_one_side_stribeck(p, R, fx):
    """Stribeck velocity of one sliding direction only: v_s,dir = v_s exp(sign p)."""
    f = exp(fx['sign'] * p)
    if fx['direction'] == 'forward':
        g = g_array(R.v, R.fcf, R.fcb, vs_f=VS * f)
    else:
        g = g_array(R.v, R.fcf, R.fcb, vs_b=VS * f)
    return lugre(R.v, g, R.E0)


def sh_one_side_lining_periodic(p, R, fx):
    """friction-lining thickness/friction variation felt only by the band that is tight in one
    direction: g'_dir = g (1 + a cos(2 pi x / lambda + phi))."""
    a = p
    lam = fx['wavelength_in']
    ph = fx['phase_rad']
    fwd = fx['direction'] == 'forward'
    x = R.x
    k = 2 * math.pi / lam
    gm = list(R.g)
    for i, vi in enumerate(R.v):
        if (vi >= 0) == fwd:
            gm[i] = gm[i] * (1.0 + a * math.cos(k * x[i] + ph))
    return lugre(R.v, gm, R.E0)


def sh_one_side_presliding(p, R, fx):
    """pre-sliding (band) stiffness of one sliding direction only: sigma0,dir = sigma0 (1 - p)."""
    s = SIG0 * (1.0 - p)
    if fx['direction'] == 'forward':
        return lugre(R.v, R.g, R.E0, sig_f=s)
    return lugre(R.v, R.g, R.E0, sig_b=s)


SHAPES = {
    'backlash': {
        'slack_deadzone': (sh_slack_deadzone, 0.20),
        'sag_softened_reengagement': (sh_sag_softened, 2.5),
        'slack_snap_reengagement': (sh_slack_snap, 2.0),
    },
    'residual_static': {
        'prony_relaxation': (sh_prony_relaxation, 0.9),
        'log_creep': (sh_log_creep, 0.18),
        'settle_to_bias': (sh_settle_to_bias, 3.0),
    },
    'transition_shape': {
        'elastoplastic_blend': (sh_elastoplastic_blend, 1.0),
        'iwan_masing_blend': (sh_iwan_masing_blend, 1.0),
        'dahl_exponent': (sh_dahl_exponent, 0.8),
    },
    'velocity': {
        'rate_state_log': (sh_rate_state_log, 0.25),
        'grosch_bell': (sh_grosch_bell, 1.0),
        'power_law_thirdbody': (sh_power_law_thirdbody, 1.5),
    },
    'actuator_lag': {
        'zener_partial_lag': (sh_zener_partial_lag, 2.0),
        'second_order_resonant': (sh_second_order_resonant, 2.0),
        'leadscrew_play': (sh_leadscrew_play, 0.02),
    },
    'self_energizing': {
        'capstan_wrap_growth': (sh_capstan_wrap_growth, 0.6),
        'servo_takeup_travel': (sh_servo_takeup_travel, 1.2),
        'tension_feedback_lag': (sh_tension_feedback_lag, 0.6),
    },
    'pretension': {
        'fung_exponential': (sh_fung_exponential, 1.5),
        'tanh_saturation': (sh_tanh_saturation, 5.0),
        'bilinear_tension_only': (sh_bilinear_tension_only, 1.0),
    },
    'asymmetry': {
        'one_side_stribeck_velocity': (sh_one_side_stribeck, 1.6),
        'one_side_lining_periodic': (sh_one_side_lining_periodic, 0.75),
        'one_side_presliding_stiffness': (sh_one_side_presliding, 0.85),
    },
}


def simulate(category, shape, p, R, fx):
    if category == 'none':
        return R.base()
    fn = SHAPES[category][shape][0]
    return fn(p, R, fx)
