"""Base semi-active LuGre model of the BRFD and the 24 hidden-effect variants.

Units: kip, in, s.  Standard library only.

Base model (paper Eqs. 1-5, parameters of configs/brfd-semiactive.yaml), written so that it
reproduces `hybridsim damper predict --no-fit` sample for sample:

* drum velocity v: NOT the file's velocity column (that column is 1/125.4 of the true
  velocity, README quirk) but d(displacement)/dt by central differences (one-sided at the two
  ends) followed by a 15-sample zero-phase moving average whose window shrinks
  symmetrically at the ends;
* x'_1, x'_2: the actuator positions of the first row;
* Fc(x1, x2, v) from Eq. (4) with b = fc_fwd / fc_bwd, clipped below at fc_floor = 0.05 kip;
  forward parameters for v >= 0, backward for v < 0;
* g(v) = Fc + (Fs - Fc) exp(-(v/vs)^2)  (Eq. 5);
* state w = sigma0 * z (force units), initial w0 = measured force of row 0;
* step i-1 -> i with v[i], x1[i], x2[i] held over the step and the exact solution of the
  linear ODE  z' = v - sigma0 |v| z / g :  w_i = s g + (w_{i-1} - s g) exp(-sigma0 |v| dt / g),
  s = sign(v) (no change when v == 0);
* F_i = w_i + sigma1 z'_i + sigma2 v_i with sigma1 = 0.
"""
import math

DT = 1.0 / 1024.0

# configs/brfd-semiactive.yaml
P = dict(s0=15.36, s1=0.0, s2=0.5, fsf=7.116, fsb=3.760, fcf=2.648, fcb=1.253, vs=1.300,
         m=[-0.14, -0.15, -15.29, -13.00, -16.66, -15.77, -0.13, -0.15],
         C=[119.68, 2.10, 1.94, 123.31], floor=0.05)
m, C = P['m'], P['C']
# Eq. (4) coefficients (kip of Fc per in of actuator position)
KF1 = C[0] * m[0] + C[1] * m[2]
KF2 = C[0] * m[1] + C[1] * m[3]
KB1 = C[2] * m[4] + C[3] * m[6]
KB2 = C[2] * m[5] + C[3] * m[7]


def derived_velocity(x):
    """Central differences (one-sided at the ends) + 15-sample zero-phase moving average
    (window shrinks symmetrically at the ends), as `hybridsim damper predict` does."""
    n = len(x)
    d = [0.0] * n
    d[0] = (x[1] - x[0]) / DT
    d[n - 1] = (x[n - 1] - x[n - 2]) / DT
    for i in range(1, n - 1):
        d[i] = (x[i + 1] - x[i - 1]) / (2 * DT)
    # prefix sums for the moving average
    cs = [0.0] * (n + 1)
    acc = 0.0
    for i in range(n):
        acc += d[i]
        cs[i + 1] = acc
    v = [0.0] * n
    for i in range(n):
        k = min(7, i, n - 1 - i)
        v[i] = (cs[i + k + 1] - cs[i - k]) / (2 * k + 1)
    return v


class Rec:
    """Inputs of one record as written to the JSON file, with derived quantities."""

    def __init__(self, x, x1, x2, F0):
        self.n = len(x)
        self.x = x
        self.x1 = x1
        self.x2 = x2
        self.F0 = F0  # row-0 force as written (sets the initial bristle state)
        self.v = derived_velocity(x)
        self.x1p = x1[0]
        self.x2p = x2[0]
        vs = P['vs']
        self.E = [math.exp(-(vi / vs) ** 2) for vi in self.v]
        self.dLf = [KF1 * (a - self.x1p) + KF2 * (b - self.x2p) for a, b in zip(x1, x2)]
        self.dLb = [KB1 * (a - self.x1p) + KB2 * (b - self.x2p) for a, b in zip(x1, x2)]


def base_force(r):
    s0, s2, fl = P['s0'], P['s2'], P['floor']
    fsf, fsb, fcf, fcb = P['fsf'], P['fsb'], P['fcf'], P['fcb']
    v, E, dLf, dLb = r.v, r.E, r.dLf, r.dLb
    exp = math.exp
    w = r.F0
    F = [0.0] * r.n
    F[0] = w + s2 * v[0]
    for i in range(1, r.n):
        vi = v[i]
        if vi >= 0:
            fc = fcf + dLf[i]
            if fc < fl:
                fc = fl
            g = fc + (fsf - fc) * E[i]
            if vi > 0:
                w = g + (w - g) * exp(-s0 * vi * DT / g)
        else:
            fc = fcb + dLb[i]
            if fc < fl:
                fc = fl
            g = fc + (fsb - fc) * E[i]
            w = -g + (w + g) * exp(s0 * vi * DT / g)
        F[i] = w + s2 * vi
    return F


# ----------------------------------------------------------------------------------------
# Effects.  Every effect is a function (r, s, q) -> force list; s is the scalar strength
# (effect is exactly the base model at s = 0), q a dict of fixed shape constants.
# ----------------------------------------------------------------------------------------

def g_generic(r, i, vi, x1e=None, x2e=None, vsf=None, vsb=None, Ev=None):
    """g(v) with optional effective actuator positions / Stribeck velocities."""
    if x1e is None:
        dLf, dLb = r.dLf[i], r.dLb[i]
    else:
        dLf = KF1 * (x1e - r.x1p) + KF2 * (x2e - r.x2p)
        dLb = KB1 * (x1e - r.x1p) + KB2 * (x2e - r.x2p)
    if vi >= 0:
        fc = max(P['fcf'] + dLf, P['floor'])
        fs = P['fsf']
        E = r.E[i] if Ev is None else Ev
        if vsf is not None:
            E = math.exp(-(vi / vsf) ** 2)
    else:
        fc = max(P['fcb'] + dLb, P['floor'])
        fs = P['fsb']
        E = r.E[i] if Ev is None else Ev
        if vsb is not None:
            E = math.exp(-(vi / vsb) ** 2)
    return fc + (fs - fc) * E


def _fc_fs(r, i, vi):
    """(Fc, Fs) of the base at sample i."""
    if vi >= 0:
        fc = P['fcf'] + r.dLf[i]
        return (fc if fc > P['floor'] else P['floor']), P['fsf']
    fc = P['fcb'] + r.dLb[i]
    return (fc if fc > P['floor'] else P['floor']), P['fsb']


def _lugre_step(w, vi, g, s0=None):
    """Exact LuGre step in force units with g and v held over DT."""
    if s0 is None:
        s0 = P['s0']
    if vi > 0:
        return g + (w - g) * math.exp(-s0 * vi * DT / g)
    if vi < 0:
        return -g + (w + g) * math.exp(s0 * vi * DT / g)
    return w


def sim_g(r, gfun, extra_force=None, s0fun=None, post=None):
    """Generic simulator: LuGre in force units with a user g(i, vi, w) and optional extra
    output force term extra_force(i) and post-step state map post(i, vi, w) -> w."""
    s2 = P['s2']
    v = r.v
    w = r.F0
    F = [0.0] * r.n
    F[0] = w + s2 * v[0] + (extra_force(0) if extra_force else 0.0)
    for i in range(1, r.n):
        vi = v[i]
        g = gfun(i, vi, w)
        s0 = s0fun(vi) if s0fun else P['s0']
        w = _lugre_step(w, vi, g, s0)
        if post is not None:
            w = post(i, vi, w)
        F[i] = w + s2 * vi + (extra_force(i) if extra_force else 0.0)
    return F


# ---------------- actuator_lag ----------------

def eff_lag_first_order(r, s, q):
    """Band clamping follows the actuator positions through a first-order lag, tau = s (s)."""
    if s <= 0:
        return base_force(r)
    a = 1.0 - math.exp(-DT / s)
    st = {'x1': r.x1[0], 'x2': r.x2[0], 'i': 0}
    x1e = [r.x1[0]] * r.n
    x2e = [r.x2[0]] * r.n
    e1, e2 = r.x1[0], r.x2[0]
    for i in range(1, r.n):
        e1 += (r.x1[i] - e1) * a
        e2 += (r.x2[i] - e2) * a
        x1e[i] = e1
        x2e[i] = e2
    return sim_g(r, lambda i, vi, w: g_generic(r, i, vi, x1e[i], x2e[i]))


def eff_lag_dead_time(r, s, q):
    """Clamping acts with a pure transport delay T = s (s) behind the actuator positions."""
    if s <= 0:
        return base_force(r)
    k = s / DT
    x1e = [0.0] * r.n
    x2e = [0.0] * r.n
    for i in range(r.n):
        t = i - k
        if t <= 0:
            x1e[i], x2e[i] = r.x1[0], r.x2[0]
        else:
            j = int(t)
            f = t - j
            j2 = min(j + 1, r.n - 1)
            x1e[i] = r.x1[j] + (r.x1[j2] - r.x1[j]) * f
            x2e[i] = r.x2[j] + (r.x2[j2] - r.x2[j]) * f
    return sim_g(r, lambda i, vi, w: g_generic(r, i, vi, x1e[i], x2e[i]))


def eff_lag_second_order(r, s, q):
    """Band tension follows the actuators as an under-damped 2nd-order system
    (omega_n = 1/s, zeta = q['zeta'])."""
    if s <= 0:
        return base_force(r)
    wn = 1.0 / s
    z = q.get('zeta', 0.5)
    nsub = max(2, int(math.ceil(wn * DT / 0.05)))
    h = DT / nsub
    out = []
    for xs in (r.x1, r.x2):
        e, ed = xs[0], 0.0
        arr = [xs[0]] * r.n
        for i in range(1, r.n):
            u = xs[i]
            for _ in range(nsub):
                def f(e_, ed_):
                    return ed_, wn * wn * (u - e_) - 2 * z * wn * ed_
                k1 = f(e, ed)
                k2 = f(e + h / 2 * k1[0], ed + h / 2 * k1[1])
                k3 = f(e + h / 2 * k2[0], ed + h / 2 * k2[1])
                k4 = f(e + h * k3[0], ed + h * k3[1])
                e += h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
                ed += h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
            arr[i] = e
        out.append(arr)
    x1e, x2e = out
    return sim_g(r, lambda i, vi, w: g_generic(r, i, vi, x1e[i], x2e[i]))


# ---------------- asymmetry ----------------

def eff_asym_stiffness(r, s, q):
    """The band taut in backward rotation is softer: sigma0_bwd = sigma0 / (1 + s)."""
    s0 = P['s0']
    s0b = s0 / (1.0 + s)
    return sim_g(r, lambda i, vi, w: g_generic(r, i, vi), s0fun=lambda vi: s0 if vi >= 0 else s0b)


def eff_asym_viscous(r, s, q):
    """Extra viscous friction only in backward rotation: F += s * v for v < 0 (kip s/in)."""
    F = base_force(r)
    v = r.v
    return [f + (s * vi if vi < 0 else 0.0) for f, vi in zip(F, v)]


def eff_asym_stribeck(r, s, q):
    """Stribeck velocity of the backward-taut band differs: vs_bwd = vs * (1 + s)."""
    vsb = P['vs'] * (1.0 + s)
    return sim_g(r, lambda i, vi, w: g_generic(r, i, vi, vsb=vsb))


# ---------------- backlash ----------------

def _deadzone_sim(r, delta_fun):
    """LuGre with a dead zone (play) of half-width delta in the band deflection:
    F = sigma0 * dz(zeta) + sigma2 v min(1, |dz|/delta), dz = sign * max(|zeta| - delta, 0),
    zeta' = v - sigma0 |v| dz(zeta) / g.   Piecewise-exact integration.
    delta_fun(i, vi, F_now, delta_old) -> delta (may change only at reversals)."""
    s0, s2 = P['s0'], P['s2']
    v = r.v
    F = [0.0] * r.n
    delta = delta_fun(0, 0.0, r.F0, None)
    F0 = r.F0
    zeta = (F0 / s0 + (delta if F0 > 0 else -delta)) if F0 != 0 else 0.0
    F[0] = F0 + s2 * v[0]
    for i in range(1, r.n):
        vi = v[i]
        # force before step
        if zeta > delta:
            fnow = s0 * (zeta - delta)
        elif zeta < -delta:
            fnow = s0 * (zeta + delta)
        else:
            fnow = 0.0
        dnew = delta_fun(i, vi, fnow, delta)
        if dnew != delta:
            # keep the transmitted force continuous
            if zeta > delta:
                zeta = zeta - delta + dnew
            elif zeta < -delta:
                zeta = zeta + delta - dnew
            else:
                zeta = zeta * (dnew / delta) if delta > 0 else 0.0
            delta = dnew
        if vi != 0.0:
            g = g_generic(r, i, vi)
            k = s0 * abs(vi) / g
            sv = 1.0 if vi > 0 else -1.0
            tleft = DT
            for _ in range(6):
                if tleft <= 0:
                    break
                if -delta <= zeta <= delta:
                    # free travel in the gap
                    edge = delta if vi > 0 else -delta
                    tt = (edge - zeta) / vi
                    if tt >= tleft:
                        zeta += vi * tleft
                        tleft = 0
                    else:
                        zeta = edge + 1e-15 * sv
                        tleft -= tt
                else:
                    side = 1.0 if zeta > 0 else -1.0
                    y = zeta - side * delta
                    yss = sv * g / s0
                    ynew = yss + (y - yss) * math.exp(-k * tleft)
                    if ynew * side >= 0:
                        zeta = ynew + side * delta
                        tleft = 0
                    else:
                        # reaches the gap edge (y = 0) inside the step
                        tt = math.log((y - yss) / (0 - yss)) / k
                        zeta = side * delta - 1e-15 * side
                        tleft -= tt
        if zeta > delta:
            dz = zeta - delta
        elif zeta < -delta:
            dz = zeta + delta
        else:
            dz = 0.0
        # a slack band carries no friction at all: the viscous part fades in with the
        # band deflection over one gap half-width (e = 1 whenever delta = 0)
        e = min(1.0, abs(dz) / delta) if delta > 0 else 1.0
        F[i] = s0 * dz + s2 * vi * e
    return F


def eff_backlash_deadzone(r, s, q):
    """Fixed play: after a reversal the band transmits no force over a travel 2*s (in)."""
    return _deadzone_sim(r, lambda i, vi, f, d: s)


def eff_backlash_loaddep(r, s, q):
    """Load-dependent play: at each reversal the gap half-width becomes s * |F| (in/kip),
    F = band force when the drum reverses (released band stretch becomes slack)."""
    vth = q.get('vrev', 0.05)
    st = {'sgn': 0}

    def dfun(i, vi, f, d):
        if d is None:
            return s * abs(f)
        if abs(vi) > vth:
            sg = 1 if vi > 0 else -1
            if st['sgn'] != 0 and sg != st['sgn']:
                st['sgn'] = sg
                return s * abs(f)
            st['sgn'] = sg
        return d
    return _deadzone_sim(r, dfun)


def eff_backlash_smooth(r, s, q):
    """Gradual take-up: F = sigma0 phi(zeta) + sigma2 v min(1, |phi|/s),
    phi = zeta - s*tanh(zeta/s) (s in in):
    near-zero band stiffness right after a reversal, stiffening to sigma0 once the slack
    (about s on each side) is taken up."""
    if s <= 0:
        return base_force(r)
    s0, s2 = P['s0'], P['s2']
    v = r.v
    tanh = math.tanh

    def phi(zz):
        return zz - s * tanh(zz / s)
    # invert phi for the initial state
    target = r.F0 / s0
    zeta = target + (s if target > 0 else -s) if target != 0 else 0.0
    for _ in range(60):
        t = tanh(zeta / s)
        fz = zeta - s * t - target
        dfz = t * t  # 1 - (1 - t^2)
        if dfz < 1e-12:
            zeta += 1e-6
            continue
        zeta -= fz / dfz
    F = [0.0] * r.n
    F[0] = r.F0 + s2 * v[0]
    nsub = 4
    h = DT / nsub
    for i in range(1, r.n):
        vi = v[i]
        if vi != 0.0:
            g = g_generic(r, i, vi)
            k = s0 * abs(vi) / g
            for _ in range(nsub):
                k1 = vi - k * phi(zeta)
                k2 = vi - k * phi(zeta + h / 2 * k1)
                k3 = vi - k * phi(zeta + h / 2 * k2)
                k4 = vi - k * phi(zeta + h * k3)
                zeta += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        ph = phi(zeta)
        F[i] = s0 * ph + s2 * vi * min(1.0, abs(ph) / s)
    return F


# ---------------- pretension ----------------

def eff_pret_hardening(r, s, q):
    """Nonlinear (hardening) clamping map: band tension grows faster than linearly with the
    actuator stroke (band / lining stiffening), so the friction change is convex in the
    Eq. (4) increment dL:  Fc = b + dL + s dL^2 / F_ref  (F_ref = 2 kip), then the floor."""
    fl = P['floor']
    fref = q.get('F_ref', 2.0)

    def g(i, vi, w):
        if vi >= 0:
            b, dL, fs = P['fcf'], r.dLf[i], P['fsf']
        else:
            b, dL, fs = P['fcb'], r.dLb[i], P['fsb']
        fc = b + dL + s * dL * dL / fref
        if fc < fl:
            fc = fl
        return fc + (fs - fc) * r.E[i]
    return sim_g(r, g)


def eff_pret_static_tracks(r, s, q):
    """Static friction tracks the clamping (Amontons: both levels scale with band normal
    force): Fs_eff = Fs * (1 + s * (Fc - b) / b), with Fc from Eq. (4)."""
    def g(i, vi, w):
        fc, fs = _fc_fs(r, i, vi)
        b = P['fcf'] if vi >= 0 else P['fcb']
        fse = fs * (1.0 + s * (fc - b) / b)
        if fse < fc:
            fse = fc
        return fc + (fse - fc) * r.E[i]
    return sim_g(r, g)


def eff_pret_drift(r, s, q):
    """Pre-tension lost with accumulated slip (band creep / lining bedding-in / heating):
    whole friction level scaled by 1 - s*(1 - exp(-S/S0)), S = int |v| dt (in)."""
    S0 = q.get('S0', 15.0)
    v = r.v
    lam = [1.0] * r.n
    S = 0.0
    for i in range(1, r.n):
        S += abs(v[i]) * DT
        lam[i] = 1.0 - s * (1.0 - math.exp(-S / S0))
    return sim_g(r, lambda i, vi, w: lam[i] * g_generic(r, i, vi))


# ---------------- residual_static ----------------

def eff_rest_relax_zero(r, s, q):
    """At rest the held band force relaxes to zero (Maxwell stress relaxation of the lining):
    w' = -s * w * exp(-(v/vr)^2), s = 1/tau (1/s)."""
    vr = q.get('vr', 0.03)

    def post(i, vi, w):
        return w * math.exp(-s * math.exp(-(vi / vr) ** 2) * DT)
    return sim_g(r, lambda i, vi, w: g_generic(r, i, vi), post=post)


def eff_rest_toward_residual(r, s, q):
    """At rest the band force moves toward a residual level R (band tension equalising
    toward the pre-tension imbalance): w' = -s (w - R) exp(-(v/vr)^2)."""
    vr = q.get('vr', 0.03)
    R = q['R']

    def post(i, vi, w):
        a = math.exp(-s * math.exp(-(vi / vr) ** 2) * DT)
        return R + (w - R) * a
    return sim_g(r, lambda i, vi, w: g_generic(r, i, vi), post=post)


def eff_rest_powerlaw(r, s, q):
    """Logarithmic / power-law creep of the held force: during a rest of duration t_r
    (|v| < vr) w' = -s w / (t_r + t0), i.e. w = w_stop (t0/(t0+t_r))^s."""
    vr = q.get('vr', 0.03)
    t0 = q.get('t0', 0.05)
    st = {'tr': 0.0}

    def post(i, vi, w):
        if abs(vi) < vr:
            tr = st['tr']
            st['tr'] = tr + DT
            return w * ((t0 + tr) / (t0 + tr + DT)) ** s
        st['tr'] = 0.0
        return w
    return sim_g(r, lambda i, vi, w: g_generic(r, i, vi), post=post)


# ---------------- self_energizing ----------------

def eff_se_capstan(r, s, q):
    """Band wrap grows as the drum rotates away from neutral in the loading direction
    (capstan e^{mu theta}): g *= exp(s * max(0, x sign(v))), s in 1/in."""
    x = r.x

    def g(i, vi, w):
        u = x[i] if vi >= 0 else -x[i]
        return g_generic(r, i, vi) * (math.exp(s * u) if u > 0 else 1.0)
    return sim_g(r, g)


def eff_se_spring(r, s, q):
    """Elastic energy stored in the bands as the drum rotates and returned as it comes
    back (paper's description of self-energizing): F += s * x (kip/in)."""
    x = r.x
    return sim_g(r, lambda i, vi, w: g_generic(r, i, vi), extra_force=lambda i: s * x[i])


def eff_se_servo(r, s, q):
    """Self-servo: the band force itself adds clamping, g_eff = g + s * |F_band|."""
    return sim_g(r, lambda i, vi, w: g_generic(r, i, vi) + s * abs(w))


# ---------------- transition_shape ----------------

def eff_ts_dahl(r, s, q):
    """Dahl-type exponent n = 1 + s: w' = sigma0 v |1 - r|^n sign(1 - r), r = sign(v) w / g
    (n = 1 is LuGre).  Exact integration for v, g held."""
    n_ = 1.0 + s
    if s == 0:
        return base_force(r)
    s0, s2 = P['s0'], P['s2']
    v = r.v
    w = r.F0
    F = [0.0] * r.n
    F[0] = w + s2 * v[0]
    for i in range(1, r.n):
        vi = v[i]
        if vi != 0.0:
            g = g_generic(r, i, vi)
            sv = 1.0 if vi > 0 else -1.0
            u = 1.0 - sv * w / g
            k = s0 * abs(vi) / g
            au = abs(u)
            if au > 0:
                au = (au ** (1 - n_) + (n_ - 1) * k * DT) ** (-1.0 / (n_ - 1))
                u = au if u > 0 else -au
            w = sv * g * (1.0 - u)
        F[i] = w + s2 * vi
    return F


def eff_ts_elastoplastic(r, s, q):
    """Elasto-plastic pre-sliding (Dupont et al. 2002 type, hard breakaway): while loading,
    the band deflects purely elastically (w' = sigma0 v) until |w| = s*g, then LuGre.
    0 <= s < 1."""
    s0, s2 = P['s0'], P['s2']
    v = r.v
    w = r.F0
    F = [0.0] * r.n
    F[0] = w + s2 * v[0]
    for i in range(1, r.n):
        vi = v[i]
        if vi != 0.0:
            g = g_generic(r, i, vi)
            sv = 1.0 if vi > 0 else -1.0
            k = s0 * abs(vi) / g
            tleft = DT
            rr = sv * w / g
            if 0.0 <= rr < s:
                # elastic part
                tt = (s * g - sv * w) / (s0 * abs(vi))
                if tt >= tleft:
                    w += s0 * vi * tleft
                    tleft = 0.0
                else:
                    w = sv * s * g
                    tleft -= tt
            if tleft > 0:
                wn = sv * g + (w - sv * g) * math.exp(-k * tleft)
                # LuGre unloading/loading; if it crosses into the elastic band (0 <= r < s)
                # from below (unloading side), switch
                rn = sv * wn / g
                if rr < 0 and rn >= 0 and s > 0:
                    # time to reach r = 0 under LuGre
                    tt = math.log((w - sv * g) / (0 - sv * g)) / k
                    w = 0.0
                    rem = tleft - tt
                    t_el = s * g / (s0 * abs(vi))
                    if t_el >= rem:
                        w = s0 * vi * rem
                    else:
                        w = sv * s * g
                        rem -= t_el
                        w = sv * g + (w - sv * g) * math.exp(-k * rem)
                else:
                    w = wn
        F[i] = w + s2 * vi
    return F


def eff_ts_maxwell(r, s, q):
    """Maxwell-slip (GMS-like) pre-sliding: a fraction s of the contact is N parallel
    elasto-slide (LuGre) elements with stiffness sigma0*k_j and capacity g/N (sum k_j/N = 1):
    same initial stiffness and same sliding level, but a gradual, multi-stage transition.
    F = (1-s) F_LuGre + s sum_j F_j."""
    ks = q.get('k', [2.8, 0.7, 0.3, 0.2])
    N = len(ks)
    s0, s2 = P['s0'], P['s2']
    v = r.v
    wb = r.F0
    wj = [r.F0 / N] * N
    F = [0.0] * r.n
    F[0] = r.F0 + s2 * v[0]
    for i in range(1, r.n):
        vi = v[i]
        if vi != 0.0:
            g = g_generic(r, i, vi)
            wb = _lugre_step(wb, vi, g)
            gj = g / N
            for j in range(N):
                wj[j] = _lugre_step(wj[j], vi, gj, s0 * ks[j] / N)
        F[i] = (1 - s) * wb + s * sum(wj) + s2 * vi
    return F


# ---------------- velocity ----------------

def eff_vel_exponent(r, s, q):
    """Stribeck shape exponent delta = 2 exp(-s): exp(-|v/vs|^delta) instead of
    exp(-(v/vs)^2) (Bo & Pavelescu; Armstrong-Helouvry)."""
    d = 2.0 * math.exp(-s)
    vs = P['vs']
    return sim_g(r, lambda i, vi, w: g_generic(r, i, vi, Ev=math.exp(-abs(vi / vs) ** d)))


def eff_vel_drag(r, s, q):
    """Quadratic (drag-type) viscous term: F += s * v |v| (kip s^2/in^2)."""
    F = base_force(r)
    return [f + s * vi * abs(vi) for f, vi in zip(F, r.v)]


def eff_vel_memory(r, s, q):
    """Frictional memory (Hess & Soom): the Stribeck term sees a lagged velocity v_m,
    tau v_m' = v - v_m, tau = s (s)."""
    if s <= 0:
        return base_force(r)
    a = 1.0 - math.exp(-DT / s)
    vs = P['vs']
    vm = [0.0] * r.n
    m_ = r.v[0]
    vm[0] = m_
    for i in range(1, r.n):
        m_ += (r.v[i] - m_) * a
        vm[i] = m_
    return sim_g(r, lambda i, vi, w: g_generic(r, i, vi, Ev=math.exp(-(vm[i] / vs) ** 2)))


EFFECTS = {
    'actuator_lag': [('first_order_lag', eff_lag_first_order, 'tau_s'),
                     ('dead_time', eff_lag_dead_time, 'delay_s'),
                     ('second_order_underdamped', eff_lag_second_order, 'one_over_omega_n_s')],
    'asymmetry': [('softer_backward_band_sigma0', eff_asym_stiffness, 'sigma0_fwd_over_bwd_minus_1'),
                  ('backward_only_viscous', eff_asym_viscous, 'extra_sigma2_bwd_kip_s_per_in'),
                  ('backward_stribeck_velocity', eff_asym_stribeck, 'vs_bwd_over_vs_minus_1')],
    'backlash': [('dead_zone', eff_backlash_deadzone, 'half_gap_in'),
                 ('load_dependent_gap', eff_backlash_loaddep, 'half_gap_per_kip_in'),
                 ('gradual_takeup', eff_backlash_smooth, 'slack_in')],
    'pretension': [('hardening_clamping', eff_pret_hardening, 'quadratic_gain'),
                   ('static_tracks_clamp', eff_pret_static_tracks, 'tracking_gain'),
                   ('slip_drift', eff_pret_drift, 'max_fraction_lost')],
    'residual_static': [('relax_to_zero', eff_rest_relax_zero, 'rate_1_per_s'),
                        ('toward_residual_level', eff_rest_toward_residual, 'rate_1_per_s'),
                        ('power_law_creep', eff_rest_powerlaw, 'exponent')],
    'self_energizing': [('capstan_wrap', eff_se_capstan, 'per_in'),
                        ('band_stretch_spring', eff_se_spring, 'kip_per_in'),
                        ('self_servo', eff_se_servo, 'servo_gain')],
    'transition_shape': [('dahl_exponent', eff_ts_dahl, 'n_minus_1'),
                         ('elasto_plastic', eff_ts_elastoplastic, 'breakaway_fraction'),
                         ('maxwell_slip', eff_ts_maxwell, 'fraction')],
    'velocity': [('stribeck_exponent', eff_vel_exponent, 'ln_2_over_delta'),
                 ('quadratic_drag', eff_vel_drag, 'kip_s2_per_in2'),
                 ('frictional_memory', eff_vel_memory, 'tau_s')],
}

# bounds of the strength (physically sensible range) used by the calibration
S_BOUNDS = {
    'first_order_lag': (1e-3, 0.5), 'dead_time': (1e-3, 0.3), 'second_order_underdamped': (5e-3, 0.3),
    'softer_backward_band_sigma0': (1e-3, 6.0), 'backward_only_viscous': (1e-3, 2.0),
    'backward_stribeck_velocity': (1e-3, 4.0),
    'dead_zone': (1e-4, 0.25), 'load_dependent_gap': (1e-4, 0.08), 'gradual_takeup': (1e-4, 0.3),
    'hardening_clamping': (1e-3, 1.5), 'static_tracks_clamp': (1e-3, 3.0), 'slip_drift': (1e-3, 0.6),
    'relax_to_zero': (1e-3, 20.0), 'toward_residual_level': (1e-3, 20.0), 'power_law_creep': (1e-3, 3.0),
    'capstan_wrap': (1e-3, 1.5), 'band_stretch_spring': (1e-3, 3.0), 'self_servo': (1e-4, 0.5),
    'dahl_exponent': (1e-3, 6.0), 'elasto_plastic': (1e-3, 0.9), 'maxwell_slip': (1e-3, 1.0),
    'stribeck_exponent': (1e-3, 1.4), 'quadratic_drag': (1e-3, 1.0), 'frictional_memory': (1e-4, 1.0),
}
