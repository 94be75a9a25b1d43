// reliability_injector: a hostile process on the run's LCM bus (tests/reliability/
// injector_test.cc, README "Reliability"). It listens to the run, and every `--every` drift
// commands of the server (after `--start-after`) injects one message of each class on each
// channel, `--rounds` times:
//   FORCE_FEEDBACK  garbage, another run's reply, a forged reply (999 kip, wrong key), a replay
//                   of the last authentic reply, an early reply for step k+1 (signed with the
//                   run key: only the binding rule can stop it);
//   HEARTBEAT       garbage, another run's FAULT, a forged FAULT, a replay;
//   RUN_CONTROL     garbage, another run's ABORT, a forged ABORT, a replay of START;
//   DRIFT_COMMAND   garbage, another run's command, a forged command (9 in), a replay of the
//                   command just sent;
//   SENSOR_FRAME    (--physical) garbage, another run's frame, a forged frame (999 kip), a replay.
// It writes what it injected, by the kind the receiver must count it as ("CHANNEL/reason"),
// to `--out` as JSON. The run key is read from `--key-file` once the run has written it
// (a key holder is needed for the early replies and to tell the server's commands from
// replays; the forged messages use another key).
#include "hybrid_lcm/drift_command_t.hpp"
#include "hybrid_lcm/force_feedback_t.hpp"
#include "hybrid_lcm/heartbeat_t.hpp"
#include "hybrid_lcm/run_control_t.hpp"
#include "hybrid_lcm/sensor_frame_t.hpp"
#include "messages/message_auth.h"
#include "messages/run_key.h"
#include "messages/transport.h"

#include <CLI/CLI.hpp>

#include <chrono>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <random>

namespace {

using Bytes = std::vector<uint8_t>;
const std::string kForeignRun = "intruder-run";

struct Injector {
  messages::LcmTransport lcm;
  messages::Channels ch;
  std::string key_file;
  bool physical = false;
  long every = 64, start_after = 128, rounds = 24;
  std::string only;  ///< inject only this kind ("" = all)

  std::string ready_file;  ///< written once every subscription is in place
  std::optional<messages::MessageAuth> auth;  ///< the run key, once it exists
  messages::MessageAuth wrong{messages::generate_run_key()};
  std::mt19937 rng{20261123};
  std::string run_id;
  int64_t max_command_sequence = 0;
  long commands_seen = 0, rounds_done = 0;
  Bytes last_feedback, last_heartbeat, last_start, last_frame;
  hybrid_lcm::drift_command_t command;
  std::map<std::string, long> injected;
  Bytes buffer;
  std::chrono::steady_clock::time_point last_command_time = std::chrono::steady_clock::now();

  Injector(const std::string& url) : lcm(url, false) {}

  bool want(const std::string& kind) const { return only.empty() || only == kind; }
  void count(const std::string& kind) { ++injected[kind]; }

  void raw(const std::string& channel, const Bytes& b, const std::string& kind) {
    if (!want(kind) || b.empty()) return;
    lcm.publish(channel, b.data(), b.size());
    count(kind);
  }
  void garbage(const std::string& channel, const std::string& kind) {
    Bytes b(std::uniform_int_distribution<int>(1, 300)(rng));
    for (uint8_t& x : b) x = static_cast<uint8_t>(rng());
    raw(channel, b, kind);
  }
  template <class T>
  void signed_with(const messages::MessageAuth& a, const std::string& channel, T& msg, const std::string& kind) {
    if (!want(kind)) return;
    a.publish(lcm, channel, msg, buffer);
    count(kind);
  }

  void load_key() {
    if (auth) return;
    try {
      auth.emplace(messages::read_key_file(key_file));
    } catch (const std::exception&) {  // not written yet
    }
  }

  void on_command(const messages::RawMessage& m) {
    load_key();
    if (!auth) return;
    hybrid_lcm::drift_command_t c;
    std::string detail;
    std::string id;
    if (!messages::peek_run_id(m.data, m.size, id) || id == kForeignRun) return;
    if (messages::check_and_decode(m, *auth, [](const std::string&) { return true; }, c, detail) !=
        messages::Received::ok)
      return;  // our own forgeries
    if (c.sequence <= max_command_sequence) return;  // our own replays
    max_command_sequence = c.sequence;
    run_id = c.run_id;
    command = c;
    last_command_time = std::chrono::steady_clock::now();
    ++commands_seen;
    if (rounds_done < rounds && commands_seen >= start_after && (commands_seen - start_after) % every == 0) {
      inject(Bytes(m.data, m.data + m.size));
      ++rounds_done;
    }
  }

  void inject(const Bytes& command_bytes) {
    const int64_t k = command.step;
    // FORCE_FEEDBACK (hybridsim counts these)
    garbage(ch.force_feedback(), "FORCE_FEEDBACK/malformed");
    hybrid_lcm::force_feedback_t fb;
    fb.utime = messages::now_utime();
    fb.run_id = kForeignRun;
    fb.step = k;
    fb.num_dampers = command.num_dampers;
    fb.force_kip.assign(static_cast<std::size_t>(command.num_dampers), 999.0);
    fb.measured_drift_in = command.drift_in;
    fb.status = hybrid_lcm::force_feedback_t::STATUS_OK;
    fb.message = "";
    fb.actuator1_position_in = command.actuator1_target_in;
    fb.actuator2_position_in = command.actuator2_target_in;
    fb.sequence = (int64_t{1} << 40) + rounds_done;
    fb.command_sequence = command.sequence;
    signed_with(wrong, ch.force_feedback(), fb, "FORCE_FEEDBACK/foreign_run");
    fb.run_id = run_id;
    signed_with(wrong, ch.force_feedback(), fb, "FORCE_FEEDBACK/bad_mac");
    raw(ch.force_feedback(), last_feedback, "FORCE_FEEDBACK/replayed");
    fb.step = k + 1;  // early: the reply of a command not sent yet, signed with the run key
    fb.sequence = (int64_t{1} << 41) + rounds_done;
    signed_with(*auth, ch.force_feedback(), fb, "FORCE_FEEDBACK/unbound_reply");
    // HEARTBEAT (hybridsim)
    garbage(ch.heartbeat(), "HEARTBEAT/malformed");
    hybrid_lcm::heartbeat_t hb;
    hb.utime = messages::now_utime();
    hb.run_id = kForeignRun;
    hb.sender = "brfd-substructure";
    hb.sequence = (int64_t{1} << 40) + rounds_done;
    hb.state = hybrid_lcm::heartbeat_t::STATE_FAULT;
    signed_with(wrong, ch.heartbeat(), hb, "HEARTBEAT/foreign_run");
    hb.run_id = run_id;
    signed_with(wrong, ch.heartbeat(), hb, "HEARTBEAT/bad_mac");
    raw(ch.heartbeat(), last_heartbeat, "HEARTBEAT/replayed");
    // RUN_CONTROL (brfd-substructure)
    garbage(ch.run_control(), "RUN_CONTROL/malformed");
    hybrid_lcm::run_control_t rc;
    rc.utime = messages::now_utime();
    rc.run_id = kForeignRun;
    rc.command = hybrid_lcm::run_control_t::COMMAND_ABORT;
    rc.num_dampers = command.num_dampers;
    rc.dt_s = 0.0;
    rc.reason = "injected ABORT";
    rc.sequence = max_command_sequence + 1000000;
    signed_with(wrong, ch.run_control(), rc, "RUN_CONTROL/foreign_run");
    rc.run_id = run_id;
    signed_with(wrong, ch.run_control(), rc, "RUN_CONTROL/bad_mac");
    raw(ch.run_control(), last_start, "RUN_CONTROL/replayed");
    // DRIFT_COMMAND (brfd-substructure)
    garbage(ch.drift_command(), "DRIFT_COMMAND/malformed");
    hybrid_lcm::drift_command_t dc = command;
    dc.run_id = kForeignRun;
    for (double& d : dc.drift_in) d = 9.0;
    dc.step = k + 1;
    dc.sequence = max_command_sequence + 1000000;
    signed_with(wrong, ch.drift_command(), dc, "DRIFT_COMMAND/foreign_run");
    dc.run_id = run_id;
    signed_with(wrong, ch.drift_command(), dc, "DRIFT_COMMAND/bad_mac");
    raw(ch.drift_command(), command_bytes, "DRIFT_COMMAND/replayed");
    if (!physical) return;
    // SENSOR_FRAME (brfd-substructure, physical)
    garbage(ch.sensor_frame(), "SENSOR_FRAME/malformed");
    hybrid_lcm::sensor_frame_t f;
    f.utime = messages::now_utime();
    f.run_id = kForeignRun;
    f.sequence = (int64_t{1} << 40) + rounds_done;
    f.command_sequence = 1;
    f.drum_displacement_in = 0.0;
    f.friction_force_kip = 999.0;
    f.actuator1_position_in = f.actuator2_position_in = 0.0;
    f.actuator1_force_lb = f.actuator2_force_lb = 0.0;
    f.rejected_commands = 0;
    f.last_rejection = "";
    signed_with(wrong, ch.sensor_frame(), f, "SENSOR_FRAME/foreign_run");
    f.run_id = run_id;
    signed_with(wrong, ch.sensor_frame(), f, "SENSOR_FRAME/bad_mac");
    raw(ch.sensor_frame(), last_frame, "SENSOR_FRAME/replayed");
  }

  /// Keeps the bytes of the last authentic message of a channel (to replay them later).
  template <class T>
  void keep_if_authentic(const messages::RawMessage& m, Bytes& into, const std::function<bool(const T&)>& also) {
    load_key();
    if (!auth) return;
    T msg;
    std::string detail;
    if (messages::check_and_decode(m, *auth, [](const std::string&) { return true; }, msg, detail) ==
            messages::Received::ok &&
        also(msg))
      into.assign(m.data, m.data + m.size);
  }

  void run() {
    lcm.subscribe(ch.drift_command(), [this](const messages::RawMessage& m) { on_command(m); });
    lcm.subscribe(ch.force_feedback(), [this](const messages::RawMessage& m) {
      keep_if_authentic<hybrid_lcm::force_feedback_t>(m, last_feedback, [](const auto& f) { return f.sequence < (int64_t{1} << 40); });
    });
    lcm.subscribe(ch.heartbeat(), [this](const messages::RawMessage& m) {
      keep_if_authentic<hybrid_lcm::heartbeat_t>(m, last_heartbeat, [](const auto&) { return true; });
    });
    lcm.subscribe(ch.run_control(), [this](const messages::RawMessage& m) {
      keep_if_authentic<hybrid_lcm::run_control_t>(
          m, last_start, [](const auto& r) { return r.command == hybrid_lcm::run_control_t::COMMAND_START; });
    });
    if (physical)
      lcm.subscribe(ch.sensor_frame(), [this](const messages::RawMessage& m) {
        keep_if_authentic<hybrid_lcm::sensor_frame_t>(m, last_frame, [](const auto&) { return true; });
      });
    // Subscribed: say so, so that a test starts the run only now (a fixed sleep could lose START
    // on a loaded machine).
    if (!ready_file.empty()) std::ofstream(ready_file) << "subscribed\n";
    // Until the rounds are done, or the run has been silent for 3 s (it ended), or 120 s.
    const auto t0 = std::chrono::steady_clock::now();
    while (rounds_done < rounds) {
      const auto now = std::chrono::steady_clock::now();
      if (now - t0 > std::chrono::seconds(120)) break;
      if (commands_seen > 0 && now - last_command_time > std::chrono::seconds(3)) break;
      lcm.handle_until(now + std::chrono::milliseconds(50));
    }
  }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"reliability_injector: hostile traffic on a run's LCM bus (tests/reliability)"};
  std::string url, prefix = "BRFD_", key_file, out, only;
  long every = 64, start_after = 128, rounds = 24;
  bool physical = false;
  app.add_option("--url", url)->required();
  app.add_option("--channel-prefix", prefix);
  app.add_option("--key-file", key_file)->required();
  app.add_option("--out", out)->required();
  app.add_option("--every", every);
  app.add_option("--start-after", start_after);
  app.add_option("--rounds", rounds);
  app.add_option("--only", only, "inject only this kind, e.g. FORCE_FEEDBACK/bad_mac");
  app.add_flag("--physical", physical, "also sensor frames");
  std::string ready_file;
  app.add_option("--ready-file", ready_file, "written once the injector is subscribed");
  CLI11_PARSE(app, argc, argv);
  try {
    Injector inj(url);
    inj.ch.prefix = prefix;
    inj.key_file = key_file;
    inj.physical = physical;
    inj.ready_file = ready_file;
    inj.every = every;
    inj.start_after = start_after;
    inj.rounds = rounds;
    inj.only = only;
    inj.run();
    std::ofstream f(out);
    f << "{\"rounds\": " << inj.rounds_done << ", \"commands_seen\": " << inj.commands_seen << ", \"injected\": {";
    bool first = true;
    for (const auto& [kind, n] : inj.injected) {
      f << (first ? "" : ", ") << "\"" << kind << "\": " << n;
      first = false;
    }
    f << "}}\n";
    return f ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "reliability_injector: " << e.what() << "\n";
    return 1;
  }
}
