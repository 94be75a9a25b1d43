#!/usr/bin/env python3
"""Blind test set 18 for the BRFD model-discrepancy tool (master seed 18018).

Writes /work/blind18/cases/tNN/{A,B}.json (measured-format semi-active records) and
/work/blind18/key.json.  Python 3 standard library only.  See ../NOTES.md.

usage:  nice -n 10 python3 gen.py [--out DIR] [--only t03,t17] [--jobs 2]

Records: drum displacement and actuator positions are assembled from pieces of the six
measured semi-active tests (time-scaled, chained, mirrored, with rests); the force column is
  F = base model (LuGre Eqs. 1-3 + semi-active Eq. 4/5, conventions of `hybridsim damper
      predict --no-fit`) + hidden effect + white Gaussian noise, quantized like the data.
Each hidden effect is a modified simulation F_true(p); its parameter p is found by a root
search so that RMS over both records of (F_true - F_base) / noise_sd equals a drawn target.
"""
import json
import math
import os
import random
import struct
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SRC_DIR = '/work/shared/data/brfd/semiactive'
CONFIG = '/work/runs/brfd-semiactive.yaml'
MASTER_SEED = 18018
FS_HZ = 1024
DT = 1.0 / FS_HZ
Q_F = 0.00080088          # kip, force quantum of the measured files (ADC step)
VEL_QUIRK = 125.4         # measured velocity column = d(disp)/dt / 125.4 (data README quirk)
SRC_FILES = ['harmonic0.015backward.json', 'harmonic0.015forward.json',
             'harmonic0.03ea1backward.json', 'harmonic0.03ea1forward.json',
             'harmonic0.03ea2backward.json', 'harmonic0.03ea2forward.json']
# nominal drum extrema of every measured semi-active test (s) and their sign
EXT_T = [0.676, 1.596, 2.526, 3.532, 4.527, 5.532, 6.528, 7.533, 8.528, 9.532, 10.527,
         11.532, 12.463, 13.384]
EXT_S = [+1, -1, +1, -1, +1, -1, +1, -1, +1, -1, +1, -1, +1, -1]
META = {"dt": DT, "sampling freq": FS_HZ, "displacement units": "in", "time units": "s",
        "friction force units": "kip", "actuator force units": "lb"}


# ----------------------------------------------------------------------------- config
def read_config(path=CONFIG):
    """Minimal reader of the two sections of brfd-semiactive.yaml that the model needs."""
    out = {}
    sec = None
    with open(path) as fh:
        for raw in fh:
            line = raw.split('#', 1)[0].rstrip()
            if not line.strip():
                continue
            if not line.startswith(' '):
                sec = line.split(':')[0].strip()
                continue
            if sec not in ('lugre', 'semiactive') or ':' not in line:
                continue
            k, val = line.strip().split(':', 1)
            val = val.strip()
            if val.startswith('['):
                out[k] = [float(s) for s in val.strip('[]').split(',')]
            elif val:
                out[k] = float(val)
    return out


CFG = read_config()
S0 = CFG['sigma0_kip_per_in']
S1 = CFG['sigma1_kip_s_per_in']
S2 = CFG['sigma2_kip_s_per_in']
FSF, FSB = CFG['fs_fwd_kip'], CFG['fs_bwd_kip']
FCF, FCB = CFG['fc_fwd_kip'], CFG['fc_bwd_kip']
VS = CFG['vs_in_per_s']
FLOOR = CFG['fc_floor_kip']
_m = CFG['slopes_kip_per_in']
_C = CFG['scaling']
KF1 = _C[0] * _m[0] + _C[1] * _m[2]      # forward, d Fc / d x1
KF2 = _C[0] * _m[1] + _C[1] * _m[3]      # forward, d Fc / d x2
KB1 = _C[2] * _m[4] + _C[3] * _m[6]      # backward, d Fc / d x1
KB2 = _C[2] * _m[5] + _C[3] * _m[7]      # backward, d Fc / d x2
assert S1 == 0.0, 'the exact-step integrator below assumes sigma1 = 0 (as in the config)'


# ----------------------------------------------------------------------------- base model
def derive_velocity(x):
    """Drum velocity as `damper predict` derives it: central differences (one-sided at the
    ends) followed by a 15-sample zero-phase (centred) moving average whose half-width shrinks
    symmetrically at the record ends."""
    n = len(x)
    cd = [0.0] * n
    for i in range(1, n - 1):
        cd[i] = (x[i + 1] - x[i - 1]) / (2 * DT)
    cd[0] = (x[1] - x[0]) / DT
    cd[-1] = (x[-1] - x[-2]) / DT
    pre = [0.0] * (n + 1)
    acc = 0.0
    for i in range(n):
        acc += cd[i]
        pre[i + 1] = acc
    v = [0.0] * n
    for i in range(n):
        k = min(7, i, n - 1 - i)
        v[i] = (pre[i + k + 1] - pre[i - k]) / (2 * k + 1)
    return v


class Rec:
    """Inputs of one record as the tool reads them."""

    def __init__(self, t, x, a1, a2, F0):
        self.t, self.x, self.a1, self.a2 = t, x, a1, a2
        self.n = len(x)
        self.F0 = F0
        self.v = derive_velocity(x)
        self.x1p, self.x2p = a1[0], a2[0]
        # Eq. (4) without the floor; the floor is applied where used
        self.dff = [KF1 * (p - self.x1p) + KF2 * (q - self.x2p) for p, q in zip(a1, a2)]
        self.dfb = [KB1 * (p - self.x1p) + KB2 * (q - self.x2p) for p, q in zip(a1, a2)]


def exp_step(z, v, g, mult=1.0):
    """Exact step of dz/dt = v - mult*sigma0*|v|*z/g with v, g held (the tool's scheme uses
    the inputs of the step's END sample).  mult = 1 is LuGre."""
    a = mult * S0 * abs(v) / g
    if a > 0.0:
        zs = v / a
        return zs + (z - zs) * math.exp(-a * DT)
    return z + v * DT


SHAPES = {
    'backlash': ['deadzone_gap', 'reengagement_impact', 'catenary_sag_softening'],
    'residual_static': ['zener_relaxation', 'thermal_contraction', 'log_relaxation'],
    'actuator_lag': ['first_order_lag', 'transport_delay', 'second_order_linkage'],
    'asymmetry': ['one_band_chatter', 'one_band_thermal_fade', 'one_band_powerlaw_speed'],
    'velocity': ['frictional_memory', 'flash_weakening', 'log_rate_strengthening'],
    'pretension': ['capstan_exponential', 'thermal_pretension_rise', 'wear_pretension_loss'],
    'self_energizing': ['wrap_angle_growth', 'servo_force_feedback', 'drum_out_of_round'],
    'transition_shape': ['dahl_exponent', 'elastoplastic_presliding', 'dwell_aging'],
}
CATEGORY_OF = {s: c for c, ss in SHAPES.items() for s in ss}

# meaning of p and main literature source of every shape (full equations: ../NOTES.md)
SHAPE_INFO = {
    'deadzone_gap': ('half-width of the band slack gap crossed at zero band force (in)',
                     'Nordin & Gutman 2002, Automatica 38:1633 (dead-zone backlash model)'),
    'reengagement_impact': ('impact gain: transient amplitude per drum speed at re-engagement (kip s/in)',
                            'Dubowsky & Freudenstein 1971, J Eng Ind 93:305; Hunt & Crossley 1975'),
    'catenary_sag_softening': ('sag tension scale of the Ernst equivalent band stiffness (kip)',
                               'Ernst 1965, Der Bauingenieur 40:52; Irvine 1981, Cable Structures'),
    'zener_relaxation': ('relaxed fraction of the held band force (-)',
                         'Zener 1948; Findley, Lai & Onaran 1976 (standard linear solid)'),
    'thermal_contraction': ('band-force loss per unit of drum heat while cooling (1/in)',
                            'Limpert 2011, Brake Design and Safety (drum thermal expansion), Newton cooling'),
    'log_relaxation': ('logarithmic relaxation rate of the held band force (-)',
                       'Bureau, Baumberger & Caroli 2002, Eur Phys J E 8:331'),
    'first_order_lag': ('time constant of the clamping response (s)',
                        'Spencer, Dyke, Sain & Carlson 1997, J Eng Mech 123:230 (first-order filter)'),
    'transport_delay': ('delay between actuator position and clamping (s)',
                        'Agrawal & Yang 2000, Earthquake Eng Struct Dyn 29:37'),
    'second_order_linkage': ('1/omega_n of the underdamped actuator-band linkage (s)',
                             'Dyke, Spencer, Quast & Sain 1995, J Eng Mech 121:322'),
    'one_band_chatter': ('relative amplitude of friction-induced oscillation on one band (-)',
                         'Ibrahim 1994, Appl Mech Rev 47:227 (chatter, squeal)'),
    'one_band_thermal_fade': ('fade coefficient of one band lining per unit heat (1/(kip in))',
                              'Limpert 2011 (brake fade); Ostermeyer 2003, Wear 254:852'),
    'one_band_powerlaw_speed': ('coefficient of the power-law speed strengthening of one band (-)',
                                'Grosch 1963, Proc R Soc A 274:21 (rubber friction vs speed)'),
    'frictional_memory': ('time constant of the frictional lag of the Stribeck curve (s)',
                          'Hess & Soom 1990, J Tribol 112:147'),
    'flash_weakening': ('depth of the high-speed (flash heating) weakening (-)',
                        'Rice 2006, J Geophys Res 111:B05311'),
    'log_rate_strengthening': ('steady-state rate-strengthening coefficient a-b (-)',
                               'Dieterich 1979, JGR 84:2161; Ruina 1983, JGR 88:10359'),
    'capstan_exponential': ('exponent scale of the capstan (Euler-Eytelwein) clamping law (-)',
                            'Euler 1762; Budynas & Nisbett, Shigley band brakes (P1/P2 = e^(f phi))'),
    'thermal_pretension_rise': ('pre-tension gain per unit drum heat (per q_ref kip in)',
                                'Limpert 2011; Day 2014, Braking of Road Vehicles (drum expansion)'),
    'wear_pretension_loss': ('pre-tension loss per w_ref of dissipated work (-)',
                             'Archard 1953, J Appl Phys 24:981; Fouvry et al. 2003, Wear 255:287'),
    'wrap_angle_growth': ('mu/R: log friction gain per inch of winding travel (1/in)',
                          'Euler-Eytelwein capstan; Downey et al. 2016, Eng Struct 113:287 (BRFD)'),
    'servo_force_feedback': ('servo gain of the band force on the clamping (-)',
                             'Cao et al. 2015, J Sound Vib 348:41 (duo-servo); Limpert 2011 (brake factor)'),
    'drum_out_of_round': ('relative friction variation of an out-of-round drum (-)',
                          'Jacobsson 2003, Proc IMechE D 217:419 (judder, thickness variation)'),
    'dahl_exponent': ('|i - 1|, departure of the Dahl exponent from LuGre (-)',
                      'Dahl 1976, AIAA J 14:1675'),
    'elastoplastic_presliding': ('elastoplastic family parameter (breakaway 0.8 p z_ss) (-)',
                                 'Dupont, Hayward, Armstrong & Altpeter 2002, IEEE TAC 47:787'),
    'dwell_aging': ('log-dwell growth coefficient of the static level (-)',
                    'Rabinowicz 1958, Proc Phys Soc 71:668; Dieterich 1972, JGR 77:3690'),
}

WEAK_ONLY = ('first_order_lag',)
V_REST = 0.02   # in/s: |v| below this counts as drum at rest / stuck (derived velocity)
T_ON = 0.05     # s: rest must last this long before rest effects act (skips reversals)


def simulate(rec, shape=None, p=0.0, prm=None):
    """Force (kip, noise-free) of the base model (shape None or p == 0) or of the base
    model with one hidden effect of strength p and secondary parameters prm."""
    prm = prm or {}
    n, v, x = rec.n, rec.v, rec.x
    dff, dfb = rec.dff, rec.dfb
    F = [0.0] * n
    z = rec.F0 / S0
    F[0] = S0 * z + S2 * v[0]
    if shape is None or p == 0.0:
        for j in range(1, n):
            vj = v[j]
            if vj >= 0:
                fc = FCF + dff[j]
                fs = FSF
            else:
                fc = FCB + dfb[j]
                fs = FSB
            if fc < FLOOR:
                fc = FLOOR
            g = fc + (fs - fc) * math.exp(-(vj / VS) ** 2)
            z = exp_step(z, vj, g)
            F[j] = S0 * z + S2 * vj
        return F

    sh = shape
    band = prm.get('band', 0)           # +1 forward band, -1 backward band
    # ---- states
    t_rest = 0.0
    z_hold = z
    theta = 0.0
    work = 0.0
    vf = v[0]
    gap = False
    s_gap = 0.0
    gdir = 0.0
    impacts = []
    xe1, xe2 = rec.a1[0], rec.a2[0]
    xd1 = xd2 = 0.0
    t_stick = 0.0
    t_dwell = 0.0
    if sh == 'reengagement_impact':
        wn = 2 * math.pi * prm['fn_hz']
        ze = prm['zeta']
        wd = wn * math.sqrt(1 - ze * ze)
        life = 6.0 / (ze * wn)
    if sh in ('first_order_lag',):
        alpha_lag = 1.0 - math.exp(-DT / p)
    if sh == 'frictional_memory':
        alpha_vf = 1.0 - math.exp(-DT / p)
    if sh == 'transport_delay':
        dshift = p / DT
    if sh == 'second_order_linkage':
        wn2 = 1.0 / p
        ze2 = prm['zeta']
        nsub = max(1, int(math.ceil(wn2 * DT / 0.05)))
        hs = DT / nsub
    if sh == 'dahl_exponent':
        expo = 1.0 + p if prm['mode'] == 'ductile' else 1.0 - p
    if sh == 'zener_relaxation':
        decay_z = math.exp(-DT / prm['tau_s'])
    if sh in ('thermal_contraction', 'thermal_pretension_rise'):
        ec = math.exp(-DT / prm['tau_s'])
    if sh == 'one_band_thermal_fade':
        ec = math.exp(-DT / prm['tau_s'])
    if sh == 'drum_out_of_round':
        kx = 2 * math.pi / prm['lambda_in']
    if sh == 'one_band_chatter':
        wch = 2 * math.pi * prm['f_hz']

    for j in range(1, n):
        vj = v[j]
        fwd = vj >= 0
        tj = j * DT
        # ---------------- kinetic friction level Fc (Eq. 4) and its variants
        if sh in ('first_order_lag', 'transport_delay', 'second_order_linkage'):
            if sh == 'first_order_lag':
                xe1 += alpha_lag * (rec.a1[j] - xe1)
                xe2 += alpha_lag * (rec.a2[j] - xe2)
            elif sh == 'transport_delay':
                q = j - dshift
                if q <= 0:
                    xe1, xe2 = rec.a1[0], rec.a2[0]
                else:
                    k0 = int(q)
                    fr = q - k0
                    xe1 = rec.a1[k0] + fr * (rec.a1[k0 + 1] - rec.a1[k0])
                    xe2 = rec.a2[k0] + fr * (rec.a2[k0 + 1] - rec.a2[k0])
            else:
                u1, u2 = rec.a1[j], rec.a2[j]
                for _ in range(nsub):
                    xd1 += hs * (wn2 * wn2 * (u1 - xe1) - 2 * ze2 * wn2 * xd1)
                    xe1 += hs * xd1
                    xd2 += hs * (wn2 * wn2 * (u2 - xe2) - 2 * ze2 * wn2 * xd2)
                    xe2 += hs * xd2
            if fwd:
                dfc = KF1 * (xe1 - rec.x1p) + KF2 * (xe2 - rec.x2p)
            else:
                dfc = KB1 * (xe1 - rec.x1p) + KB2 * (xe2 - rec.x2p)
        else:
            dfc = dff[j] if fwd else dfb[j]
        b = FCF if fwd else FCB
        fs = FSF if fwd else FSB
        if sh == 'capstan_exponential':
            fc = b + b * (math.exp(min(p * dfc / b, 50.0)) - 1.0) / p
        else:
            fc = b + dfc
        if fc < FLOOR:
            fc = FLOOR
        # ---------------- static level (dwell aging)
        if sh == 'dwell_aging':
            if abs(vj) < V_REST:
                t_stick += DT
                t_dwell = t_stick
            else:
                t_stick = 0.0
            fs = fs * (1.0 + p * math.log(1.0 + t_dwell / prm['t0_s']))
            if fs < fc:
                fs = fc
        # ---------------- Stribeck curve, Eq. (5)
        if sh == 'frictional_memory':
            vf += alpha_vf * (vj - vf)
            g = fc + (fs - fc) * math.exp(-(vf / VS) ** 2)
        else:
            g = fc + (fs - fc) * math.exp(-(vj / VS) ** 2)
        # ---------------- multiplicative friction-level effects
        fb = S0 * z
        if sh == 'one_band_thermal_fade':
            pw = abs(fb * vj) if (1 if fwd else -1) == band else 0.0
            theta = theta * ec + pw * prm['tau_s'] * (1.0 - ec)
            if (1 if fwd else -1) == band:
                g = g / (1.0 + p * theta)
        elif sh == 'one_band_powerlaw_speed':
            if (1 if fwd else -1) == band:
                g = g * (1.0 + p * (abs(vj) / prm['v_ref']) ** prm['m'])
        elif sh == 'flash_weakening':
            av = abs(vj)
            if av > prm['v_w']:
                g = g * (1.0 - p * (1.0 - prm['v_w'] / av))
        elif sh == 'log_rate_strengthening':
            g = g * (1.0 + p * math.log(1.0 + abs(vj) / prm['v0']))
        elif sh == 'thermal_pretension_rise':
            theta = theta * ec + abs(fb * vj) * prm['tau_s'] * (1.0 - ec)
            g = g * (1.0 + p * theta / prm['q_ref'])
        elif sh == 'wear_pretension_loss':
            work += abs(fb * vj) * DT
            g = g * max(0.2, 1.0 - p * work / prm['w_ref'])
        elif sh == 'wrap_angle_growth':
            g = g * math.exp(min(p * (x[j] if fwd else -x[j]), 5.0))
        elif sh == 'servo_force_feedback':
            g = g * min(3.0, 1.0 + p * abs(fb) / prm['f_ref'])
        elif sh == 'drum_out_of_round':
            g = g * (1.0 + p * math.sin(kx * x[j] + prm['phase']))
        if g < 1e-3:
            g = 1e-3
        # ---------------- bristle / band-force state update
        zprev = z
        if sh == 'deadzone_gap':
            if gap:
                s_gap += vj * DT * gdir
                z = 0.0
                if s_gap >= 2.0 * p or s_gap < 0.0:
                    gap = False
            else:
                z = exp_step(z, vj, g)
                if zprev != 0.0 and z * zprev < 0.0 and (z > 0) == (vj > 0):
                    gap = True
                    gdir = 1.0 if vj > 0 else -1.0
                    s_gap = abs(z) / 1.0   # travel already made past zero (z ~ x there)
                    z = 0.0
        elif sh == 'catenary_sag_softening':
            fbb = S0 * z
            keff = 1.0 / (1.0 + (p / (abs(fbb) + prm['f_min'])) ** 3)
            # softened band stiffness scales the rate only; the target stays sign(v) g / S0
            if vj != 0:
                a = keff * S0 * abs(vj) / g
                zs = (1.0 if vj > 0 else -1.0) * g / S0
                z = zs + (zprev - zs) * math.exp(-a * DT)
        elif sh == 'dahl_exponent':
            if vj != 0.0:
                sg = 1.0 if vj > 0 else -1.0
                u = 1.0 - S0 * z * sg / g
                au = abs(u)
                dxs = S0 * abs(vj) * DT / g
                if au > 0.0:
                    if expo > 1.0:
                        au = (au ** (1.0 - expo) + (expo - 1.0) * dxs) ** (1.0 / (1.0 - expo))
                    elif expo < 1.0:
                        w = au ** (1.0 - expo) - (1.0 - expo) * dxs
                        au = w ** (1.0 / (1.0 - expo)) if w > 0 else 0.0
                    else:
                        au = au * math.exp(-dxs)
                u = au if u >= 0 else -au
                z = sg * (g / S0) * (1.0 - u)
        elif sh == 'elastoplastic_presliding':
            zmax = g / S0
            zba = 0.8 * p * zmax
            zma = zba + (zmax - zba) * p
            if vj != 0.0:
                if (z > 0) == (vj > 0) and z != 0.0:
                    az = abs(z)
                    if az <= zba:
                        al = 0.0
                    elif az >= zma:
                        al = 1.0
                    else:
                        al = 0.5 * math.sin(math.pi * (az - 0.5 * (zba + zma)) / (zma - zba)) + 0.5
                else:
                    al = 1.0 - p
                z = exp_step(z, vj, g, al) if al > 0 else z + vj * DT
        else:
            z = exp_step(z, vj, g)

        # ---------------- rest effects (drum still)
        if abs(vj) < V_REST:
            t_rest += DT
        else:
            t_rest = 0.0
        if sh == 'zener_relaxation':
            if t_rest > T_ON:
                if t_rest - DT <= T_ON:
                    z_hold = z
                zt = (1.0 - p) * z_hold
                z = zt + (z - zt) * decay_z
        elif sh == 'log_relaxation':
            if t_rest > T_ON:
                if t_rest - DT <= T_ON:
                    z_hold = z
                fac = 1.0 - p * math.log(1.0 + (t_rest - T_ON) / prm['t0_s'])
                z = z_hold * (fac if fac > 0 else 0.0)
        elif sh == 'thermal_contraction':
            th_new = theta * ec + abs(S0 * zprev * vj) * prm['tau_s'] * (1.0 - ec)
            dth = th_new - theta
            theta = th_new
            if z != 0.0:
                zn = z + (1.0 if z > 0 else -1.0) * p * dth / S0
                z = zn if zn * z > 0 else 0.0

        fo = S0 * z + S2 * vj
        # ---------------- additive force effects
        if sh == 'reengagement_impact':
            if zprev != 0.0 and z * zprev < 0.0 and (z > 0) == (vj > 0):
                impacts.append((tj, p * vj))
            if impacts:
                add = 0.0
                keep = []
                for (te, amp) in impacts:
                    tau = tj - te
                    if tau < life:
                        keep.append((te, amp))
                        add += amp * math.exp(-ze * wn * tau) * math.sin(wd * tau)
                impacts = keep
                fo += add
        elif sh == 'one_band_chatter':
            if (1 if fwd else -1) == band:
                wgt = 1.0 - math.exp(-(vj / 0.3) ** 2)
                fo += p * abs(S0 * z) * wgt * math.sin(wch * tj + prm['phase'])
        F[j] = fo
    return F


# ----------------------------------------------------------------------------- sources
class Source:
    def __init__(self, name):
        d = json.load(open(os.path.join(SRC_DIR, name)))['data']
        self.name = name
        self.x = [r[1] for r in d]
        self.a1 = [r[4] for r in d]
        self.a2 = [r[5] for r in d]
        self.n = len(d)
        self.ext = []
        h = 20
        pre = [0.0]
        for xv in self.x:
            pre.append(pre[-1] + xv)
        sm = [(pre[min(self.n, i + h + 1)] - pre[max(0, i - h)]) / (min(self.n, i + h + 1) - max(0, i - h))
              for i in range(self.n)]
        for tn, sg in zip(EXT_T, EXT_S):
            c = int(round(tn * FS_HZ))
            lo, hi = c - 150, c + 150
            best = max(range(lo, hi), key=lambda i: sg * sm[i])
            self.ext.append(best)
        # actuator events (motion windows), padded
        d1 = [p - self.a1[0] for p in self.a1]
        d2 = [q - self.a2[0] for q in self.a2]
        act = [abs(p) > 4e-4 or abs(q) > 4e-4 for p, q in zip(d1, d2)]
        segs = []
        i = 0
        while i < self.n:
            if act[i]:
                k = i
                while k < self.n and act[k]:
                    k += 1
                if segs and i - segs[-1][1] < 150:
                    segs[-1][1] = k
                else:
                    segs.append([i, k])
                i = k
            else:
                i += 1
        self.events = []
        pad = 60
        for (i0, i1) in segs:
            i0p, i1p = max(0, i0 - pad), min(self.n - 1, i1 + pad)
            # preceding drum extremum
            ex = max(e for e in self.ext if e <= i0 + 80)
            self.events.append({'i0': i0p, 'i1': i1p, 'off_s': (i0p - ex) * DT,
                                'd1': [self.a1[k] - self.a1[i0p] for k in range(i0p, i1p + 1)],
                                'd2': [self.a2[k] - self.a2[i0p] for k in range(i0p, i1p + 1)]})


def f32(v):
    """Round to single precision, as the acquisition system stores its channels."""
    return struct.unpack('f', struct.pack('f', v))[0]


class Grid:
    """Uniform quantization of one channel (step of the measured files, anchored at a measured
    value), values stored in single precision like the measured data."""

    def __init__(self, values, q):
        self.anchor = values[0]
        self.q = q

    def snap(self, val):
        return f32(self.anchor + round((val - self.anchor) / self.q) * self.q)


_SOURCES = None
_GRIDS = None


def sources():
    global _SOURCES, _GRIDS
    if _SOURCES is None:
        _SOURCES = [Source(nm) for nm in SRC_FILES]
        # steps of the measured channels: drum LVDT ~5.89e-5 in, actuator encoders 1/409600 in
        _GRIDS = {'x': Grid(_SOURCES[0].x, 5.8896e-5),
                  'a1': Grid(_SOURCES[0].a1, 1.0 / 409600),
                  'a2': Grid(_SOURCES[0].a2, 1.0 / 409600)}
    return _SOURCES, _GRIDS


def resample(seq, i0, i1, scale):
    """Piece seq[i0..i1] played `scale` times slower (linear interpolation), as a list that
    starts at seq[i0] and ends at seq[i1]."""
    L = (i1 - i0) * scale
    m = max(1, int(round(L)))
    out = []
    for k in range(m + 1):
        q = i0 + (i1 - i0) * k / m
        a = int(q)
        if a >= i1:
            out.append(seq[i1])
        else:
            fr = q - a
            out.append(seq[a] + fr * (seq[a + 1] - seq[a]))
    return out


# ----------------------------------------------------------------------------- records
def build_record(rng, early):
    """Drum displacement and actuator positions (grid-snapped) of one record + its layout."""
    srcs, grids = sources()
    s_rec = rng.uniform(0.75, 1.35)

    def sc():
        return s_rec * rng.uniform(0.9, 1.1)

    xs = []          # drum displacement samples (float, unsnapped)
    rest_mask = []   # True where a synthetic hold (dither applied later)
    halfcycles = []  # (start sample, scale, source, extremum index) of body half-cycles

    def hold(dur, val):
        m = int(round(dur * FS_HZ))
        xs.extend([val] * m)
        rest_mask.extend([True] * m)

    def piece(src, i0, i1, scale, mirror):
        seg = resample(src.x, i0, i1, scale)
        if mirror:
            seg = [-u for u in seg]
        shift = (xs[-1] - seg[0]) if xs else 0.0
        seg = [u + shift for u in seg]
        if xs:
            seg = seg[1:]
        xs.extend(seg)
        rest_mask.extend([False] * len(seg))

    # --- durations
    if early:
        r0 = rng.uniform(0.08, 0.35)
        L_target = rng.uniform(6.5, 21.0)
        k_pass = 0
        k_min = 0
    else:
        r0 = rng.uniform(0.3, 2.0)
        L_target = rng.uniform(12.5, 24.5)
        k_pass = rng.randint(4, 6)       # passive body half-cycles after the ramp-up
        k_min = k_pass + 2
    final_hold = rng.uniform(1.7, 3.5)
    su, sd = sc(), sc()
    src_d = rng.choice(srcs)
    e_d = rng.choice([10, 11])
    len_down = (src_d.n - 1 - src_d.ext[e_d]) * sd * DT
    # --- initial rest + ramp-up
    src = rng.choice(srcs)
    m0 = rng.random() < 0.5
    x_start = -src.x[0] if m0 else src.x[0]
    hold(r0, x_start)
    piece(src, 0, src.ext[2], su, m0)
    sign_end = -1 if m0 else 1           # ramp-up ends at + (unmirrored)
    # --- body half-cycles, added while the record stays within its target length
    K = 0
    while True:
        hd = rng.uniform(0.15, 1.2) if (K > 0 and rng.random() < 0.3) else 0.0
        src = rng.choice(srcs)
        e = rng.randint(2, 10)           # half-cycle ext[e] -> ext[e+1]
        sc_h = sc()
        dur_h = (src.ext[e + 1] - src.ext[e]) * sc_h * DT
        now = len(xs) * DT
        if now + hd + dur_h + len_down + final_hold > L_target:
            if K >= k_min:
                break
            hd = 0.0
        if hd > 0:
            hold(hd, xs[-1])
        mirror = (EXT_S[e] > 0) != (sign_end > 0)
        halfcycles.append((len(xs) - 1, sc_h, src, e))
        piece(src, src.ext[e], src.ext[e + 1], sc_h, mirror)
        sign_end = -sign_end
        K += 1
    # --- ramp-down (from ext[10] (+) or ext[11] (-)) + final rest
    mirror = (EXT_S[e_d] > 0) != (sign_end > 0)
    piece(src_d, src_d.ext[e_d], src_d.n - 1, sd, mirror)
    n_motion = len(xs)
    final_hold = max(1.7, min(final_hold, 25.0 - len(xs) * DT - 0.01))
    hold(final_hold, xs[-1])
    n = len(xs)
    if n < int(6.6 * FS_HZ):
        hold((int(6.6 * FS_HZ) - n) * DT, xs[-1])
        n = len(xs)
    # --- snap drum to the measured grid, dither the synthetic holds
    gx = grids['x']
    x = []
    for i in range(n):
        val = xs[i]
        if rest_mask[i] and i < n - 16:
            u = rng.random()
            val += gx.q * (-1 if u < 0.12 else (1 if u > 0.88 else 0))
        x.append(gx.snap(val))

    # --- actuators
    evs_all = [ev for s in srcs for ev in s.events]
    base_src = rng.choice(srcs)
    lev1, lev2 = base_src.a1[0], base_src.a2[0]
    d1 = [0.0] * n
    d2 = [0.0] * n
    moving = [False] * n
    placed = []

    def place(t0, scale, ev, mirror):
        nonlocal lev1, lev2
        s1 = resample(ev['d1'], 0, len(ev['d1']) - 1, scale)
        s2 = resample(ev['d2'], 0, len(ev['d2']) - 1, scale)
        i0 = int(round(t0 * FS_HZ))
        sg = -1.0 if mirror else 1.0
        for k in range(len(s1)):
            if i0 + k < n:
                d1[i0 + k] = sg * s1[k]
                d2[i0 + k] = sg * s2[k]
                moving[i0 + k] = True
        placed.append((i0, i0 + len(s1) - 1, sg * s1[-1], sg * s2[-1]))

    last_end = -1.0
    if early:
        ev = rng.choice(evs_all)
        t0 = rng.uniform(max(0.05, r0 - 0.05), 0.72)
        scale = rng.uniform(0.8, 1.3)
        place(t0, scale, ev, rng.random() < 0.5)
        last_end = t0 + (len(ev['d1']) - 1) * scale * DT
    prev_evt = False
    body_evt = 0
    for k, (hs, sc_h, src, e) in enumerate(halfcycles):
        if k < k_pass:
            continue
        want = rng.random() < 0.75
        if not early and body_evt == 0 and k == len(halfcycles) - 1:
            want = True
        if not want:
            continue
        ev = rng.choice(evs_all)
        t0 = hs * DT + ev['off_s'] * sc_h
        if t0 < last_end + 0.02:
            # previous event still running: start right after it if still early in the stroke
            if last_end + 0.02 - t0 > 0.25 * sc_h:
                continue
            t0 = last_end + 0.02
        place(t0, sc_h, ev, rng.random() < 0.5)
        last_end = t0 + (len(ev['d1']) - 1) * sc_h * DT
        body_evt += 1
    # actuator levels: holds carry the offset left by the previous event
    a1 = [0.0] * n
    a2 = [0.0] * n
    g1, g2 = grids['a1'], grids['a2']
    placed.sort()
    pi = 0
    cur1, cur2 = lev1, lev2
    i = 0
    while i < n:
        if pi < len(placed) and i == placed[pi][0]:
            i0, i1, e1, e2 = placed[pi]
            for k in range(i0, min(i1 + 1, n)):
                a1[k] = g1.snap(cur1 + d1[k])
                a2[k] = g2.snap(cur2 + d2[k])
            cur1 += e1
            cur2 += e2
            i = i1 + 1
            pi += 1
            continue
        u = rng.random()
        a1[i] = g1.snap(cur1 + g1.q * (-1 if u < 0.04 else (1 if u > 0.96 else 0)))
        u = rng.random()
        a2[i] = g2.snap(cur2 + g2.q * (-1 if u < 0.04 else (1 if u > 0.96 else 0)))
        i += 1
    a1[0] = g1.snap(lev1)
    a2[0] = g2.snap(lev2)
    t = [i * DT for i in range(n)]
    layout = {'duration_s': round((n - 1) * DT, 4), 'active_early': early,
              'time_scale': round(s_rec, 4), 'body_half_cycles': K,
              'actuator_events': len(placed),
              'final_rest_s': round((n - n_motion) * DT, 3)}
    return t, x, a1, a2, layout


def first_motion(rec, thr=0.002):
    for i in range(rec.n):
        if abs(rec.a1[i] - rec.x1p) > thr or abs(rec.a2[i] - rec.x2p) > thr:
            return i * DT
    return None


# ----------------------------------------------------------------------------- effects
def draw_params(shape, rng):
    """Secondary (fixed) parameters of each hidden-effect shape, start value and bound of p."""
    P = {}
    if shape == 'deadzone_gap':
        return P, 0.01, 1.0
    if shape == 'reengagement_impact':
        P = {'fn_hz': rng.uniform(4.0, 10.0), 'zeta': rng.uniform(0.06, 0.15)}
        return P, 0.05, 20.0
    if shape == 'catenary_sag_softening':
        P = {'f_min': rng.uniform(0.15, 0.3)}
        return P, 0.1, 8.0
    if shape == 'zener_relaxation':
        P = {'tau_s': rng.uniform(0.3, 1.2)}
        return P, 0.05, 1.0
    if shape == 'thermal_contraction':
        P = {'tau_s': rng.uniform(2.0, 6.0)}
        return P, 0.005, 5.0
    if shape == 'log_relaxation':
        P = {'t0_s': rng.uniform(0.05, 0.3)}
        return P, 0.02, 3.0
    if shape == 'first_order_lag':
        return P, 0.01, 3.0
    if shape == 'transport_delay':
        return P, 0.01, 1.5
    if shape == 'second_order_linkage':
        P = {'zeta': rng.uniform(0.15, 0.35)}
        return P, 0.005, 0.5
    if shape == 'one_band_chatter':
        P = {'band': rng.choice([1, -1]), 'f_hz': rng.uniform(9.0, 16.0),
             'phase': rng.uniform(0, 2 * math.pi)}
        return P, 0.01, 1.5
    if shape == 'one_band_thermal_fade':
        P = {'band': rng.choice([1, -1]), 'tau_s': rng.uniform(4.0, 12.0)}
        return P, 0.002, 5.0
    if shape == 'one_band_powerlaw_speed':
        P = {'band': rng.choice([1, -1]), 'm': rng.uniform(0.3, 0.6), 'v_ref': 1.0}
        return P, 0.02, 4.0
    if shape == 'frictional_memory':
        return P, 0.005, 1.0
    if shape == 'flash_weakening':
        P = {'v_w': rng.uniform(0.8, 1.3)}
        return P, 0.05, 0.95
    if shape == 'log_rate_strengthening':
        P = {'v0': rng.uniform(0.05, 0.2)}
        return P, 0.01, 2.0
    if shape == 'capstan_exponential':
        return P, 0.05, 30.0
    if shape == 'thermal_pretension_rise':
        P = {'tau_s': rng.uniform(15.0, 40.0), 'q_ref': 100.0}
        return P, 0.02, 20.0
    if shape == 'wear_pretension_loss':
        P = {'w_ref': 100.0}
        return P, 0.02, 20.0
    if shape == 'wrap_angle_growth':
        return P, 0.01, 2.5
    if shape == 'servo_force_feedback':
        P = {'f_ref': 10.0}
        return P, 0.02, 2.0
    if shape == 'drum_out_of_round':
        P = {'lambda_in': rng.uniform(0.6, 1.6), 'phase': rng.uniform(0, 2 * math.pi)}
        return P, 0.01, 0.9
    if shape == 'dahl_exponent':
        P = {'mode': rng.choice(['ductile', 'brittle'])}
        return P, 0.05, (6.0 if P['mode'] == 'ductile' else 0.9)
    if shape == 'elastoplastic_presliding':
        return P, 0.05, 1.0
    if shape == 'dwell_aging':
        P = {'t0_s': rng.uniform(0.01, 0.05)}
        return P, 0.01, 4.0
    raise KeyError(shape)


def effect_ratio(recs, bases, shape, p, prm, sd):
    num = 0.0
    cnt = 0
    for rec, Fb in zip(recs, bases):
        Ft = simulate(rec, shape, p, prm)
        for a, b in zip(Ft, Fb):
            d = a - b
            num += d * d
        cnt += rec.n
    return math.sqrt(num / cnt) / sd


def solve_p(recs, bases, shape, prm, sd, target, p0, pmax):
    """Root of ratio(p) = target: scan p geometrically from p0 up to pmax (factor ~1.6) for the
    first value with ratio >= target, then refine in that bracket (secant guarded by
    bisection).  Returns (None, best ratio) when the target is out of reach."""
    lo, flo = 0.0, -target
    p = min(p0, pmax)
    best = 0.0
    while True:
        f = effect_ratio(recs, bases, shape, p, prm, sd) - target
        best = max(best, f + target)
        if f >= 0:
            hi, fhi = p, f
            break
        lo, flo = p, f
        if p >= pmax:
            return None, best
        p = min(1.6 * p, pmax)
    m, f = hi, fhi
    for it in range(60):
        if abs(f) <= 0.002 * target:
            break
        m = lo + (hi - lo) * (-flo) / (fhi - flo) if fhi != flo else 0.5 * (lo + hi)
        if not (lo < m < hi) or it % 3 == 2:
            m = 0.5 * (lo + hi)
        f = effect_ratio(recs, bases, shape, m, prm, sd) - target
        if f < 0:
            lo, flo = m, f
        else:
            hi, fhi = m, f
        if hi - lo < 1e-10 * max(1.0, hi):
            break
    return m, f + target


# ----------------------------------------------------------------------------- trials
def trial_plan():
    rng = random.Random(MASTER_SEED)
    cats = list(SHAPES)
    order = cats[:]
    rng.shuffle(order)
    two_weak = set(order[:4])          # 4 categories get 2 weak + 1 strong, 4 get 1 + 2
    specs = []
    for c in cats:
        shapes = SHAPES[c][:]
        rng.shuffle(shapes)
        strengths = ['weak', 'weak', 'strong'] if c in two_weak else ['weak', 'strong', 'strong']
        rng.shuffle(strengths)
        # a first-order lag can at most erase the actuator modulation (bounded effect): weak slot
        for k, s in enumerate(shapes):
            if s in WEAK_ONLY and strengths[k] != 'weak':
                w = strengths.index('weak')
                strengths[k], strengths[w] = strengths[w], strengths[k]
        for s, st in zip(shapes, strengths):
            specs.append({'category': c, 'shape': s, 'strength': st})
    for _ in range(6):
        specs.append({'category': 'none', 'shape': 'none', 'strength': 'none'})
    rng.shuffle(specs)
    early = [True] * 20 + [False] * 40   # one third of the 60 records start with actuation
    rng.shuffle(early)
    plan = {}
    for k, sp in enumerate(specs):
        tid = 't%02d' % (k + 1)
        sp = dict(sp)
        sp['early'] = (early[2 * k], early[2 * k + 1])
        plan[tid] = sp
    return plan


def quantize_force(f):
    return round(round(f / Q_F) * Q_F, 9)


def write_record(path, rec, Ftrue, noise_sd, rng):
    F = [rec.F0] + [quantize_force(Ftrue[i] + rng.gauss(0.0, noise_sd)) for i in range(1, rec.n)]
    rows = []
    for i in range(rec.n):
        fi = F[i]
        # actuator load cells (lb): taut band carries |F|/C_taut, slack one ~ 25 lb + |F|/C_slack
        if fi >= 0:
            f2 = 25.0 + 1000.0 * fi / _C[1]
            f1 = 25.0 + 1000.0 * fi / _C[0]
        else:
            f1 = 25.0 + 1000.0 * (-fi) / _C[2]
            f2 = 25.0 + 1000.0 * (-fi) / _C[3]
        f1 = round(round((f1 + rng.gauss(0, 0.6)) / 0.31794) * 0.31794, 6)
        f2 = round(round((f2 + rng.gauss(0, 0.6)) / 0.39989) * 0.39989, 6)
        rows.append([rec.t[i], rec.x[i], fi, round(rec.v[i] / VEL_QUIRK, 12),
                     rec.a1[i], rec.a2[i], f1, f2])
    obj = {'data': rows}
    obj.update(META)
    with open(path, 'w') as fh:
        json.dump(obj, fh, separators=(', ', ': '))
    return F


def make_trial(args):
    tid, spec, outdir = args
    seed = '%d-%s' % (MASTER_SEED, tid)
    rng_n = random.Random(seed + '-noise')
    noise_sd = rng_n.uniform(0.02, 0.06)
    rng_e = random.Random(seed + '-effect')
    target = {'weak': rng_e.uniform(2.7, 3.8), 'strong': rng_e.uniform(8.5, 11.5),
              'none': 0.0}[spec['strength']]
    attempt = 0
    noise_attempt = 0
    while True:
        if attempt >= 3:
            # target out of reach with these records and this noise level (effects bounded by
            # the actuator activity or by the rest time): redraw the noise SD from U(0.02, 0.06)
            noise_sd = rng_n.uniform(0.02, 0.06)
            noise_attempt += 1
        rng_r = random.Random('%s-records-%d' % (seed, attempt))
        recs = []
        layouts = []
        for rname, early in zip('AB', spec['early']):
            t, x, a1, a2, lay = build_record(rng_r, early)
            F0 = quantize_force(rng_r.uniform(-2.0, 3.2))
            rec = Rec(t, x, a1, a2, F0)
            lay['F0_kip'] = F0
            fm = first_motion(rec)
            lay['first_actuator_motion_s'] = None if fm is None else round(fm, 4)
            recs.append(rec)
            layouts.append(lay)
        bases = [simulate(r) for r in recs]
        if spec['shape'] == 'none':
            p, ratio, prm = 0.0, 0.0, {}
            break
        ok = False
        for pt in range(3):
            prm, p0, pmax = draw_params(spec['shape'], rng_e)
            p, ratio = solve_p(recs, bases, spec['shape'], prm, noise_sd, target, p0, pmax)
            if p is not None:
                ok = True
                break
        if ok:
            break
        attempt += 1
        if attempt > 30:
            raise RuntimeError('%s: target ratio unreachable for %s' % (tid, spec['shape']))
    os.makedirs(os.path.join(outdir, 'cases', tid), exist_ok=True)
    rng_w = random.Random(seed + '-write')
    for rname, rec, lay in zip('AB', recs, layouts):
        Ft = simulate(rec, spec['shape'], p, prm) if spec['shape'] != 'none' else simulate(rec)
        write_record(os.path.join(outdir, 'cases', tid, rname + '.json'), rec, Ft, noise_sd, rng_w)
    entry = {'category': spec['category'], 'shape': spec['shape'], 'strength': spec['strength'],
             'p': p, 'noise_kip': noise_sd, 'ratio': ratio, 'target_ratio': target,
             'params': prm, 'record_attempt': attempt,
             'p_meaning': SHAPE_INFO[spec['shape']][0] if spec['shape'] in SHAPE_INFO else '',
             'reference': SHAPE_INFO[spec['shape']][1] if spec['shape'] in SHAPE_INFO else '',
             'noise_redraws': noise_attempt,
             'records': {'A': layouts[0], 'B': layouts[1]}}
    return tid, entry


def main(argv):
    outdir = ROOT
    only = None
    jobs = 2
    i = 0
    while i < len(argv):
        if argv[i] == '--out':
            outdir = argv[i + 1]
            i += 2
        elif argv[i] == '--only':
            only = set(argv[i + 1].split(','))
            i += 2
        elif argv[i] == '--jobs':
            jobs = int(argv[i + 1])
            i += 2
        else:
            raise SystemExit('unknown argument ' + argv[i])
    try:
        os.nice(5)
    except OSError:
        pass
    t0 = time.time()
    plan = trial_plan()
    todo = [(tid, sp, outdir) for tid, sp in sorted(plan.items()) if only is None or tid in only]
    sources()
    if jobs > 1:
        from multiprocessing import Pool
        with Pool(jobs) as pool:
            res = pool.map(make_trial, todo, chunksize=1)
    else:
        res = [make_trial(a) for a in todo]
    key = dict(sorted(res))
    if only is None:
        with open(os.path.join(outdir, 'key.json'), 'w') as fh:
            json.dump(key, fh, indent=1, sort_keys=True)
    else:
        with open(os.path.join(outdir, 'key_partial.json'), 'w') as fh:
            json.dump(key, fh, indent=1, sort_keys=True)
    print('generated %d trials in %.1f s -> %s' % (len(res), time.time() - t0, outdir))


if __name__ == '__main__':
    main(sys.argv[1:])
