#include "server/batch/batch_set.h"

#include "common/number_format.h"
#include "server/batch/batch_files.h"
#include "server/run/run_config.h"
#include "structure/shear_building.h"

namespace server::batch_internal {

namespace fs = std::filesystem;
using nlohmann::json;

json manifest_json(const BatchSet& b) {
  json j;
  j["config"] = b.config;
  j["records"] = b.records_spec;
  j["name"] = b.name;
  j["stories"] = b.stories;
  j["dampers"] = b.dampers;
  j["duration_s"] = b.duration_s;
  json recs = json::array();
  for (std::size_t i = 0; i < b.records.size(); ++i) {
    const BatchRecord& r = b.records[i];
    recs.push_back({{"index", i}, {"label", r.label}, {"record", r.shown}, {"path", r.path}, {"scale", r.scale}});
  }
  j["set"] = recs;
  return j;
}

BatchSet manifest_from_json(const json& j) {
  BatchSet b;
  b.config = j.at("config").get<std::string>();
  b.records_spec = j.at("records").get<std::string>();
  b.name = j.value("name", "");
  b.stories = j.at("stories").get<int>();
  b.dampers = j.at("dampers").get<int>();
  b.duration_s = j.value("duration_s", 0.0);
  for (const json& r : j.at("set")) {
    BatchRecord rec;
    rec.label = r.at("label").get<std::string>();
    rec.shown = r.at("record").get<std::string>();
    rec.path = r.at("path").get<std::string>();
    rec.scale = r.at("scale").get<double>();
    b.records.push_back(rec);
  }
  return b;
}

fs::path runs_dir(const std::string& out) { return fs::path(out) / "runs"; }
fs::path final_dir(const std::string& out, const std::string& label) { return runs_dir(out) / label; }
fs::path partial_dir(const std::string& out, const std::string& label) { return runs_dir(out) / (label + ".partial"); }

RunResult read_result(const std::string& out, const std::string& label) {
  RunResult r;
  for (const fs::path& dir : {final_dir(out, label), partial_dir(out, label)}) {
    const fs::path s = dir / "summary.json";
    std::error_code ec;
    if (!fs::exists(s, ec)) continue;
    try {
      r.summary = json::parse(read_file(s));
      r.state = r.summary.value("status", "failed") == "ok" ? "ok" : "failed";
    } catch (const std::exception& e) {
      r.summary = json{{"status", "failed"}, {"error", s.string() + ": unreadable: " + std::string(e.what())}};
      r.state = "failed";
    }
    r.finished = dir == final_dir(out, label);
    if (!r.finished && r.state == "ok") r.state = "not_run";  // never renamed: not a result
    return r;
  }
  return r;
}

BatchSet prepare_set(const BatchOptions& o) {
  if (o.config.empty()) throw BatchInputError("--config is required (e.g. configs/three-story.yaml)");
  if (o.records.empty()) throw BatchInputError("--records is required: a record list file or a folder");
  BatchSet b;
  const RunConfig config = load_run_config(o.config);
  if (config.damper.mode != "virtual" || config.damper.launch != "spawn")
    throw BatchInputError("config " + o.config + ": a batch runs virtual substructures it spawns itself "
                          "(damper.mode: virtual, damper.launch: spawn); run physical tests one at a "
                          "time with hybridsim run");
  const structure::ShearBuilding building(config.building);
  b.config = fs::absolute(o.config).lexically_normal().string();
  b.records_spec = fs::absolute(o.records).lexically_normal().string();
  b.name = config.name;
  b.stories = building.num_stories();
  b.dampers = building.num_dampers();
  b.duration_s = o.duration_s != 0.0 ? o.duration_s : config.record.duration_s;
  b.records = load_record_set(o.records);
  return b;
}

bool readable_summary(const fs::path& summary_path, std::string* why) {
  std::error_code ec;
  if (!fs::exists(summary_path, ec)) {
    if (why) *why = "missing";
    return false;
  }
  try {
    const json j = json::parse(read_file(summary_path));
    if (j.is_object() && j.contains("status") && j["status"].is_string()) return true;
    if (why) *why = "no status";
  } catch (const std::exception& e) {
    if (why) *why = fs::file_size(summary_path, ec) == 0 ? std::string("0 bytes") : std::string(e.what());
  }
  return false;
}

void check_finished_matches(const std::string& out, const BatchRecord& r, double duration_s) {
  const fs::path info = final_dir(out, r.label) / "batch-run.json";
  std::error_code ec;
  if (!fs::exists(info, ec)) return;
  // A run whose summary cannot be read is not finished: it is set aside and redone.
  if (!readable_summary(final_dir(out, r.label) / "summary.json", nullptr)) return;
  json j;
  try {
    j = json::parse(read_file(info));
  } catch (const std::exception& e) {
    throw BatchInputError(info.string() + ": unreadable (" + std::string(e.what()) +
                          "): move runs/" + r.label + " away to run that record again");
  }
  const std::string path = j.value("path", "");
  const double scale = j.value("scale", 0.0);
  if (path != r.path || scale != r.scale)
    throw BatchInputError("runs/" + r.label + " in " + out + " holds record " + path + " at scale " + common::format_shortest(scale) +
                          ", but the set now says " + r.path + " at scale " + common::format_shortest(r.scale) +
                          ": use another --out or another label");
  const double duration = j.value("duration_s", duration_s);
  if (duration != duration_s)
    throw BatchInputError("runs/" + r.label + " in " + out + " simulated " + common::format_shortest(duration) +
                          " s (record.duration_s), but this batch asks for " + common::format_shortest(duration_s) +
                          " s: use another --out");
}

}  // namespace server::batch_internal
