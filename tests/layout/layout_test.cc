// The layout rule of the project (README "Layout"): every folder is one library with a rank;
// a file may include project headers only from its own folder or from folders of LOWER rank,
// so dependencies point one way, common <- messages <- {structure, damper/*} <- {validation,
// server/*}, and no cycle between folders is possible. Header files must also not include
// each other in a cycle. The test reads the real tree (every .h/.cc under the source root),
// so a new folder or an upward include fails here, naming the file and the line. README.md's
// Layout table is checked against the same tree: a row per ranked folder, in rank order, its
// targets the ones the folder's CMakeLists.txt defines, and every top-level folder covered.
#include "test_paths.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
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

namespace {

struct ReadmeRow {
  std::string folder;                // "damper/fit" (no trailing slash)
  std::vector<std::string> targets;  // the names in backticks of the target column
  int line = 0;
};

// Rows of the table under "## Layout" in README.md (up to the next heading).
std::vector<ReadmeRow> readme_layout_rows() {
  std::ifstream in(fs::path(test_paths::source_dir()) / "README.md");
  std::vector<ReadmeRow> rows;
  bool inside = false;
  int n = 0;
  const std::regex row_re(R"(^\|\s*`([^`]+)/`\s*\|([^|]*)\|)");
  const std::regex name_re("`([^`]+)`");
  for (std::string text; std::getline(in, text);) {
    ++n;
    if (text.rfind("## ", 0) == 0 || text.rfind("### ", 0) == 0) inside = text == "## Layout";
    std::smatch m;
    if (!inside || !std::regex_search(text, m, row_re)) continue;
    ReadmeRow r{m[1].str(), {}, n};
    const std::string cell = m[2].str();
    for (std::sregex_iterator it(cell.begin(), cell.end(), name_re), end; it != end; ++it) r.targets.push_back((*it)[1].str());
    rows.push_back(r);
  }
  return rows;
}

}  // namespace

TEST(Layout, ReadmeLayoutTableIsTheTree) {
  const fs::path root = test_paths::source_dir();
  const std::vector<ReadmeRow> rows = readme_layout_rows();
  ASSERT_GT(rows.size(), 10u) << "no Layout table found in README.md";
  std::map<std::string, const ReadmeRow*> by_folder;
  int last_rank = -1;
  std::string last_folder;
  for (const ReadmeRow& r : rows) {
    EXPECT_TRUE(fs::is_directory(root / r.folder)) << "README.md:" << r.line << ": `" << r.folder << "/` is not a folder";
    EXPECT_TRUE(by_folder.emplace(r.folder, &r).second) << "README.md:" << r.line << ": `" << r.folder << "/` twice";
    const auto rank = kRank.find(r.folder);
    if (rank == kRank.end()) continue;
    // Lower rows use upper rows: the ranked folders stand in rank order.
    EXPECT_GE(rank->second, last_rank) << "README.md:" << r.line << ": `" << r.folder << "/` (rank " << rank->second
                                       << ") is listed below `" << last_folder << "/` (rank " << last_rank << ")";
    last_rank = rank->second;
    last_folder = r.folder;
    // The target column names exactly the targets of the folder's CMakeLists.txt.
    std::ifstream cm(root / r.folder / "CMakeLists.txt");
    std::stringstream text;
    text << cm.rdbuf();
    const std::string cmake = text.str();
    const std::regex target_re(R"(add_(library|executable)\(\s*([A-Za-z0-9_.+-]+))");
    std::set<std::string> defined, listed(r.targets.begin(), r.targets.end());
    for (std::sregex_iterator it(cmake.begin(), cmake.end(), target_re), end; it != end; ++it) defined.insert((*it)[2].str());
    EXPECT_EQ(listed, defined) << "README.md:" << r.line << ": the targets of `" << r.folder << "/`";
  }
  for (const auto& [folder, rank] : kRank) {
    (void)rank;
    if (!fs::exists(root / folder)) continue;
    EXPECT_EQ(by_folder.count(folder), 1u) << folder << "/ has no row in README.md's Layout table";
  }
  // Every top-level folder of the tree (not a build folder, not hidden) has a row, itself or
  // its sub-folders.
  for (const auto& entry : fs::directory_iterator(root)) {
    const std::string name = entry.path().filename().string();
    if (!entry.is_directory() || name[0] == '.' || fs::exists(entry.path() / "CMakeCache.txt")) continue;
    bool covered = false;
    for (const ReadmeRow& r : rows) covered = covered || r.folder == name || r.folder.rfind(name + "/", 0) == 0;
    EXPECT_TRUE(covered) << name << "/ has no row in README.md's Layout table";
  }
}
