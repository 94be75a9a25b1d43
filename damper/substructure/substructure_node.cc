#include "damper/substructure/substructure_node.h"

#include "hybrid_lcm/drift_command_t.hpp"
#include "hybrid_lcm/force_feedback_t.hpp"
#include "hybrid_lcm/heartbeat_t.hpp"
#include "hybrid_lcm/run_control_t.hpp"

#include <chrono>
#include <cmath>
#include <iostream>
#include <vector>

namespace damper {

namespace {

using Clock = std::chrono::steady_clock;

class Node {
 public:
  explicit Node(const SubstructureNodeOptions& o) : o_(o), lcm_(messages::open_lcm(o.url, o.lab_network)) {
    run_id_ = o.run_id;
    lcm_->subscribe(o.channels.run_control(), &Node::on_control, this);
    lcm_->subscribe(o.channels.drift_command(), &Node::on_command, this);
  }

  int run() {
    auto next_heartbeat = Clock::now();
    while (exit_code_ < 0) {
      const auto now = Clock::now();
      if (now >= next_heartbeat) {
        publish_heartbeat();
        next_heartbeat = now + std::chrono::duration_cast<Clock::duration>(
                                   std::chrono::duration<double>(o_.heartbeat_period_s));
      }
      if (started_ && now - last_command_ > std::chrono::duration<double>(o_.command_watchdog_s)) {
        std::cerr << "brfd-substructure: no drift command on '" << o_.channels.drift_command() << "' for "
                  << o_.command_watchdog_s << " s: the server is gone, exiting\n";
        return 1;
      }
      if (lcm_->handleTimeout(20) < 0) {
        std::cerr << "brfd-substructure: LCM handle failed on '" << o_.url << "'\n";
        return 1;
      }
    }
    return exit_code_;
  }

 private:
  template <class T>
  void publish(const std::string& channel, const T& msg) {
    const int size = msg.getEncodedSize();
    buffer_.resize(static_cast<std::size_t>(size));
    msg.encode(buffer_.data(), 0, size);
    lcm_->publish(channel, buffer_.data(), static_cast<unsigned>(size));
  }

  void publish_heartbeat() {
    hybrid_lcm::heartbeat_t hb;
    hb.utime = messages::now_utime();
    hb.run_id = run_id_;
    hb.sender = "brfd-substructure";
    hb.sequence = heartbeat_sequence_++;
    hb.state = !started_ ? hybrid_lcm::heartbeat_t::STATE_IDLE
               : steps_ == 0 ? hybrid_lcm::heartbeat_t::STATE_READY
                             : hybrid_lcm::heartbeat_t::STATE_RUNNING;
    publish(o_.channels.heartbeat(), hb);
  }

  void on_control(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
    hybrid_lcm::run_control_t msg;
    try {
      msg = messages::decode<hybrid_lcm::run_control_t>(*rbuf, channel);
    } catch (const messages::DecodeError& e) {
      std::cerr << "brfd-substructure: " << e.what() << "\n";
      return;
    }
    if (!run_id_.empty() && msg.run_id != run_id_) return;
    if (msg.command == hybrid_lcm::run_control_t::COMMAND_START) {
      if (!started_) {
        run_id_ = msg.run_id;
        if (msg.num_dampers < 1 || msg.num_dampers > 64 || !(msg.dt_s > 0.0 && msg.dt_s < 1.0)) {
          std::cerr << "brfd-substructure: START on '" << channel << "' has num_dampers "
                    << msg.num_dampers << " and dt_s " << msg.dt_s << ": out of range, ignored\n";
          return;
        }
        models_.assign(static_cast<std::size_t>(msg.num_dampers), BrfdModel(o_.model));
        dt_s_ = msg.dt_s;
        feedback_.run_id = run_id_;
        feedback_.num_dampers = msg.num_dampers;
        feedback_.force_kip.assign(models_.size(), 0.0);
        feedback_.measured_drift_in.assign(models_.size(), 0.0);
        started_ = true;
        last_command_ = Clock::now();
      }
      publish_heartbeat();  // the server waits for this before the first step
    } else if (msg.command == hybrid_lcm::run_control_t::COMMAND_STOP) {
      exit_code_ = 0;
    } else if (msg.command == hybrid_lcm::run_control_t::COMMAND_ABORT) {
      std::cerr << "brfd-substructure: run aborted by the server: " << msg.reason << "\n";
      exit_code_ = 3;
    }
  }

  void on_command(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
    hybrid_lcm::drift_command_t cmd;
    try {
      cmd = messages::decode<hybrid_lcm::drift_command_t>(*rbuf, channel);
    } catch (const messages::DecodeError& e) {
      std::cerr << "brfd-substructure: " << e.what() << "\n";
      return;
    }
    if (!started_ || cmd.run_id != run_id_) return;
    last_command_ = Clock::now();
    if (cmd.step == last_step_) {  // a repeated command: answer again, do not step twice
      publish(o_.channels.force_feedback(), feedback_);
      return;
    }
    feedback_.step = cmd.step;
    feedback_.status = hybrid_lcm::force_feedback_t::STATUS_OK;
    feedback_.message.clear();
    if (cmd.num_dampers != static_cast<int>(models_.size())) {
      fault("drift command on '" + channel + "' has " + std::to_string(cmd.num_dampers) +
            " dampers, the run started with " + std::to_string(models_.size()));
      return;
    }
    for (std::size_t k = 0; k < models_.size(); ++k) {
      const double d = cmd.drift_in[k], v = cmd.drift_velocity_in_per_s[k];
      if (!std::isfinite(d) || !std::isfinite(v) || std::abs(d) > o_.max_drum_displacement_in ||
          std::abs(v) > o_.max_drum_velocity_in_per_s) {
        fault("drift command step " + std::to_string(cmd.step) + " damper " + std::to_string(k + 1) +
              ": drum displacement " + std::to_string(d) + " in / velocity " + std::to_string(v) +
              " in/s outside the limits +-" + std::to_string(o_.max_drum_displacement_in) + " in, +-" +
              std::to_string(o_.max_drum_velocity_in_per_s) + " in/s");
        return;
      }
    }
    for (std::size_t k = 0; k < models_.size(); ++k) {
      DamperInput in;
      in.drum_disp_in = cmd.drift_in[k];
      in.drum_vel_in_per_s = cmd.drift_velocity_in_per_s[k];
      in.actuator1_in = o_.model.semiactive.actuator1_initial_in;
      in.actuator2_in = o_.model.semiactive.actuator2_initial_in;
      feedback_.force_kip[k] = o_.echo ? 0.0 : models_[k].step(in, dt_s_);
      feedback_.measured_drift_in[k] = cmd.drift_in[k];
    }
    last_step_ = cmd.step;
    ++steps_;
    feedback_.utime = messages::now_utime();
    publish(o_.channels.force_feedback(), feedback_);
  }

  void fault(const std::string& why) {
    std::cerr << "brfd-substructure: " << why << "\n";
    feedback_.status = hybrid_lcm::force_feedback_t::STATUS_FAULT;
    feedback_.message = why;
    feedback_.utime = messages::now_utime();
    publish(o_.channels.force_feedback(), feedback_);
  }

  SubstructureNodeOptions o_;
  std::unique_ptr<lcm::LCM> lcm_;
  std::string run_id_;
  std::vector<BrfdModel> models_;
  hybrid_lcm::force_feedback_t feedback_;
  std::vector<uint8_t> buffer_;
  double dt_s_ = 0.0;
  bool started_ = false;
  long steps_ = 0;
  int64_t last_step_ = -1;
  int64_t heartbeat_sequence_ = 0;
  int exit_code_ = -1;
  Clock::time_point last_command_ = Clock::now();
};

}  // namespace

int run_substructure_node(const SubstructureNodeOptions& options) {
  Node node(options);
  return node.run();
}

}  // namespace damper
