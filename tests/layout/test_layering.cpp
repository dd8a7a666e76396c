// The layering of docs/layout.md, checked on the sources' #include lines: each folder includes
// only itself and the folders below it, among binpick's layers and among the detect stage's
// sub-folders (the order of the pipeline). The libraries' link order catches calls up the
// layers; this catches the header-only ones (a type, an inline function) as well.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
const fs::path root = BINPICK_SOURCE_DIR;

// The folders of a layer's sources; the layer of a path is its longest matching prefix.
struct Layer {
  std::string name;
  std::vector<std::string> prefixes;
  std::set<std::string> may_include;  // other layers (itself always)
};

const std::vector<Layer>& layers() {
  static const std::vector<Layer> all = {
      {"core", {"host/core/"}, {}},
      {"runtime", {"host/runtime/"}, {"core"}},
      {"formats", {"host/formats/"}, {"core"}},
      {"shards", {"host/shards/"}, {"core"}},
      {"train", {"host/train/"}, {"core", "runtime", "formats", "shards"}},
      {"detect", {"host/detect/"}, {"core", "runtime", "formats", "shards", "train"}},
      {"synth", {"synth/"}, {"core", "runtime", "formats", "shards"}},
      {"eval", {"host/eval/"}, {"core", "runtime", "formats", "shards", "train", "detect", "synth"}},
      {"tune",
       {"host/tune/"},
       {"core", "runtime", "formats", "shards", "train", "detect", "synth", "eval"}},
      {"bench", {"bench/lib/"},
       {"core", "runtime", "formats", "shards", "train", "detect", "synth", "eval", "tune"}},
      {"app", {"host/app/"},
       {"core", "runtime", "formats", "shards", "train", "detect", "synth", "eval", "tune", "bench"}},
  };
  return all;
}

// The detect stage's folders in pipeline order (params: the parameters and their files, which
// every step reads); "" is host/detect/ itself (the detector, which
// orchestrates), and batch/ runs the detector over datasets.
const std::vector<std::string> detect_order = {"params", "scene",  "bin",    "hypotheses",
                                               "vote",   "cluster", "refine", "verify",
                                               "select", "pick",    "",       "batch"};

// Known exceptions, each to be removed by the change that ends it (none now).
const std::set<std::pair<std::string, std::string>> allowed = {};

std::string layer_of(const std::string& path) {
  std::string best;
  std::size_t best_len = 0;
  for (const Layer& l : layers())
    for (const auto& p : l.prefixes)
      if (path.rfind(p, 0) == 0 && p.size() > best_len) best = l.name, best_len = p.size();
  return best;
}

// host/detect/FOLDER/... -> FOLDER's rank in detect_order; host/detect/file -> the rank of "".
int detect_rank(const std::string& path) {
  const std::string rest = path.substr(std::string("host/detect/").size());
  const auto slash = rest.find('/');
  const std::string folder = slash == std::string::npos ? "" : rest.substr(0, slash);
  for (std::size_t i = 0; i < detect_order.size(); ++i)
    if (detect_order[i] == folder) return int(i);
  return -1;
}

struct Include {
  std::string from, to;
  int line;
};

std::vector<Include> includes_of_sources() {
  std::vector<Include> out;
  const std::regex include(R"(^\s*#\s*include\s+"([^"]+)\")");
  for (const char* top : {"host", "synth", "bench/lib"})
    for (const auto& entry : fs::recursive_directory_iterator(root / top)) {
      const auto ext = entry.path().extension();
      if (!entry.is_regular_file() || (ext != ".cpp" && ext != ".hpp" && ext != ".h")) continue;
      const std::string from = fs::relative(entry.path(), root).generic_string();
      std::ifstream in(entry.path());
      std::string text;
      for (int n = 1; std::getline(in, text); ++n) {
        std::smatch m;
        if (std::regex_search(text, m, include)) out.push_back({from, m[1].str(), n});
      }
    }
  return out;
}

TEST(Layering, NoLayerIncludesOneAboveIt) {
  const auto includes = includes_of_sources();
  ASSERT_GT(includes.size(), 500u) << "the sources were not found under " << root;
  std::map<std::string, const Layer*> by_name;
  for (const Layer& l : layers()) by_name[l.name] = &l;
  for (const Include& inc : includes) {
    const std::string from = layer_of(inc.from), to = layer_of(inc.to);
    if (from.empty() || to.empty() || from == to) continue;
    EXPECT_TRUE(by_name.at(from)->may_include.count(to))
        << inc.from << ":" << inc.line << " (" << from << ") includes " << inc.to << " (" << to
        << ")";
  }
}

TEST(Layering, NoDetectFolderIncludesOneLaterInThePipeline) {
  int checked = 0;
  for (const Include& inc : includes_of_sources()) {
    if (inc.from.rfind("host/detect/", 0) != 0 || inc.to.rfind("host/detect/", 0) != 0) continue;
    const int from = detect_rank(inc.from), to = detect_rank(inc.to);
    ASSERT_GE(from, 0) << inc.from << " is in no folder of the detect stage's order";
    ASSERT_GE(to, 0) << inc.to << " is in no folder of the detect stage's order";
    ++checked;
    if (allowed.count({inc.from, inc.to})) continue;
    EXPECT_LE(to, from) << inc.from << ":" << inc.line << " includes " << inc.to
                        << ", a later stage (order: params, scene, bin, hypotheses, vote, cluster, "
                           "refine, verify, select, pick, the detector, batch)";
  }
  EXPECT_GT(checked, 100);
}

}  // namespace
