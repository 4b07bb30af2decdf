#include "render/review/index_page.h"
#include "rig/io/atomic_file.h"

#include <cctype>
#include <fstream>
#include <stdexcept>

namespace stirrup::render {

std::string htmlEscape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

namespace {

// The file's name relative to the page, when the file exists there.
std::string linkable(const std::filesystem::path& dir, const std::filesystem::path& file) {
  if (file.empty() || !std::filesystem::is_regular_file(file)) return {};
  std::error_code ec;
  const std::filesystem::path rel = std::filesystem::relative(file, dir, ec);
  if (ec || rel.empty()) return {};
  return rel.generic_string();
}

// Percent-encodes what a relative URL can't hold as is.
std::string urlPath(const std::string& s) {
  std::string out;
  const char* hex = "0123456789ABCDEF";
  for (unsigned char c : s) {
    if (std::isalnum(c) || c == '/' || c == '.' || c == '_' || c == '-') out += char(c);
    else out += std::string("%") + hex[c >> 4] + hex[c & 15];
  }
  return out;
}

}  // namespace

std::filesystem::path writeIndexPage(const std::filesystem::path& dir, const std::vector<MovieResult>& movies,
                                     const std::string& title) {
  namespace fs = std::filesystem;
  fs::create_directories(dir);
  const fs::path file = dir / "index.html";
  rig::replaceFileAtomically(file, [&](const fs::path& tmp) {
    std::ofstream o(tmp);
    o << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" << htmlEscape(title)
      << "</title>\n<style>\n"
         "body{font-family:'DejaVu Sans',sans-serif;background:#1c1c1e;color:#e6e6e6;margin:24px}\n"
         "section{border-top:1px solid #444;padding:16px 0}\n"
         "h2{margin:0 0 8px;font-size:20px} .facts{color:#aaa;font-size:13px;margin-bottom:8px}\n"
         ".row{display:flex;flex-wrap:wrap;gap:16px;align-items:flex-start}\n"
         "video{max-width:640px;width:100%;background:#000} img{max-width:640px;width:100%}\n"
         "a{color:#8cc4ff}\n"
         "</style>\n</head>\n<body>\n<h1>" << htmlEscape(title) << "</h1>\n";
    o << "<p>" << movies.size() << " movies. Each shows a one-second slate, then the frames with burn-ins "
         "(scene, movement, view, rig profile, frame, timecode).</p>\n";
    for (const MovieResult& m : movies) {
      o << "<section id=\"" << htmlEscape(m.name) << "\">\n<h2>" << htmlEscape(m.name) << "</h2>\n";
      o << "<div class=\"facts\">scene " << htmlEscape(m.scene) << " &middot; movement " << htmlEscape(m.movement)
        << " &middot; view " << htmlEscape(m.view) << " &middot; rig profile " << htmlEscape(m.profile) << " &middot; "
        << m.frames << " frames + " << m.slate_frames << " slate at " << m.fps << " fps</div>\n";
      o << "<div class=\"row\">\n";
      std::string mp4, others;
      for (const fs::path& movie : m.movies) {
        const std::string rel = linkable(dir, movie);
        if (rel.empty()) continue;
        if (movie.extension() == ".mp4" && mp4.empty()) mp4 = rel;
        others += " <a href=\"" + htmlEscape(urlPath(rel)) + "\">" + htmlEscape(rel) + "</a>";
      }
      if (!mp4.empty())
        o << "<video controls preload=\"auto\" muted playsinline src=\"" << htmlEscape(urlPath(mp4))
          << "\" data-movie=\"" << htmlEscape(m.name) << "\"></video>\n";
      const std::string sheet = linkable(dir, m.contact_sheet);
      if (!sheet.empty())
        o << "<a href=\"" << htmlEscape(urlPath(sheet)) << "\"><img alt=\"contact sheet of " << htmlEscape(m.name)
          << "\" src=\"" << htmlEscape(urlPath(sheet)) << "\"></a>\n";
      const std::string plot = linkable(dir, m.plot);
      if (!plot.empty())
        o << "<a href=\"" << htmlEscape(urlPath(plot)) << "\"><img alt=\"channel plot of " << htmlEscape(m.movement)
          << "\" src=\"" << htmlEscape(urlPath(plot)) << "\"></a>\n";
      o << "</div>\n";
      if (!others.empty()) o << "<p>files:" << others << "</p>\n";
      o << "</section>\n";
    }
    // Each video reports what the browser made of it in data attributes (data-duration, data-error),
    // for people inspecting the page and for the headless-browser test.
    o << "<script>\n"
         "document.querySelectorAll('video').forEach(function (v) {\n"
         "  function note() { v.dataset.duration = String(v.duration); v.dataset.ready = String(v.readyState);\n"
         "    v.dataset.width = String(v.videoWidth); v.dataset.height = String(v.videoHeight); }\n"
         "  v.addEventListener('loadedmetadata', note); v.addEventListener('loadeddata', note);\n"
         "  v.addEventListener('error', function () { v.dataset.error = String(v.error ? v.error.code : -1); });\n"
         "  if (v.readyState > 0) note();\n"
         "});\n"
         "</script>\n";
    o << "</body>\n</html>\n";
    if (!o.flush()) throw std::runtime_error(file.string() + ": cannot write");
  });
  return file;
}

}  // namespace stirrup::render
