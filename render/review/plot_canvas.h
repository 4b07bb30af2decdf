// The plotter: a drawing surface for diagrams with two back ends. Canvas (spine plots, channel plots,
// contact sheets): antialiased lines and disks, filled rectangles, images and DejaVu text, in a float RGB
// buffer written as an 8-bit PNG by OpenImageIO (via FILE.tmp.EXT and a rename). SvgCanvas (the plots of
// `stirrup check`'s HTML page): the same lines, rectangles and text as SVG markup. A chart drawn through
// PlotSurface draws to either.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>

#include "render/review/text.h"

namespace stirrup::render {

using Color = std::array<float, 3>;  // display-referred (written as is to 8 bits)

// The charts' palette: paper, ink and grid greys, and the Okabe-Ito colours, which stay apart for
// colour-blind readers. Shared by the channel plots and any chart that draws curves with a legend.
namespace plot_palette {
inline const Color kBackground = {0.98f, 0.98f, 0.97f};
inline const Color kPanel = {1.0f, 1.0f, 1.0f};
inline const Color kFrameLine = {0.55f, 0.55f, 0.55f};
inline const Color kGrid = {0.88f, 0.88f, 0.88f};
inline const Color kZero = {0.70f, 0.70f, 0.70f};
inline const Color kInk = {0.12f, 0.12f, 0.12f};
inline const Color kMuted = {0.40f, 0.40f, 0.40f};

// Colour-blind-safe (Okabe-Ito).
inline const Color kBlue = {0.0f, 0.45f, 0.70f};
inline const Color kOrange = {0.90f, 0.62f, 0.0f};
inline const Color kGreen = {0.0f, 0.62f, 0.45f};
inline const Color kVermilion = {0.84f, 0.37f, 0.0f};
inline const Color kPurple = {0.80f, 0.47f, 0.65f};
inline const Color kSky = {0.34f, 0.71f, 0.91f};
}  // namespace plot_palette

// A colour written "#rgb" or "#rrggbb" (as in SVG and CSS), each channel its byte over 255.
Color hexColor(std::string_view hex);

// What a plot is drawn on, in pixels with y down: the PNG raster (Canvas) or SVG markup (SvgCanvas).
class PlotSurface {
 public:
  PlotSurface(int width, int height) : width_(width), height_(height) {}
  virtual ~PlotSurface() = default;

  int width() const { return width_; }
  int height() const { return height_; }

  // A segment of the given width.
  virtual void line(glm::dvec2 a, glm::dvec2 b, double width, const Color& c) = 0;
  // A segment drawn `dash` pixels on, `dash` off, from a.
  virtual void dashedLine(glm::dvec2 a, glm::dvec2 b, double width, const Color& c, double dash) = 0;
  // The segments joining the points in turn.
  virtual void polyline(const std::vector<glm::dvec2>& points, double width, const Color& c) = 0;
  // A rectangle from `lo` to `hi` filled, with a one-pixel edge.
  virtual void rect(glm::dvec2 lo, glm::dvec2 hi, const Color& fill, const Color& edge) = 0;
  // Text with its baseline at y; x is the left edge, centre or right edge.
  virtual void text(glm::dvec2 at, const std::string& s, int size, const Color& c, TextAlign align = TextAlign::Left,
                    FontStyle style = FontStyle::Sans) = 0;
  // Writes the file whole or not at all; throws rig::InputError naming the file on failure.
  virtual void write(const std::filesystem::path& file) const = 0;

 protected:
  int width_, height_;
};

// The raster back end, written as a PNG.
class Canvas : public PlotSurface {
 public:
  Canvas(int width, int height, const Color& background);

  // A segment of the given width: each pixel is covered by its distance to the segment, with a
  // one-pixel ramp at the edge, which is enough antialiasing for diagrams.
  void line(glm::dvec2 a, glm::dvec2 b, double width, const Color& c) override;
  void dashedLine(glm::dvec2 a, glm::dvec2 b, double width, const Color& c, double dash) override;
  void polyline(const std::vector<glm::dvec2>& points, double width, const Color& c) override;
  // Filled over the pixels [lo, hi) (corners rounded down), its edge a line along the outermost ones.
  void rect(glm::dvec2 lo, glm::dvec2 hi, const Color& fill, const Color& edge) override;
  void disk(glm::dvec2 centre, double radius, const Color& c) { line(centre, centre, 2.0 * radius, c); }
  void fill(int x0, int y0, int x1, int y1, const Color& c);  // [x0, x1) x [y0, y1)
  // Text with its baseline at y; x is the left edge, centre or right edge.
  void text(int x, int y, const std::string& s, int size, const Color& c, TextAlign align = TextAlign::Left,
            FontStyle style = FontStyle::Sans);
  // The same at (x, y) rounded toward zero.
  void text(glm::dvec2 at, const std::string& s, int size, const Color& c, TextAlign align = TextAlign::Left,
            FontStyle style = FontStyle::Sans) override;
  // Pastes an RGB image (display-referred, row-major, w*h*3) with its top-left at (x, y).
  void paste(int x, int y, int w, int h, const std::vector<float>& rgb);
  // Writes an 8-bit PNG; throws rig::InputError naming the file on failure.
  void write(const std::filesystem::path& file) const override;

  void blend(int x, int y, double coverage, const Color& c);

 private:
  std::vector<float> rgb_;
};

// The SVG back end: each call an element, in the order drawn, with no background (the page shows
// through). Numbers to a tenth of a pixel; what SVG has by default (black text, a stroke width of 1,
// the root's font size) is left out.
class SvgCanvas : public PlotSurface {
 public:
  // `font_size`: the text size set once on the root element.
  SvgCanvas(int width, int height, int font_size);

  void line(glm::dvec2 a, glm::dvec2 b, double width, const Color& c) override;
  void dashedLine(glm::dvec2 a, glm::dvec2 b, double width, const Color& c, double dash) override;
  void polyline(const std::vector<glm::dvec2>& points, double width, const Color& c) override;
  void rect(glm::dvec2 lo, glm::dvec2 hi, const Color& fill, const Color& edge) override;
  void text(glm::dvec2 at, const std::string& s, int size, const Color& c, TextAlign align = TextAlign::Left,
            FontStyle style = FontStyle::Sans) override;
  // The whole <svg> element, to stand alone or inline in an HTML page.
  std::string markup() const;
  // Writes markup() to the file (via FILE.tmp and a rename).
  void write(const std::filesystem::path& file) const override;

 private:
  int font_size_;
  std::string body_;
};

}  // namespace stirrup::render
