"""Base model: semi-active LuGre of Coble et al. (seed paper), Eqs. (1)-(5), with the
parameters of /work/main/configs/brfd-semiactive.yaml (copied here, numbers only).

Discretisation chosen to reproduce `hybridsim damper predict --no-fit`:
  * drum velocity from the displacement column: central differences (one-sided at the ends),
    then a centred 15-sample moving average whose half-width shrinks symmetrically at the ends;
  * bristle force Fb = sigma0 z advanced by the exact exponential solution of Eq. (1) over each
    sample with v (and x1, x2) of the NEW sample held constant;
  * F = Fb + sigma2 v (sigma1 = 0); Fb(0) = recorded force at t = 0.
"""
import math

P = dict(sigma0=15.36, sigma1=0.0, sigma2=0.500, fs_fwd=7.116, fs_bwd=3.760,
         fc_fwd=2.648, fc_bwd=1.253, vs=1.300, fc_floor=0.05,
         m=[-0.14, -0.15, -15.29, -13.00, -16.66, -15.77, -0.13, -0.15],
         C=[119.68, 2.10, 1.94, 123.31])
DT = 1.0 / 1024.0


def velocity(x, dt=DT, half=7):
    n = len(x)
    d = [0.0] * n
    for i in range(n):
        if i == 0:
            d[i] = (x[1] - x[0]) / dt
        elif i == n - 1:
            d[i] = (x[n - 1] - x[n - 2]) / dt
        else:
            d[i] = (x[i + 1] - x[i - 1]) / (2 * dt)
    # centred moving average, half-width shrinking symmetrically at the ends
    cs = [0.0]
    for a in d:
        cs.append(cs[-1] + a)
    v = [0.0] * n
    for i in range(n):
        h = min(half, i, n - 1 - i)
        v[i] = (cs[i + h + 1] - cs[i - h]) / (2 * h + 1)
    return v


def fc_eq4(v, x1, x2, x1p, x2p, p=P, b_fwd=None, b_bwd=None):
    m, C = p['m'], p['C']
    if v >= 0:
        b = p['fc_fwd'] if b_fwd is None else b_fwd
        fc = b + (C[0] * m[0] + C[1] * m[2]) * (x1 - x1p) + (C[0] * m[1] + C[1] * m[3]) * (x2 - x2p)
    else:
        b = p['fc_bwd'] if b_bwd is None else b_bwd
        fc = b + (C[2] * m[4] + C[3] * m[6]) * (x1 - x1p) + (C[2] * m[5] + C[3] * m[7]) * (x2 - x2p)
    return max(fc, p['fc_floor'])


def g_of_v(v, fc, p=P):
    fs = p['fs_fwd'] if v >= 0 else p['fs_bwd']
    return fc + (fs - fc) * math.exp(-(v / p['vs']) ** 2)


def simulate(x, x1, x2, fb0, p=P, dt=DT, v=None):
    """Return (F, Fb, v, Fc) lists for the base model."""
    if v is None:
        v = velocity(x, dt)
    x1p, x2p = x1[0], x2[0]
    n = len(x)
    F = [0.0] * n; Fb = [0.0] * n; FC = [0.0] * n
    fb = fb0
    for k in range(n):
        vk = v[k]
        fc = fc_eq4(vk, x1[k], x2[k], x1p, x2p, p)
        FC[k] = fc
        if k > 0:
            g = g_of_v(vk, fc, p)
            s = 1.0 if vk > 0 else (-1.0 if vk < 0 else 0.0)
            fb = g * s + (fb - g * s) * math.exp(-p['sigma0'] * abs(vk) * dt / g)
        Fb[k] = fb
        F[k] = fb + p['sigma2'] * vk
    return F, Fb, v, FC
