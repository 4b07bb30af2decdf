#include "render/review/plot_canvas.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "render/image_files/image_file.h"
#include "render/review/index_page.h"
#include "rig/error.h"

namespace stirrup::render {

Color hexColor(std::string_view hex) {
  const bool short_form = hex.size() == 4;
  if (hex.empty() || hex[0] != '#' || (!short_form && hex.size() != 7)) throw std::invalid_argument("hexColor: expected #rgb or #rrggbb");
  Color c{};
  for (int k = 0; k < 3; ++k) {
    const std::string digits = short_form ? std::string(2, hex[std::size_t(1 + k)]) : std::string(hex.substr(std::size_t(1 + 2 * k), 2));
    c[std::size_t(k)] = float(std::stoi(digits, nullptr, 16)) / 255.0f;
  }
  return c;
}

Canvas::Canvas(int width, int height, const Color& background)
    : PlotSurface(width, height), rgb_(std::size_t(width) * std::size_t(height) * 3) {
  for (std::size_t i = 0; i < rgb_.size(); ++i) rgb_[i] = background[i % 3];
}

void Canvas::line(glm::dvec2 a, glm::dvec2 b, double width, const Color& c) {
  const double r = 0.5 * width;
  const int x0 = std::max(0, int(std::floor(std::min(a.x, b.x) - r - 1)));
  const int x1 = std::min(width_ - 1, int(std::ceil(std::max(a.x, b.x) + r + 1)));
  const int y0 = std::max(0, int(std::floor(std::min(a.y, b.y) - r - 1)));
  const int y1 = std::min(height_ - 1, int(std::ceil(std::max(a.y, b.y) + r + 1)));
  const glm::dvec2 ab = b - a;
  const double len2 = glm::dot(ab, ab);
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const glm::dvec2 p(x + 0.5, y + 0.5);
      const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
      const double d = glm::length(p - (a + t * ab));
      blend(x, y, std::clamp(r + 0.5 - d, 0.0, 1.0), c);
    }
}

void Canvas::dashedLine(glm::dvec2 a, glm::dvec2 b, double width, const Color& c, double dash) {
  const double length = glm::length(b - a);
  if (length <= 0.0 || dash <= 0.0) return line(a, b, width, c);
  const glm::dvec2 along = (b - a) / length;
  for (double s = 0.0; s < length; s += 2.0 * dash) line(a + s * along, a + std::min(s + dash, length) * along, width, c);
}

void Canvas::polyline(const std::vector<glm::dvec2>& points, double width, const Color& c) {
  for (std::size_t k = 0; k + 1 < points.size(); ++k) line(points[k], points[k + 1], width, c);
}

void Canvas::rect(glm::dvec2 lo, glm::dvec2 hi, const Color& fill_colour, const Color& edge) {
  const int x0 = int(std::floor(lo.x)), y0 = int(std::floor(lo.y)), x1 = int(std::floor(hi.x)), y1 = int(std::floor(hi.y));
  fill(x0, y0, x1, y1, fill_colour);
  const double l = x0 + 0.5, t = y0 + 0.5, r = x1 - 0.5, b = y1 - 0.5;
  polyline({{l, t}, {r, t}, {r, b}, {l, b}, {l, t}}, 1.0, edge);
}

void Canvas::fill(int x0, int y0, int x1, int y1, const Color& c) {
  for (int y = std::max(0, y0); y < std::min(height_, y1); ++y)
    for (int x = std::max(0, x0); x < std::min(width_, x1); ++x) blend(x, y, 1.0, c);
}

void Canvas::text(int x, int y, const std::string& s, int size, const Color& c, TextAlign align, FontStyle style) {
  std::vector<float> mask(std::size_t(width_) * std::size_t(height_), 0.0f);
  drawTextMask(mask, width_, height_, x, y, s, size, style, align);
  for (int py = 0; py < height_; ++py)
    for (int px = 0; px < width_; ++px) {
      const float m = mask[std::size_t(py) * width_ + px];
      if (m > 0.0f) blend(px, py, std::min(1.0f, m), c);
    }
}

void Canvas::text(glm::dvec2 at, const std::string& s, int size, const Color& c, TextAlign align, FontStyle style) {
  text(int(at.x), int(at.y), s, size, c, align, style);
}

void Canvas::paste(int x, int y, int w, int h, const std::vector<float>& rgb) {
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      const int X = x + px, Y = y + py;
      if (X < 0 || Y < 0 || X >= width_ || Y >= height_) continue;
      for (int k = 0; k < 3; ++k) rgb_[(std::size_t(Y) * width_ + X) * 3 + k] = rgb[(std::size_t(py) * w + px) * 3 + k];
    }
}

void Canvas::write(const std::filesystem::path& file) const {
  ImageFileSpec spec;
  spec.width = width_, spec.height = height_;
  spec.channel_formats.assign(3, StoredAs::UInt8);
  writeImageFile(file, "", spec, rgb_.data());
}

void Canvas::blend(int x, int y, double coverage, const Color& c) {
  if (coverage <= 0.0 || x < 0 || y < 0 || x >= width_ || y >= height_) return;
  float* px = &rgb_[(std::size_t(y) * width_ + x) * 3];
  for (int k = 0; k < 3; ++k) px[k] = float(px[k] + coverage * (c[k] - px[k]));
}

namespace {

// A coordinate to a tenth of a pixel, without a trailing ".0".
std::string svgNumber(double v) {
  std::string s = rig::printfNumber("%.1f", v);
  if (s.size() > 2 && s.compare(s.size() - 2, 2, ".0") == 0) s.resize(s.size() - 2);
  return s == "-0" ? "0" : s;
}

// "#rgb" where each channel's byte is a doubled hex digit, else "#rrggbb".
std::string svgColour(const Color& c) {
  int bytes[3];
  bool doubled = true;
  for (int k = 0; k < 3; ++k) {
    bytes[k] = int(std::lround(std::clamp(c[std::size_t(k)], 0.0f, 1.0f) * 255.0f));
    doubled = doubled && bytes[k] % 17 == 0;
  }
  char buf[8];
  if (doubled) std::snprintf(buf, sizeof buf, "#%x%x%x", bytes[0] / 17, bytes[1] / 17, bytes[2] / 17);
  else std::snprintf(buf, sizeof buf, "#%02x%02x%02x", bytes[0], bytes[1], bytes[2]);
  return buf;
}

std::string strokeWidth(double width) { return width == 1.0 ? "" : " stroke-width=\"" + svgNumber(width) + "\""; }

}  // namespace

SvgCanvas::SvgCanvas(int width, int height, int font_size) : PlotSurface(width, height), font_size_(font_size) {}

void SvgCanvas::line(glm::dvec2 a, glm::dvec2 b, double width, const Color& c) {
  body_ += "<line x1=\"" + svgNumber(a.x) + "\" x2=\"" + svgNumber(b.x) + "\" y1=\"" + svgNumber(a.y) + "\" y2=\"" + svgNumber(b.y) +
           "\" stroke=\"" + svgColour(c) + "\"" + strokeWidth(width) + "/>";
}

void SvgCanvas::dashedLine(glm::dvec2 a, glm::dvec2 b, double width, const Color& c, double dash) {
  line(a, b, width, c);
  body_.insert(body_.size() - 2, " stroke-dasharray=\"" + svgNumber(dash) + "," + svgNumber(dash) + "\"");
}

void SvgCanvas::polyline(const std::vector<glm::dvec2>& points, double width, const Color& c) {
  std::string pts;
  for (const glm::dvec2& p : points) {
    if (!pts.empty()) pts += ' ';
    pts += svgNumber(p.x) + "," + svgNumber(p.y);
  }
  body_ += "<polyline fill=\"none\" stroke=\"" + svgColour(c) + "\"" + strokeWidth(width) + " points=\"" + pts + "\"/>";
}

void SvgCanvas::rect(glm::dvec2 lo, glm::dvec2 hi, const Color& fill, const Color& edge) {
  body_ += "<rect x=\"" + svgNumber(lo.x) + "\" y=\"" + svgNumber(lo.y) + "\" width=\"" + svgNumber(hi.x - lo.x) + "\" height=\"" +
           svgNumber(hi.y - lo.y) + "\" fill=\"" + svgColour(fill) + "\" stroke=\"" + svgColour(edge) + "\"/>";
}

void SvgCanvas::text(glm::dvec2 at, const std::string& s, int size, const Color& c, TextAlign align, FontStyle style) {
  body_ += "<text x=\"" + svgNumber(at.x) + "\" y=\"" + svgNumber(at.y) + "\"";
  if (align != TextAlign::Left) body_ += std::string(" text-anchor=\"") + (align == TextAlign::Center ? "middle" : "end") + "\"";
  if (size != font_size_) body_ += " font-size=\"" + std::to_string(size) + "\"";
  if (style == FontStyle::SansBold) body_ += " font-weight=\"bold\"";
  if (style == FontStyle::Mono) body_ += " font-family=\"monospace\"";
  if (svgColour(c) != "#000") body_ += " fill=\"" + svgColour(c) + "\"";
  body_ += '>';
  body_ += htmlEscape(s) + "</text>";
}

std::string SvgCanvas::markup() const {
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(width_) + "\" height=\"" + std::to_string(height_) +
         "\" font-size=\"" + std::to_string(font_size_) + "\">" + body_ + "</svg>";
}

void SvgCanvas::write(const std::filesystem::path& file) const { rig::writeFileAtomically(file, markup() + "\n"); }

}  // namespace stirrup::render
