// Message authentication (messages/message_auth.h, docs/physical.md "Message authentication"):
//  - the primitive is HMAC-SHA256: RFC 4231 test case 2 (a 4-byte key zero-padded is the same
//    HMAC key, RFC 2104 section 2);
//  - the bytes covered are the documented layout (sensor_frame_t written out by hand, field by
//    field, big-endian), and the test vectors quoted in docs/physical.md for every message type
//    are the ones computed here (the test reads the doc: the two cannot drift apart);
//  - no single-bit change of a signed message passes the receive rule (check_and_decode:
//    fingerprint, run id, HMAC, strict decode); another key, or hmac_length other than 32,
//    never verifies; a forged array length is never decoded (no allocation of it);
//  - BadMessageLog counts by kind, round-trips its JSON file, and under policy stop throws
//    naming the first bad message.
#include "hybrid_lcm/drift_command_t.hpp"
#include "hybrid_lcm/force_feedback_t.hpp"
#include "hybrid_lcm/heartbeat_t.hpp"
#include "hybrid_lcm/run_control_t.hpp"
#include "hybrid_lcm/sensor_frame_t.hpp"
#include "messages/bad_message_log.h"
#include "messages/message_auth.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <string>

namespace {

using messages::MessageAuth;
using messages::RunKey;

RunKey counting_key() {  // 00 01 02 .. 1f, the key of docs/physical.md's test vectors
  RunKey k{};
  for (int i = 0; i < 32; ++i) k[static_cast<std::size_t>(i)] = static_cast<uint8_t>(i);
  return k;
}

std::string hex(const uint8_t* p, std::size_t n) {
  std::string s;
  char b[3];
  for (std::size_t i = 0; i < n; ++i) {
    std::snprintf(b, sizeof b, "%02x", p[i]);
    s += b;
  }
  return s;
}
std::string hex(const std::vector<uint8_t>& v) { return hex(v.data(), v.size()); }

constexpr int64_t kUtime = 1700000000000000;

hybrid_lcm::sensor_frame_t vector_sensor_frame() {
  hybrid_lcm::sensor_frame_t f;
  f.utime = kUtime;
  f.run_id = "run-1";
  f.sequence = 7;
  f.command_sequence = 6;
  f.drum_displacement_in = 0.25;
  f.friction_force_kip = 1.25;
  f.actuator1_position_in = 0.655;
  f.actuator2_position_in = 0.8559;
  f.actuator1_force_lb = 12.5;
  f.actuator2_force_lb = -3.0;
  f.rejected_commands = 0;
  f.last_rejection = "";
  f.hmac_length = 0;
  return f;
}
hybrid_lcm::drift_command_t vector_drift_command() {
  hybrid_lcm::drift_command_t c;
  c.utime = kUtime;
  c.run_id = "run-1";
  c.step = 7;
  c.sim_time_s = 7.0 / 1024.0;
  c.num_dampers = 1;
  c.drift_in = {0.25};
  c.drift_velocity_in_per_s = {1.5};
  c.actuator_targets_valid = 0;
  c.actuator1_target_in = {0.655};
  c.actuator2_target_in = {0.8559};
  c.sequence = 8;
  c.hmac_length = 0;
  return c;
}
hybrid_lcm::force_feedback_t vector_force_feedback() {
  hybrid_lcm::force_feedback_t f;
  f.utime = kUtime;
  f.run_id = "run-1";
  f.step = 7;
  f.num_dampers = 1;
  f.force_kip = {1.25};
  f.measured_drift_in = {0.25};
  f.status = hybrid_lcm::force_feedback_t::STATUS_OK;
  f.message = "";
  f.actuator1_position_in = {0.655};
  f.actuator2_position_in = {0.8559};
  f.sequence = 7;
  f.command_sequence = 8;
  f.hmac_length = 0;
  return f;
}
hybrid_lcm::run_control_t vector_run_control() {
  hybrid_lcm::run_control_t r;
  r.utime = kUtime;
  r.run_id = "run-1";
  r.command = hybrid_lcm::run_control_t::COMMAND_ABORT;
  r.num_dampers = 1;
  r.dt_s = 0.0;
  r.reason = "test";
  r.sequence = 9;
  r.hmac_length = 0;
  return r;
}
hybrid_lcm::heartbeat_t vector_heartbeat() {
  hybrid_lcm::heartbeat_t h;
  h.utime = kUtime;
  h.run_id = "run-1";
  h.sender = "brfd-substructure";
  h.sequence = 7;
  h.state = hybrid_lcm::heartbeat_t::STATE_RUNNING;
  h.hmac_length = 0;
  return h;
}

/// The hmac quoted for `type` in docs/physical.md's test-vector table ("| `type` | `hex` |").
std::string documented_hmac(const std::string& type) {
  std::ifstream f(test_paths::source_dir() + "/docs/physical.md");
  const std::string doc((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  const std::string key = "| `" + type + "` | `";
  const auto at = doc.find(key);
  if (at == std::string::npos) return "(not in docs/physical.md)";
  return doc.substr(at + key.size(), 64);
}

template <class T>
std::string signed_hmac(T msg) {
  std::vector<uint8_t> buffer;
  MessageAuth(counting_key()).sign(msg, buffer);
  return hex(msg.hmac);
}

TEST(MessageAuth, PrimitiveIsHmacSha256Rfc4231Case2) {
  RunKey jefe{};
  jefe[0] = 'J', jefe[1] = 'e', jefe[2] = 'f', jefe[3] = 'e';  // zero-padded: the same HMAC key
  const std::string data = "what do ya want for nothing?";
  uint8_t out[32];
  MessageAuth(jefe).mac(reinterpret_cast<const uint8_t*>(data.data()), data.size(), out);
  EXPECT_EQ(hex(out, 32), "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843");
}

TEST(MessageAuth, SensorFrameCoversTheDocumentedBytesAndEveryDocumentedVectorHolds) {
  std::vector<uint8_t> m;
  MessageAuth::mac_input(vector_sensor_frame(), m);
  EXPECT_EQ(hex(m),
            "00060a24181e4000"          // utime
            "00000006" "72756e2d3100"   // run_id "run-1": length incl. NUL, bytes, NUL
            "0000000000000007"          // sequence
            "0000000000000006"          // command_sequence
            "3fd0000000000000"          // drum_displacement_in 0.25
            "3ff4000000000000"          // friction_force_kip 1.25
            "3fe4f5c28f5c28f6"          // actuator1_position_in 0.655
            "3feb63886594af4f"          // actuator2_position_in 0.8559
            "4029000000000000"          // actuator1_force_lb 12.5
            "c008000000000000"          // actuator2_force_lb -3.0
            "00000000"                  // rejected_commands
            "00000001" "00");           // last_rejection "": length 1, the NUL
  const std::map<std::string, std::string> computed{
      {"sensor_frame_t", signed_hmac(vector_sensor_frame())},
      {"drift_command_t", signed_hmac(vector_drift_command())},
      {"force_feedback_t", signed_hmac(vector_force_feedback())},
      {"run_control_t", signed_hmac(vector_run_control())},
      {"heartbeat_t", signed_hmac(vector_heartbeat())}};
  for (const auto& [type, mac] : computed) {
    std::printf("test vector %-17s hmac %s\n", type.c_str(), mac.c_str());
    EXPECT_EQ(documented_hmac(type), mac) << type << ": docs/physical.md quotes another value";
  }
  // The HMAC is over exactly those bytes: the same as mac() of the hand-written layout.
  uint8_t direct[32];
  MessageAuth(counting_key()).mac(m.data(), m.size(), direct);
  EXPECT_EQ(hex(direct, 32), computed.at("sensor_frame_t"));
}

template <class T>
void expect_no_single_bit_change_passes(T msg) {
  MessageAuth auth(counting_key());
  std::vector<uint8_t> signed_bytes;
  auth.sign(msg, signed_bytes);
  ASSERT_TRUE(auth.verify(signed_bytes.data(), signed_bytes.size()));
  long passed = 0, flips = 0;
  for (std::size_t i = 0; i < signed_bytes.size(); ++i) {
    for (int bit = 0; bit < 8; ++bit) {
      std::vector<uint8_t> b = signed_bytes;
      b[i] ^= static_cast<uint8_t>(1u << bit);
      T decoded;
      std::string detail;
      const std::string channel = "CH";
      const messages::RawMessage raw{channel, b.data(), b.size(), 0};
      const auto r = messages::check_and_decode(raw, auth, [](const std::string& id) { return id == "run-1"; },
                                                decoded, detail);
      if (r == messages::Received::ok) ++passed;
      ++flips;
    }
  }
  EXPECT_EQ(passed, 0) << T::getTypeName() << ": " << flips << " single-bit changes";
  // Truncated or extended: never verifies.
  EXPECT_FALSE(auth.verify(signed_bytes.data(), signed_bytes.size() - 1));
  std::vector<uint8_t> longer = signed_bytes;
  longer.push_back(0);
  EXPECT_FALSE(auth.verify(longer.data(), longer.size()));
  // Another key.
  RunKey other = counting_key();
  other[5] ^= 1;
  EXPECT_FALSE(MessageAuth(other).verify(signed_bytes.data(), signed_bytes.size()));
  // Unsigned (hmac_length 0).
  T plain = msg;
  plain.hmac_length = 0;
  plain.hmac.clear();
  std::vector<uint8_t> p(static_cast<std::size_t>(plain.getEncodedSize()));
  plain.encode(p.data(), 0, static_cast<int>(p.size()));
  EXPECT_FALSE(auth.verify(p.data(), p.size()));
}

TEST(MessageAuth, NoSingleBitChangeOfASignedMessageDecodesAndVerifies) {
  expect_no_single_bit_change_passes(vector_sensor_frame());
  expect_no_single_bit_change_passes(vector_drift_command());
  expect_no_single_bit_change_passes(vector_force_feedback());
  expect_no_single_bit_change_passes(vector_run_control());
  expect_no_single_bit_change_passes(vector_heartbeat());
}

TEST(MessageAuth, ForgedHugeArrayLengthIsRefusedBeforeDecoding) {
  // num_dampers = 2^31 - 1 in an unsigned force feedback: LCM's generated decoder resizes
  // force_kip to that length (16 GiB of doubles) before noticing the bytes are missing.
  hybrid_lcm::force_feedback_t f = vector_force_feedback();
  std::vector<uint8_t> b(static_cast<std::size_t>(f.getEncodedSize()));
  f.encode(b.data(), 0, static_cast<int>(b.size()));
  const std::size_t at = 8 + 8 + 4 + 6 + 8;  // fingerprint, utime, run_id "run-1", step
  b[at] = 0x7f, b[at + 1] = 0xff, b[at + 2] = 0xff, b[at + 3] = 0xff;
  const std::string channel = "FF";
  hybrid_lcm::force_feedback_t out;
  std::string detail;
  const auto r = messages::check_and_decode(messages::RawMessage{channel, b.data(), b.size(), 0},
                                            MessageAuth(counting_key()), [](const std::string&) { return true; }, out,
                                            detail);
  EXPECT_EQ(r, messages::Received::bad_mac) << detail;
  EXPECT_TRUE(out.force_kip.empty());
  // Garbage shorter than a fingerprint, and another type's bytes: malformed, named.
  const uint8_t few[3] = {1, 2, 3};
  EXPECT_EQ(messages::check_and_decode(messages::RawMessage{channel, few, 3, 0}, MessageAuth(counting_key()),
                                       [](const std::string&) { return true; }, out, detail),
            messages::Received::malformed);
  hybrid_lcm::heartbeat_t hb = vector_heartbeat();
  std::vector<uint8_t> hbb(static_cast<std::size_t>(hb.getEncodedSize()));
  hb.encode(hbb.data(), 0, static_cast<int>(hbb.size()));
  EXPECT_EQ(messages::check_and_decode(messages::RawMessage{channel, hbb.data(), hbb.size(), 0},
                                       MessageAuth(counting_key()), [](const std::string&) { return true; }, out, detail),
            messages::Received::malformed);
  EXPECT_NE(detail.find("not a force_feedback_t"), std::string::npos) << detail;
}

TEST(BadMessageLog, CountsByKindSaysOnceRoundTripsAndStopsUnderPolicyStop) {
  messages::BadMessageLog drop("test");
  drop.report("FORCE_FEEDBACK/bad_mac", "x");
  drop.report("FORCE_FEEDBACK/bad_mac", "y");
  drop.report("HEARTBEAT/replayed", "z");
  EXPECT_EQ(drop.total(), 3);
  EXPECT_EQ(drop.counts().at("FORCE_FEEDBACK/bad_mac"), 2);
  EXPECT_TRUE(drop.stop_reason().empty());
  const std::string path = ::testing::TempDir() + "/bad-messages.json";
  drop.write_json_file(path);
  EXPECT_EQ(messages::BadMessageLog::read_json_file(path), drop.counts());
  EXPECT_TRUE(messages::BadMessageLog::read_json_file(path + ".missing").empty());

  messages::BadMessageLog stop("test", messages::BadMessagePolicy::stop);
  try {
    stop.report("SENSOR_FRAME/bad_mac", "frame 12");
    FAIL() << "policy stop did not throw";
  } catch (const messages::BadMessageError& e) {
    EXPECT_NE(std::string(e.what()).find("SENSOR_FRAME/bad_mac: frame 12"), std::string::npos) << e.what();
  }
  stop.report("SENSOR_FRAME/replayed", "later", false);  // the first one stays the reason
  EXPECT_NE(stop.stop_reason().find("SENSOR_FRAME/bad_mac"), std::string::npos);
  EXPECT_EQ(stop.total(), 2);
  EXPECT_THROW(messages::parse_bad_message_policy("ignore"), std::invalid_argument);
}

}  // namespace
