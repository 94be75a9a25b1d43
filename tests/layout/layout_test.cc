// The layout rule of the project (README "Layout"): every folder is one library with a rank;
// a file may include project headers only from its own folder or from folders of LOWER rank,
// so dependencies point one way, common <- messages <- {structure, damper/*} <- {validation,
// server/*}, and no cycle between folders is possible. Header files must also not include
// each other in a cycle. The test reads the real tree (every .h/.cc under the source root),
// so a new folder or an upward include fails here, naming the file and the line.
#include "test_paths.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

// Folder -> rank. Lower ranks are below: they may be used by higher ones, never the reverse.
const std::map<std::string, int> kRank = {
    {"common", 0},
    {"messages", 1},
    {"structure", 2},
    {"damper/model", 2},
    {"damper/data", 3},
    {"damper/physical", 3},
    {"control", 3},
    {"damper/fit", 4},
    {"damper/synthetic", 4},
    {"damper/substructure", 4},
    {"damper/rig", 4},
    {"damper/diagnose", 5},
    {"validation", 6},
    {"server/run", 7},
    {"server/batch", 8},
    {"server/ida", 9},
    {"server/cli", 10},
};

// Longest folder of kRank that contains `rel` (a path relative to the source root), or "".
std::string folder_of(const std::string& rel) {
  std::string best;
  for (const auto& [folder, rank] : kRank) {
    (void)rank;
    if (rel.rfind(folder + "/", 0) == 0 && folder.size() > best.size()) best = folder;
  }
  return best;
}

struct Include {
  std::string file;     // including file, relative to the source root
  int line = 0;
  std::string target;   // included project header, relative to the source root
};

std::vector<Include> project_includes() {
  const fs::path root = test_paths::source_dir();
  const std::regex include_re(R"(^\s*#\s*include\s*\"([^\"]+)\")");
  std::vector<Include> out;
  for (const auto& folder : kRank) {
    const fs::path dir = root / folder.first;
    if (!fs::exists(dir)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
      const auto ext = entry.path().extension();
      if (!entry.is_regular_file() || (ext != ".h" && ext != ".cc")) continue;
      const std::string rel = fs::relative(entry.path(), root).generic_string();
      if (folder_of(rel) != folder.first) continue;  // belongs to a deeper folder
      std::ifstream in(entry.path());
      std::string text;
      int line = 0;
      while (std::getline(in, text)) {
        ++line;
        std::smatch m;
        if (std::regex_search(text, m, include_re) && fs::exists(root / m[1].str()))
          out.push_back({rel, line, m[1].str()});
      }
    }
  }
  return out;
}

}  // namespace

TEST(Layout, EveryLibraryFolderIsRankedAndHasACMakeTarget) {
  const fs::path root = test_paths::source_dir();
  for (const auto& [folder, rank] : kRank) {
    (void)rank;
    if (!fs::exists(root / folder)) continue;  // a rank kept for a folder not (yet) there
    EXPECT_TRUE(fs::exists(root / folder / "CMakeLists.txt")) << folder << " has no CMakeLists.txt";
  }
  // Every folder with sources under the library roots is in the table.
  for (const std::string top : {"common", "messages", "structure", "damper", "control", "validation", "server"}) {
    if (!fs::exists(root / top)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(root / top)) {
      if (!entry.is_regular_file() || entry.path().extension() != ".cc") continue;
      const std::string rel = fs::relative(entry.path(), root).generic_string();
      EXPECT_NE(folder_of(rel), "") << rel << " is in no ranked folder: add its folder to kRank in "
                                    << "tests/layout/layout_test.cc and the README layout table";
    }
  }
}

TEST(Layout, IncludesPointOnlyDownward) {
  const auto includes = project_includes();
  ASSERT_GT(includes.size(), 50u) << "the scan found almost no includes: wrong source root?";
  int upward = 0;
  for (const auto& inc : includes) {
    const std::string from = folder_of(inc.file);
    const std::string to = folder_of(inc.target);
    if (to.empty() || from == to) continue;
    if (kRank.at(to) >= kRank.at(from)) {
      ++upward;
      ADD_FAILURE() << inc.file << ":" << inc.line << " includes " << inc.target << ": " << from << " (rank "
                    << kRank.at(from) << ") may only use folders of lower rank, " << to << " has rank "
                    << kRank.at(to);
    }
  }
  EXPECT_EQ(upward, 0);
}

TEST(Layout, NoHeaderIncludeCycle) {
  std::map<std::string, std::vector<std::string>> graph;
  for (const auto& inc : project_includes())
    if (inc.file.size() > 2 && inc.file.substr(inc.file.size() - 2) == ".h") graph[inc.file].push_back(inc.target);
  std::map<std::string, int> state;  // 0 new, 1 on stack, 2 done
  std::vector<std::string> stack;
  std::function<void(const std::string&)> visit = [&](const std::string& h) {
    state[h] = 1;
    stack.push_back(h);
    for (const auto& next : graph[h]) {
      if (state[next] == 1) {
        std::string cycle;
        for (auto it = std::find(stack.begin(), stack.end(), next); it != stack.end(); ++it) cycle += *it + " -> ";
        ADD_FAILURE() << "include cycle: " << cycle << next;
      } else if (state[next] == 0) {
        visit(next);
      }
    }
    stack.pop_back();
    state[h] = 2;
  };
  for (const auto& [h, targets] : graph) {
    (void)targets;
    if (state[h] == 0) visit(h);
  }
}
