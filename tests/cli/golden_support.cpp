#include "tests/cli/golden_support.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "render/review/index_page.h"
#include "tests/cli/run_command.h"

namespace stirrup::test {

namespace fs = std::filesystem;

std::string goldenName(int frame) { return frameFileName("trot_side", frame); }

std::string frameFileName(const std::string& base, int frame) {
  char digits[16];
  std::snprintf(digits, sizeof digits, "%04d", frame);
  return base + "." + digits + ".png";
}

GoldenSet loadGoldenSet() {
  const fs::path file = kGoldenDir / "scenes.json";
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": cannot be read");
  GoldenSet set;
  std::string field;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    field = "resolution";
    set.resolution = j.at(field).get<std::string>();
    field = "preset";
    set.preset = j.at(field).get<std::string>();
    const nlohmann::json& shots = j.at("shots");
    for (std::size_t i = 0; i < shots.size(); ++i) {
      field = "shots[" + std::to_string(i) + "]";
      GoldenShot s;
      s.scene = shots[i].at("scene").get<std::string>();
      s.camera = shots[i].at("camera").get<std::string>();
      s.frames = shots[i].at("frames").get<std::vector<int>>();
      s.why = shots[i].at("why").get<std::string>();
      if (s.frames.empty()) throw std::runtime_error("expected at least one frame");
      set.shots.push_back(s);
    }
    const nlohmann::json& movies = j.at("movies");
    for (std::size_t i = 0; i < movies.size(); ++i) {
      field = "movies[" + std::to_string(i) + "]";
      GoldenMovie m;
      m.movie = movies[i].at("movie").get<std::string>();
      m.frames_limit = movies[i].at("frames_limit").get<int>();
      m.date = movies[i].at("date").get<std::string>();
      m.files = movies[i].at("files").get<std::vector<std::string>>();
      m.why = movies[i].at("why").get<std::string>();
      if (m.frames_limit < 1) throw std::runtime_error("frames_limit: expected at least 1");
      if (m.files.empty()) throw std::runtime_error("files: expected at least one file");
      set.movies.push_back(m);
    }
  } catch (const std::exception& e) {
    throw std::runtime_error(file.string() + ": " + field + ": " + e.what());
  }
  return set;
}

namespace {

std::string frameList(const std::vector<int>& frames) {
  std::string list;
  for (int f : frames) list += (list.empty() ? "" : ",") + std::to_string(f);
  return list;
}

}  // namespace

GoldenRender fixedTrotRender(int frame, const fs::path& base) {
  GoldenRender r;
  r.name = "fixed:" + std::to_string(frame);
  r.out = base / ("frame" + std::to_string(frame));
  r.args = "render " + quote((kGoldenDir / "trot_side.json").string()) + " --frames " + std::to_string(frame) +
           " --out " + quote(r.out.string());
  r.files.push_back({r.out / goldenName(frame), goldenName(frame)});
  r.why = "the fixed trot side camera (tests/golden/trot_side.json)";
  return r;
}

GoldenRender shotRender(const GoldenSet& set, const GoldenShot& shot, const fs::path& base) {
  GoldenRender r;
  r.name = "shot:" + shot.name();
  r.out = base / shot.name();
  const fs::path scene = fs::path(STIRRUP_SOURCE_DIR) / "scenes" / (shot.scene + ".json");
  r.args = "render " + quote(scene.string()) + " --camera " + quote(shot.camera) + " --frames " + frameList(shot.frames) +
           " --resolution " + set.resolution + " --preset " + set.preset + " --out " + quote(r.out.string());
  for (int frame : shot.frames) {
    const std::string name = frameFileName(shot.name(), frame);
    r.files.push_back({r.out / name, fs::path("scenes") / name});
  }
  r.why = shot.why;
  return r;
}

GoldenRender movieRender(const GoldenSet& set, const GoldenMovie& movie, const fs::path& base) {
  GoldenRender r;
  r.name = "movie:" + movie.movie;
  r.out = base / ("movie_" + movie.movie);
  r.args = "movies --only " + quote(movie.movie) + " --frames-limit " + std::to_string(movie.frames_limit) +
           " --resolution " + set.resolution + " --preset " + set.preset + " --date " + quote(movie.date) +
           " --keep-frames --out " + quote(r.out.string());
  for (const std::string& file : movie.files) {
    const fs::path image = r.out / file;
    r.files.push_back({image, fs::path("movies") / image.filename()});
  }
  r.why = movie.why;
  return r;
}

std::vector<GoldenRender> allGoldenRenders(const fs::path& base) {
  std::vector<GoldenRender> all;
  for (int frame : kGoldenFrames) all.push_back(fixedTrotRender(frame, base));
  const GoldenSet set = loadGoldenSet();
  for (const GoldenShot& shot : set.shots) all.push_back(shotRender(set, shot, base));
  for (const GoldenMovie& movie : set.movies) all.push_back(movieRender(set, movie, base));
  return all;
}

namespace {

std::string html(const std::string& s) { return render::htmlEscape(s); }

std::string number(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

void writeReport(const GoldenComparison& c, const fs::path& reference_copy, const render::DiffThresholds& t) {
  const render::DiffResult& d = c.diff;
  const double pixels = double(d.width) * d.height;
  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>golden: " << html(c.image.filename().string())
    << "</title>\n<style>body{font-family:sans-serif} figure{display:inline-block;margin:0 1em 1em 0}"
       " img{image-rendering:pixelated;width:640px;border:1px solid #888} td{padding:0 1em 0 0}</style>"
       "</head><body>\n"
    << "<h1>Golden image " << html(c.image.filename().string()) << ": FAIL</h1>\n"
    << "<figure><img src=\"" << html(reference_copy.filename().string()) << "\" alt=\"reference\"><figcaption>reference ("
    << html(c.reference.string()) << ")</figcaption></figure>\n"
    << "<figure><img src=\"" << html(c.image.filename().string()) << "\" alt=\"new\"><figcaption>new image</figcaption></figure>\n"
    << "<figure><img src=\"" << html(c.diff_image.filename().string())
    << "\" alt=\"diff\"><figcaption>|new &minus; reference| &times; 16</figcaption></figure>\n"
    << "<table>\n"
    << "<tr><td>size</td><td>" << d.width << " &times; " << d.height << ", " << d.channels << " channels</td></tr>\n"
    << "<tr><td>mean error</td><td>" << number("%.6f", d.mean_error) << "</td></tr>\n"
    << "<tr><td>RMS error</td><td>" << number("%.6f", d.rms_error) << "</td></tr>\n"
    << "<tr><td>max error</td><td>" << number("%.6f", d.max_error) << " (" << number("%.1f", d.max_error * 255)
    << "/255) at pixel (" << d.worst_x << ", " << d.worst_y << ")</td></tr>\n"
    << "<tr><td>PSNR</td><td>" << number("%.2f", d.psnr_db) << " dB</td></tr>\n"
    << "<tr><td>pixels over fail</td><td>" << d.pixels_over_fail << " (" << number("%.4f", 100.0 * d.pixels_over_fail / pixels)
    << "%)</td></tr>\n"
    << "<tr><td>pixels over warn</td><td>" << d.pixels_over_warn << " (" << number("%.4f", 100.0 * d.pixels_over_warn / pixels)
    << "%)</td></tr>\n"
    << "<tr><td>thresholds</td><td>fail: more than " << number("%.4f", 100.0 * t.fail_fraction) << "% of the pixels ("
    << number("%.1f", t.fail_fraction * pixels) << ") off by more than " << number("%.6f", t.fail) << " ("
    << number("%.1f", t.fail * 255) << "/255)" << (std::isfinite(t.hardfail) ? ", or any pixel over " + number("%.6f", t.hardfail) : "")
    << "; warn: more than " << number("%.4f", 100.0 * t.warn_fraction) << "% over " << number("%.6f", t.warn)
    << "</td></tr>\n"
    << "</table>\n<p>After an intended change to the look or the rig: <code>scripts/update-goldens</code>.</p>\n"
    << "</body></html>\n";
  std::ofstream out(c.report);
  out << o.str();
}

}  // namespace

std::string GoldenComparison::message() const {
  std::ostringstream o;
  o << image.filename().string() << ": " << diff.summary() << "\n  new: " << image << "\n  reference: " << reference
    << "\n  diff (x16): " << diff_image;
  if (!report.empty()) o << "\n  report: " << report;
  o << "\n  after an intended change: scripts/update-goldens";
  return o.str();
}

GoldenComparison compareWithGolden(const fs::path& reference, const fs::path& image) {
  GoldenComparison c;
  c.image = image;
  c.reference = reference;
  c.diff_image = image.parent_path() / (image.filename().string() + ".diff.png");
  const render::DiffThresholds t = goldenThresholds();
  c.diff = render::compareImageFiles(reference, image, t, c.diff_image);
  if (c.failed()) {
    const fs::path stem = image.parent_path() / image.stem();
    const fs::path reference_copy = stem.string() + ".reference.png";
    fs::copy_file(reference, reference_copy, fs::copy_options::overwrite_existing);
    c.report = stem.string() + ".report.html";
    writeReport(c, reference_copy, t);
  }
  return c;
}

}  // namespace stirrup::test
