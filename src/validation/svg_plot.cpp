// The figures of docs/validation.md: a line plot of a validation case's curves as SVG text,
// written without a plotting library so that `particula validate --report` needs nothing else
// and gives the same bytes from the same data on every machine.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "particula/validation/report.hpp"

namespace particula {

namespace {

constexpr double kWidth = 640, kHeight = 400, kLeft = 78, kRight = 30, kTop = 34, kBottom = 52;
constexpr std::array<const char*, 5> kRunColours = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e"};
constexpr std::array<const char*, 3> kReferenceColours = {"#000000", "#555555", "#8c564b"};
/// A reference curve with more points than this is drawn as a dashed line (an exact
/// solution), fewer as markers (published, digitized points).
constexpr std::size_t kMarkerLimit = 80;
constexpr double kLegendWidth = 244;

std::string xml_escape(const std::string& s) {
  std::string out;
  for (const char ch : s) {
    if (ch == '&') out += "&amp;";
    else if (ch == '<') out += "&lt;";
    else if (ch == '>') out += "&gt;";
    else if (ch == '"') out += "&quot;";
    else out += ch;
  }
  return out;
}

/// The finite range of one coordinate over every series, widened where it is a single value.
struct Range {
  double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  }
  void settle() {
    if (!std::isfinite(lo)) lo = 0, hi = 1;
    if (hi - lo <= 1e-12 * std::max(std::fabs(lo), std::fabs(hi))) {
      const double pad = lo == 0 ? 1 : 0.1 * std::fabs(lo);
      lo -= pad, hi += pad;
    }
  }
};

/// 1, 2 or 5 times a power of ten, about range / 5.
double tick_step(double range) {
  const double raw = range / 5, p = std::pow(10.0, std::floor(std::log10(raw))), m = raw / p;
  return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p;
}

/// The axis rounded out to whole ticks, and the ticks.
std::vector<double> ticks(Range& r) {
  const double step = tick_step(r.hi - r.lo);
  r.lo = std::floor(r.lo / step + 1e-9) * step;
  r.hi = std::ceil(r.hi / step - 1e-9) * step;
  std::vector<double> t;
  for (double k = std::round(r.lo / step); k * step <= r.hi + 1e-9 * step; k += 1) {
    const double v = k * step;
    t.push_back(std::fabs(v) < 1e-9 * step ? 0.0 : v);
  }
  return t;
}

struct Frame {
  Range x, y;
  double px(double v) const { return kLeft + (v - x.lo) / (x.hi - x.lo) * (kWidth - kLeft - kRight); }
  double py(double v) const { return kHeight - kBottom - (v - y.lo) / (y.hi - y.lo) * (kHeight - kTop - kBottom); }
};

void axes(std::string& svg, const Frame& f, const std::vector<double>& xt, const std::vector<double>& yt,
          const ValidationPlot& p) {
  const double x0 = kLeft, x1 = kWidth - kRight, y0 = kTop, y1 = kHeight - kBottom;
  svg += fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"none\" stroke=\"#000\"/>\n",
                     x0, y0, x1 - x0, y1 - y0);
  for (const double t : xt)
    svg += fmt::format(
        "<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{0:.1f}\" y2=\"{2:.1f}\" stroke=\"#ddd\"/>"
        "<text x=\"{0:.1f}\" y=\"{3:.1f}\" text-anchor=\"middle\">{4:g}</text>\n",
        f.px(t), y0, y1, y1 + 16, t);
  for (const double t : yt)
    svg += fmt::format(
        "<line x1=\"{1:.1f}\" y1=\"{0:.1f}\" x2=\"{2:.1f}\" y2=\"{0:.1f}\" stroke=\"#ddd\"/>"
        "<text x=\"{3:.1f}\" y=\"{4:.1f}\" text-anchor=\"end\">{5:g}</text>\n",
        f.py(t), x0, x1, x0 - 5, f.py(t) + 4, t);
  svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{}</text>\n", (x0 + x1) / 2,
                     kHeight - 14, xml_escape(p.x_label));
  svg += fmt::format("<text transform=\"translate(16 {:.1f}) rotate(-90)\" text-anchor=\"middle\">{}</text>\n",
                     (y0 + y1) / 2, xml_escape(p.y_label));
  svg += fmt::format("<text x=\"{:.1f}\" y=\"20\" text-anchor=\"middle\" font-weight=\"bold\">{}</text>\n",
                     kWidth / 2, xml_escape(p.title));
}

/// One curve; returns the legend's sample of it (a short line or a marker).
std::string curve(std::string& svg, const Frame& f, const PlotSeries& s, const char* colour) {
  const bool markers = s.reference && s.x.size() <= kMarkerLimit;
  if (markers) {
    for (std::size_t i = 0; i < s.x.size(); ++i)
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i]))
        svg += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"3\" fill=\"none\" stroke=\"{}\"/>\n", f.px(s.x[i]),
                           f.py(s.y[i]), colour);
    return fmt::format("<circle cx=\"{{0:.1f}}\" cy=\"{{1:.1f}}\" r=\"3\" fill=\"none\" stroke=\"{}\"/>", colour);
  }
  const char* dash = s.reference ? " stroke-dasharray=\"6 4\"" : "";
  std::string points;
  for (std::size_t i = 0; i < s.x.size(); ++i)
    if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) points += fmt::format("{:.1f},{:.1f} ", f.px(s.x[i]), f.py(s.y[i]));
  if (!points.empty()) points.pop_back();
  svg += fmt::format("<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\"{} points=\"{}\"/>\n", colour, dash, points);
  return fmt::format("<line x1=\"{{0:.1f}}\" y1=\"{{1:.1f}}\" x2=\"{{2:.1f}}\" y2=\"{{1:.1f}}\" stroke=\"{}\" "
                     "stroke-width=\"1.5\"{}/>",
                     colour, dash);
}

/// The top-left corner of the legend box: the corner of the plot area (top right, top left,
/// bottom right, bottom left) that covers the fewest points of the curves.
std::pair<double, double> legend_corner(const Frame& f, const ValidationPlot& p, double height) {
  const double x0 = kLeft + 4, x1 = kWidth - kRight - 4 - kLegendWidth, y0 = kTop + 4,
               y1 = kHeight - kBottom - 4 - height;
  const std::pair<double, double> corners[] = {{x1, y0}, {x0, y0}, {x1, y1}, {x0, y1}};
  std::size_t best = 0, fewest = static_cast<std::size_t>(-1);
  for (std::size_t c = 0; c < 4; ++c) {
    std::size_t n = 0;
    for (const auto& s : p.series)
      for (std::size_t i = 0; i < s.x.size(); ++i) {
        const double px = f.px(s.x[i]), py = f.py(s.y[i]);
        n += px >= corners[c].first && px <= corners[c].first + kLegendWidth && py >= corners[c].second &&
             py <= corners[c].second + height;
      }
    if (n < fewest) fewest = n, best = c;
  }
  return corners[best];
}

}  // namespace

std::string svg_plot(const ValidationPlot& p) {
  Frame f;
  for (const auto& s : p.series) {
    for (const double v : s.x) f.x.add(v);
    for (const double v : s.y) f.y.add(v);
  }
  f.x.settle();
  f.y.settle();
  const std::vector<double> xt = ticks(f.x), yt = ticks(f.y);
  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0:.0f}\" height=\"{1:.0f}\" viewBox=\"0 0 {0:.0f} {1:.0f}\" "
      "font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n",
      kWidth, kHeight);
  axes(svg, f, xt, yt, p);
  const double lh = 16 * static_cast<double>(p.series.size()) + 6;
  const auto [lx, ly0] = legend_corner(f, p, lh);
  std::size_t runs = 0, refs = 0;
  std::string legend;
  for (std::size_t k = 0; k < p.series.size(); ++k) {
    const PlotSeries& s = p.series[k];
    const char* colour = s.reference ? kReferenceColours[refs++ % kReferenceColours.size()]
                                     : kRunColours[runs++ % kRunColours.size()];
    const std::string sample = curve(svg, f, s, colour);
    const double ly = ly0 + 12 + 16 * static_cast<double>(k);
    legend += fmt::format(fmt::runtime(sample), lx + 6, ly - 4, lx + 26);
    legend += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\">{}</text>\n", lx + 32, ly, xml_escape(s.label));
  }
  svg += fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.0f}\" height=\"{:.1f}\" fill=\"#fff\" "
                     "fill-opacity=\"0.85\" stroke=\"#999\"/>\n",
                     lx, ly0, kLegendWidth, lh);
  svg += legend + "</svg>\n";
  return svg;
}

}  // namespace particula
