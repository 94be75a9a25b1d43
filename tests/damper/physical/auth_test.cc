// Command authentication (damper/physical/command_auth.h, docs/physical.md): the HMAC input
// is what the docs say (a test vector a lab can check its bridge against), and the gate
// rejects forged, tampered, foreign-run, replayed and stale commands, each with its reason.
// The same over LCM against a running brfd-rig is in system_test.cc.
#include "actuator_commands.h"
#include "damper/physical/command_auth.h"
#include "messages/run_key.h"
#include "run_process.h"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cstdio>

namespace {

using damper::physical::CommandGate;
using damper::physical::RunKey;

RunKey key_of(uint8_t first) {
  RunKey k{};
  for (std::size_t i = 0; i < k.size(); ++i) k[i] = static_cast<uint8_t>(first + i);
  return k;
}

hybrid_lcm::actuator_command_t command(int64_t utime, int64_t sequence) {
  return actuator_commands::run_command("run-1", sequence, utime, 0.25);
}

std::string hex(const std::vector<uint8_t>& v) {
  std::string s;
  char b[3];
  for (uint8_t x : v) {
    std::snprintf(b, sizeof b, "%02x", x);
    s += b;
  }
  return s;
}

TEST(CommandAuth, MacInputIsTheDocumentedByteLayoutAndTheTestVectorHolds) {
  const auto c = command(1700000000000000, 7);
  std::vector<uint8_t> bytes;
  damper::physical::command_mac_input(c, bytes);
  // utime 8 + run_id (4 + 5 + NUL) + sequence 8 + 3 doubles 24 + mode 1
  ASSERT_EQ(bytes.size(), 8u + 4u + 6u + 8u + 24u + 1u);
  EXPECT_EQ(hex(bytes),
            "00060a24181e4000"            // utime, big-endian
            "00000006" "72756e2d3100"     // run_id "run-1": length incl. NUL, bytes, NUL
            "0000000000000007"            // sequence
            "3fd0000000000000"            // 0.25
            "3fe4f5c28f5c28f6"            // 0.655
            "3feb63886594af4f"            // 0.8559
            "00");                        // mode RUN
  damper::physical::CommandSigner signer(key_of(0));
  auto signed_cmd = c;
  signer.sign(signed_cmd);
  ASSERT_EQ(signed_cmd.hmac_length, 32);
  std::printf("test vector (key 000102..1f): hmac %s\n", hex(signed_cmd.hmac).c_str());
  // docs/physical.md quotes this value for lab bridges; Python hmac.new(bytes(range(32)), input,
  // hashlib.sha256) gives the same.
  EXPECT_EQ(hex(signed_cmd.hmac), "ef88ff5e94134a558000cdb33da84e4deea0376fbe56a4ddd3dfaecf56b62156");
}

TEST(CommandAuth, GateAcceptsGoodCommandsAndRejectsForgedReplayedStaleAndForeign) {
  const RunKey key = key_of(10);
  damper::physical::CommandSigner signer(key);
  CommandGate gate(key, {"run-1", 0.05, 0.01});
  const int64_t now = 1700000000000000;
  std::string why;

  auto good = command(now - 1000, 1);
  signer.sign(good);
  EXPECT_EQ(gate.check(good, now, why), CommandGate::Verdict::accepted) << why;

  auto forged = command(now - 1000, 2);
  damper::physical::CommandSigner(key_of(99)).sign(forged);  // someone without the run key
  EXPECT_EQ(gate.check(forged, now, why), CommandGate::Verdict::forged);
  EXPECT_NE(why.find("forged"), std::string::npos) << why;

  auto tampered = command(now - 1000, 2);
  signer.sign(tampered);
  tampered.drum_displacement_in = 1.9;  // changed after signing
  EXPECT_EQ(gate.check(tampered, now, why), CommandGate::Verdict::forged);

  auto unsigned_cmd = command(now - 1000, 2);
  EXPECT_EQ(gate.check(unsigned_cmd, now, why), CommandGate::Verdict::forged);

  EXPECT_EQ(gate.check(good, now + 500, why), CommandGate::Verdict::replayed);  // the same bytes again
  EXPECT_NE(why.find("replayed"), std::string::npos) << why;

  auto stale = command(now - 200000, 3);  // 200 ms old, limit 50 ms
  signer.sign(stale);
  EXPECT_EQ(gate.check(stale, now, why), CommandGate::Verdict::stale);
  EXPECT_NE(why.find("stale"), std::string::npos) << why;

  auto future = command(now + 100000, 3);  // 100 ms ahead of the receiver's clock
  signer.sign(future);
  EXPECT_EQ(gate.check(future, now, why), CommandGate::Verdict::stale);

  auto foreign = command(now - 1000, 3);
  foreign.run_id = "run-2";
  signer.sign(foreign);
  EXPECT_EQ(gate.check(foreign, now, why), CommandGate::Verdict::foreign_run);

  auto next = command(now - 1000, 3);
  signer.sign(next);
  EXPECT_EQ(gate.check(next, now, why), CommandGate::Verdict::accepted) << why;
  EXPECT_EQ(gate.last_accepted_sequence(), 3);
  // A lower sequence after a higher one is a replay even with a fresh timestamp and a valid HMAC.
  auto older = command(now - 1000, 2);
  signer.sign(older);
  EXPECT_EQ(gate.check(older, now, why), CommandGate::Verdict::replayed);
}

TEST(RunKey, WrittenWithMode0600ReadBackAndRefusedWhenOthersMayReadIt) {
  const std::string dir = test_support::fresh_temp_dir("key");
  const std::string path = dir + "/run.key";
  const RunKey k = damper::physical::generate_run_key();
  damper::physical::write_key_file(path, k);
  struct stat st {};
  ASSERT_EQ(stat(path.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  EXPECT_EQ(damper::physical::read_key_file(path), k);
  EXPECT_NE(damper::physical::generate_run_key(), k);
  chmod(path.c_str(), 0644);
  EXPECT_THROW(damper::physical::read_key_file(path), damper::physical::KeyFileError);
  test_support::write_text(dir + "/short.key", "abcd\n");
  chmod((dir + "/short.key").c_str(), 0600);
  EXPECT_THROW(damper::physical::read_key_file(dir + "/short.key"), damper::physical::KeyFileError);
}

}  // namespace
