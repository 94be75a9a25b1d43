#include "damper/fit/predict.h"

#include "common/gnuplot.h"
#include "damper/fit/band_brake_fit.h"
#include "damper/fit/validate.h"

#include "damper/model/brfd_config.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace damper {

std::optional<double> first_actuator_motion_s(const BrfdTest& test, double threshold_in) {
  if (!test.has_actuator_positions || test.size() == 0) return std::nullopt;
  const double x1 = test.actuator1_in[0], x2 = test.actuator2_in[0];
  for (std::size_t i = 0; i < test.size(); ++i) {
    if (std::abs(test.actuator1_in[i] - x1) > threshold_in ||
        std::abs(test.actuator2_in[i] - x2) > threshold_in)
      return test.time_s[i];
  }
  return std::nullopt;
}

std::string metrics_line(const ErrorMetrics& m) {
  std::ostringstream o;
  o << std::setprecision(4) << "nrmse=" << m.nrmse_std << " rmse_kip=" << m.rmse_kip
    << " nrmse_range=" << m.nrmse_range;
  return o.str();
}

namespace {


}  // namespace

std::string plot_prediction(const std::string& csv_path, const std::string& png_path,
                            const std::string& title, double t0, double t1, bool has_act) {
  const std::string gp_path = png_path.substr(0, png_path.size() - 4) + ".gp";
  {
    std::ofstream gp(gp_path);
    if (!gp) return "cannot write gnuplot script " + gp_path;
    gp << "set terminal pngcairo noenhanced size 1500,1100 font ',10'\n"
       << "set output " << common::gnuplot_quote(png_path) << "\n"
       << "set datafile separator ','\n"
       << "set key autotitle columnhead\n"
       << "set grid\n"
       << "set multiplot layout " << (has_act ? 3 : 2) << ",1 title " << common::gnuplot_quote(title) << "\n"
       << "set object 1 rect from " << t0 << ", graph 0 to " << t1
       << ", graph 1 fc rgb '#e8f0ff' fs solid 1.0 behind\n"
       << "set label 1 'fit window (passive)' at " << t0 << ", graph 0.95 offset 1,0\n"
       << "set xlabel 'time (s)'\nset ylabel 'damper force (kip)'\n"
       << "plot " << common::gnuplot_quote(csv_path) << " u 1:6 w l lw 1.5 lc rgb '#000000' t 'measured', "
       << "'' u 1:7 w l lw 1.5 lc rgb '#d62728' t 'predicted'\n"
       << "unset object 1\nunset label 1\n";
    if (has_act) {
      gp << "set ylabel 'actuator position (in)'\n"
         << "plot " << common::gnuplot_quote(csv_path) << " u 1:4 w l t 'x_1 (actuator 1)', '' u 1:5 w l t 'x_2 (actuator 2)'\n";
    }
    gp << "set xlabel 'drum displacement (in)'\nset ylabel 'damper force (kip)'\n"
       << "plot " << common::gnuplot_quote(csv_path) << " u 2:6 w l lw 1 lc rgb '#000000' t 'measured', "
       << "'' u 2:7 w l lw 1 lc rgb '#d62728' t 'predicted'\n"
       << "unset multiplot\n";
  }
  return common::run_gnuplot(gp_path);
}

PredictResult run_predict(const PredictOptions& opt) {
  auto log = [&opt](const std::string& s) {
    if (opt.log) opt.log(s);
  };
  PredictResult r;
  BrfdParams params = opt.config_path.empty() ? BrfdParams{} : load_brfd_params(opt.config_path);
  const BrfdTest test = read_brfd_test(opt.test_path, opt.read);
  r.test_name = test.name();
  for (const std::string& note : test.notes) log(note);

  if (test.has_actuator_positions && opt.initial_positions_from_test) {
    params.semiactive.actuator1_initial_in = test.actuator1_in[0];
    params.semiactive.actuator2_initial_in = test.actuator2_in[0];
    params.band_brake.actuator1_initial_in = test.actuator1_in[0];
    params.band_brake.actuator2_initial_in = test.actuator2_in[0];
    std::ostringstream o;
    o << std::setprecision(6) << "x'_1 = " << test.actuator1_in[0] << " in, x'_2 = "
      << test.actuator2_in[0] << " in (actuator positions at t = 0)";
    log(o.str());
  }

  r.first_actuator_motion_s = first_actuator_motion_s(test, opt.actuator_motion_threshold_in);
  const double t_end = test.time_s.back() + test.dt_s;
  if (r.first_actuator_motion_s) {
    std::ostringstream o;
    o << "first electric actuator motion (> " << opt.actuator_motion_threshold_in
      << " in from the t = 0 position) at t = " << *r.first_actuator_motion_s << " s";
    log(o.str());
  } else {
    log(test.has_actuator_positions ? "electric actuators never move in this test"
                                     : "no actuator position columns: actuators held (passive test)");
  }

  if (opt.fit) {
    IdentificationOptions io = opt.identification;
    if (opt.fit_window_s) {
      io.t0_s = opt.fit_window_s->first;
      io.t1_s = opt.fit_window_s->second;
      if (!(io.t1_s > io.t0_s))
        throw std::invalid_argument("--fit-window: T1 must be greater than T0");
      if (r.first_actuator_motion_s && io.t1_s > *r.first_actuator_motion_s) {
        std::ostringstream o;
        o << "warning: the fit window ends at " << io.t1_s << " s, after the first actuator motion at "
          << *r.first_actuator_motion_s << " s: it includes actuated (non-passive) data";
        log(o.str());
      }
    } else {
      io.t0_s = test.time_s.front();
      io.t1_s = r.first_actuator_motion_s ? *r.first_actuator_motion_s : t_end;
    }
    if (params.kind == DamperKind::band_brake) {
      // Band brake: the same passive window, its own identification (damper/fit/band_brake_fit.h).
      const std::size_t b = index_at_time(test, io.t0_s);
      const std::size_t e = std::isfinite(io.t1_s) ? index_at_time(test, io.t1_s) : test.size();
      BandBrakeFitOptions bo;
      bo.eq4_gains_kip_per_in = paper_eq4_gains_kip_per_in();
      const BandBrakeFitResult bf = identify_band_brake({{&test, b, e, 1.0}}, params.band_brake, bo);
      r.identification.params = params;
      r.identification.params.band_brake = bf.params;
      const BandBrakeReplay rp = replay_band_brake(bf.params, test, b, e);
      std::vector<double> full(test.size(), 0.0);
      std::copy(rp.force_kip.begin(), rp.force_kip.end(), full.begin() + static_cast<long>(b));
      r.identification.residual = force_error(test.force_kip, full, b, e);
      r.identification.t0_s = test.time_s[b];
      r.identification.t1_s = e < test.size() ? test.time_s[e] : t_end;
      r.identification.evaluations = bf.evaluations;
      r.identification.algorithm = bf.algorithm;
    } else {
      r.identification = identify_lugre(test, params, io);
    }
    r.fitted = true;
    params = r.identification.params;
    r.fit_t0_s = r.identification.t0_s;
    r.fit_t1_s = r.identification.t1_s;
    std::ostringstream o;
    o << std::setprecision(5) << "fit window: " << r.fit_t0_s << ":" << r.fit_t1_s << " s ("
      << (opt.fit_window_s ? "--fit-window" : (r.first_actuator_motion_s ? "before the first actuator motion" : "whole test"))
      << ")";
    log(o.str());
    log(params.kind == DamperKind::band_brake ? describe(params.band_brake) : describe(r.identification));
  } else {
    r.fit_t0_s = r.fit_t1_s = test.time_s.front();
    log("--no-fit: using the config's parameters as they are");
  }
  r.params = params;

  r.time_s = test.time_s;
  r.measured_kip = test.force_kip;
  r.predicted_kip = replay_force_kip(params, test, 0, test.size(), opt.identification.replay);
  r.metrics = force_error(r.measured_kip, r.predicted_kip, 0, test.size());
  // A finite file can still give a meaningless answer (a 1e300 kip force overflows the
  // error sums): refuse it as input, never print nrmse=inf as a result.
  for (std::size_t i = 0; i < r.predicted_kip.size(); ++i) {
    if (!std::isfinite(r.predicted_kip[i])) {
      throw BrfdDataError(test.path + ": the predicted force is not finite from row " + std::to_string(i) +
                          " on (t = " + std::to_string(test.time_s[i]) +
                          " s): the test's values are outside the model's physical range");
    }
  }
  if (!std::isfinite(r.metrics.rmse_kip) || !std::isfinite(r.metrics.nrmse_std) ||
      !std::isfinite(r.metrics.nrmse_range)) {
    std::size_t worst = 0;
    for (std::size_t i = 1; i < test.size(); ++i)
      if (std::abs(test.force_kip[i]) > std::abs(test.force_kip[worst])) worst = i;
    std::ostringstream o;
    o << test.path << ": the error metrics are not finite: measured force " << test.force_kip[worst]
      << " kip at row " << worst << " is outside any physical range";
    throw BrfdDataError(o.str());
  }
  const std::size_t after = index_at_time(test, r.fit_t1_s);
  if (r.fitted && after + 100 < test.size())
    r.metrics_after_fit = force_error(r.measured_kip, r.predicted_kip, after, test.size());

  if (!opt.out_dir.empty()) {
    std::filesystem::create_directories(opt.out_dir);
    const std::string base = (std::filesystem::path(opt.out_dir) / (r.test_name + "_predict")).string();
    r.csv_path = base + ".csv";
    std::ofstream csv(r.csv_path);
    if (!csv) throw std::runtime_error("cannot write " + r.csv_path);
    csv << "time_s,drum_disp_in,drum_vel_in_per_s,actuator1_in,actuator2_in,measured_force_kip,"
           "predicted_force_kip,kinetic_friction_kip\n";
    csv << std::setprecision(8);
    BrfdModel model(params);
    const BandBrakeModel band(params.band_brake);
    const bool is_band = params.kind == DamperKind::band_brake;
    for (std::size_t i = 0; i < test.size(); ++i) {
      const DamperInput in = input_at(test, i, params);
      double fc = 0.0;
      if (is_band) {
        const BandTensions t = band.tensions(in);
        fc = in.drum_vel_in_per_s >= 0.0 ? t.fc_fwd_kip : t.fc_bwd_kip;
      } else {
        fc = model.kinetic_friction_kip(in);
      }
      csv << test.time_s[i] << ',' << in.drum_disp_in << ',' << in.drum_vel_in_per_s << ','
          << in.actuator1_in << ',' << in.actuator2_in << ',' << test.force_kip[i] << ','
          << r.predicted_kip[i] << ',' << fc << '\n';
    }
    csv.close();
    r.config_out_path = base + "_config.yaml";
    std::ofstream yaml(r.config_out_path);
    if (!yaml) throw std::runtime_error("cannot write " + r.config_out_path);
    yaml << "# Effective damper parameters of `hybridsim damper predict` on " << test.path << "\n";
    if (r.fitted)
      yaml << "# LuGre parameters and b identified on " << r.fit_t0_s << ":" << r.fit_t1_s << " s\n";
    yaml << brfd_params_to_yaml(params);
    log("wrote " + r.csv_path + " and " + r.config_out_path);
    if (opt.figure) {
      r.png_path = base + ".png";
      std::ostringstream title;
      title << std::setprecision(4) << r.test_name << " (" << to_string(params.kind) << "): "
            << metrics_line(r.metrics);
      r.figure_warning = plot_prediction(r.csv_path, r.png_path, title.str(), r.fit_t0_s,
                                         r.fit_t1_s, test.has_actuator_positions);
      if (r.figure_warning.empty()) log("wrote " + r.png_path);
      else log("warning: " + r.figure_warning);
    }
  }
  if (r.fitted && r.metrics_after_fit.samples > 0)
    log("after the fit window only: " + metrics_line(r.metrics_after_fit));
  return r;
}

}  // namespace damper
