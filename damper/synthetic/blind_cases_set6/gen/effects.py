"""Base model + one hidden effect.  simulate(inp, eff) -> noise-free friction force (kip).

inp: dict with x, x1, x2 (recorded columns, as written), v (base velocity estimate), fb0.
eff: dict(category=..., shape=..., amp=..., **other parameters); category 'none' = base.
All effects reduce to the base model when amp = 0.  References: see ../NOTES.md.
"""
import math
from base import P, DT, fc_eq4

def lowpass(a, tau, dt=DT):
    if tau <= 0:
        return list(a)
    al = 1.0 - math.exp(-dt / tau)
    out = [0.0] * len(a); y = a[0]
    for i, s in enumerate(a):
        y += al * (s - y); out[i] = y
    return out

def act_effective(x, x0, eff):
    """Actuator position seen by the band (actuator_lag shapes)."""
    sh, amp = eff['shape'], eff['amp']
    n = len(x); d = [xi - x0 for xi in x]
    if sh == 'first_order':                      # tau = amp
        y = lowpass(d, amp)
    elif sh == 'dead_time_first_order':          # pure delay amp + small lag
        nd = int(round(amp / DT))
        dd = [d[0]] * nd + d[:n - nd] if nd > 0 else d
        y = lowpass(dd, eff['tau'])
    elif sh == 'second_order':                   # amp = 1/omega_n ; zeta
        wn = 1.0 / amp; z = eff['zeta']
        y = [0.0] * n; p = d[0]; q = 0.0; h = DT / 4
        for i in range(n):
            u = d[i]
            for _ in range(4):
                a = wn * wn * (u - p) - 2 * z * wn * q
                q += a * h; p += q * h
            y[i] = p
    elif sh == 'rate_limited':                   # max slew = 1/amp in/s, plus creep lag
        r = (1.0 / amp) * DT; y = [0.0] * n; p = d[0]
        for i in range(n):
            e = d[i] - p
            p += max(-r, min(r, e)); y[i] = p
        y = lowpass(y, eff.get('tau', 0.0))
    else:
        y = d
    return [x0 + yi for yi in y]

def simulate(inp, eff):
    x, x1, x2, v, fb0 = inp['x'], inp['x1'], inp['x2'], inp['v'], inp['fb0']
    cat = eff['category']; sh = eff.get('shape'); amp = eff.get('amp', 0.0)
    n = len(x); dt = DT
    s0, s2, vs = P['sigma0'], P['sigma2'], P['vs']
    x1p, x2p = x1[0], x2[0]
    if cat == 'actuator_lag' and amp > 0:
        x1 = act_effective(x1, x1p, eff); x2 = act_effective(x2, x2p, eff)
    F = [0.0] * n
    fb = fb0
    # --- per-shape state
    gap = None; gap_w = eff.get('gap0', 0.0); fpeak = abs(fb0)
    take_u = None
    eng_u = None; eng_e = 1.0; prev_out = fb0
    rest_t = 0.0; rest_fb = fb0; vf = 0.0; al_rest = 1 - math.exp(-dt / 0.03)
    Tth = 0.0; Tn = 0.0
    if cat == 'transition_shape' and sh == 'maxwell_slip':
        w = eff['weights']; k_el = [s0 * eff['amp'] * wi for wi in eff['kfrac']]
        elems = [fb0 * wi for wi in w]
    for k in range(n):
        vk = v[k]
        sgn = 1.0 if vk > 0 else (-1.0 if vk < 0 else 0.0)
        fwd = vk >= 0
        # ---- kinetic level Fc (Eq. 4) and effects on it
        fc = fc_eq4(vk, x1[k], x2[k], x1p, x2p)
        b = P['fc_fwd'] if fwd else P['fc_bwd']
        fs = P['fs_fwd'] if fwd else P['fs_bwd']
        if cat == 'pretension' and amp > 0:
            r = fc / b
            if sh == 'power_law_clamp':
                fc = max(P['fc_floor'], b * r ** (1.0 + eff['sign'] * amp))
            elif sh == 'saturating':
                dl = fc - b; ds = 1.0 / amp
                fc = max(P['fc_floor'], b + ds * math.tanh(dl / ds))
            elif sh == 'fs_tracks_clamp':
                fs = max(fs + amp * (fs / b) * (fc - b), fc)
        vs_k = vs; s0_k = s0; s2_k = s2
        if cat == 'asymmetry' and amp > 0 and (fwd == (eff['dir'] == 'fwd')):
            if sh == 'stiffness_one_dir':
                s0_k = s0 * (1.0 + eff['sign'] * amp)
            elif sh == 'lining_one_dir':
                fc *= (1.0 + eff['sign'] * amp); fs *= (1.0 + eff['sign'] * amp)
            elif sh == 'stribeck_viscous_one_dir':
                vs_k = vs * (1.0 + 2.0 * amp); s2_k = s2 * (1.0 + 3.0 * amp)
        g = fc + (fs - fc) * math.exp(-(vk / vs_k) ** 2)
        av = abs(vk)
        if cat == 'velocity' and amp > 0:
            if sh == 'log_strengthening':
                g *= 1.0 + amp * math.log(1.0 + av / eff['v0'])
            elif sh == 'speed_weakening':
                g *= 1.0 - amp * av / (av + eff['vw'])
        if cat == 'self_energizing' and amp > 0:
            if sh == 'capstan_wrap':
                g *= min(3.0, max(0.3, math.exp(amp * sgn * (x[k] - eff['x0']))))
            elif sh == 'thermal_fade':
                g /= (1.0 + amp * Tth)
            elif sh == 'servo_buildup':
                g *= (1.0 + amp * Tn)
        if k > 0:
            # ---- presliding / bristle dynamics
            dx = vk * dt
            if cat == 'transition_shape' and amp > 0 and sh == 'dahl_exponent' and sgn != 0:
                a = eff['alpha']
                u = 1.0 - fb * sgn / g
                ds = s0_k * av * dt / g
                if u > 0:
                    if abs(a - 1) < 1e-9:
                        u = u * math.exp(-ds)
                    else:
                        t_ = u ** (1 - a) - (1 - a) * ds
                        if a < 1:
                            u = max(t_, 0.0) ** (1 / (1 - a))
                        else:
                            u = t_ ** (1 / (1 - a))
                else:
                    u = u * math.exp(-ds)
                fb = sgn * g * (1.0 - u)
            elif cat == 'transition_shape' and amp > 0 and sh == 'maxwell_slip':
                tot = 0.0
                for i in range(len(elems)):
                    fi = elems[i] + k_el[i] * dx; lim = g * w[i]
                    if fi > lim: fi = lim
                    elif fi < -lim: fi = -lim
                    elems[i] = fi; tot += fi
                fb = tot
            elif cat == 'transition_shape' and amp > 0 and sh == 'elastoplastic':
                zba = amp  # breakaway as fraction of g
                for _ in range(4):
                    h = dx / 4
                    r = fb / g if g > 0 else 0.0
                    if sgn == 0 or r * sgn <= 0:
                        al = 0.0
                    else:
                        q = abs(r)
                        if q <= zba: al = 0.0
                        elif q >= 1.0: al = 1.0
                        else: al = 0.5 * math.sin(math.pi * (q - 0.5 * (1 + zba)) / (1 - zba)) + 0.5
                    fb += s0_k * h * (1.0 - al * fb * sgn / g)
            elif gap is not None:
                gap += (vk * dt) * gap_dir
                if gap >= gap_w or gap <= 0.0:
                    gap = None; fb = 0.0; eng_u = 0.0
            else:
                if sgn != 0:
                    fnew = g * sgn + (fb - g * sgn) * math.exp(-s0_k * av * dt / g)
                else:
                    fnew = fb
                o_new = fnew + s2_k * vk * eng_e
                if cat == 'backlash' and amp > 0 and sh in ('zero_cross_gap', 'load_dependent_gap') \
                        and prev_out * o_new < 0 and o_new * sgn > 0:
                    gap = 0.0; gap_dir = sgn; fb = 0.0
                    gap_w = amp if sh == 'zero_cross_gap' else eff['gap0'] + amp * fpeak
                    fpeak = 0.0
                else:
                    if cat == 'backlash' and sh == 'progressive_takeup' and amp > 0:
                        if fb * fnew < 0 and fnew * sgn > 0:
                            take_u = 0.0; take_dir = sgn
                        elif take_u is not None:
                            take_u += vk * dt * take_dir
                            if take_u < 0: take_u = None
                    fb = fnew
            fpeak = max(fpeak, abs(fb))
        # ---- rest effects (residual_static)
        vf += al_rest * (av - vf)
        if cat == 'residual_static' and amp > 0:
            if vf < eff['v_rest'] and k > 0:
                if rest_t == 0.0:
                    rest_fb = fb
                rest_t += dt
                te = rest_t - eff['t_hold']
                if te > 0:
                    if sh == 'exp_relaxation':
                        tgt = rest_fb * (1.0 - amp)
                        fb = tgt + (fb - tgt) * math.exp(-dt / eff['tau'])
                    elif sh == 'log_creep':
                        fb = rest_fb * max(0.0, 1.0 - amp * math.log(1.0 + te / eff['tc']))
                    elif sh == 'recovery_to_preload':
                        tgt = rest_fb + amp * (eff['f_eq'] - rest_fb)
                        fb = tgt + (fb - tgt) * math.exp(-dt / eff['tau'])
            else:
                rest_t = 0.0
        # ---- output
        if gap is not None:
            out = eff.get('c_gap', 0.05) * vk
        else:
            fo = fb
            if take_u is not None:
                fo = fb * (1.0 - math.exp(-take_u / amp))
                if take_u > 6 * amp: take_u = None
            # after a gap the lining re-engages over u_e = 0.03 in: viscous part ramps in (no jump)
            if eng_u is not None:
                eng_u += av * dt
                eng_e = min(1.0, eng_u / 0.03)
                if eng_e >= 1.0: eng_u = None
            out = fo + s2_k * vk * eng_e
        if cat == 'velocity' and sh == 'power_viscous' and amp > 0:
            out += amp * sgn * av ** eff['delta']
        if cat == 'self_energizing' and amp > 0:
            if sh == 'thermal_fade':
                Tth += dt * (abs(out * vk) - Tth / eff['tau_th'])
            elif sh == 'servo_buildup':
                Tn += (1 - math.exp(-dt / eff['tau_b'])) * (min(abs(fb) / g, 1.5) - Tn)
        prev_out = out if k > 0 else fb0
        F[k] = out if k > 0 else fb0
    return F
