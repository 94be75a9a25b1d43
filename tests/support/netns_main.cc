// GoogleTest main for tests that talk LCM over udpm: the whole test process first moves into
// a private network namespace (loopback only, 239.0.0.0/8 routed to lo), so no multicast
// ever leaves the machine (../shared/docs/lcm-transport.md). Child processes inherit it.
#include "messages/lcm_bus.h"

#include <gtest/gtest.h>

#include <iostream>

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (!messages::in_private_network_namespace()) {
    try {
      messages::enter_private_network_namespace();
    } catch (const std::exception& e) {
      std::cerr << "cannot isolate LCM traffic: " << e.what() << "\n";
      return 1;
    }
  }
  return RUN_ALL_TESTS();
}
