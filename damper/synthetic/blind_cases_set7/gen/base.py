"""Base model: semi-active LuGre of the BRFD paper (Eqs. 1-5), parameters of
configs/brfd-semiactive.yaml. Standard library only."""
import math

P = dict(sigma0=15.36, sigma1=0.0, sigma2=0.5, fs_fwd=7.116, fs_bwd=3.760,
         fc_fwd=2.648, fc_bwd=1.253, vs=1.300, fc_floor=0.05,
         m=[-0.14, -0.15, -15.29, -13.00, -16.66, -15.77, -0.13, -0.15],
         C=[119.68, 2.10, 1.94, 123.31])
DT = 1.0 / 1024.0


def velocity(x, dt=DT, half=7):
    """Drum velocity from displacement: central differences (one-sided at the ends), then a
    centred 15-sample moving average whose half-width shrinks symmetrically at the ends.
    (The velocity column of the files is ~1/125 of in/s and lags: not used.)"""
    n = len(x)
    d = [0.0] * n
    d[0] = (x[1] - x[0]) / dt
    d[-1] = (x[-1] - x[-2]) / dt
    for k in range(1, n - 1):
        d[k] = (x[k + 1] - x[k - 1]) / (2 * dt)
    cs = [0.0]
    for v in d:
        cs.append(cs[-1] + v)
    out = [0.0] * n
    for k in range(n):
        h = min(half, k, n - 1 - k)
        out[k] = (cs[k + h + 1] - cs[k - h]) / (2 * h + 1)
    return out


def fc_eq4(x1, x2, v, x1p, x2p, p=P):
    m, C = p['m'], p['C']
    if v >= 0:
        fc = p['fc_fwd'] + (C[0] * m[0] + C[1] * m[2]) * (x1 - x1p) + (C[0] * m[1] + C[1] * m[3]) * (x2 - x2p)
    else:
        fc = p['fc_bwd'] + (C[2] * m[4] + C[3] * m[6]) * (x1 - x1p) + (C[2] * m[5] + C[3] * m[7]) * (x2 - x2p)
    return max(fc, p['fc_floor'])


def g_of(v, fc, p=P):
    fs = p['fs_fwd'] if v >= 0 else p['fs_bwd']
    return fc + (fs - fc) * math.exp(-(v / p['vs']) ** 2)


def simulate(x, a1, a2, f0, p=P, hooks=None, dt=DT):
    """Returns (force list, velocity list, fc list). hooks: optional object with methods to
    modify the model (used by the effects): hooks.fc(k, fc, v, state), hooks.g(...), ..."""
    v = velocity(x, dt)
    x1p, x2p = a1[0], a2[0]
    n = len(x)
    s0, s2 = p['sigma0'], p['sigma2']
    fb = f0
    F = [0.0] * n
    FC = [0.0] * n
    for k in range(n):
        vk = v[k]
        fc = fc_eq4(a1[k], a2[k], vk, x1p, x2p, p)
        if k > 0:
            g = g_of(vk, fc, p)
            sg = (vk > 0) - (vk < 0)
            fb = g * sg + (fb - g * sg) * math.exp(-s0 * abs(vk) * dt / g)
        F[k] = fb + s2 * vk
        FC[k] = fc
    return F, v, FC
