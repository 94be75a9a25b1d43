#pragma once
/// @file hidden_shapes.h
/// Synthetic "measured" BRFD tests with ONE hidden physical effect, for checking a
/// model-discrepancy workflow (`hybridsim diagnose`) blind. Written independently of the
/// project's effect library: every shape below is taken from the friction literature, not from
/// damper/model/effects.h. Units: kip, in, s (actuator load cells in lb).
///
/// A test is built in four layers:
///  1. drum and actuator motion: the paper's semi-active harmonic test (1 in, 0.5 Hz, ramped up
///     over one cycle and down over one cycle, electric actuators moved harmonically during
///     selected drum strokes, Table 3 of ../shared/seed) or an earthquake-like broadband motion
///     (spectral representation, Shinozuka & Deodatis 1991, of a Kanai-Tajimi/Clough-Penzien
///     displacement spectrum under a Jennings-Housner-Tsai 1968 envelope);
///  2. the base force of the project's BrfdModel (LuGre Eqs. 1-3 with the semi-active kinetic
///     friction of Eq. 4 in the Stribeck function of Eq. 5; configs/brfd-semiactive.yaml);
///  3. one hidden effect (HiddenShape), with the equations of damper/synthetic/README.md:
///       backlash               three-stage reversal after Cao et al. (2015): unloading and free
///                              travel with near-zero force, contact stage of rising stiffness
///                              F ∝ ξ², then full friction;
///       actuator_second_order  x_eff'' + 2ζω x_eff' + ω² x_eff = ω² x_cmd between the recorded
///                              (commanded) and the effective actuator positions;
///       actuator_delay         x_eff(t) = x_cmd(t - T);
///       displacement_friction  b, Fs → (1 + k |x|^p)·(b, Fs) (wear/heating, wrap angle);
///       velocity_friction      Dieterich-Ruina rate-and-state factor
///                              1 + a ln(v/v0) + b_rs ln(v0 θ / D_c), aging law for θ;
///       residual_static        stress relaxation of the held band force at rest (standard linear
///                              solid): F → F_stop [(1-ρ) + ρ e^(-t/τ)], wiped by drum travel;
///       viscous                extra F_v = c |v|^α sgn(v) (power law of fluid viscous
///                              dampers, Constantinou & Symans 1993);
///       asymmetry              forward b, Fs × (1+α), backward × (1-α);
///       none                   the base model exactly;
///  4. seeded Gaussian force noise N(0, σ²) (std::mt19937_64; deterministic per seed with the
///     same standard library).
///
/// The ground-truth label is the effect FAMILY (effect_family()), one of the fixed list
///   backlash, actuator_lag, displacement_friction, velocity_friction, residual_static,
///   viscous, asymmetry, none
/// (actuator_second_order and actuator_delay are both family actuator_lag). The label is never
/// written into the measured JSON file (that would leak the answer); write_truth_json() writes
/// it to a separate side-car file.

#include "damper/data/brfd_data.h"
#include "damper/model/brfd_model.h"

#include <cstdint>
#include <string>
#include <vector>

namespace damper::synthetic {

/// The hidden-effect shapes. Their family labels are effect_family().
enum class HiddenShape {
  none,
  backlash,
  actuator_second_order,
  actuator_delay,
  displacement_friction,
  velocity_friction,
  residual_static,
  viscous,
  asymmetry,
};

/// All shapes, in enum order.
const std::vector<HiddenShape>& all_hidden_shapes();
/// Shape name as used in file names and logs ("backlash", "actuator_second_order", ...).
std::string to_string(HiddenShape shape);
/// Parses a shape name; throws std::invalid_argument naming the value and the valid names.
HiddenShape hidden_shape_from_string(const std::string& name);
/// Ground-truth family label: "backlash", "actuator_lag", "displacement_friction",
/// "velocity_friction", "residual_static", "viscous", "asymmetry" or "none".
std::string effect_family(HiddenShape shape);
/// The fixed list of family labels above, in that order.
const std::vector<std::string>& effect_families();

// ---- parameters of each shape (the first field is its "strength") -------------------------

/// Three-stage backlash after each drum reversal (Cao, Downey, Laflamme, Taylor, Ricles 2015,
/// J. Sound Vib. 348:41-56; Downey et al. 2016, Eng. Struct. 113:287-298). With s the drum travel
/// since the reversal, F_r the force at the reversal, ξ = (s - s_f)/s_c clipped to [0, 1]:
///   F = F_r (1 - s/s_u)²₊ + F_e(t)
/// where F_e is the base model restarted at the reversal with a slack band (bristle state 0)
/// and driven by the velocity the band takes up from the drum:
///   stage 1 (s < s_f):           0            unloading of the old band, then free travel, F ≈ 0
///   stage 2 (s_f ≤ s < s_f+s_c): ξ v          re-tensioning, band stiffness rising as σ0 ξ
///   stage 3 (s ≥ s_f + s_c):     v            full friction (the model's own transition)
/// After s_f + s_c the band is fully engaged again (stiffness σ0); it then regains the base
/// model's friction level within the model's elastic transition of about 2 Fs/σ0.
struct BacklashShape {
  double free_travel_in = 0.08;     ///< s_f (strength): free travel after a reversal, in
  double contact_travel_in = 0.06;  ///< s_c: re-tensioning travel, in
  double unload_travel_in = 0.02;   ///< s_u (≤ s_f): travel over which F_r unloads to 0, in
};

/// Second-order electric-actuator response between the recorded (commanded) position x_cmd and
/// the effective position x_eff that tensions the band (mass-spring-damper servo model):
///   x_eff'' + 2 ζ ω_n x_eff' + ω_n² x_eff = ω_n² x_cmd,  x_eff = x', x_eff' = 0 at t = 0.
/// Step response overshoot exp(-ζπ/√(1-ζ²)) for ζ < 1 (Ogata, Modern Control Engineering §5-3).
struct ActuatorSecondOrderShape {
  double natural_freq_hz = 3.0;  ///< f_n = ω_n/2π (strength: lower = stronger), Hz
  double damping_ratio = 0.4;    ///< ζ
};

/// Pure transport delay of the electric actuators: x_eff(t) = x_cmd(t - T) (x' before t = T).
/// (Actuator delay of real-time hybrid tests: Horiuchi et al. 1999, Earthquake Eng. Struct. Dyn.
/// 28:1121-1141.)
struct ActuatorDelayShape {
  double delay_s = 0.08;  ///< T (strength), s
};

/// Friction rising with drum displacement, even in x (wear/heating of the lining, or a change
/// of wrap angle with drum rotation: capstan T2/T1 = e^(μθ), Euler-Eytelwein):
///   b(x) = b (1 + k |x|^p),  Fs(x) = Fs (1 + k |x|^p).
struct DisplacementFrictionShape {
  double gain_per_in_p = 0.3;  ///< k (strength), 1/in^p
  double exponent = 2.0;       ///< p
};

/// Rate-and-state friction factor (Dieterich 1979; Ruina 1983; Marone 1998, Annu. Rev. Earth
/// Planet. Sci. 26:643) multiplying b and Fs:
///   φ = 1 + a ln(v*/v0) + b_rs ln(v0 θ / D_c),  dθ/dt = 1 - v* θ / D_c (aging law),
///   v* = |v| + v_floor.  Steady state: φ_ss = 1 + (a - b_rs) ln(v*/v0):
///   velocity weakening for b_rs > a, strengthening for b_rs < a. φ is clipped to [0.2, 3].
/// Not a Stribeck curve: logarithmic in speed over all speeds, with a memory length D_c.
struct VelocityFrictionShape {
  double a = 0.04;                  ///< direct-effect coefficient a
  double b_rs = 0.14;               ///< evolution coefficient b (strength: b - a weakening)
  double ref_speed_in_per_s = 2.0;  ///< v0
  double memory_length_in = 0.05;   ///< D_c
  double speed_floor_in_per_s = 0.02;  ///< v_floor, regularizes ln at reversals
};

/// Residual static force that relaxes at rest: stress relaxation of the visco-elastic band
/// lining (standard linear solid; Ferry, Viscoelastic Properties of Polymers, ch. 1), wiped by
/// renewed sliding (contact renewal over a slip distance, as in Dieterich's D_c).
/// The measured force is F = F_m + Δ with
///   dΔ/dt = w (-ρ F_m - Δ)/τ - (1 - w) |v| Δ / ℓ,   w = exp(-(v/v_r)²),
/// so after the drum stops (F_m held by the model) F(t) = F_stop [(1-ρ) + ρ e^(-(t-t_stop)/τ)].
struct ResidualStaticShape {
  double relaxed_fraction = 0.5;       ///< ρ (strength), 0..1
  double time_constant_s = 0.25;       ///< τ, s
  double rest_speed_in_per_s = 0.01;   ///< v_r, in/s
  double wipe_travel_in = 0.02;        ///< ℓ, in
};

/// Extra viscous term F_v = c |v|^α sgn(v) (α = 1: linear viscous, e.g. a lubricant film or
/// heated lining; α < 1: the power law of fluid viscous dampers, Constantinou & Symans 1993).
struct ViscousShape {
  double coefficient_kip_s_per_in = 0.25;  ///< c (strength), kip (s/in)^α
  double exponent = 1.0;                   ///< α
};

/// Extra forward/backward asymmetry (self-energizing band brake: forward b, Fs × (1+α),
/// backward × (1-α); Downey et al. 2016).
struct AsymmetryShape {
  double fraction = 0.2;  ///< α (strength), -1 < α < 1
};

/// One hidden effect: `shape` selects which of the parameter blocks is used.
struct HiddenEffect {
  HiddenShape shape = HiddenShape::none;
  BacklashShape backlash;
  ActuatorSecondOrderShape actuator_second_order;
  ActuatorDelayShape actuator_delay;
  DisplacementFrictionShape displacement_friction;
  VelocityFrictionShape velocity_friction;
  ResidualStaticShape residual_static;
  ViscousShape viscous;
  AsymmetryShape asymmetry;
  /// Scales the strength field of the selected shape (1 = the defaults above). For
  /// actuator_second_order it divides the natural frequency.
  double strength_scale = 1.0;
};

// ---- motion ---------------------------------------------------------------------------------

/// One harmonic electric-actuator move: x_i(t) = x'_i - A sin(2π (t - t0)/T) for t0 ≤ t ≤ t0+T
/// (retract first, then extend, back to x'_i), on actuator 1 and/or 2.
struct ActuatorMove {
  double start_s = 0.0;      ///< t0
  double period_s = 1.0;     ///< T
  double amplitude_in = 0.03;
  bool actuator1 = true;
  bool actuator2 = false;
};

/// The semi-active harmonic test of the paper: x(t) = A e(t) sin(2π f t) with the envelope e
/// rising linearly over the first drum cycle and falling over the cycle that ends at
/// motion_end_s, then at rest until duration_s.
struct HarmonicProfile {
  double amplitude_in = 1.0;
  double frequency_hz = 0.5;
  double motion_end_s = 14.0;
  double duration_s = 15.0;
  std::vector<ActuatorMove> moves;  ///< paper_harmonic_moves() for the paper's tests
};

/// Actuator moves of harmonic validation test 1..6 of Table 3 (test 1: actuator one 0.03 in
/// forward, 2: one backward, 3: two forward, 4: two backward, 5: both 0.015 in forward, 6: both
/// backward): one actuator period per drum stroke of that direction (T = 1/(2f)), starting at
/// the stroke's start (forward strokes at (k + 3/4)/f, backward at (k + 1/4)/f) in drum cycles
/// k = 1, 2, 3 (forward) or 2, 3, 4 (backward), as in the measured tests. Throws
/// std::invalid_argument for another number.
std::vector<ActuatorMove> paper_harmonic_moves(int test_number, double frequency_hz = 0.5);

/// Earthquake-like broadband drum displacement: x(t) = s e(t) Σ_k A_k cos(ω_k t + φ_k) with
/// A_k = √(2 S(ω_k) Δω), φ_k uniform (from the seed), S the Kanai-Tajimi spectrum with a
/// Clough-Penzien high-pass, e(t) the Jennings-Housner-Tsai envelope ((t/t1)², 1, e^(-c(t-t2)))
/// with a cosine taper to 0 over the last taper_s before motion_end_s, and s such that
/// max |x| = peak_in (before the residual drift is added). At rest after motion_end_s. The Kanai-Tajimi/Clough-Penzien form is a
/// ground-acceleration spectrum; here it only shapes a broadband drum displacement around
/// dominant_freq_hz (the drift of a building responding to the record).
struct EarthquakeProfile {
  double peak_in = 1.0;
  double dominant_freq_hz = 1.0;      ///< ω_g/2π of Kanai-Tajimi
  double ground_damping = 0.6;        ///< ζ_g
  double highpass_freq_hz = 0.15;     ///< ω_f/2π of the Clough-Penzien filter
  double highpass_damping = 0.6;      ///< ζ_f
  double min_freq_hz = 0.1, max_freq_hz = 4.0;
  int components = 200;
  double rise_end_s = 2.0;            ///< t1
  double strong_end_s = 8.0;          ///< t2
  double decay_per_s = 0.15;          ///< c
  double taper_s = 0.5;               ///< cosine taper to rest before motion_end_s
  /// Residual drift the drum ends at (a smooth step over the taper; the measured earthquake
  /// profiles end displaced, e.g. 0.19 in): the last stroke then ends under load.
  double residual_drift_in = 0.2;
  double motion_end_s = 14.0;
  double duration_s = 15.0;
  std::vector<ActuatorMove> moves{{5.0, 1.0, 0.02, true, true}, {9.0, 1.0, 0.02, true, true}};
};

// ---- generation -----------------------------------------------------------------------------

/// Everything one synthetic test needs.
struct SyntheticSpec {
  enum class Motion { harmonic, earthquake } motion = Motion::harmonic;
  HarmonicProfile harmonic{1.0, 0.5, 14.0, 15.0, paper_harmonic_moves(6)};
  EarthquakeProfile earthquake;
  HiddenEffect effect;
  double noise_std_kip = 0.05;      ///< σ of the Gaussian force noise, kip
  double initial_force_kip = 0.8;   ///< residual band force at t = 0 (the measured tests start
                                    ///< at 0.8-0.9 kip); z0 = bristle_for_force of it
  std::uint64_t seed = 1;
  double dt_s = 1.0 / 1024.0;       ///< sample period of the measured files
  std::string name = "synthetic";   ///< BrfdTest::path (file name stem)
};

/// A generated test, its ground truth and the noise-free layers (for checks).
struct SyntheticTest {
  /// As read_brfd_test() would return it (8-column layout). Actuator forces (lb) are the band
  /// tensions implied by the paper's scaling factors (Table 2, Fig. 6): forward rotation
  /// |F|/C2 on actuator 2 (taut) and |F|/C1 on actuator 1 (slack); backward |F|/C3 on 1 and
  /// |F|/C4 on 2; they do not enter the model.
  BrfdTest test;
  HiddenShape shape = HiddenShape::none;
  std::string label;                ///< effect_family(shape)
  std::vector<double> base_force_kip;    ///< base model on the recorded inputs, no effect
  std::vector<double> clean_force_kip;   ///< with the hidden effect, before noise
  std::vector<double> actuator1_effective_in;  ///< positions the model saw (lag/delay)
  std::vector<double> actuator2_effective_in;
};

/// Generates one test from the base model `params` (configs/brfd-semiactive.yaml; its
/// actuator1/2_initial_in are the recorded x'_1, x'_2). Deterministic per spec.seed. Throws
/// std::invalid_argument naming the field for a parameter out of range.
SyntheticTest generate_synthetic_test(const BrfdParams& params, const SyntheticSpec& spec);

/// Drum displacement (in) and velocity (in/s, exact derivative) of the profile at `time_s`.
/// The earthquake motion draws its phases from `seed`.
void harmonic_motion(const HarmonicProfile& p, const std::vector<double>& time_s,
                     std::vector<double>& disp_in, std::vector<double>& vel_in_per_s);
void earthquake_motion(const EarthquakeProfile& p, std::uint64_t seed,
                       const std::vector<double>& time_s, std::vector<double>& disp_in,
                       std::vector<double>& vel_in_per_s);

/// Second-order actuator filter of ActuatorSecondOrderShape, advanced with classical RK4 over
/// 8 sub-steps per sample (ω_n dt ≤ 0.1 per sub-step for f_n ≤ 130 Hz at 1024 Hz).
class SecondOrderActuator {
 public:
  SecondOrderActuator(double natural_freq_hz, double damping_ratio, double initial_in);
  /// Advances over dt_s with the command held and returns x_eff at the end.
  double step(double command_in, double dt_s);
  double position_in() const { return x_; }
 private:
  double wn_, zeta_, x_, v_ = 0.0;
};

/// Writes the test as JSON in the layout of ../shared/data/brfd/semiactive/*.json:
/// {"data": [[t, x, F, v, x1, x2, F1_lb, F2_lb], ...], "dt", "sampling freq", unit keys}.
/// The velocity column is in in/s (read_brfd_test checks it against d(x)/dt). Requires the
/// 8-column fields (has_actuator_positions). Throws std::runtime_error naming the path on I/O
/// error.
void write_measured_json(const BrfdTest& test, const std::string& path);
/// Side-car ground truth {"label", "shape", "seed", "noise_std_kip", "strength_scale",
/// "motion"} for a blind check.
void write_truth_json(const SyntheticTest& test, const SyntheticSpec& spec, const std::string& path);

}  // namespace damper::synthetic
