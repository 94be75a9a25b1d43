"""The 24 hidden-effect shapes of blind set 38: law (exactly as simulated in model.simulate),
amplitude bound, other parameters (drawn per trial) and literature source.

Notation: v = drum velocity of the black box (gradient + 15-sample mean of the displacement
column), Fz = sigma0*z (band/bristle force state), g = Eq. (5), Fc = Eq. (4) floored at 0.05,
b = Fc at x = x', lin = Fc - b (the linear actuator term of Eq. 4), d1 = x1 - x1', d2 = x2 - x2',
fwd = (v >= 0). Each step i-1 -> i: Fz_i = Fz* + (Fz_{i-1} - Fz*) exp(-k dt), coefficients
frozen at sample i (base: Fz* = sgn(v) g, k = sigma0 |v| / g); F_i = Fz_i + sigma2 v_i.
"""

SHAPES = {
    # ------------------------------------------------------------------ backlash
    "deadzone_hard": {
        "category": "backlash",
        "equation": ("When the unloading band force Fz crosses zero after a reversal, Fz := 0 and the "
                     "band is slack; gap position p := 0, then p += v dt; while |p| < delta: dFz/dt = 0. "
                     "At |p| >= delta the band re-engages abruptly: base LuGre update (rho = 1). "
                     "i.e. dFz/dt = rho sigma0 (v - |v| Fz / g), rho = H(|p| - delta); the slack band "
                     "transmits nothing: F = Fz + rho sigma2 v (F = 0 while slack)."),
        "amp_name": "delta_in", "amp_max": 0.5,
        "bound": "lost motion delta <= 0.5 in (drum stroke +-1.3 in; measured backlash travel ~0.1-0.3 in)",
        "params": {},
        "source": ("Nordin, M. and Gutman, P.-O. (2002), Controlling mechanical systems with backlash - "
                   "a survey, Automatica 38(10), 1633-1649 (dead-zone backlash model); "
                   "Tao, G. and Kokotovic, P. V. (1996), Adaptive Control of Systems with Actuator and "
                   "Sensor Nonlinearities, Wiley."),
    },
    "deadzone_hertz": {
        "category": "backlash",
        "equation": ("Slack as in a dead zone (Fz := 0 at the zero crossing of the unloading force, held "
                     "at 0 while |p| < delta, p = drum travel since the crossing, signed); after |p| >= delta "
                     "the contact re-engages with a Hertzian (penetration^1.5) stiffness: "
                     "dFz/dt = rho(s) sigma0 (v - |v| Fz/g), rho(s) = min(1, sqrt(s / lambda)), "
                     "s = drum travel since re-engagement, lambda = lam_ratio * delta; F = Fz + rho sigma2 v "
                     "(rho = 0 while slack)."),
        "amp_name": "delta_in", "amp_max": 0.45,
        "bound": "delta <= 0.45 in; lambda = lam_ratio*delta with lam_ratio in [0.6, 1.5]",
        "params": {"lam_ratio": (0.6, 1.5)},
        "source": ("Dubowsky, S. and Freudenstein, F. (1971), Dynamic analysis of mechanical systems with "
                   "clearances, Part 1, J. Eng. Ind. (ASME) 93(1), 305-309 (impact pair with Hertzian "
                   "contact); Johnson, K. L. (1985), Contact Mechanics, Cambridge Univ. Press."),
    },
    "soft_stage": {
        "category": "backlash",
        "equation": ("Three-stage model: at the zero crossing of the unloading force the band enters a "
                     "backlash stage of low residual stiffness kappa*sigma0 that lasts while |p| < delta "
                     "(p = signed drum travel since the crossing): dFz/dt = kappa sigma0 (v - |v| Fz/g); "
                     "F = Fz + kappa sigma2 v in that stage; afterwards the normal LuGre stage (kappa -> 1)."),
        "amp_name": "delta_in", "amp_max": 0.6,
        "bound": "delta <= 0.6 in; kappa in [0.05, 0.15]",
        "params": {"kappa": (0.05, 0.15)},
        "source": ("Cao, L., Downey, A., Laflamme, S., Taylor, D. and Ricles, J. (2015), Variable friction "
                   "device for structural control based on duo-servo vehicle brake: modeling and "
                   "experimental validation, J. Sound Vib. 348, 41-56 (3-stage dynamic friction model "
                   "with a backlash stage)."),
    },
    # ------------------------------------------------------------------ residual_static
    "sls_relax": {
        "category": "residual_static",
        "equation": ("At rest (rest detector on for t_r s, after the first motion): "
                     "Fz(t_r) = Fz_on [ (1 - beta) + beta exp(-t_r / tau) ] (standard-linear-solid stress "
                     "relaxation of the held band force to a plateau), added incrementally to the LuGre "
                     "state; motion resumes from the relaxed state. Rest detector: max-min of the "
                     "displacement column over the last 192 samples < 0.0015 in."),
        "amp_name": "beta", "amp_max": 0.8,
        "bound": "relaxed fraction beta <= 0.8; tau in [0.25, 1.2] s",
        "params": {"tau_s": (0.25, 1.2)},
        "source": ("Zener, C. (1948), Elasticity and Anelasticity of Metals, Univ. of Chicago Press "
                   "(standard linear solid); Findley, W. N., Lai, J. S. and Onaran, K. (1976), Creep and "
                   "Relaxation of Nonlinear Viscoelastic Materials, North-Holland."),
    },
    "log_relax": {
        "category": "residual_static",
        "equation": ("At rest (same detector): Fz(t_r) = Fz_on max(0, 1 - beta ln(1 + t_r / tau)) "
                     "(logarithmic-in-time relaxation of a held frictional contact), added incrementally."),
        "amp_name": "beta", "amp_max": 0.3,
        "bound": "beta <= 0.3 per e-fold of time; tau in [0.01, 0.08] s",
        "params": {"tau_s": (0.01, 0.08)},
        "source": ("Baumberger, T. and Caroli, C. (2006), Solid friction from stick-slip down to pinning "
                   "and aging, Adv. Phys. 55(3-4), 279-348; Dieterich, J. H. (1972), Time-dependent "
                   "friction in rocks, J. Geophys. Res. 77(20), 3690-3697."),
    },
    "powerlaw_creep_up": {
        "category": "residual_static",
        "equation": ("At rest (same detector): Fz(t_r) = Fz_on [1 + beta (t_r / t0)^n], t0 = 1 s "
                     "(Findley power-law creep: the held band force creeps up, as at the end of the "
                     "measured tests), added incrementally."),
        "amp_name": "beta", "amp_max": 0.6,
        "bound": "beta <= 0.6 (held force +60% after 1 s); n in [0.25, 0.5]",
        "params": {"n": (0.25, 0.5), "t0_s": (1.0, 1.0)},
        "source": ("Findley, W. N., Lai, J. S. and Onaran, K. (1976), Creep and Relaxation of Nonlinear "
                   "Viscoelastic Materials, North-Holland (power law eps = eps0 + m t^n)."),
    },
    # ------------------------------------------------------------------ transition_shape
    "elastoplastic": {
        "category": "transition_shape",
        "equation": ("dFz/dt = sigma0 (v - alpha |v| Fz / g), alpha = 1 - w (1 - alpha_EP); "
                     "alpha_EP = 0 if sgn(Fz) != sgn(v) or |Fz| <= phi g; 1 if |Fz| >= g; else "
                     "0.5 sin(pi (|Fz| - (g + phi g)/2) / (g - phi g)) + 0.5 (pure elastic pre-sliding "
                     "up to the breakaway force phi g; steady level g unchanged)."),
        "amp_name": "w", "amp_max": 1.0,
        "bound": "blend w <= 1 (w = 1: full elasto-plastic model); phi = z_ba/z_ss in [0.3, 0.75]",
        "params": {"phi": (0.3, 0.75)},
        "source": ("Dupont, P., Hayward, V., Armstrong, B. and Altpeter, F. (2002), Single state "
                   "elastoplastic friction models, IEEE Trans. Autom. Control 47(5), 787-792."),
    },
    "gms2": {
        "category": "transition_shape",
        "equation": ("Two parallel Maxwell-slip/LuGre elements sharing the level g: F = FA + FB + sigma2 v, "
                     "dFA/dt = sigma0 e^eps (v - |v| FA/(w g)) * w, dFB/dt = sigma0 e^-eps (v - |v| FB/((1-w) g)) * (1-w), "
                     "i.e. FA -> sgn(v) w g with stiffness w sigma0 e^eps, FB -> sgn(v)(1-w) g with stiffness "
                     "(1-w) sigma0 e^-eps (two-stage rise, same steady level g); FA(0) = w F0, FB(0) = (1-w) F0."),
        "amp_name": "eps", "amp_max": 2.5,
        "bound": "stiffness contrast e^(2 eps) <= e^5 ~ 150; share w in [0.3, 0.7]",
        "params": {"w": (0.3, 0.7)},
        "source": ("Al-Bender, F., Lampaert, V. and Swevers, J. (2005), The generalized Maxwell-slip "
                   "model: a novel model for friction simulation and compensation, IEEE Trans. Autom. "
                   "Control 50(11), 1883-1887; Iwan, W. D. (1966), A distributed-element model for "
                   "hysteresis and its steady-state dynamic response, J. Appl. Mech. 33(4), 893-900."),
    },
    "frictional_lag": {
        "category": "transition_shape",
        "equation": ("Stribeck term evaluated at a lagged sliding speed s: tau_L ds/dt = |v| - s "
                     "(exact first-order update), g = Fc + (Fs - Fc) exp(-(s/vs)^2); the steady level "
                     "(s = |v|) is unchanged."),
        "amp_name": "tau_L_s", "amp_max": 0.3,
        "bound": "frictional-memory time tau_L <= 0.3 s",
        "params": {},
        "source": ("Hess, D. P. and Soom, A. (1990), Friction at a lubricated line contact operating at "
                   "oscillating sliding velocities, J. Tribol. 112(1), 147-152 (frictional lag); "
                   "Swevers, J., Al-Bender, F., Ganseman, C. G. and Prajogo, T. (2000), An integrated "
                   "friction model structure with improved presliding behavior for accurate friction "
                   "compensation, IEEE Trans. Autom. Control 45(4), 675-686."),
    },
    # ------------------------------------------------------------------ velocity
    "ratestate_log": {
        "category": "velocity",
        "equation": ("Fc_eff = max(0.05, Fc * max(0.3, 1 + a ln(max(|v|, v_min) / v_ref))) in Eq. (5) "
                     "(steady-state rate-and-state law, velocity strengthening a = A - B > 0), same in "
                     "both directions; Fs unchanged."),
        "amp_name": "a", "amp_max": 0.3,
        "bound": "a = A - B <= 0.3 (per e-fold of speed); v_ref in [1.0, 2.0] in/s; v_min = 0.05 in/s",
        "params": {"v_ref": (1.0, 2.0), "v_min": (0.05, 0.05)},
        "source": ("Dieterich, J. H. (1979), Modeling of rock friction 1. Experimental results and "
                   "constitutive equations, J. Geophys. Res. 84(B5), 2161-2168; Ruina, A. (1983), Slip "
                   "instability and state variable friction laws, J. Geophys. Res. 88(B12), 10359-10370."),
    },
    "grosch_hump": {
        "category": "velocity",
        "equation": ("Fc_eff = max(0.05, Fc * (1 + A exp(-ln(|v|/v_p)^2 / (2 w^2)))) (log-normal friction "
                     "maximum at speed v_p), same in both directions; Fs unchanged."),
        "amp_name": "A", "amp_max": 0.8,
        "bound": "hump height A <= 0.8 (x Fc); v_p in [1.3, 2.6] in/s; w in [0.25, 0.45]",
        "params": {"v_p": (1.3, 2.6), "width": (0.25, 0.45)},
        "source": ("Grosch, K. A. (1963), The relation between the friction and visco-elastic properties "
                   "of rubber, Proc. R. Soc. Lond. A 274(1356), 21-39."),
    },
    "thermal_weakening": {
        "category": "velocity",
        "equation": ("Fc_eff = max(0.05, Fc * (1 - a q/(1+q))), q = (|v|/v_w)^n (friction weakening at "
                     "high sliding speed), same in both directions; Fs unchanged."),
        "amp_name": "a", "amp_max": 0.6,
        "bound": "weakening a <= 0.6; v_w in [1.6, 2.6] in/s; n in [3, 6]",
        "params": {"v_w": (1.6, 2.6), "n": (3.0, 6.0)},
        "source": ("Molinari, A., Estrin, Y. and Mercier, S. (1999), Dependence of the coefficient of "
                   "friction on the sliding conditions in the high velocity range, J. Tribol. 121(1), "
                   "35-41."),
    },
    # ------------------------------------------------------------------ actuator_lag
    "rate_limit": {
        "category": "actuator_lag",
        "equation": ("Eq. (4) uses clamping positions xe_j: xe_j,i = xe_j,i-1 + clip(x_j,i - xe_j,i-1, "
                     "-r dt, r dt), xe_j,0 = x'_j (slew-rate-limited band take-up), both actuators; "
                     "amplitude = 1/r."),
        "amp_name": "inv_rate_s_per_in", "amp_max": 25.0,
        "bound": "slew rate r >= 0.04 in/s (amp = 1/r <= 25 s/in)",
        "params": {},
        "source": ("Berg, J. M., Hammett, K. D., Schwartz, C. A. and Banda, S. S. (1996), An analysis of "
                   "the destabilizing effect of daisy chained rate-limited actuators, IEEE Trans. "
                   "Control Syst. Technol. 4(2), 171-176."),
    },
    "linkage_play": {
        "category": "actuator_lag",
        "equation": ("Eq. (4) uses xe_j = play operator of x_j with half-width h: xe := x - h if x - xe > h, "
                     "xe := x + h if x - xe < -h, else unchanged; xe_0 = x'_j."),
        "amp_name": "h_in", "amp_max": 0.02,
        "bound": "play half-width h <= 0.02 in",
        "params": {},
        "source": ("Tao, G. and Kokotovic, P. V. (1996), Adaptive Control of Systems with Actuator and "
                   "Sensor Nonlinearities, Wiley (backlash/play operator); Nordin and Gutman (2002), "
                   "Automatica 38(10), 1633-1649."),
    },
    "sls_creep": {
        "category": "actuator_lag",
        "equation": ("Eq. (4) uses xe_j = x'_j + (1 - c)(x_j - x'_j) + c y_j, tau dy_j/dt = (x_j - x'_j) - y_j "
                     "(exact first-order update): an instantaneous part plus a retarded (creeping) part of "
                     "the linkage/band response."),
        "amp_name": "c", "amp_max": 0.9,
        "bound": "retarded fraction c <= 0.9; tau in [0.15, 0.8] s",
        "params": {"tau_s": (0.15, 0.8)},
        "source": ("Zener, C. (1948), Elasticity and Anelasticity of Metals, Univ. of Chicago Press "
                   "(standard linear solid / Kelvin-Voigt retardation); Findley, Lai and Onaran (1976)."),
    },
    # ------------------------------------------------------------------ self_energizing
    "servo_feedback": {
        "category": "self_energizing",
        "equation": ("g_eff = g (1 + gamma |F_{i-1}|) (duo-servo self-energizing: the band normal load "
                     "grows with the transmitted force of the previous sample)."),
        "amp_name": "gamma_per_kip", "amp_max": 0.15,
        "bound": "gamma <= 0.15 1/kip (brake-factor gain <= 1.5 at 3.3 kip)",
        "params": {},
        "source": ("Cao, L. et al. (2015), J. Sound Vib. 348, 41-56 (duo-servo self-energizing brake); "
                   "Day, A. (2014), Braking of Road Vehicles, Butterworth-Heinemann (brake factor, "
                   "self-servo drum brakes)."),
    },
    "capstan_wrap": {
        "category": "self_energizing",
        "equation": ("g_eff = g exp(kappa x sgn(v)) (Euler-Eytelwein capstan: the taut band's effective "
                     "wrap grows as the drum turns away from centre in the loading direction, "
                     "sgn(v) = +1 for v >= 0)."),
        "amp_name": "kappa_per_in", "amp_max": 0.45,
        "bound": "kappa = mu dtheta/dx <= 0.45 1/in (exp(0.45*1.3) = 1.8)",
        "params": {},
        "source": ("Euler-Eytelwein capstan equation; Jung, J. H., Pan, N. and Kang, T. J. (2008), "
                   "Capstan equation including bending rigidity and non-linear frictional behavior, "
                   "Mech. Mach. Theory 43(6), 661-675; Downey, A. et al. (2016), High capacity variable "
                   "friction damper based on band brake technology, Eng. Struct. 113, 287-298."),
    },
    "progressive_wrap": {
        "category": "self_energizing",
        "equation": ("g_eff = g (1 + kappa (1 - exp(-s / lambda))), s = drum travel since the last "
                     "sign change of v (band tension builds up as the drum draws the band taut)."),
        "amp_name": "kappa", "amp_max": 0.6,
        "bound": "kappa <= 0.6; lambda in [0.4, 1.0] in",
        "params": {"lam_in": (0.4, 1.0)},
        "source": ("Downey, A. et al. (2016), Eng. Struct. 113, 287-298 (self-energizing band: tension "
                   "increases as the drum draws the band taut); Cao et al. (2015), J. Sound Vib. 348."),
    },
    # ------------------------------------------------------------------ pretension
    "power_clamp": {
        "category": "pretension",
        "equation": ("Fc = b [max(0, 1 + lin/(p b))]^p (power-law / Hertz-type clamping stiffness; p = 1 "
                     "is Eq. 4), floor 0.05; p = 1 + amp."),
        "amp_name": "p_minus_1", "amp_max": 2.0,
        "bound": "exponent p <= 3",
        "params": {},
        "source": ("Johnson, K. L. (1985), Contact Mechanics, Cambridge Univ. Press (non-linear contact "
                   "load-approach law); Greenwood, J. A. and Williamson, J. B. P. (1966), Contact of "
                   "nominally flat surfaces, Proc. R. Soc. Lond. A 295, 300-319."),
    },
    "tanh_saturation": {
        "category": "pretension",
        "equation": "Fc = b + F_sat tanh(lin / F_sat), amplitude = 1/F_sat, floor 0.05 (clamping saturation).",
        "amp_name": "inv_Fsat_per_kip", "amp_max": 2.5,
        "bound": "F_sat >= 0.4 kip",
        "params": {},
        "source": ("Lu, L.-Y., Lin, T.-K., Jheng, R.-J. and Wu, H.-H. (2018), Theoretical and experimental "
                   "investigation of position-controlled semi-active friction damper for seismic "
                   "structures, J. Sound Vib. 412, 184-206 (bounded clamping force of a "
                   "position-controlled friction damper)."),
    },
    "actuator_coupling": {
        "category": "pretension",
        "equation": ("Fc = b + lin + K12 d1 d2 (bilinear coupling of the two actuators, same K12 in both "
                     "directions), floor 0.05; K12 = sign * amp."),
        "amp_name": "K12_abs_kip_per_in2", "amp_max": 6000.0,
        "bound": "|K12| <= 6000 kip/in^2 (cross term <= ~1.6x the linear term at d1 = d2 = 0.03 in)",
        "params": {},
        "source": ("Paper (seed) Eq. (4) discussion: coupling between the actuators ignored by design; "
                   "bilinear interaction term as in response-surface regression, Montgomery, D. C. (2017), "
                   "Design and Analysis of Experiments, Wiley."),
    },
    # ------------------------------------------------------------------ asymmetry
    "stribeck_velocity_dir": {
        "category": "asymmetry",
        "equation": "vs_dir = vs exp(sign * amp) in one direction (dir), vs in the other.",
        "amp_name": "abs_ln_ratio", "amp_max": 1.0,
        "bound": "Stribeck-velocity ratio in [e^-1, e^1]",
        "params": {},
        "source": ("Canudas de Wit, C., Olsson, H., Astrom, K. J. and Lischinsky, P. (1995), A new model "
                   "for control systems with friction, IEEE Trans. Autom. Control 40(3), 419-425; "
                   "Johanastrom and Canudas de Wit (2008), IEEE Control Syst. Mag. 28(6), 101-114 "
                   "(direction-dependent LuGre parameters)."),
    },
    "stiffness_dir": {
        "category": "asymmetry",
        "equation": ("sigma0_dir = sigma0 exp(sign * amp) for the direction dir (the other band's "
                     "compliance differs): dFz/dt = sigma0_dir (v - |v| Fz/g), F = Fz + sigma2 v."),
        "amp_name": "abs_ln_ratio", "amp_max": 1.2,
        "bound": "stiffness ratio in [e^-1.2, e^1.2]",
        "params": {},
        "source": ("Downey et al. (2016), Eng. Struct. 113 (taut/slack band asymmetry); Cao et al. (2015), "
                   "J. Sound Vib. 348 (direction-dependent duo-servo stiffness)."),
    },
    "viscous_dir": {
        "category": "asymmetry",
        "equation": "sigma2_dir = sigma2 + amp in the direction dir only: F = Fz + sigma2_dir v.",
        "amp_name": "d_sigma2_kip_s_per_in", "amp_max": 1.5,
        "bound": "extra viscous coefficient <= 1.5 kip s/in",
        "params": {},
        "source": ("Olsson, H., Astrom, K. J., Canudas de Wit, C., Gafvert, M. and Lischinsky, P. (1998), "
                   "Friction models and friction compensation, Eur. J. Control 4(3), 176-195 "
                   "(direction-dependent viscous coefficients)."),
    },
}

CATEGORIES = ["backlash", "residual_static", "transition_shape", "velocity", "actuator_lag",
              "self_energizing", "pretension", "asymmetry"]


def shapes_of(cat):
    return [k for k, s in SHAPES.items() if s["category"] == cat]
