// The layers as docs/architecture.md draws them: every `#include "..."` of the sources (src,
// include, drivers, ui) is checked against the page's table of layers, their folders and the
// layers each may include. A header under src/ is private to its layer.
#include <gtest/gtest.h>

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
const fs::path kRoot = GANTRY_SOURCE_DIR;

struct Layer {
  std::string name;
  std::vector<std::string> folders;  // relative to the root, with a trailing '/'
  std::set<std::string> may_include;
};

std::vector<std::string> cells(const std::string& row) {
  std::vector<std::string> out;
  std::stringstream in(row);
  std::string cell;
  std::getline(in, cell, '|');  // before the first bar
  while (std::getline(in, cell, '|')) {
    const auto b = cell.find_first_not_of(' '), e = cell.find_last_not_of(' ');
    out.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
  }
  if (!out.empty() && out.back().empty()) out.pop_back();
  return out;
}

// Words of a cell, each without its backquotes; "—" is none.
std::vector<std::string> words(const std::string& cell) {
  std::vector<std::string> out;
  std::stringstream in(cell);
  for (std::string w; in >> w;) {
    std::erase(w, '`');
    std::erase(w, ',');
    if (!w.empty() && w != "—") out.push_back(w);
  }
  return out;
}

// The table under "## Layers and what each may include" in docs/architecture.md.
std::vector<Layer> documented_layers() {
  std::ifstream page(kRoot / "docs/architecture.md");
  std::vector<Layer> layers;
  bool in_section = false;
  for (std::string line; std::getline(page, line);) {
    if (line.rfind("## ", 0) == 0) in_section = line == "## Layers and what each may include";
    if (!in_section || line.rfind("| ", 0) != 0) continue;
    const std::vector<std::string> c = cells(line);
    if (c.size() != 3 || c[0] == "layer" || c[0].rfind("---", 0) == 0) continue;
    Layer l;
    l.name = c[0];
    for (std::string f : words(c[1])) l.folders.push_back(f.back() == '/' ? f : f + '/');
    for (const std::string& w : words(c[2])) l.may_include.insert(w);
    layers.push_back(l);
  }
  return layers;
}

// The layer a file (relative to the root) belongs to, "" when none.
std::string layer_of(const std::vector<Layer>& layers, const std::string& file) {
  std::string best;
  size_t longest = 0;
  for (const Layer& l : layers)
    for (const std::string& f : l.folders)
      if (file.rfind(f, 0) == 0 && f.size() > longest) best = l.name, longest = f.size();
  return best;
}

// Where a quoted include resolves: beside the file first, then the include roots.
std::string resolve(const fs::path& file, const std::string& target) {
  for (const fs::path& base : {kRoot / file.parent_path(), kRoot / "include", kRoot / "drivers",
                               kRoot / "src", kRoot / "ui"}) {
    const fs::path p = (base / target).lexically_normal();
    if (fs::is_regular_file(p)) return p.lexically_relative(kRoot).generic_string();
  }
  return "";
}

struct Violation {
  std::string file, target, why;
};

std::vector<Violation> violations(const std::vector<Layer>& layers, size_t* checked) {
  std::map<std::string, const Layer*> by_name;
  for (const Layer& l : layers) by_name[l.name] = &l;
  const std::regex include(R"(^\s*#\s*include\s+"([^"]+)\")");
  std::vector<Violation> out;
  for (const char* top : {"src", "include", "drivers", "ui"})
    for (const auto& e : fs::recursive_directory_iterator(kRoot / top)) {
      const std::string ext = e.path().extension().string();
      if (!e.is_regular_file() || (ext != ".cpp" && ext != ".hpp" && ext != ".h")) continue;
      const fs::path rel = e.path().lexically_relative(kRoot);
      const std::string file = rel.generic_string();
      const std::string from = layer_of(layers, file);
      if (from.empty()) {
        out.push_back({file, "", "this file is in no layer of docs/architecture.md's table"});
        continue;
      }
      std::ifstream in(e.path());
      std::smatch m;
      for (std::string line; std::getline(in, line);) {
        if (!std::regex_search(line, m, include)) continue;
        const std::string target = resolve(rel, m[1]);
        if (target.empty()) continue;  // a library's header
        ++*checked;
        const std::string to = layer_of(layers, target);
        if (to.empty() || to == from) continue;
        if (!by_name.at(from)->may_include.count(to))
          out.push_back({file, target, from + " may not include " + to});
        else if (target.rfind("src/", 0) == 0)
          out.push_back({file, target, "a header under src/ is private to its layer (" + to +
                                           "); make it public under include/gantry/"});
      }
    }
  return out;
}

TEST(Layering, ArchitecturePageListsTheLayers) {
  const std::vector<Layer> layers = documented_layers();
  std::set<std::string> names;
  for (const Layer& l : layers) names.insert(l.name);
  for (const char* n : {"base", "canon", "lang", "motion", "hal", "step", "interp", "drivers",
                        "machine", "preview", "cli", "ui"})
    EXPECT_TRUE(names.count(n)) << n;
  // Each may include only layers listed above it in the table: no cycle can be written.
  std::set<std::string> below;
  for (const Layer& l : layers) {
    for (const std::string& i : l.may_include)
      EXPECT_TRUE(below.count(i)) << l.name << " may include " << i << ", not listed before it";
    below.insert(l.name);
  }
}

TEST(Layering, EveryIncludeIsOneTheMatrixAllows) {
  size_t checked = 0;
  const std::vector<Violation> v = violations(documented_layers(), &checked);
  EXPECT_GT(checked, 500u);  // the walk found the sources
  for (const Violation& x : v) ADD_FAILURE() << x.file << " includes " << x.target << ": " << x.why;
}

// The check itself: an include the matrix refuses is found.
TEST(Layering, AnUpwardIncludeIsFound) {
  std::vector<Layer> layers = documented_layers();
  for (Layer& l : layers)
    if (l.name == "machine") l.may_include.erase("interp");
  size_t checked = 0;
  const std::vector<Violation> v = violations(layers, &checked);
  bool found = false;
  for (const Violation& x : v) found |= x.why == "machine may not include interp";
  EXPECT_TRUE(found);
}

}  // namespace
