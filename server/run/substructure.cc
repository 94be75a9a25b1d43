#include "server/run/substructure.h"

#include "hybrid_lcm/drift_command_t.hpp"
#include "hybrid_lcm/force_feedback_t.hpp"
#include "hybrid_lcm/heartbeat_t.hpp"
#include "hybrid_lcm/run_control_t.hpp"

#include "messages/message_auth.h"
#include "messages/transport.h"

#include <lcm/lcm-cpp.hpp>

#include "common/run_guard.h"

#include <cmath>
#include <map>
#include <cstdio>

namespace server {

using Clock = std::chrono::steady_clock;

InProcessSubstructure::InProcessSubstructure(const damper::BrfdParams& params)
    : prototype_(damper::make_damper_model(params)), actuator_params_(params.electric_actuators) {}

void InProcessSubstructure::start(const std::string&, int num_dampers, double dt_s) {
  bank_ = damper::DamperBank(*prototype_, num_dampers);
  drive_ = damper::ActuatorDrive(actuator_params_, bank_);
  dt_s_ = dt_s;
}

void InProcessSubstructure::exchange(long, double, const Eigen::VectorXd& drum_disp_in,
                                     const Eigen::VectorXd& drum_vel_in_per_s,
                                     SubstructureReply& reply) {
  // Semi-active control: the electric actuators follow the targets (actuator model), the
  // positions reached go into Eq. (4); without targets the bank keeps x'.
  if (const Eigen::MatrixX2d* t = actuator_targets_)
    for (int k = 0; k < bank_.size(); ++k) drive_.follow(bank_, k, (*t)(k, 0), (*t)(k, 1), dt_s_);
  bank_.step(drum_disp_in, drum_vel_in_per_s, dt_s_, reply.force_kip);
  reply.measured_drum_in = drum_disp_in;
  if (reply.actuator_in.rows() == bank_.size()) {
    for (int k = 0; k < bank_.size(); ++k) {
      reply.actuator_in(k, 0) = bank_.input(k).actuator1_in;
      reply.actuator_in(k, 1) = bank_.input(k).actuator2_in;
    }
  }
}

struct LcmSubstructure::Impl {
  LcmLinkSettings settings;
  std::unique_ptr<messages::LcmTransport> lcm;  // handler exceptions come back after lcm_handle
  std::unique_ptr<lcm::LogFile> log;
  std::string run_id;
  int num_dampers = 0;
  hybrid_lcm::drift_command_t command;
  hybrid_lcm::force_feedback_t feedback;
  bool have_feedback = false;
  long expected_step = -1;
  bool substructure_ready = false;
  std::string last_heartbeat_fault;
  std::vector<uint8_t> encode_buffer;
  std::string waiting_on;  ///< channel of the reply being waited for (messages)
  std::unique_ptr<messages::MessageAuth> auth;
  std::unique_ptr<messages::BadMessageLog> bad;
  int64_t sequence = 0;                     ///< of the messages the server publishes
  int64_t last_feedback_sequence = 0;       ///< of the last reply taken
  std::map<std::string, int64_t> heartbeat_sequence;  ///< last heartbeat taken, per sender
  long idle_heartbeats = 0;  ///< heartbeats without a run id (a node that took no START)

  void log_event(const std::string& channel, const void* data, int size) {
    if (!log) return;
    lcm::LogEvent ev;
    ev.eventnum = 0;  // lcm renumbers on write
    ev.timestamp = messages::now_utime();
    ev.channel = channel;
    ev.datalen = size;
    ev.data = const_cast<void*>(data);
    log->writeEvent(&ev);
  }

  template <class T>
  void publish(const std::string& channel, T& msg) {
    try {
      msg.sequence = ++sequence;
      auth->publish(*lcm, channel, msg, encode_buffer);
    } catch (const std::exception& e) {
      throw SubstructureError(e.what());
    }
    log_event(channel, encode_buffer.data(), static_cast<int>(encode_buffer.size()));
  }

  // Handlers run inside messages::LcmTransport's guard: a DecodeError is rethrown by
  // handle_until after lcm_handle has returned, never through liblcm.
  // A bad message is counted and dropped; under policy stop report() throws, and the guard
  // hands the BadMessageError to pump_until after lcm_handle has returned.
  void on_feedback(const messages::RawMessage& m) {
    log_event(m.channel, m.data, static_cast<int>(m.size));
    hybrid_lcm::force_feedback_t msg;
    std::string detail;
    const messages::Received r = messages::check_and_decode(
        m, *auth, [this](const std::string& id) { return id == run_id; }, msg, detail);
    if (r != messages::Received::ok) return bad->report(std::string("FORCE_FEEDBACK/") + messages::to_string(r), detail);
    if (msg.sequence <= last_feedback_sequence)
      return bad->report("FORCE_FEEDBACK/replayed", "sequence " + std::to_string(msg.sequence) +
                                                        " <= last taken " + std::to_string(last_feedback_sequence));
    if (have_feedback || msg.step != expected_step || msg.command_sequence != command.sequence)
      return bad->report("FORCE_FEEDBACK/unbound_reply",
                         "reply for step " + std::to_string(msg.step) + " / command sequence " +
                             std::to_string(msg.command_sequence) + " while " +
                             (have_feedback ? "no command" : "step " + std::to_string(expected_step) + " / command sequence " +
                                                                 std::to_string(command.sequence)) +
                             " is outstanding");
    last_feedback_sequence = msg.sequence;
    feedback = std::move(msg);
    have_feedback = true;
  }

  void on_heartbeat(const messages::RawMessage& m) {
    log_event(m.channel, m.data, static_cast<int>(m.size));
    hybrid_lcm::heartbeat_t hb;
    std::string detail, peeked;
    const messages::Received r = messages::check_and_decode(
        m, *auth, [&](const std::string& id) { peeked = id; return id == run_id; }, hb, detail);
    // An idle node before any START has no run id: it belongs to no run yet, nothing to drop.
    if (r == messages::Received::foreign_run && peeked.empty()) {
      ++idle_heartbeats;
      return;
    }
    if (r != messages::Received::ok) return bad->report(std::string("HEARTBEAT/") + messages::to_string(r), detail);
    auto [last, fresh] = heartbeat_sequence.emplace(hb.sender, hb.sequence);
    if (!fresh) {
      if (hb.sequence <= last->second)
        return bad->report("HEARTBEAT/replayed", "sender '" + hb.sender + "' sequence " + std::to_string(hb.sequence) +
                                                     " <= last taken " + std::to_string(last->second));
      last->second = hb.sequence;
    }
    if (hb.state == hybrid_lcm::heartbeat_t::STATE_READY || hb.state == hybrid_lcm::heartbeat_t::STATE_RUNNING)
      substructure_ready = true;
    if (hb.state == hybrid_lcm::heartbeat_t::STATE_FAULT) last_heartbeat_fault = hb.sender + " reports a fault";
  }

  /// Handles LCM traffic until `done()` or the deadline. Returns false on timeout.
  template <class Pred>
  bool pump_until(Pred done, Clock::time_point deadline) {
    while (!done()) {
      common::throw_if_interrupted();  // SIGINT/SIGTERM (a signal ends the wait with EINTR)
      if (Clock::now() >= deadline) return false;
      bool dispatched = false;
      try {
        dispatched = lcm->handle_until(std::min(deadline, Clock::now() + std::chrono::milliseconds(50)));
      } catch (const messages::TransportError& e) {
        throw SubstructureError("LCM handle() failed on URL '" + settings.url + "': " + e.what());
      } catch (const messages::BadMessageError& e) {  // policy stop
        throw SubstructureError(e.what());
      }
      if (!dispatched && settings.peer_gone) {
        const std::string gone = settings.peer_gone();
        if (!gone.empty())
          throw SubstructureError("substructure stopped answering on LCM channel '" + waiting_on + "': " + gone);
      }
    }
    return true;
  }
};

LcmSubstructure::LcmSubstructure(const LcmLinkSettings& settings) : impl_(std::make_unique<Impl>()) {
  impl_->settings = settings;
  impl_->auth = std::make_unique<messages::MessageAuth>(settings.key);
  impl_->bad = std::make_unique<messages::BadMessageLog>("hybridsim", settings.on_bad_message);
  impl_->lcm = std::make_unique<messages::LcmTransport>(settings.url, settings.lab_network);
  if (!settings.log_path.empty()) {
    impl_->log = std::make_unique<lcm::LogFile>(settings.log_path, "w");
    if (!impl_->log->good()) throw SubstructureError("cannot write LCM log " + settings.log_path);
    // A large stdio buffer keeps log writes to one write() per MiB, off the step's p99.
    std::setvbuf(impl_->log->getFilePtr(), nullptr, _IOFBF, 1 << 20);
  }
  Impl* impl = impl_.get();
  impl_->lcm->subscribe(settings.channels.force_feedback(), [impl](const messages::RawMessage& m) { impl->on_feedback(m); });
  impl_->lcm->subscribe(settings.channels.heartbeat(), [impl](const messages::RawMessage& m) { impl->on_heartbeat(m); });
}

LcmSubstructure::~LcmSubstructure() = default;

void LcmSubstructure::start(const std::string& run_id, int num_dampers, double dt_s) {
  Impl& m = *impl_;
  m.run_id = run_id;
  m.num_dampers = num_dampers;
  m.command.run_id = run_id;
  m.command.num_dampers = num_dampers;
  m.command.drift_in.assign(static_cast<std::size_t>(num_dampers), 0.0);
  m.command.drift_velocity_in_per_s.assign(static_cast<std::size_t>(num_dampers), 0.0);
  m.command.actuator_targets_valid = 0;
  m.command.actuator1_target_in.assign(static_cast<std::size_t>(num_dampers), 0.0);
  m.command.actuator2_target_in.assign(static_cast<std::size_t>(num_dampers), 0.0);
  hybrid_lcm::run_control_t start;
  start.run_id = run_id;
  start.command = hybrid_lcm::run_control_t::COMMAND_START;
  start.num_dampers = num_dampers;
  start.dt_s = dt_s;
  const Clock::time_point deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(m.settings.start_timeout_s));
  m.waiting_on = m.settings.channels.heartbeat();
  // Messages published before the peer subscribes are lost: repeat START until it answers.
  while (!m.substructure_ready) {
    start.utime = messages::now_utime();
    m.publish(m.settings.channels.run_control(), start);
    const Clock::time_point retry =
        std::min<Clock::time_point>(deadline, Clock::now() + std::chrono::milliseconds(100));
    m.pump_until([&] { return m.substructure_ready; }, retry);
    if (!m.substructure_ready && Clock::now() >= deadline) {
      throw SubstructureError("no heartbeat from the substructure on LCM channel '" +
                              m.settings.channels.heartbeat() + "' within " +
                              std::to_string(m.settings.start_timeout_s) + " s of START on '" +
                              m.settings.channels.run_control() + "' (URL " + m.settings.url + ")" +
                              [&]() -> std::string {
                                const auto it = m.bad->counts().find("HEARTBEAT/bad_mac");
                                if (it != m.bad->counts().end())
                                  return "; " + std::to_string(it->second) +
                                         " heartbeats of this run failed the HMAC check: does the substructure hold "
                                         "the run's key (--key-file, transport.key_file)?";
                                if (m.idle_heartbeats > 0)
                                  return "; a substructure is listening (" + std::to_string(m.idle_heartbeats) +
                                         " idle heartbeats) but did not take START: does it hold the run's key "
                                         "(--key-file, transport.key_file)?";
                                return "";
                              }());
    }
  }
}

void LcmSubstructure::exchange(long step, double sim_time_s, const Eigen::VectorXd& drum_disp_in,
                               const Eigen::VectorXd& drum_vel_in_per_s, SubstructureReply& reply) {
  Impl& m = *impl_;
  for (int k = 0; k < m.num_dampers; ++k) {
    m.command.drift_in[k] = drum_disp_in[k];
    m.command.drift_velocity_in_per_s[k] = drum_vel_in_per_s[k];
  }
  m.command.actuator_targets_valid = actuator_targets_ != nullptr;
  if (actuator_targets_) {
    for (int k = 0; k < m.num_dampers; ++k) {
      m.command.actuator1_target_in[k] = (*actuator_targets_)(k, 0);
      m.command.actuator2_target_in[k] = (*actuator_targets_)(k, 1);
    }
  }
  m.command.step = step;
  m.command.sim_time_s = sim_time_s;
  m.expected_step = step;
  m.have_feedback = false;
  m.waiting_on = m.settings.channels.force_feedback();
  const auto sent = Clock::now();
  m.command.utime = messages::now_utime();
  m.publish(m.settings.channels.drift_command(), m.command);
  const Clock::time_point deadline =
      sent + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(m.settings.step_timeout_s));
  if (!m.pump_until([&] { return m.have_feedback; }, deadline)) {
    throw SubstructureError("substructure stopped answering: no force feedback on LCM channel '" +
                            m.settings.channels.force_feedback() + "' for step " +
                            std::to_string(step) + " within " +
                            std::to_string(m.settings.step_timeout_s) + " s" +
                            (m.last_heartbeat_fault.empty() ? "" : " (" + m.last_heartbeat_fault + ")"));
  }
  if (keep_round_trips_)
    round_trip_us_.push_back(std::chrono::duration<double, std::micro>(Clock::now() - sent).count());
  const hybrid_lcm::force_feedback_t& fb = m.feedback;
  if (fb.status != hybrid_lcm::force_feedback_t::STATUS_OK) {
    const char* what = fb.status == hybrid_lcm::force_feedback_t::STATUS_SAFETY_TRIP ? "safety trip" : "fault";
    throw SubstructureError(std::string("substructure ") + what + " at step " + std::to_string(step) +
                            " (channel '" + m.settings.channels.force_feedback() + "'): " + fb.message);
  }
  if (fb.num_dampers != m.num_dampers) {
    throw SubstructureError("force feedback on '" + m.settings.channels.force_feedback() + "' has " +
                            std::to_string(fb.num_dampers) + " dampers, expected " +
                            std::to_string(m.num_dampers));
  }
  for (int k = 0; k < m.num_dampers; ++k) {
    if (!std::isfinite(fb.force_kip[k]) || !std::isfinite(fb.measured_drift_in[k]) ||
        !std::isfinite(fb.actuator1_position_in[k]) || !std::isfinite(fb.actuator2_position_in[k])) {
      throw SubstructureError("force feedback on '" + m.settings.channels.force_feedback() +
                              "' carries a non-finite value at step " + std::to_string(step));
    }
    reply.force_kip[k] = fb.force_kip[k];
    reply.measured_drum_in[k] = fb.measured_drift_in[k];
    if (reply.actuator_in.rows() > k) {
      reply.actuator_in(k, 0) = fb.actuator1_position_in[k];
      reply.actuator_in(k, 1) = fb.actuator2_position_in[k];
    }
  }
}

const messages::BadMessageLog& LcmSubstructure::bad_messages() const { return *impl_->bad; }

void LcmSubstructure::stop(bool abort, const std::string& reason) {
  Impl& m = *impl_;
  hybrid_lcm::run_control_t msg;
  msg.utime = messages::now_utime();
  msg.run_id = m.run_id;
  msg.command = abort ? hybrid_lcm::run_control_t::COMMAND_ABORT : hybrid_lcm::run_control_t::COMMAND_STOP;
  msg.num_dampers = m.num_dampers;
  msg.dt_s = 0.0;
  msg.reason = reason;
  try {
    m.publish(m.settings.channels.run_control(), msg);
  } catch (const std::exception&) {
    // Stopping is best effort: the substructure also exits on its own command watchdog.
  }
  if (m.log) m.log.reset();  // flushes and closes the LCM log
}

}  // namespace server
