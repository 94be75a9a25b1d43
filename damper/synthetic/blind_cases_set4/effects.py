"""Hidden-effect table: category -> shapes -> (weak, strong) parameters.
Equations and references: ../NOTES.md.  Implemented in brfd_model.simulate()."""

SHAPES = {
    'backlash': {
        'deadzone': ({'gap_in': 0.04, 'nsub': 4}, {'gap_in': 0.12, 'nsub': 4}),
        'smooth':   ({'gap_in': 0.06, 'nsub': 4}, {'gap_in': 0.16, 'nsub': 4}),
    },
    'residual_static': {
        'exp_relax': ({'rho': 0.80, 'tau_s': 0.30}, {'rho': 0.50, 'tau_s': 0.25}),
        'log_relax': ({'c': 0.05, 't0_s': 0.02}, {'c': 0.10, 't0_s': 0.02}),
    },
    'actuator_lag': {
        'first_order':  ({'tau_s': 0.06}, {'tau_s': 0.20}),
        'delay':        ({'delay_s': 0.06}, {'delay_s': 0.20}),
        'second_order': ({'fn_hz': 3.0, 'zeta': 0.7}, {'fn_hz': 1.0, 'zeta': 0.8}),
    },
    'asymmetry': {
        'stiffness_dir': ({'k_ratio': 0.72, 'nsub': 2}, {'k_ratio': 0.35, 'nsub': 2}),
        'velocity_dir':  ({'vs_mult': 0.75, 's2_mult': 1.3}, {'vs_mult': 0.5, 's2_mult': 1.8}),
    },
    'velocity': {
        'stribeck_exponent': ({'delta': 1.4}, {'delta': 0.8}),
        'lorentzian':        ({'alpha': 0.35}, {'alpha': 1.0}),
        'log_strengthening': ({'a': 0.02, 'v0': 0.05}, {'a': 0.08, 'v0': 0.05}),
        'frictional_memory': ({'tau_s': 0.03}, {'tau_s': 0.08}),
    },
    'pretension': {
        'hardening':        ({'h': 0.5}, {'h': 0.9}),
        'gain':             ({'k': 0.7}, {'k': 0.4}),
        'static_follows':   ({'lam': 0.6}, {'lam': 1.0}),
        'pretension_loss':  ({'u_max_in': 0.004, 's0_in': 15.0}, {'u_max_in': 0.010, 's0_in': 10.0}),
    },
    'self_energizing': {
        'capstan_position': ({'kappa': 0.12}, {'kappa': 0.30}),
        'band_stretch':     ({'kappa': 0.12}, {'kappa': 0.30}),
        'thermal':          ({'beta': 0.002, 'tau_th_s': 40.0}, {'beta': 0.006, 'tau_th_s': 40.0}),
    },
    'transition_shape': {
        'elastoplastic': ({'beta': 0.25, 'alpha_opp': 1.0, 'nsub': 4}, {'beta': 0.3, 'alpha_opp': 0.0, 'nsub': 4}),
        'dahl_exponent': ({'i': 1.4, 'nsub': 4}, {'i': 2.2, 'nsub': 4}),
        'gms': ({'mix': 0.35, 'alphas': [0.25, 0.25, 0.25, 0.25], 'deltas': [0.026, 0.068, 0.136, 0.255], 'g_ref': 2.0},
                {'mix': 1.0, 'alphas': [0.25, 0.25, 0.25, 0.25], 'deltas': [0.026, 0.068, 0.136, 0.255], 'g_ref': 2.0}),
    },
}
