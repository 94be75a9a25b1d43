#include "messages/lcm_bus.h"

#include <arpa/inet.h>
#include <net/if.h>
#include <net/route.h>
#include <netinet/in.h>
#include <sched.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <sstream>

namespace messages {

int64_t now_utime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

bool in_private_network_namespace() {
  std::ifstream dev("/proc/net/dev");
  if (!dev) return false;
  std::string line;
  int devices = 0;
  bool only_lo = true;
  std::getline(dev, line);  // two header lines
  std::getline(dev, line);
  while (std::getline(dev, line)) {
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    std::string name = line.substr(0, colon);
    name.erase(0, name.find_first_not_of(' '));
    ++devices;
    if (name != "lo") only_lo = false;
  }
  return devices > 0 && only_lo;
}

namespace {

std::string errno_text() { return std::strerror(errno); }

void write_file(const std::string& path, const std::string& text) {
  std::ofstream f(path);
  f << text;
}

void bring_loopback_up_with_multicast_route() {
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) throw TransportError("socket() for loopback setup failed: " + errno_text());
  struct ifreq ifr {};
  std::strncpy(ifr.ifr_name, "lo", IFNAMSIZ - 1);
  if (ioctl(fd, SIOCGIFFLAGS, &ifr) < 0 ||
      (ifr.ifr_flags |= IFF_UP | IFF_RUNNING, ioctl(fd, SIOCSIFFLAGS, &ifr) < 0)) {
    const std::string e = errno_text();
    close(fd);
    throw TransportError("cannot bring up loopback in the private network namespace: " + e);
  }
  // ip route add 239.0.0.0/8 dev lo
  struct rtentry route {};
  auto* dst = reinterpret_cast<sockaddr_in*>(&route.rt_dst);
  auto* mask = reinterpret_cast<sockaddr_in*>(&route.rt_genmask);
  dst->sin_family = AF_INET;
  inet_pton(AF_INET, "239.0.0.0", &dst->sin_addr);
  mask->sin_family = AF_INET;
  inet_pton(AF_INET, "255.0.0.0", &mask->sin_addr);
  route.rt_flags = RTF_UP;
  char lo_name[] = "lo";
  route.rt_dev = lo_name;
  if (ioctl(fd, SIOCADDRT, &route) < 0 && errno != EEXIST) {
    const std::string e = errno_text();
    close(fd);
    throw TransportError("cannot route 239.0.0.0/8 to loopback in the private network namespace: " + e);
  }
  close(fd);
}

}  // namespace

void enter_private_network_namespace() {
  if (unshare(CLONE_NEWNET) != 0) {
    // Not root: try an unprivileged user namespace mapped to our own uid.
    const uid_t uid = geteuid();
    const gid_t gid = getegid();
    if (unshare(CLONE_NEWUSER | CLONE_NEWNET) != 0) {
      throw TransportError("cannot create a private network namespace (unshare: " + errno_text() +
                           "); run as root, enable user namespaces, or set transport.private_netns: "
                           "false with a lab URL and transport.lab_network: true");
    }
    write_file("/proc/self/setgroups", "deny");
    write_file("/proc/self/uid_map", std::to_string(uid) + " " + std::to_string(uid) + " 1\n");
    write_file("/proc/self/gid_map", std::to_string(gid) + " " + std::to_string(gid) + " 1\n");
  }
  bring_loopback_up_with_multicast_route();
}

std::unique_ptr<lcm::LCM> open_lcm(const std::string& url, bool lab_network) {
  if (url.empty()) {
    throw TransportError("empty LCM URL: set transport.url in the config (LCM would otherwise "
                         "publish on its default multicast address)");
  }
  const bool multicast = url.rfind("udpm://", 0) == 0 || url.rfind("mpudpm://", 0) == 0;
  if (multicast && !lab_network && !in_private_network_namespace()) {
    throw TransportError("refusing LCM URL '" + url +
                         "' outside a private network namespace: multicast would leave this "
                         "machine. Set transport.private_netns: true, or transport.lab_network: "
                         "true if this is a lab network meant for it");
  }
  auto lc = std::make_unique<lcm::LCM>(url);
  if (!lc->good() || lc->getFileno() < 0) {
    throw TransportError("cannot open LCM URL '" + url + "' (provider failed to start)");
  }
  return lc;
}

}  // namespace messages
