// Every link between the docs and every citation of a doc from the code lands somewhere: a
// markdown link's file exists and its #anchor is one of that file's headings; a comment's
// `docs/FILE.md, "Heading"` names a heading FILE has; a `docs/FILE.md` named anywhere exists.
// Citing docs/pipeline.md by step number is refused: its steps moved to docs/detect/.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
const fs::path root = BINPICK_SOURCE_DIR;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

// GitHub's anchor of a heading: lower case, punctuation dropped, spaces to dashes.
std::string slug(const std::string& heading) {
  std::string out;
  for (unsigned char c : lower(heading)) {
    if (std::isalnum(c) || c == '-' || c == '_') out += char(c);
    else if (c == ' ') out += '-';
    else if (c >= 0x80) out += char(c);  // letters beyond ASCII stay
  }
  return out;
}

// The headings of a markdown file (outside code blocks), as written and as anchors.
struct Headings {
  std::set<std::string> text, anchors;
};
const Headings& headings_of(const fs::path& file) {
  static std::map<fs::path, Headings> cache;
  auto found = cache.find(file);
  if (found != cache.end()) return found->second;
  Headings h;
  std::istringstream in(slurp(file));
  bool code = false;
  for (std::string line; std::getline(in, line);) {
    if (line.starts_with("```")) code = !code;
    if (code || !line.starts_with("#")) continue;
    const auto start = line.find_first_not_of('#');
    if (start == std::string::npos || line[start] != ' ') continue;
    std::string title = line.substr(start + 1);
    h.anchors.insert(slug(title));
    title.erase(std::remove(title.begin(), title.end(), '`'), title.end());
    h.text.insert(lower(title));
  }
  return cache.emplace(file, h).first->second;
}

std::vector<fs::path> files_under(const std::vector<std::string>& tops,
                                  const std::set<std::string>& extensions) {
  std::vector<fs::path> out;
  for (const auto& top : tops) {
    const fs::path dir = root / top;
    if (fs::is_regular_file(dir)) {
      out.push_back(dir);
      continue;
    }
    if (!fs::is_directory(dir)) continue;
    for (const auto& e : fs::recursive_directory_iterator(dir))
      if (e.is_regular_file() && extensions.count(e.path().extension().string()))
        out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string where(const fs::path& file, const std::string& text, std::size_t at) {
  const auto line = std::count(text.begin(), text.begin() + long(at), '\n') + 1;
  return fs::relative(file, root).generic_string() + ":" + std::to_string(line);
}

TEST(DocLinks, MarkdownLinksLandOnAFileAndAHeading) {
  const auto docs = files_under({"docs", "README.md"}, {".md"});
  ASSERT_GT(docs.size(), 10u);
  const std::regex link(R"(\]\(([^)\s]+)\))");
  std::size_t checked = 0;
  for (const fs::path& file : docs) {
    const std::string text = slurp(file);
    for (auto it = std::sregex_iterator(text.begin(), text.end(), link);
         it != std::sregex_iterator(); ++it) {
      const std::string target = (*it)[1];
      if (target.starts_with("http") || target.starts_with("mailto:")) continue;
      const auto hash = target.find('#');
      const std::string path = target.substr(0, hash);
      const fs::path resolved = path.empty() ? file : file.parent_path() / path;
      const std::string at = where(file, text, std::size_t(it->position()));
      ++checked;
      if (!fs::exists(resolved)) {
        ADD_FAILURE() << at << ": " << target << ": no such file";
        continue;
      }
      if (hash == std::string::npos || resolved.extension() != ".md") continue;
      const std::string anchor = target.substr(hash + 1);
      EXPECT_TRUE(headings_of(resolved).anchors.count(anchor))
          << at << ": " << target << ": no heading with that anchor in " << resolved;
    }
  }
  EXPECT_GT(checked, 50u);
}

TEST(DocLinks, CitationsInCodeAndDocsNameFilesAndHeadingsThatExist) {
  const auto files = files_under({"host", "synth", "kernels", "shaders", "bench", "tests", "fuzz",
                                  "tools", "docs", "README.md", "run.sh", "CMakeLists.txt"},
                                 {".cpp", ".hpp", ".h", ".cl", ".comp", ".vert", ".frag",
                                  ".glsl", ".md", ".sh", ".py", ".txt"});
  // docs/FILE.md, optionally followed by , "Heading" (or #"Heading").
  const std::regex cite(R"re(\bdocs/([\w./-]+\.md)(?:(?:,\s*|\s*#)"([^"]+)")?)re");
  const std::regex by_step(R"(pipeline\.md,?\s*(detect\s+)?step\b)");
  std::size_t checked = 0;
  for (const fs::path& file : files) {
    if (file.filename() == "test_doc_links.cpp") continue;  // its own examples
    const std::string text = slurp(file);
    for (auto it = std::sregex_iterator(text.begin(), text.end(), cite);
         it != std::sregex_iterator(); ++it) {
      const fs::path doc = root / "docs" / (*it)[1].str();
      const std::string at = where(file, text, std::size_t(it->position()));
      ++checked;
      if (!fs::exists(doc)) {
        ADD_FAILURE() << at << ": docs/" << (*it)[1] << " does not exist";
        continue;
      }
      if (!(*it)[2].matched) continue;
      std::string heading = (*it)[2];
      heading.erase(std::remove(heading.begin(), heading.end(), '`'), heading.end());
      EXPECT_TRUE(headings_of(doc).text.count(lower(heading)))
          << at << ": docs/" << (*it)[1] << " has no heading \"" << (*it)[2] << "\"";
    }
    for (auto it = std::sregex_iterator(text.begin(), text.end(), by_step);
         it != std::sregex_iterator(); ++it)
      ADD_FAILURE() << where(file, text, std::size_t(it->position()))
                    << ": cites docs/pipeline.md by step; its steps are in docs/detect/";
  }
  EXPECT_GT(checked, 20u);
}

// The reference stays a reference: the overview short, the detect pages together under a
// thousand lines (measurements and histories go to docs/decisions/), and every decision listed
// in its index.
TEST(DocLinks, TheReferenceStaysShortAndEveryDecisionIsListed) {
  const auto lines = [](const fs::path& p) {
    const std::string t = slurp(p);
    return std::size_t(std::count(t.begin(), t.end(), '\n'));
  };
  EXPECT_LE(lines(root / "docs" / "pipeline.md"), 300u);
  std::size_t detect = 0;
  for (const fs::path& p : files_under({"docs/detect"}, {".md"})) detect += lines(p);
  EXPECT_LT(detect, 1000u) << "docs/detect/ has " << detect << " lines";
  const std::string index = slurp(root / "docs" / "decisions" / "README.md");
  std::size_t entries = 0;
  for (const fs::path& p : files_under({"docs/decisions"}, {".md"})) {
    if (p.filename() == "README.md") continue;
    ++entries;
    EXPECT_NE(index.find("(" + p.filename().string() + ")"), std::string::npos)
        << p.filename() << " is not listed in docs/decisions/README.md";
    const std::string text = slurp(p);
    for (const char* section : {"\n## Decision", "\n## Alternatives", "\n## Evidence", "\n## Command"})
      EXPECT_NE(text.find(section), std::string::npos) << p.filename() << " lacks" << section;
  }
  EXPECT_GT(entries, 50u);
}

}  // namespace
