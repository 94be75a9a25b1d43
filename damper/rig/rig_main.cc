// brfd-rig: emulator of the BRFD lab controller (damper/rig/rig_node.h). Started by
// `hybridsim run` for `damper: mode: physical` with `rig: launch: local`, or by hand.
#include "common/strict_yaml.h"
#include "damper/rig/rig_config.h"
#include "damper/rig/rig_node.h"
#include "messages/node_main.h"

#include <CLI/CLI.hpp>

#include <iostream>

int main(int argc, char** argv) {
  CLI::App app{"brfd-rig: emulator of the BRFD lab controller over LCM (units kip, in, s; load cells lb)"};
  damper::rig::RigNodeOptions o;
  std::string config_path;
  bool check_only = false;
  app.add_option("--config", config_path, "rig config YAML (configs/rig-default.yaml)")->required();
  app.add_flag("--check-config", check_only, "load and check the config, print it, exit (0 ok, 2 bad)");
  app.add_option("--url", o.url, "LCM URL, as the server config's transport.url");
  app.add_option("--channel-prefix", o.channels.prefix, "channel prefix, as transport.channel_prefix");
  app.add_option("--run-id", o.run_id, "accept only this run's commands");
  app.add_option("--key-file", o.key_file, "HMAC key file (64 hex characters, mode 0600)");
  app.add_option("--log-dir", o.log_dir, "folder for rig-commands.csv and rig-summary.json");
  app.add_flag("--lab-network", o.lab_network, "the URL is a lab network: allow multicast outside a netns");
  return messages::run_node_main("brfd-rig", app, argc, argv, [&] {
    o.config = damper::rig::load_rig_config(config_path);
    if (check_only) {
      std::cout << damper::rig::rig_config_to_yaml(o.config);
      return 0;
    }
    if (o.url.empty()) throw std::invalid_argument("--url is required");
    if (o.key_file.empty()) throw std::invalid_argument("--key-file is required: commands are authenticated");
    return damper::rig::run_rig(o);
  });
}
