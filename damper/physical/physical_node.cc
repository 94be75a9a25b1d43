#include "damper/physical/physical_node.h"

#include "damper/physical/realtime.h"
#include "messages/run_key.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

namespace damper::physical {

namespace {

using hybrid_lcm::actuator_command_t;
using hybrid_lcm::force_feedback_t;
using hybrid_lcm::heartbeat_t;
using messages::seconds_to_duration;
using TimePoint = messages::TimePoint;

messages::Duration seconds(double s) { return seconds_to_duration(s); }
double since_s(TimePoint a, TimePoint b) { return messages::seconds_between(a, b); }

const std::vector<std::string>& record_columns() {
  static const std::vector<std::string> c{
      "step", "sim_time_s", "target_in", "compensated_in", "command_in", "measured_in", "force_kip",
      "actuator1_in", "actuator2_in", "actuator1_force_lb", "actuator2_force_lb", "ats_a0", "ats_a1_s",
      "ats_a2_s2", "frame_sequence", "acked_command_sequence", "command_sequence"};
  return c;
}

}  // namespace

using Phase = PhysicalNode::Phase;

PhysicalNode::PhysicalNode(messages::LcmInterface& lcm, const PhysicalNodeOptions& o)
    : PhysicalNode(lcm, o, read_key_file(o.key_file)) {}

PhysicalNode::PhysicalNode(messages::LcmInterface& lcm, const PhysicalNodeOptions& o, const RunKey& key)
    : lcm_(lcm),
      o_(o),
      s_(o.settings),
      period_(1.0 / o.settings.controller_rate_hz),
      created_(lcm.now()),
      safety_(o.settings.limits, period_),
      act_(lcm, o.channels, key, safety_),
      ats_(o.settings.ats, period_),
      endpoint_(lcm, messages::endpoint_settings_of(o, key), *this) {
  act_.count_bad_frames_in(&endpoint_.bad_message_log());
  hold_positions_.actuator1_in = o.model.semiactive.actuator1_initial_in;
  hold_positions_.actuator2_in = o.model.semiactive.actuator2_initial_in;
  safe_ = hold_positions_;
  safe_.drum_in = s_.ramp.safe_drum_in;
  target_.reserve(1 << 19);
  measured_.reserve(1 << 19);
  target_by_command_.reserve(1 << 19);
  frames_seen_.reserve(1 << 19);
  why_.reserve(512);
}

// ---- server side (through the shared endpoint) ------------------------------------------------

int8_t PhysicalNode::heartbeat_state() const {
  if (start_failed_) return heartbeat_t::STATE_FAULT;
  switch (phase_) {
    case Phase::idle:
    case Phase::waiting_rig:
    case Phase::positioning: return heartbeat_t::STATE_IDLE;
    case Phase::running: return steps_done_ == 0 ? heartbeat_t::STATE_READY : heartbeat_t::STATE_RUNNING;
    case Phase::ramp_out: return heartbeat_t::STATE_STOPPED;
    default: return tripped_ ? heartbeat_t::STATE_FAULT : heartbeat_t::STATE_STOPPED;
  }
}

void PhysicalNode::on_run_control(const hybrid_lcm::run_control_t& msg, TimePoint now) {
  if (msg.command == hybrid_lcm::run_control_t::COMMAND_START) {
    if (phase_ != Phase::idle) {
      endpoint_.publish_heartbeat();
      return;
    }
    const std::string& run_id = endpoint_.run_id();
    act_.set_run_id(run_id);
    if (msg.num_dampers != 1) {
      fail_start("physical mode drives one BRFD rig, the run has " + std::to_string(msg.num_dampers) + " dampers", now);
      return;
    }
    if (std::abs(msg.dt_s - period_) > 1e-9 * period_ + 1e-12) {
      std::ostringstream m;
      m << std::setprecision(10) << "the run's dt_s " << msg.dt_s << " s is not the controller period 1/"
        << s_.controller_rate_hz << " s (rig.controller_rate_hz): physical mode sends one actuator command per step";
      fail_start(m.str(), now);
      return;
    }
    endpoint_.prepare_reply(1);
    endpoint_.reply().actuator1_position_in[0] = hold_positions_.actuator1_in;
    endpoint_.reply().actuator2_position_in[0] = hold_positions_.actuator2_in;
    if (!o_.results_dir.empty()) {
      recorder_ = std::make_unique<SampleRecorder>((std::filesystem::path(o_.results_dir) / "physical.csv").string(),
                                                   record_columns());
    }
    phase_ = Phase::waiting_rig;
    rig_deadline_ = now + seconds(s_.watchdogs.rig_start_timeout_s);
    std::cout << "brfd-substructure: physical mode, run " << run_id << ": waiting for sensor frames on '"
              << o_.channels.sensor_frame() << "'" << std::endl;
    endpoint_.publish_heartbeat();
  } else if (msg.command == hybrid_lcm::run_control_t::COMMAND_STOP) {
    if (phase_ == Phase::running && !tripped_) {
      std::cout << "brfd-substructure: STOP (" << msg.reason << "): ramping out to the safe state" << std::endl;
      begin_ramp(Phase::ramp_out, now);
    } else if (phase_ == Phase::idle || phase_ == Phase::waiting_rig) {
      phase_ = Phase::done;
      exit_code_ = 0;
    }
  } else if (msg.command == hybrid_lcm::run_control_t::COMMAND_ABORT) {
    if (!tripped_ && phase_ != Phase::done) {
      aborted_ = true;
      trip("aborted by the server: " + msg.reason, now);
      exit_code_ = 3;
    }
  }
}

void PhysicalNode::on_drift(hybrid_lcm::drift_command_t& cmd, TimePoint) {
  if (phase_ == Phase::idle) return;
  if (tripped_ || phase_ == Phase::ramp_out || phase_ == Phase::hold || phase_ == Phase::safe_ramp) {
    endpoint_.reply_status(cmd.step, tripped_ ? force_feedback_t::STATUS_SAFETY_TRIP : force_feedback_t::STATUS_FAULT,
                           tripped_ ? trip_reason_ : "the run is stopping");
    return;
  }
  if (phase_ != Phase::running) return;
  if (endpoint_.answer_repeat(cmd.step)) return;  // repeated command: answer again
  if ((step_open_ || has_pending_) && cmd.step == current_step_) return;
  if (cmd.num_dampers != 1) {
    endpoint_.reply_status(cmd.step, force_feedback_t::STATUS_FAULT,
                           "drift command has " + std::to_string(cmd.num_dampers) + " dampers, the run started with 1");
    return;
  }
  std::swap(pending_, cmd);  // the endpoint's scratch takes the old one: no allocation
  current_step_ = pending_.step;
  has_pending_ = true;
}

// ---- state machine ------------------------------------------------------------------------------

TimePoint PhysicalNode::next_deadline(TimePoint now) const {
  TimePoint d = std::min(endpoint_.next_heartbeat(), now + std::chrono::milliseconds(20));
  switch (phase_) {
    case Phase::idle: d = std::min(d, created_ + seconds(o_.start_watchdog_s) + std::chrono::milliseconds(1)); break;
    case Phase::waiting_rig: d = std::min(d, now + std::chrono::milliseconds(1)); break;
    case Phase::positioning:
    case Phase::ramp_out:
    case Phase::hold:
    case Phase::safe_ramp: d = std::min(d, next_tick_); break;
    case Phase::running:
      // Just past each watchdog limit (they trip on "longer than").
      d = std::min(d, act_.last_frame_time() + seconds(s_.watchdogs.sensor_frame_timeout_s) + std::chrono::microseconds(1));
      d = std::min(d, endpoint_.last_command_time() + seconds(s_.watchdogs.server_command_timeout_s) +
                          std::chrono::microseconds(1));
      break;
    default: break;
  }
  return d;
}

void PhysicalNode::advance(TimePoint now) {
  if (finished()) return;
  endpoint_.advance(now);  // heartbeat when due
  if (phase_ == Phase::idle && now - created_ > seconds(o_.start_watchdog_s)) {
    std::cerr << "brfd-substructure: no START on '" << o_.channels.run_control() << "' within " << o_.start_watchdog_s
              << " s, exiting\n";
    start_watchdog_fired_ = true;
    quit_ = true;
    return;
  }
  if (act_.frames_received() != frames_checked_) {
    frames_checked_ = act_.frames_received();
    const hybrid_lcm::sensor_frame_t& f = act_.latest_frame();
    if (f.rejected_commands > rejected_seen_) {
      rejected_seen_ = f.rejected_commands;
      std::cerr << "brfd-substructure: the rig reports " << rejected_seen_ << " rejected command(s); last: "
                << f.last_rejection << "\n";
    }
    if (!tripped_ && (phase_ == Phase::positioning || phase_ == Phase::running || phase_ == Phase::ramp_out) &&
        !safety_.frame_ok(f, why_)) {
      trip(why_, now);
    }
  }
  switch (phase_) {
    case Phase::waiting_rig:
      if (act_.frames_received() > 0) {
        const hybrid_lcm::sensor_frame_t& f = act_.latest_frame();
        start_ = hold_positions_;
        start_.drum_in = s_.ramp.safe_drum_in;
        ActuatorSetpoint measured{f.drum_displacement_in, f.actuator1_position_in, f.actuator2_position_in};
        ramp_ = SetpointRamp(measured, start_,
                             SetpointRamp::duration_for(measured, start_, s_.ramp.positioning_s,
                                                        s_.ramp.ramp_velocity_in_per_s,
                                                        0.9 * s_.limits.actuator_velocity_in_per_s));
        phase_ = Phase::positioning;
        phase_start_ = now;
        next_tick_ = now;
        tick_ = 0;
        first_positioning_sequence_ = act_.last_sequence() + 1;
        std::cout << "brfd-substructure: rig answers; positioning from drum " << measured.drum_in << " in to "
                  << start_.drum_in << " in over " << ramp_.duration_s() << " s" << std::endl;
      } else if (now > rig_deadline_) {
        fail_start("no sensor frame from the rig on LCM channel '" + o_.channels.sensor_frame() + "' within " +
                       std::to_string(s_.watchdogs.rig_start_timeout_s) +
                       " s of START (is brfd-rig or the lab bridge running on " + o_.url + "?)",
                   now);
      }
      break;
    case Phase::positioning:
    case Phase::ramp_out:
    case Phase::hold:
    case Phase::safe_ramp:
      if (phase_ == Phase::positioning && since_s(act_.last_frame_time(), now) > s_.watchdogs.sensor_frame_timeout_s &&
          !drain_pending_traffic()) {
        fail_start("sensor frame watchdog: no sensor frame for " +
                       std::to_string(1e3 * since_s(act_.last_frame_time(), now)) + " ms while positioning",
                   now);
        break;
      }
      if (now - next_tick_ > seconds(8 * period_)) next_tick_ = now;  // fell behind: do not burst
      while (now >= next_tick_ && phase_ != Phase::done) {
        tick(now);
        next_tick_ += seconds(period_);
        ++tick_;
      }
      break;
    case Phase::running:
      if (step_open_ && act_.frames_received() > frames_at_publish_) answer_step(now);
      if (!step_open_ && has_pending_) process_command(now);
      if (!tripped_ && since_s(act_.last_frame_time(), now) > s_.watchdogs.sensor_frame_timeout_s &&
          !drain_pending_traffic()) {
        trip("sensor frame watchdog: no sensor frame from the rig on '" + o_.channels.sensor_frame() + "' for " +
                 std::to_string(1e3 * since_s(act_.last_frame_time(), now)) + " ms (limit " +
                 std::to_string(1e3 * s_.watchdogs.sensor_frame_timeout_s) +
                 " ms, watchdogs.sensor_frame_timeout_s): the rig or lab bridge is gone",
             now);
      } else if (!tripped_ && endpoint_.command_silence_s(now) > s_.watchdogs.server_command_timeout_s) {
        trip("server command watchdog: no drift command on '" + o_.channels.drift_command() + "' for " +
                 std::to_string(endpoint_.command_silence_s(now)) + " s (limit " +
                 std::to_string(s_.watchdogs.server_command_timeout_s) + " s, watchdogs.server_command_timeout_s)",
             now);
        exit_code_ = 4;
      }
      break;
    default: break;
  }
}

/// Handles every message already waiting (this process may have been the late one).
/// Returns true if a sensor frame came in.
bool PhysicalNode::drain_pending_traffic() {
  const long before = act_.frames_received();
  lcm_.drain();
  return act_.frames_received() != before;
}

void PhysicalNode::tick(TimePoint now) {
  const double t = tick_ * period_;
  switch (phase_) {
    case Phase::positioning:
      if (!act_.send(ramp_.at(t), actuator_command_t::MODE_RUN, why_)) {
        fail_start("positioning refused by the safety layer: " + why_, now);
        return;
      }
      if (t >= ramp_.duration_s()) {
        const hybrid_lcm::sensor_frame_t& f = act_.latest_frame();
        if (f.command_sequence < first_positioning_sequence_) {
          fail_start("the rig accepted none of our actuator commands (rejected " + std::to_string(f.rejected_commands) +
                         ", last: '" + f.last_rejection + "'): does it hold the same HMAC key?",
                     now);
          return;
        }
        phase_ = Phase::running;
        act_.reset_frame_gap();
        act_.record_frames(&frames_seen_);
        run_start_ = now;
        endpoint_.arm_watchdog(now);
        std::cout << "brfd-substructure: at the start position, ready" << std::endl;
        endpoint_.publish_heartbeat();
      }
      break;
    case Phase::hold:
      if (!act_.send(safety_.last_published(), actuator_command_t::MODE_HOLD, why_)) {
        std::cerr << "brfd-substructure: hold command refused: " << why_ << "\n";
      }
      if (now >= hold_until_) begin_ramp(Phase::safe_ramp, now);
      break;
    case Phase::ramp_out:
    case Phase::safe_ramp: {
      const int8_t mode = phase_ == Phase::ramp_out ? actuator_command_t::MODE_RUN : actuator_command_t::MODE_SAFE_RAMP;
      if (!act_.send(ramp_.at(t), mode, why_)) {
        std::cerr << "brfd-substructure: ramp command refused: " << why_ << "\n";
        phase_ = Phase::done;
        return;
      }
      if (t >= ramp_.duration_s()) {
        act_.send(ramp_.to(), actuator_command_t::MODE_END, why_);  // the run is over
        std::cout << "brfd-substructure: " << (phase_ == Phase::ramp_out ? "ramp-out" : "safe ramp")
                  << " done, drum at " << ramp_.to().drum_in << " in" << std::endl;
        phase_ = Phase::done;
      }
      break;
    }
    default: break;
  }
}

void PhysicalNode::begin_ramp(Phase phase, TimePoint now) {
  const ActuatorSetpoint from = safety_.has_published() ? safety_.last_published() : safe_;
  ramp_ = SetpointRamp(from, safe_, SetpointRamp::duration_for(from, safe_, s_.ramp.ramp_out_s, s_.ramp.ramp_velocity_in_per_s,
                                                                        0.9 * s_.limits.actuator_velocity_in_per_s));
  phase_ = phase;
  next_tick_ = now;
  tick_ = 0;
  step_open_ = has_pending_ = false;
}

void PhysicalNode::process_command(TimePoint now) {
  has_pending_ = false;
  step_open_ = true;
  current_step_ = pending_.step;
  current_sim_time_ = pending_.sim_time_s;
  current_target_ = pending_.drift_in[0];
  if (!safety_.target_ok(current_target_, why_)) {
    trip(why_, now);
    return;
  }
  // ATS adds a correction (a0-1) x + a1 v + a2 a to the target, with v and a from the targets'
  // differences. a includes the fed-back force: when this loop or the rig is descheduled for a
  // few ms, the rig holds a command that leads the target by ~25 ms, the drum stops, the
  // friction force falls by about a kip in one step, and a2 * (jump of a) moved the command by
  // 0.015-0.025 in in one period: 15-25 in/s, a safety trip on a motion of 7 in/s (seen 2 in 20
  // flake-check runs, load 3-11). The correction may change by at most half the drum rate limit
  // per period; the target itself is never shaped, so a bad drift command still trips.
  {
    const double raw_correction = ats_.compensate(current_target_) - current_target_;
    const double max_change = 0.5 * s_.limits.velocity_in_per_s * period_;
    const double change = std::clamp(raw_correction - ats_correction_in_, -max_change, max_change);
    if (change != raw_correction - ats_correction_in_) ++ats_correction_limited_steps_;
    ats_correction_in_ += change;
    current_compensated_ = current_target_ + ats_correction_in_;
  }
  const double r = ramp_factor(static_cast<double>(steps_done_) * period_, s_.ramp.ramp_in_s);
  ActuatorSetpoint sp = start_;
  sp.drum_in = start_.drum_in + r * (current_compensated_ - start_.drum_in);
  if (pending_.actuator_targets_valid) {
    // Semi-active control: the electric actuators go to the controller's targets (blended in
    // like the drum), shaped at the actuator model's velocity limit; the safety layer checks
    // stroke and rate of what results (a target beyond the stroke trips the run).
    const ActuatorSetpoint& last = safety_.has_published() ? safety_.last_published() : start_;
    const double step_max = o_.model.electric_actuators.velocity_limit_in_per_s * period_;
    const double goal1 = start_.actuator1_in + r * (pending_.actuator1_target_in[0] - start_.actuator1_in);
    const double goal2 = start_.actuator2_in + r * (pending_.actuator2_target_in[0] - start_.actuator2_in);
    sp.actuator1_in = last.actuator1_in + std::clamp(goal1 - last.actuator1_in, -step_max, step_max);
    sp.actuator2_in = last.actuator2_in + std::clamp(goal2 - last.actuator2_in, -step_max, step_max);
    if (!std::isfinite(goal1) || !std::isfinite(goal2)) sp.actuator1_in = sp.actuator2_in = goal1 + goal2;
  }
  // What the actuator is meant to do (the tracking check's reference): the target, blended
  // in over the ramp-in like the command.
  current_intended_ = start_.drum_in + r * (current_target_ - start_.drum_in);
  if (!act_.send(sp, actuator_command_t::MODE_RUN, why_)) {  // refused: never published
    trip(why_, now);
    return;
  }
  current_command_ = sp.drum_in;
  frames_at_publish_ = act_.frames_received();
  if (target_by_command_.empty()) first_run_command_ = act_.last_sequence();
  if (target_by_command_.size() < target_by_command_.capacity()) target_by_command_.push_back(current_target_);
}

void PhysicalNode::answer_step(TimePoint now) {
  const hybrid_lcm::sensor_frame_t& f = act_.latest_frame();
  const double measured = f.drum_displacement_in;
  ats_.observe(current_command_, measured);
  target_.push_back(current_target_);
  measured_.push_back(measured);
  if (f.command_sequence < act_.last_sequence()) ++late_frames_;
  if (recorder_) {
    const Eigen::Vector3d& a = ats_.coefficients();
    const double row[] = {static_cast<double>(current_step_), current_sim_time_, current_target_,
                          current_compensated_, current_command_, measured, f.friction_force_kip,
                          f.actuator1_position_in, f.actuator2_position_in, f.actuator1_force_lb,
                          f.actuator2_force_lb, a[0], a[1], a[2], static_cast<double>(f.sequence),
                          static_cast<double>(f.command_sequence), static_cast<double>(act_.last_sequence())};
    recorder_->add_row(row);
  }
  ++steps_done_;
  if (!safety_.tracking_ok(current_intended_, measured, why_)) {
    trip(why_, now);
    return;
  }
  step_open_ = false;
  hybrid_lcm::force_feedback_t& reply = endpoint_.reply();
  reply.force_kip[0] = f.friction_force_kip;
  reply.measured_drift_in[0] = measured;
  reply.actuator1_position_in[0] = f.actuator1_position_in;
  reply.actuator2_position_in[0] = f.actuator2_position_in;
  endpoint_.reply_ok(current_step_);
}

/// A limit or watchdog tripped: answer the open step with the reason, hold, then ramp to
/// the safe state; the run is over.
void PhysicalNode::trip(const std::string& why, TimePoint now) {
  if (tripped_) return;
  tripped_ = true;
  trip_reason_ = why;
  trip_step_ = step_open_ || has_pending_ ? current_step_ : endpoint_.last_answered_step() + 1;
  if (!aborted_) exit_code_ = 4;
  std::cerr << "brfd-substructure: " << (aborted_ ? "ABORT" : "SAFETY TRIP") << " at step " << trip_step_ << ": "
            << why << "\n";
  if (!aborted_ && (step_open_ || has_pending_)) {
    endpoint_.reply_status(current_step_, force_feedback_t::STATUS_SAFETY_TRIP, why);
  }
  step_open_ = has_pending_ = false;
  hold_until_ = now + seconds(s_.ramp.hold_s);
  phase_ = Phase::hold;
  next_tick_ = now;
  tick_ = 0;
  endpoint_.publish_heartbeat();
}

void PhysicalNode::fail_start(const std::string& why, TimePoint now) {
  std::cerr << "brfd-substructure: cannot start the physical run: " << why << "\n";
  start_failed_ = true;
  start_failure_ = why;
  exit_code_ = 2;
  endpoint_.publish_heartbeat();
  if (act_.commands_sent() > 0 && !tripped_) {
    tripped_ = true;
    trip_reason_ = why;
    phase_ = Phase::hold;
    hold_until_ = now + seconds(s_.ramp.hold_s);
    next_tick_ = now;
    tick_ = 0;
  } else {
    phase_ = Phase::done;
  }
}

void PhysicalNode::transport_failed(const std::string& why) {
  std::cerr << "brfd-substructure: " << why << "\n";
  if (!tripped_) {  // nothing more is sent: the transport is what failed
    tripped_ = true;
    trip_reason_ = "transport failure: " + why;
    trip_step_ = step_open_ || has_pending_ ? current_step_ : endpoint_.last_answered_step() + 1;
  }
  exit_code_ = 1;
  quit_ = true;
}

// ---- results ------------------------------------------------------------------------------------

TrackingIndicators PhysicalNode::tracking() const {
  TrackingIndicators t = tracking_indicators(target_, measured_, period_, 0, target_.size());
  const ControllerTimeSeries c = controller_time_series(frames_seen_, target_by_command_, first_run_command_);
  t.delay_ms = cross_correlation_delay_ms(c.target_in, c.measured_in, period_, 0, c.target_in.size(), 128);
  return t;
}

int PhysicalNode::finish() {
  if (start_watchdog_fired_) return 1;
  if (recorder_) recorder_->finish();
  act_.record_frames(nullptr);
  TrackingIndicators t = tracking_indicators(target_, measured_, period_, 0, target_.size());
  // The actuator's delay on the controller's clock (tracking.h): independent of whether
  // this loop kept one step per controller period. The per-step figure is kept beside it.
  const double step_delay_ms = t.delay_ms;
  const ControllerTimeSeries c = controller_time_series(frames_seen_, target_by_command_, first_run_command_);
  t.delay_ms = cross_correlation_delay_ms(c.target_in, c.measured_in, period_, 0, c.target_in.size(), 128);
  const double periods_per_step =
      steps_done_ > 0 ? static_cast<double>(c.target_in.size()) / static_cast<double>(steps_done_) : 0.0;
  const Eigen::Vector3d& a = ats_.identified();
  const double equivalent_delay_ms = a[0] > 0 ? 1e3 * a[1] / a[0] : 0.0;
  if (!target_.empty()) {
    std::cout << "brfd-substructure: tracking: " << format_tracking(t) << "\n"
              << "brfd-substructure: ATS " << (s_.ats.enabled ? "on" : "off (identified only)") << ": a0 " << a[0]
              << ", a1 " << a[1] << " s, a2 " << a[2] << " s^2 (compensates " << equivalent_delay_ms << " ms), "
              << ats_.updates() << " updates; " << late_frames_ << " frames before the rig took our command; longest gap between frames "
              << 1e3 * act_.max_frame_gap_s() << " ms"
              << std::endl;
  }
  std::string status = "ok";
  if (start_failed_) status = "start_failed";
  else if (aborted_) status = "aborted";
  else if (tripped_) status = "tripped";
  if (!o_.results_dir.empty() && phase_ != Phase::idle) {
    const std::filesystem::path dir(o_.results_dir);
    nlohmann::json j;
    j["samples"] = t.samples;
    j["delay_ms"] = t.delay_ms;
    j["nrms_error_pct"] = t.nrms_error_pct;
    j["rms_error_in"] = t.rms_error_in;
    j["peak_error_in"] = t.peak_error_in;
    j["peak_target_in"] = t.peak_target_in;
    j["step_delay_ms"] = step_delay_ms;
    j["controller_periods_per_step"] = periods_per_step;
    j["missing_frames"] = c.missing_frames;
    j["definitions"] = {{"delay_ms", "lag of measured behind target drum displacement at the cross-correlation peak, "
                                     "on the controller's clock (sensor frame numbers; the target of the command in "
                                     "force at each frame)"},
                        {"step_delay_ms", "the same lag counted in server steps (smaller than delay_ms when the loop "
                                          "ran slower than the controller: controller_periods_per_step > 1)"},
                        {"nrms_error_pct", "RMS(measured - target) / max|target| * 100"},
                        {"peak_error_in", "max |measured - target|"}};
    j["ats"] = {{"enabled", s_.ats.enabled}, {"a0", a[0]}, {"a1_s", a[1]}, {"a2_s2", a[2]},
                {"equivalent_delay_ms", equivalent_delay_ms}, {"updates", ats_.updates()},
                {"correction_rate_limited_steps", ats_correction_limited_steps_}};
    j["late_frames"] = late_frames_;
    j["max_sensor_frame_gap_ms"] = 1e3 * act_.max_frame_gap_s();
    j["rig_rejected_commands"] = rejected_seen_;
    std::ofstream(dir / "tracking.json") << std::setw(2) << j << "\n";

    nlohmann::json sj;
    sj["status"] = status;
    sj["reason"] = start_failed_ ? start_failure_ : trip_reason_;
    sj["trip_step"] = tripped_ ? trip_step_ : -1;
    sj["last_answered_step"] = endpoint_.last_answered_step();
    sj["steps"] = steps_done_;
    sj["commands_sent"] = act_.commands_sent();
    sj["last_command_sequence"] = act_.last_sequence();
    sj["frames_received"] = act_.frames_received();
    sj["max_sensor_frame_gap_ms"] = 1e3 * act_.max_frame_gap_s();
    const SafetyLimits& l = s_.limits;
    sj["limits"] = {{"stroke_in", l.stroke_in}, {"velocity_in_per_s", l.velocity_in_per_s},
                    {"actuator_min_in", l.actuator_min_in}, {"actuator_max_in", l.actuator_max_in},
                    {"actuator_force_lb", l.actuator_force_lb}, {"drift_in", l.drift_in},
                    {"tracking_error_in", l.tracking_error_in}};
    sj["watchdogs"] = {{"sensor_frame_timeout_s", s_.watchdogs.sensor_frame_timeout_s},
                       {"server_command_timeout_s", s_.watchdogs.server_command_timeout_s}};
    std::ofstream(dir / "safety.json") << std::setw(2) << sj << "\n";
  }
  if (!o_.results_dir.empty()) endpoint_.bad_messages().write_json_file(
      (std::filesystem::path(o_.results_dir) / messages::kSubstructureMessagesFile).string());
  std::cout << "brfd-substructure: physical run " << status
            << (trip_reason_.empty() ? std::string() : ": " + trip_reason_) << " (" << steps_done_ << " steps, "
            << act_.commands_sent() << " actuator commands)" << std::endl;
  return exit_code_ < 0 ? 0 : exit_code_;
}

int run_physical_substructure(const PhysicalNodeOptions& options) {
  // Before LCM starts its receive thread, so that thread runs at the same real-time priority
  // (otherwise it is the one that waits behind other load, and the loop blocks on its lock).
  enter_realtime(options.settings.realtime_priority, "brfd-substructure");
  messages::LcmTransport lcm(options.url, options.lab_network);
  PhysicalNode node(lcm, options);
  try {
    messages::run_loop(lcm, node);
  } catch (const std::exception& e) {  // transport failure, or a handler threw (after lcm_handle)
    node.transport_failed(std::string("LCM on '") + options.url + "': " + e.what());
  }
  return node.finish();
}

}  // namespace damper::physical
