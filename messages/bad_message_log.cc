#include "messages/bad_message_log.h"

#include "common/atomic_file.h"

#include <fstream>
#include <iostream>
#include <iterator>
#include <regex>

namespace messages {

BadMessagePolicy parse_bad_message_policy(const std::string& name) {
  if (name == "drop") return BadMessagePolicy::drop;
  if (name == "stop") return BadMessagePolicy::stop;
  throw std::invalid_argument("bad-message policy must be drop or stop, not '" + name + "'");
}

BadMessageLog::BadMessageLog(std::string who, BadMessagePolicy policy) : who_(std::move(who)), policy_(policy) {}

void BadMessageLog::report(const std::string& kind, const std::string& detail, bool throw_on_stop) {
  long& n = counts_[kind];
  ++n;
  const bool stop = policy_ == BadMessagePolicy::stop;
  if (n == 1)
    std::cerr << who_ << ": " << (stop ? "bad message " : "dropped ") << kind << ": " << detail
              << (stop ? "" : " (counted; said once per kind)") << std::endl;
  if (!stop) return;
  if (stop_reason_.empty()) stop_reason_ = "bad message " + kind + ": " + detail + " (transport.on_bad_message: stop)";
  if (throw_on_stop) throw BadMessageError(stop_reason_);
}

long BadMessageLog::total() const {
  long t = 0;
  for (const auto& kv : counts_) t += kv.second;
  return t;
}

std::string BadMessageLog::to_json() const {
  std::string s = "{";
  bool first = true;
  for (const auto& [kind, n] : counts_) {
    s += (first ? "\"" : ", \"") + kind + "\": " + std::to_string(n);
    first = false;
  }
  return s + "}\n";
}

void BadMessageLog::write_json_file(const std::string& path) const {
  try {
    common::write_file_atomic(path, to_json());
  } catch (const std::exception& e) {
    std::cerr << who_ << ": cannot write the bad-message counts: " << e.what() << std::endl;
  }
}

std::map<std::string, long> BadMessageLog::read_json_file(const std::string& path) {
  std::map<std::string, long> out;
  std::ifstream f(path);
  if (!f) return out;
  const std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  static const std::regex entry("\"([A-Z_]+/[a-z_]+)\"\\s*:\\s*([0-9]+)");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), entry); it != std::sregex_iterator(); ++it)
    out[(*it)[1].str()] = std::stol((*it)[2].str());
  return out;
}

}  // namespace messages
