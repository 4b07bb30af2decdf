#include "render/review/index_page.h"

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <gtest/gtest.h>

namespace stirrup::render {
namespace {

namespace fs = std::filesystem;

void touch(const fs::path& f) { std::ofstream(f) << "x"; }

TEST(IndexPage, LinksOnlyFilesThatExist) {
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "test_index_page";
  fs::remove_all(dir);
  fs::create_directories(dir);
  touch(dir / "a_side.mp4");
  touch(dir / "a_side_sheet.png");
  touch(dir / "a_plot.png");
  MovieResult a;
  a.name = "a_side";
  a.movies = {dir / "a_side.mp4", dir / "a_side.mov"};  // the .mov is missing
  a.contact_sheet = dir / "a_side_sheet.png";
  a.plot = dir / "a_plot.png";
  MovieResult b;
  b.name = "b <side>";
  b.movies = {dir / "b_side.mp4"};  // missing: no video
  b.contact_sheet = dir / "b_side_sheet.png";
  b.plot = dir / "a_plot.png";
  const fs::path page = writeIndexPage(dir, {a, b});
  std::ifstream in(page);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string html = ss.str();
  const std::regex link("(?:src|href)=\"([^\"]+)\"");
  int links = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), link); it != std::sregex_iterator(); ++it) {
    EXPECT_TRUE(fs::exists(dir / (*it)[1].str())) << (*it)[1].str();
    ++links;
  }
  EXPECT_GE(links, 5);  // video, sheet (img + a), plot twice (img + a) and more
  EXPECT_EQ(html.find("a_side.mov"), std::string::npos);
  EXPECT_EQ(html.find("b_side"), std::string::npos);
  EXPECT_NE(html.find("b &lt;side&gt;"), std::string::npos);  // names are escaped
  std::size_t videos = 0;
  for (std::size_t p = html.find("<video"); p != std::string::npos; p = html.find("<video", p + 1)) ++videos;
  EXPECT_EQ(videos, 1u);
  EXPECT_FALSE(fs::exists(dir / "index.html.tmp"));
}

}  // namespace
}  // namespace stirrup::render
