// brfd-substructure: the damper substructure process. Started by `hybridsim run` (or by hand
// for an external substructure); talks to the server over LCM (damper/substructure/substructure_node.h).
#include "damper/model/brfd_config.h"
#include "damper/physical/physical_node.h"
#include "damper/substructure/substructure_node.h"
#include "messages/node_main.h"
#include "messages/run_key.h"

#include <CLI/CLI.hpp>

#include <iostream>

int main(int argc, char** argv) {
  CLI::App app{"brfd-substructure: BRFD damper substructure over LCM (units kip, in, s)"};
  damper::SubstructureNodeOptions o;
  std::string model_config;
  app.add_option("--model-config", model_config, "damper model YAML (configs/brfd-default.yaml)");
  app.add_option("--url", o.url, "LCM URL, as in the server config's transport.url")->required();
  app.add_option("--channel-prefix", o.channels.prefix, "channel prefix, as transport.channel_prefix");
  app.add_option("--run-id", o.run_id, "answer only this run id");
  app.add_flag("--lab-network", o.lab_network, "the URL is a lab network: allow multicast outside a netns");
  app.add_flag("--echo", o.echo, "answer with zero force at once (LCM round-trip benchmark)");
  app.add_option("--watchdog-s", o.command_watchdog_s, "exit if a started run sends no command this long");
  std::string mode = "virtual";
  damper::physical::PhysicalNodeOptions p;
  std::string physical_config;
  app.add_option("--mode", mode, "virtual (BRFD model) or physical (rig / lab controller, docs/physical.md)")
      ->check(CLI::IsMember({"virtual", "physical"}));
  app.add_option("--physical-config", physical_config, "physical mode: the run config's rig block (physical.yaml)");
  app.add_option("--key-file", p.key_file,
                 "HMAC key file of the run (64 hex characters, mode 0600): every message is signed and verified")
      ->required();
  app.add_option("--results-dir", p.results_dir,
                 "where substructure-messages.json (and in physical mode physical.csv, tracking.json, safety.json) go");
  std::string on_bad_message = "drop";
  app.add_option("--on-bad-message", on_bad_message, "a malformed, foreign, forged or replayed message: drop or stop")
      ->check(CLI::IsMember({"drop", "stop"}));
  return messages::run_node_main("brfd-substructure", app, argc, argv, [&] {
    if (!o.echo) {
      if (model_config.empty()) throw std::invalid_argument("--model-config is required (except with --echo)");
      o.model = damper::load_brfd_params(model_config);
    }
    o.key = messages::read_key_file(p.key_file);
    o.on_bad_message = p.on_bad_message = messages::parse_bad_message_policy(on_bad_message);
    o.results_dir = p.results_dir;
    if (mode == "physical") {
      if (o.echo) throw std::invalid_argument("--echo and --mode physical exclude each other");
      if (physical_config.empty()) throw std::invalid_argument("--mode physical needs --physical-config");
      p.url = o.url;
      p.lab_network = o.lab_network;
      p.channels = o.channels;
      p.run_id = o.run_id;
      p.model = o.model;
      p.settings = damper::physical::load_physical_settings(physical_config);
      return damper::physical::run_physical_substructure(p);
    }
    return damper::run_substructure_node(o);
  });
}
