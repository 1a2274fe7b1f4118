#include "objscan/eval/plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "objscan/io/atomic_file.h"

namespace objscan::eval {
namespace {

// The plot as drawing primitives in pixel coordinates, rendered to SVG or to a canvas.
enum class Anchor { kLeft, kCenter, kRight };

struct Primitive {
  enum Kind { kLine, kPolyline, kRect, kDot, kText } kind = kLine;
  std::vector<Eigen::Vector2d> points;  // line: 2, polyline: n, rect: 2 corners, dot: 1 centre
  io::Rgb color = {0, 0, 0};
  double width_px = 1.0;  // line width, dot radius
  std::string text;       // text: top-left / top-centre / top-right at points[0]
  int text_scale = 1;
  Anchor anchor = Anchor::kLeft;
};

struct Drawing {
  int width = 860, height = 540;
  std::vector<Primitive> items;

  void Line(double x0, double y0, double x1, double y1, io::Rgb c, double w = 1.0) {
    Primitive p;
    p.kind = Primitive::kLine;
    p.points = {{x0, y0}, {x1, y1}};
    p.color = c;
    p.width_px = w;
    items.push_back(p);
  }
  void Polyline(std::vector<Eigen::Vector2d> pts, io::Rgb c, double w) {
    Primitive p;
    p.kind = Primitive::kPolyline;
    p.points = std::move(pts);
    p.color = c;
    p.width_px = w;
    items.push_back(p);
  }
  void Rect(double x0, double y0, double x1, double y1, io::Rgb c) {
    Primitive p;
    p.kind = Primitive::kRect;
    p.points = {{x0, y0}, {x1, y1}};
    p.color = c;
    items.push_back(p);
  }
  void Dot(double x, double y, double r, io::Rgb c) {
    Primitive p;
    p.kind = Primitive::kDot;
    p.points = {{x, y}};
    p.width_px = r;
    p.color = c;
    items.push_back(p);
  }
  void Text(double x, double y, const std::string& s, int scale = 1, Anchor a = Anchor::kLeft,
            io::Rgb c = {0, 0, 0}) {
    Primitive p;
    p.kind = Primitive::kText;
    p.points = {{x, y}};
    p.text = s;
    p.text_scale = scale;
    p.anchor = a;
    p.color = c;
    items.push_back(p);
  }
};

std::string Hex(io::Rgb c) {
  char buf[8];
  std::snprintf(buf, sizeof(buf), "#%02x%02x%02x", c[0], c[1], c[2]);
  return buf;
}

std::string XmlEscape(const std::string& s) {
  std::string out;
  for (char ch : s) {
    switch (ch) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      default: out += ch;
    }
  }
  return out;
}

std::string ToSvg(const Drawing& d) {
  std::ostringstream s;
  s.precision(6);
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << d.width << "\" height=\"" << d.height
    << "\" viewBox=\"0 0 " << d.width << ' ' << d.height << "\">\n";
  s << "<rect x=\"0\" y=\"0\" width=\"" << d.width << "\" height=\"" << d.height << "\" fill=\"#ffffff\"/>\n";
  for (const Primitive& p : d.items) {
    switch (p.kind) {
      case Primitive::kLine:
        s << "<line x1=\"" << p.points[0].x() << "\" y1=\"" << p.points[0].y() << "\" x2=\"" << p.points[1].x()
          << "\" y2=\"" << p.points[1].y() << "\" stroke=\"" << Hex(p.color) << "\" stroke-width=\"" << p.width_px
          << "\"/>\n";
        break;
      case Primitive::kPolyline: {
        s << "<polyline fill=\"none\" stroke=\"" << Hex(p.color) << "\" stroke-width=\"" << p.width_px
          << "\" stroke-linejoin=\"round\" points=\"";
        for (const auto& q : p.points) s << q.x() << ',' << q.y() << ' ';
        s << "\"/>\n";
        break;
      }
      case Primitive::kRect: {
        const double x0 = std::min(p.points[0].x(), p.points[1].x());
        const double y0 = std::min(p.points[0].y(), p.points[1].y());
        s << "<rect x=\"" << x0 << "\" y=\"" << y0 << "\" width=\"" << std::abs(p.points[1].x() - p.points[0].x())
          << "\" height=\"" << std::abs(p.points[1].y() - p.points[0].y()) << "\" fill=\"" << Hex(p.color)
          << "\"/>\n";
        break;
      }
      case Primitive::kDot:
        s << "<circle cx=\"" << p.points[0].x() << "\" cy=\"" << p.points[0].y() << "\" r=\"" << p.width_px
          << "\" fill=\"" << Hex(p.color) << "\"/>\n";
        break;
      case Primitive::kText: {
        // The PNG font is 7 px tall per scale unit; the SVG baseline sits at the same place.
        const char* anchor = p.anchor == Anchor::kLeft ? "start" : p.anchor == Anchor::kCenter ? "middle" : "end";
        s << "<text x=\"" << p.points[0].x() << "\" y=\"" << p.points[0].y() + 7.0 * p.text_scale
          << "\" font-family=\"monospace\" font-size=\"" << 10 * p.text_scale << "\" text-anchor=\"" << anchor
          << "\" fill=\"" << Hex(p.color) << "\">" << XmlEscape(p.text) << "</text>\n";
        break;
      }
    }
  }
  s << "</svg>\n";
  return s.str();
}

io::Canvas ToCanvas(const Drawing& d) {
  io::Canvas c(d.width, d.height, {255, 255, 255});
  for (const Primitive& p : d.items) {
    switch (p.kind) {
      case Primitive::kLine: c.DrawLine(p.points[0], p.points[1], p.color, p.width_px); break;
      case Primitive::kPolyline: c.DrawPolyline(p.points, p.color, p.width_px); break;
      case Primitive::kRect:
        c.FillRect(static_cast<int>(std::lround(std::min(p.points[0].x(), p.points[1].x()))),
                   static_cast<int>(std::lround(std::min(p.points[0].y(), p.points[1].y()))),
                   static_cast<int>(std::lround(std::max(p.points[0].x(), p.points[1].x()))),
                   static_cast<int>(std::lround(std::max(p.points[0].y(), p.points[1].y()))), p.color);
        break;
      case Primitive::kDot: c.FillCircle(p.points[0], p.width_px, p.color); break;
      case Primitive::kText: {
        const int w = io::Canvas::TextWidth(p.text, p.text_scale);
        int x = static_cast<int>(std::lround(p.points[0].x()));
        if (p.anchor == Anchor::kCenter) x -= w / 2;
        if (p.anchor == Anchor::kRight) x -= w;
        c.DrawText(x, static_cast<int>(std::lround(p.points[0].y())), p.text, p.color, p.text_scale);
        break;
      }
    }
  }
  return c;
}

std::string FormatTick(double v, double step) {
  int decimals = 0;
  while (decimals < 6 && std::abs(step * std::pow(10.0, decimals) - std::round(step * std::pow(10.0, decimals))) > 1e-6) {
    ++decimals;
  }
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, std::abs(v) < 1e-12 ? 0.0 : v);
  return buf;
}

// The frame shared by line and bar plots: title, axes box, y grid with labels, legend entries.
struct Frame {
  double left = 70, right = 0, top = 46, bottom = 0;  // plot area in pixels
  double y_lo = 0, y_hi = 1;
  std::vector<double> y_ticks;
  double Y(double v) const { return bottom - (v - y_lo) / (y_hi - y_lo) * (bottom - top); }
};

Frame MakeFrame(Drawing* d, const std::string& title, const std::string& y_label, double y_lo, double y_hi,
                int legend_entries, const std::string& note) {
  Frame f;
  f.right = d->width - (legend_entries > 0 ? 200.0 : 24.0);
  f.bottom = d->height - (note.empty() ? 52.0 : 66.0);
  if (!(y_hi > y_lo)) y_hi = y_lo + 1.0;
  f.y_ticks = NiceTicks(y_lo, y_hi);
  f.y_lo = std::min(y_lo, f.y_ticks.front());
  f.y_hi = std::max(y_hi, f.y_ticks.back());
  d->Text(d->width / 2.0, 10, title, 2, Anchor::kCenter);
  d->Text(f.left - 8, f.top - 16, y_label, 1, Anchor::kLeft, {60, 60, 60});
  const double step = f.y_ticks.size() > 1 ? f.y_ticks[1] - f.y_ticks[0] : 1.0;
  for (double t : f.y_ticks) {
    const double y = f.Y(t);
    d->Line(f.left, y, f.right, y, {225, 225, 225});
    d->Text(f.left - 6, y - 3.5, FormatTick(t, step), 1, Anchor::kRight, {60, 60, 60});
  }
  if (!note.empty()) d->Text(12, d->height - 18, note, 1, Anchor::kLeft, {90, 90, 90});
  return f;
}

void DrawAxesBox(Drawing* d, const Frame& f) {
  d->Line(f.left, f.bottom, f.right, f.bottom, {0, 0, 0});
  d->Line(f.left, f.top, f.left, f.bottom, {0, 0, 0});
}

void LegendEntry(Drawing* d, const Frame& f, int index, const std::string& label, io::Rgb color, bool dot) {
  const double x = f.right + 16, y = f.top + 4 + index * 18.0;
  if (dot) {
    d->Dot(x + 8, y + 4, 3.5, color);
  } else {
    d->Rect(x, y, x + 16, y + 9, color);
  }
  d->Text(x + 22, y + 1, label, 1);
}

void Range(const std::vector<double>& v, double* lo, double* hi) {
  for (double x : v) {
    if (!std::isfinite(x)) continue;
    *lo = std::min(*lo, x);
    *hi = std::max(*hi, x);
  }
}

Drawing Layout(const LinePlot& plot) {
  Drawing d;
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo;
  double y_lo = x_lo, y_hi = -x_lo;
  for (const auto& s : plot.series) {
    Range(s.x, &x_lo, &x_hi);
    Range(s.y, &y_lo, &y_hi);
  }
  if (!std::isfinite(x_lo)) x_lo = 0, x_hi = 1;
  if (!std::isfinite(y_lo)) y_lo = 0, y_hi = 1;
  if (plot.y_min) y_lo = *plot.y_min;
  if (plot.y_max) y_hi = *plot.y_max;
  if (!(x_hi > x_lo)) x_hi = x_lo + 1.0;
  const int legend = static_cast<int>(plot.series.size()) + (plot.highlight_label.empty() ? 0 : 1);
  const Frame f = MakeFrame(&d, plot.title, plot.y_label, y_lo, y_hi, legend, plot.note);
  const std::vector<double> x_ticks = NiceTicks(x_lo, x_hi);
  const double xl = std::min(x_lo, x_ticks.front()), xh = std::max(x_hi, x_ticks.back());
  auto X = [&](double v) { return f.left + (v - xl) / (xh - xl) * (f.right - f.left); };
  auto Y = [&](double v) { return f.Y(std::clamp(v, f.y_lo, f.y_hi)); };
  const double x_step = x_ticks.size() > 1 ? x_ticks[1] - x_ticks[0] : 1.0;
  for (double t : x_ticks) {
    d.Line(X(t), f.top, X(t), f.bottom, {235, 235, 235});
    d.Text(X(t), f.bottom + 6, FormatTick(t, x_step), 1, Anchor::kCenter, {60, 60, 60});
  }
  d.Text((f.left + f.right) / 2, f.bottom + 24, plot.x_label, 1, Anchor::kCenter);
  DrawAxesBox(&d, f);
  int index = 0;
  for (const auto& s : plot.series) {
    std::vector<Eigen::Vector2d> pts;
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) pts.emplace_back(X(s.x[i]), Y(s.y[i]));
    }
    if (s.line && pts.size() > 1) d.Polyline(pts, s.color, 2.0);
    // A series that does not move along x (e.g. a run that never travelled) would be an invisible
    // line: draw its points.
    const bool degenerate = !pts.empty() && std::all_of(pts.begin(), pts.end(), [&](const Eigen::Vector2d& q) {
      return std::abs(q.x() - pts.front().x()) < 0.5;
    });
    if (s.markers || degenerate) {
      for (const auto& p : pts) d.Dot(p.x(), p.y(), 3.0, s.color);
    }
    LegendEntry(&d, f, index++, s.label, s.color, !s.line);
  }
  const io::Rgb red = {220, 20, 20};
  for (const auto& s : plot.series) {
    for (std::size_t i = 0; i < s.highlight_x.size() && i < s.highlight_y.size(); ++i) {
      d.Dot(X(s.highlight_x[i]), Y(s.highlight_y[i]), 3.5, red);
    }
  }
  if (!plot.highlight_label.empty()) LegendEntry(&d, f, index, plot.highlight_label, red, true);
  return d;
}

Drawing Layout(const BarPlot& plot) {
  Drawing d;
  double y_lo = 0.0, y_hi = -std::numeric_limits<double>::infinity();
  for (const auto& s : plot.series) Range(s.values, &y_lo, &y_hi);
  if (!std::isfinite(y_hi)) y_hi = 1.0;
  if (plot.y_min) y_lo = *plot.y_min;
  if (plot.y_max) y_hi = *plot.y_max;
  const Frame f = MakeFrame(&d, plot.title, plot.y_label, y_lo, y_hi, static_cast<int>(plot.series.size()), plot.note);
  const std::size_t groups = std::max<std::size_t>(1, plot.groups.size());
  const double group_w = (f.right - f.left) / groups;
  const double bar_w = 0.8 * group_w / std::max<std::size_t>(1, plot.series.size());
  for (std::size_t g = 0; g < plot.groups.size(); ++g) {
    const double x0 = f.left + g * group_w + 0.1 * group_w;
    for (std::size_t s = 0; s < plot.series.size(); ++s) {
      if (g >= plot.series[s].values.size() || !std::isfinite(plot.series[s].values[g])) continue;
      const double v = std::clamp(plot.series[s].values[g], f.y_lo, f.y_hi);
      d.Rect(x0 + s * bar_w, f.Y(std::max(0.0, f.y_lo)), x0 + (s + 1) * bar_w - 1.0, f.Y(v), plot.series[s].color);
    }
    d.Text(f.left + (g + 0.5) * group_w, f.bottom + 6, plot.groups[g], 1, Anchor::kCenter);
  }
  DrawAxesBox(&d, f);
  for (std::size_t s = 0; s < plot.series.size(); ++s) {
    LegendEntry(&d, f, static_cast<int>(s), plot.series[s].label, plot.series[s].color, false);
  }
  return d;
}

template <class Plot>
void SaveBoth(const Plot& plot, const std::string& path_stem) {
  const Drawing d = Layout(plot);
  io::WriteFileAtomically(path_stem + ".svg", ToSvg(d));
  ToCanvas(d).SavePng(path_stem + ".png");
}

}  // namespace

io::Rgb PlotColor(int i) {
  static constexpr io::Rgb kPalette[] = {{31, 119, 180}, {255, 127, 14}, {44, 160, 44},  {148, 103, 189},
                                         {140, 86, 75},  {227, 119, 194}, {127, 127, 127}, {188, 189, 34},
                                         {23, 190, 207}, {214, 39, 40}};
  constexpr int n = sizeof(kPalette) / sizeof(kPalette[0]);
  return kPalette[((i % n) + n) % n];
}

std::vector<double> NiceTicks(double lo, double hi, int target) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) return {0.0, 1.0};
  if (hi < lo) std::swap(lo, hi);
  if (hi - lo < 1e-12) {
    lo -= 0.5;
    hi += 0.5;
  }
  const double raw = (hi - lo) / std::max(1, target - 1);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  double step = magnitude;
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0}) {
    step = m * magnitude;
    if (step >= raw) break;
  }
  std::vector<double> ticks;
  const double first = std::floor(lo / step + 1e-9) * step;
  for (double t = first; t < hi + step - 1e-9 * step; t += step) ticks.push_back(std::abs(t) < 1e-12 ? 0.0 : t);
  if (ticks.size() < 2) ticks.push_back(ticks.empty() ? lo : ticks.back() + step);
  return ticks;
}

std::string RenderSvg(const LinePlot& plot) { return ToSvg(Layout(plot)); }
std::string RenderSvg(const BarPlot& plot) { return ToSvg(Layout(plot)); }
io::Canvas RenderCanvas(const LinePlot& plot) { return ToCanvas(Layout(plot)); }
io::Canvas RenderCanvas(const BarPlot& plot) { return ToCanvas(Layout(plot)); }
void SavePlot(const LinePlot& plot, const std::string& path_stem) { SaveBoth(plot, path_stem); }
void SavePlot(const BarPlot& plot, const std::string& path_stem) { SaveBoth(plot, path_stem); }

}  // namespace objscan::eval
