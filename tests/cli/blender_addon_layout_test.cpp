// The Blender add-on's modules import one way (docs/code-layout.md, "blender/"): every `from . import`
// at a module's top, none inside a function, and no module reached again from what it imports. Read from
// the sources, no Blender needed.
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

std::map<std::string, std::vector<std::string>> addonImports(std::vector<std::string>* nested) {
  std::map<std::string, std::vector<std::string>> out;
  const std::regex top("^from \\. import (.*)$"), inner("^\\s+from \\. import (.*)$"), name("[A-Za-z_]+");
  for (const fs::directory_entry& e : fs::directory_iterator(fs::path(STIRRUP_SOURCE_DIR) / "blender" / "stirrup_blender")) {
    if (e.path().extension() != ".py" || e.path().stem() == "__init__") continue;
    const std::string module = e.path().stem().string();
    std::ifstream in(e.path());
    std::string line;
    out[module];
    while (std::getline(in, line)) {
      std::smatch m;
      if (std::regex_match(line, m, inner)) nested->push_back(module + ": " + line);
      if (!std::regex_match(line, m, top)) continue;
      const std::string list = m[1];
      for (auto it = std::sregex_iterator(list.begin(), list.end(), name); it != std::sregex_iterator(); ++it) out[module].push_back(it->str());
    }
  }
  return out;
}

TEST(BlenderAddonLayout, ModulesImportOneWay) {
  std::vector<std::string> nested;
  const auto imports = addonImports(&nested);
  ASSERT_GE(imports.size(), 10u) << "the add-on's modules were not found";
  EXPECT_TRUE(nested.empty()) << "an import inside a function (a cycle hidden): " << nested.front();
  // A depth-first walk: a module met again on the path it is reached by closes a cycle.
  std::vector<std::string> path, cycles;
  std::set<std::string> done;
  std::function<void(const std::string&)> walk = [&](const std::string& m) {
    if (done.count(m)) return;
    for (const std::string& on : path)
      if (on == m) {
        std::ostringstream c;
        for (const std::string& p : path) c << p << " -> ";
        cycles.push_back(c.str() + m);
        return;
      }
    path.push_back(m);
    const auto it = imports.find(m);
    if (it != imports.end())
      for (const std::string& next : it->second) walk(next);
    path.pop_back();
    done.insert(m);
  };
  for (const auto& [m, _] : imports) walk(m);
  EXPECT_TRUE(cycles.empty()) << cycles.front();
}

}  // namespace
}  // namespace stirrup::test
