"""Base model + one hidden effect. simulate(x, a1, a2, f0, eff, s) -> force (kip, noise-free).
eff = {"category": ..., "shape": ..., <fixed params>}; s = the strength scalar that the
generator calibrates (s = 0 gives exactly the base model). Standard library only."""
import math
from base import P, DT, velocity, fc_eq4, g_of


def _lag_actuators(a, shape, s, prm):
    n = len(a)
    if s <= 0:
        return list(a)
    out = [a[0]] * n
    if shape == "first_order":          # tau = s (s)
        al = math.exp(-DT / s)
        y = a[0]
        for k in range(n):
            y = a[k] + (y - a[k]) * al
            out[k] = y
    elif shape == "pure_delay":         # T = s (s)
        m = int(round(s / DT))
        for k in range(n):
            out[k] = a[max(0, k - m)]
    elif shape == "second_order":       # wn = 2 pi / (s * 2 pi) ... tau-like s: wn = 1/s
        wn = 1.0 / s
        z = prm["zeta"]
        y, yd = a[0], 0.0
        nsub = 4
        h = DT / nsub
        for k in range(n):
            for _ in range(nsub):
                ydd = wn * wn * (a[k] - y) - 2 * z * wn * yd
                yd += ydd * h
                y += yd * h
            out[k] = y
    return out


def simulate(x, a1, a2, f0, eff=None, s=0.0, v=None):
    p = P
    if v is None:
        v = velocity(x)
    n = len(x)
    cat = eff["category"] if eff else "none"
    shape = eff["shape"] if eff else ""
    if s == 0.0:
        cat = "none"
    x1p, x2p = a1[0], a2[0]
    if cat == "actuator_lag":
        a1 = _lag_actuators(a1, shape, s, eff)
        a2 = _lag_actuators(a2, shape, s, eff)
    s0, s2 = p["sigma0"], p["sigma2"]
    fb = f0
    F = [0.0] * n
    F[0] = fb + s2 * v[0]
    # effect states
    E = 0.0                  # dissipated energy (thermal fade)
    trav = 1e9               # travel since last reversal (engagement ramp)
    dirn = 0
    gap = s if (cat == "backlash" and shape == "deadzone_gap") else 0.0
    e = fb / s0 + (gap / 2) * ((fb > 0) - (fb < 0))   # band deflection incl. slack
    rest_run = 0
    fb_rest = 0.0
    M = 6
    ms_z = None
    if cat == "transition_shape" and shape == "maxwell_slip":
        ms_z = [fb / s0 for _ in range(M)]   # element deflections (each stiffness s0/M)
        fb_l = fb
    fb_l, fb_ep = fb, fb
    for k in range(1, n):
        vk = v[k]
        fwd = vk >= 0
        fc = fc_eq4(a1[k], a2[k], vk, x1p, x2p)
        fs = p["fs_fwd"] if fwd else p["fs_bwd"]
        vs = p["vs"]
        sig0 = s0
        sig2 = s2
        if cat == "pretension":
            b = p["fc_fwd"] if fwd else p["fc_bwd"]
            m, C = p["m"], p["C"]
            if fwd:
                d = (C[0] * m[0] + C[1] * m[2]) * (a1[k] - x1p) + (C[0] * m[1] + C[1] * m[3]) * (a2[k] - x2p)
            else:
                d = (C[2] * m[4] + C[3] * m[6]) * (a1[k] - x1p) + (C[2] * m[5] + C[3] * m[7]) * (a2[k] - x2p)
            if shape == "saturating":          # contact/clamp saturation: d/(1+s|d|)
                d = d / (1.0 + s * abs(d))
            elif shape == "hardening":         # stiffening band: d + s d|d|
                d = d + s * d * abs(d)
            fc = max(b + d, p["fc_floor"])
            if shape == "static_scales":       # Amontons: static friction scales with clamp too
                fs = fs * max(0.05, 1.0 + s * (fc / b - 1.0))
        elif cat == "velocity":
            av = abs(vk)
            if shape == "rate_state_log":
                fc = max(p["fc_floor"], fc * (1.0 + eff["sign"] * s * math.log(1.0 + av / eff["v_ref"])))
            elif shape == "power_strengthening":
                fc = fc + s * av ** eff["n"]
        elif cat == "asymmetry":
            if shape == "sigma0_dir":
                sig0 = s0 * (1 + s) if fwd else s0 / (1 + s)
            elif shape == "sigma2_dir":
                sig2 = s2 + s if fwd else max(0.0, s2 - s)
            elif shape == "vs_dir":
                vs = vs * (1 + s) if fwd else vs / (1 + s)
        if cat == "velocity" and shape == "stribeck_exponent":
            g = fc + (fs - fc) * math.exp(-abs(vk / vs) ** (2.0 - s))
        else:
            g = fc + (fs - fc) * math.exp(-(vk / vs) ** 2)
        if cat == "self_energizing":
            if shape == "capstan_rotation":     # Euler-Eytelwein: T ~ exp(mu * wrap), wrap grows with x along v
                g *= math.exp(s * x[k] * (1 if fwd else -1))
            elif shape == "thermal_fade":
                g *= 1.0 - s * (1.0 - math.exp(-E / eff["E0"]))
        if cat == "backlash" and shape == "engagement_ramp":
            sg = (vk > eff["v_dir"]) - (vk < -eff["v_dir"])
            if sg != 0 and sg != dirn:
                dirn = sg
                trav = 0.0
            trav += abs(vk) * DT
            g *= 1.0 - s * math.exp(-trav / eff["lam"])
        sg = (vk > 0) - (vk < 0)
        # ---- bristle / band state update over the sample (velocity of the new sample held)
        if cat == "backlash" and shape == "deadzone_gap":
            nsub = 8
            h = DT / nsub
            dl = gap / 2
            for _ in range(nsub):
                if abs(e) <= dl:
                    e += vk * h
                else:
                    se = 1 if e > 0 else -1
                    z = e - dl * se
                    zt = g / sig0 * sg
                    z2 = zt + (z - zt) * math.exp(-sig0 * abs(vk) * h / g)
                    if z2 * se < 0:
                        e = dl * se + z2        # entered the slack: continue from its edge
                    else:
                        e = z2 + dl * se
            fb = sig0 * (e - dl if e > dl else (e + dl if e < -dl else 0.0))
        elif cat == "transition_shape" and shape == "dahl_exponent":
            nsub = 8
            h = DT / nsub
            ex = math.exp(eff["i_dir"] * s)   # Dahl exponent i (LuGre/Dahl-1 at s = 0)
            for _ in range(nsub):
                r = 1.0 - fb * sg / g
                if sg == 0:
                    break
                fb += sig0 * vk * h * (abs(r) ** ex) * (1 if r > 0 else -1)
        elif cat == "transition_shape" and shape == "elastoplastic":
            # parallel: (1-s) LuGre + s Dupont et al. (2002) elasto-plastic single-state model
            fb_l = g * sg + (fb_l - g * sg) * math.exp(-sig0 * abs(vk) * DT / g)
            nsub = 8
            h = DT / nsub
            zss = g / sig0
            zba = eff["beta"] * zss
            z = fb_ep / sig0
            for _ in range(nsub):
                if sg == 0:
                    break
                if z * sg <= 0 or abs(z) <= zba:
                    al = 0.0
                elif abs(z) >= zss:
                    al = 1.0
                else:
                    al = 0.5 * math.sin(math.pi * (abs(z) - 0.5 * (zss + zba)) / (zss - zba)) + 0.5
                z += vk * h * (1.0 - al * abs(z) / zss) if z * sg > 0 else vk * h
            fb_ep = sig0 * z
            fb = (1 - s) * fb_l + s * fb_ep
        elif ms_z is not None:
            # parallel: (1-s) LuGre + s Maxwell-slip (Iwan) elements with spread break-away
            fb_l = g * sg + (fb_l - g * sg) * math.exp(-sig0 * abs(vk) * DT / g)
            kk = sig0 / M
            tot = 0.0
            for i in range(M):
                w = (1.0 + eff["spread"] * (i - (M - 1) / 2) / ((M - 1) / 2)) / M
                lim = w * g / kk
                zi = ms_z[i] + vk * DT
                if zi > lim:
                    zi = lim
                elif zi < -lim:
                    zi = -lim
                ms_z[i] = zi
                tot += kk * zi
            fb = (1 - s) * fb_l + s * tot
        else:
            fb = g * sg + (fb - g * sg) * math.exp(-sig0 * abs(vk) * DT / g)
        if cat == "residual_static":
            if abs(vk) < eff["v_rest"]:
                rest_run += 1
            else:
                rest_run = 0
            if rest_run == 1:
                fb_rest = fb
            if rest_run >= 30:
                tr = rest_run * DT
                if shape == "exp_relaxation":     # standard-linear-solid band relaxation
                    fb = fb_rest * (1.0 - s * (1.0 - math.exp(-tr / eff["tau"])))
                elif shape == "log_creep":        # logarithmic (rate-state / rubber) relaxation
                    dF = s * math.log(1.0 + tr / eff["tau0"])
                    fb = fb_rest - math.copysign(min(dF, 0.95 * abs(fb_rest)), fb_rest)
                elif shape == "drift_to_offset":  # recovery toward a set-point of the band pretension
                    fb = fb_rest + (eff["f_set"] - fb_rest) * s * (1.0 - math.exp(-tr / eff["tau"]))
        F[k] = fb + sig2 * vk
        if cat == "self_energizing" and shape == "thermal_fade":
            E += (abs(F[k] * vk) - E / eff["tau_cool"]) * DT
    return F
