#pragma once
/// @file bad_message_log.h
/// What every receiver of a run does with a message it cannot trust (README "Reliability"):
/// a malformed, foreign-run, forged (bad HMAC), replayed or unbound (a reply to no outstanding
/// command) message is counted per kind, the first of each kind is said on stderr, and it is
/// dropped. Policy `stop` (transport.on_bad_message) makes the first one end the run instead:
/// report() then throws BadMessageError, or the owner asks stop_reason().
///
/// Kinds are "<CHANNEL>/<reason>", CHANNEL without the run's prefix (FORCE_FEEDBACK,
/// HEARTBEAT, DRIFT_COMMAND, RUN_CONTROL, SENSOR_FRAME, ACTUATOR_COMMAND), reason one of
/// malformed, foreign_run, bad_mac, replayed, unbound_reply.

#include <map>
#include <stdexcept>
#include <string>

namespace messages {

/// A bad message under policy stop.
class BadMessageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The file brfd-substructure writes its counts to in its results folder (--results-dir);
/// hybridsim puts them into summary.json ("bad_messages").
inline const char* kSubstructureMessagesFile = "substructure-messages.json";

enum class BadMessagePolicy { drop, stop };

/// "drop" or "stop" (throws std::invalid_argument otherwise).
BadMessagePolicy parse_bad_message_policy(const std::string& name);

class BadMessageLog {
 public:
  /// `who` prefixes the stderr line ("hybridsim", "brfd-substructure").
  explicit BadMessageLog(std::string who, BadMessagePolicy policy = BadMessagePolicy::drop);

  /// Counts one message of `kind`; the first of a kind is said on stderr with `detail`.
  /// Under policy stop also keeps the first as stop_reason() and, if `throw_on_stop`,
  /// throws BadMessageError (the owner's handler guard carries it out of the dispatch).
  void report(const std::string& kind, const std::string& detail, bool throw_on_stop = true);

  const std::map<std::string, long>& counts() const { return counts_; }
  long total() const;
  BadMessagePolicy policy() const { return policy_; }
  /// Non-empty under policy stop once a bad message came: what it was.
  const std::string& stop_reason() const { return stop_reason_; }

  /// The counts as a JSON object {"KIND": n, ...} (kinds have no characters JSON escapes).
  std::string to_json() const;
  /// Writes to_json() to `path` atomically (common/atomic_file.h); errors said on stderr (the
  /// counts are a report, never a reason to lose the run's other files).
  void write_json_file(const std::string& path) const;
  /// Reads what to_json() wrote (a missing or unreadable file: empty map).
  static std::map<std::string, long> read_json_file(const std::string& path);

 private:
  std::string who_;
  BadMessagePolicy policy_;
  std::map<std::string, long> counts_;
  std::string stop_reason_;
};

}  // namespace messages
