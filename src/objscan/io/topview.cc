#include "objscan/io/topview.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace objscan::io {
namespace {

constexpr Rgb kBackground = {255, 255, 255};
constexpr Rgb kInk = {30, 30, 30};
constexpr int kMaxSidePx = 20000;

Rgb ToRgb(const std::array<unsigned char, 3>& c) { return {c[0], c[1], c[2]}; }

// Drawing layers: furniture always over walls, walls over the floor; within a layer the higher
// surface wins.
int LayerOf(world::Category c) {
  if (c == world::Category::kFloor) return 0;
  if (c == world::Category::kWall) return 1;
  return 2;
}

struct Raster {
  int width = 0, height = 0;
  std::vector<float> depth;           // layer * kLayerStride + z
  std::vector<std::int32_t> owner;    // object index or -1
  Canvas* canvas = nullptr;
};
constexpr float kLayerStride = 1000.0f;

// Fills a world triangle projected to pixels with depth test; colour from `shade_of(z)`.
template <class ShadeFn>
void RasterTriangle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c, float za, float zb,
                    float zc, float layer_base, std::int32_t owner, const ShadeFn& shade_of, Raster* r) {
  const double area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  if (std::abs(area) < 1e-9) return;  // vertical faces have no footprint
  const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x(), b.x(), c.x()}))));
  const int x1 = std::min(r->width - 1, static_cast<int>(std::ceil(std::max({a.x(), b.x(), c.x()}))));
  const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y(), b.y(), c.y()}))));
  const int y1 = std::min(r->height - 1, static_cast<int>(std::ceil(std::max({a.y(), b.y(), c.y()}))));
  const double inv = 1.0 / area;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const Eigen::Vector2d p(x + 0.5, y + 0.5);
      // Barycentric weights; the sign convention follows the triangle's orientation.
      const double w0 = ((b - p).x() * (c - p).y() - (b - p).y() * (c - p).x()) * inv;
      const double w1 = ((c - p).x() * (a - p).y() - (c - p).y() * (a - p).x()) * inv;
      const double w2 = 1.0 - w0 - w1;
      if (w0 < 0 || w1 < 0 || w2 < 0) continue;
      const float z = static_cast<float>(w0 * za + w1 * zb + w2 * zc);
      const std::size_t i = static_cast<std::size_t>(y) * r->width + x;
      const float key = layer_base + z;
      if (key <= r->depth[i]) continue;
      r->depth[i] = key;
      r->owner[i] = owner;
      r->canvas->SetPixel(x, y, shade_of(z));
    }
  }
}

std::string LegendLabel(world::Category c, int count) {
  std::string name = world::CategoryName(c);
  std::replace(name.begin(), name.end(), '_', ' ');
  if (world::IsStructural(c)) return name;
  return name + " (" + std::to_string(count) + ")";
}

}  // namespace

TopView RenderTopView(const world::Scene& scene, const TopViewOptions& options) {
  options.Validate();
  // The map covers walls and furniture (the floor quad extends past the walls).
  geometry::Aabb3 extent;
  for (const auto& o : scene.objects()) {
    if (o.category != world::Category::kFloor && o.category != world::Category::kCeiling) {
      extent.Extend(scene.ObjectBounds(o));
    }
  }
  if (extent.Empty()) extent = scene.Bounds();
  if (extent.Empty()) extent.Extend(Eigen::Vector3d(-1, -1, 0)), extent.Extend(Eigen::Vector3d(1, 1, 0));
  extent.min_m -= Eigen::Vector3d(options.margin_m, options.margin_m, 0);
  extent.max_m += Eigen::Vector3d(options.margin_m, options.margin_m, 0);

  const int ts = options.text_scale;
  const int pad = 6 * ts;
  const WorldToPixel map(extent, options.metres_per_pixel, 0);
  if (map.width_px() > kMaxSidePx || map.height_px() > kMaxSidePx) {
    throw InputError("top view of scene '" + scene.name() + "' would be " + std::to_string(map.width_px()) + "x" +
                     std::to_string(map.height_px()) + " px: increase metres_per_pixel");
  }

  // ---- the map, supersampled
  const int ss = options.supersample;
  const WorldToPixel fine = map.Scaled(ss);
  Canvas map_canvas(fine.width_px(), fine.height_px(), kBackground);
  Raster raster;
  raster.width = map_canvas.width();
  raster.height = map_canvas.height();
  raster.depth.assign(static_cast<std::size_t>(raster.width) * raster.height, -std::numeric_limits<float>::infinity());
  raster.owner.assign(raster.depth.size(), -1);
  raster.canvas = &map_canvas;

  const Eigen::Vector3d light = Eigen::Vector3d(-0.35, 0.45, 1.0).normalized();  // from the top-left
  const double furniture_top_m = std::max(0.5, scene.FurnitureBounds().Empty() ? 2.0 : scene.FurnitureBounds().max_m.z());
  std::map<world::Category, int> present;
  for (std::size_t oi = 0; oi < scene.objects().size(); ++oi) {
    const world::SceneObject& o = scene.objects()[oi];
    // Seen from above a ceiling would hide the rooms it covers.
    if (o.category == world::Category::kCeiling) continue;
    ++present[o.category];
    const Rgb base = ToRgb(world::CategoryColor(o.category));
    const int layer = LayerOf(o.category);
    std::vector<Eigen::Vector3d> world_vertices(o.mesh.vertices.size());
    std::vector<Eigen::Vector2d> pixels(o.mesh.vertices.size());
    for (std::size_t v = 0; v < o.mesh.vertices.size(); ++v) {
      world_vertices[v] = o.T_world_object * o.mesh.vertices[v].cast<double>();
      pixels[v] = fine.ToPixel(world_vertices[v]);
    }
    // Whether any triangle covers a pixel seen from above (panels and boxes do; a surface of
    // vertical triangles does not).
    bool has_footprint = false;
    for (const auto& t : o.mesh.triangles) {
      const Eigen::Vector2d ab = pixels[t[1]] - pixels[t[0]], ac = pixels[t[2]] - pixels[t[0]];
      if (std::abs(ab.x() * ac.y() - ab.y() * ac.x()) >= 1.0) {
        has_footprint = true;
        break;
      }
    }
    for (const auto& t : o.mesh.triangles) {
      const Eigen::Vector3d& A = world_vertices[t[0]];
      const Eigen::Vector3d& B = world_vertices[t[1]];
      const Eigen::Vector3d& C = world_vertices[t[2]];
      Eigen::Vector3d n = (B - A).cross(C - A);
      const double len = n.norm();
      if (len < 1e-12) continue;
      n /= len;
      if (n.z() < 0) n = -n;  // seen from above either way
      const double lambert = 0.8 + 0.2 * std::max(0.0, n.dot(light));
      auto shade_of = [&](float z) -> Rgb {
        if (layer < 2) return base;
        // Low surfaces darker, high ones lighter: a table top reads above the chairs under it.
        const double h = std::clamp(z / furniture_top_m, 0.0, 1.0);
        const Rgb by_height = MixRgb(ShadeRgb(base, 0.72), MixRgb(base, {255, 255, 255}, 0.3), h);
        return ShadeRgb(by_height, lambert);
      };
      RasterTriangle(pixels[t[0]], pixels[t[1]], pixels[t[2]], static_cast<float>(A.z()), static_cast<float>(B.z()),
                     static_cast<float>(C.z()), layer * kLayerStride, static_cast<std::int32_t>(oi), shade_of, &raster);
      if (layer == 1 && !has_footprint) {
        // A wall of zero thickness (a scanned wall is a surface, not a panel) has no footprint: its
        // vertical triangles leave their edges, which the thickening below widens.
        for (int k = 0; k < 3; ++k) {
          const Eigen::Vector2d& a = pixels[t[k]];
          const Eigen::Vector2d& b = pixels[t[(k + 1) % 3]];
          const int steps = static_cast<int>(std::ceil((b - a).norm())) + 1;
          for (int i = 0; i <= steps; ++i) {
            const Eigen::Vector2d p = a + (b - a) * (static_cast<double>(i) / steps);
            const int x = static_cast<int>(std::floor(p.x())), y = static_cast<int>(std::floor(p.y()));
            if (x < 0 || y < 0 || x >= raster.width || y >= raster.height) continue;
            const std::size_t j = static_cast<std::size_t>(y) * raster.width + x;
            if (raster.owner[j] >= 0 && LayerOf(scene.objects()[raster.owner[j]].category) >= 1) continue;
            raster.owner[j] = static_cast<std::int32_t>(oi);
            raster.depth[j] = kLayerStride + static_cast<float>(std::max({A.z(), B.z(), C.z()}));
            map_canvas.SetPixel(x, y, base);
          }
        }
      }
    }
  }

  {
    // Thin wall panels (1 cm) would be a hairline: thicken them by one output pixel on each side,
    // over the floor only.
    const int r = ss;
    std::vector<std::int32_t> owner = raster.owner;
    for (int y = 0; y < raster.height; ++y) {
      for (int x = 0; x < raster.width; ++x) {
        const std::int32_t o = owner[static_cast<std::size_t>(y) * raster.width + x];
        if (o < 0 || scene.objects()[o].category != world::Category::kWall) continue;
        const Rgb wall = map_canvas.Pixel(x, y);
        for (int dy = -r; dy <= r; ++dy) {
          for (int dx = -r; dx <= r; ++dx) {
            const int xx = x + dx, yy = y + dy;
            if (xx < 0 || yy < 0 || xx >= raster.width || yy >= raster.height) continue;
            const std::size_t j = static_cast<std::size_t>(yy) * raster.width + xx;
            const std::int32_t oj = raster.owner[j];
            if (oj >= 0 && LayerOf(scene.objects()[oj].category) > 0) continue;
            raster.owner[j] = o;
            map_canvas.SetPixel(xx, yy, wall);
          }
        }
      }
    }
  }
  if (options.outlines) {
    // Darken both sides of every boundary that involves a piece of furniture.
    const auto is_furniture = [&](std::int32_t owner) {
      return owner >= 0 && LayerOf(scene.objects()[owner].category) == 2;
    };
    std::vector<std::uint8_t> edge(raster.owner.size(), 0);
    for (int y = 0; y < raster.height; ++y) {
      for (int x = 0; x < raster.width; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * raster.width + x;
        const std::int32_t a = raster.owner[i];
        if (x + 1 < raster.width && raster.owner[i + 1] != a && (is_furniture(a) || is_furniture(raster.owner[i + 1]))) {
          edge[i] = edge[i + 1] = 1;
        }
        if (y + 1 < raster.height) {
          const std::size_t j = i + raster.width;
          if (raster.owner[j] != a && (is_furniture(a) || is_furniture(raster.owner[j]))) edge[i] = edge[j] = 1;
        }
      }
    }
    for (int y = 0; y < raster.height; ++y) {
      for (int x = 0; x < raster.width; ++x) {
        if (edge[static_cast<std::size_t>(y) * raster.width + x]) map_canvas.SetPixel(x, y, ShadeRgb(map_canvas.Pixel(x, y), 0.45));
      }
    }
  }
  const Canvas map_small = map_canvas.Downsampled(ss);

  // ---- layout: title band on top, legend on the right
  const int title_h = options.title ? Canvas::TextHeight("X", ts) + 2 * pad : 0;
  std::vector<std::pair<world::Category, int>> entries(present.begin(), present.end());
  std::stable_sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) {
    return world::IsStructural(a.first) != world::IsStructural(b.first) ? !world::IsStructural(a.first)
                                                                        : world::CategoryId(a.first) < world::CategoryId(b.first);
  });
  const int swatch = 9 * ts;
  const int row_h = swatch + 4 * ts;
  int legend_w = 0, legend_h = 0;
  if (options.legend && !entries.empty()) {
    for (const auto& [c, n] : entries) legend_w = std::max(legend_w, Canvas::TextWidth(LegendLabel(c, n), ts));
    legend_w += swatch + 3 * pad;
    legend_h = static_cast<int>(entries.size()) * row_h + 2 * pad;
  }
  // Footer under the map for the scale bar and the axis arrows, so they never hide the scene.
  const int footer_h = std::max(options.scale_bar ? Canvas::TextHeight("1 m", ts) + 10 * ts : 0, 16 * ts) + pad;
  const int width = map_small.width() + legend_w;
  const int height = std::max(title_h + map_small.height() + footer_h, title_h + legend_h);
  TopView view;
  view.canvas = Canvas(width, height, kBackground);
  view.canvas.Blit(map_small, 0, title_h);
  view.map = map.Shifted(Eigen::Vector2d(0, title_h));

  if (options.title) {
    std::string title = scene.name().empty() ? "scene" : scene.name();
    const int max_chars = std::max(8, (width - 2 * pad) / (6 * ts));
    if (static_cast<int>(title.size()) > max_chars) title = "..." + title.substr(title.size() - (max_chars - 3));
    view.canvas.DrawText(pad, pad, title, kInk, ts);
  }
  if (options.legend && !entries.empty()) {
    const int x = map_small.width() + pad;
    int y = title_h + pad;
    for (const auto& [c, n] : entries) {
      const Rgb color = ToRgb(world::CategoryColor(c));
      view.canvas.FillRect(x, y, x + swatch, y + swatch, color);
      view.canvas.DrawRect(x, y, x + swatch, y + swatch, ShadeRgb(color, 0.5), 1);
      view.canvas.DrawText(x + swatch + pad, y + (swatch - 7 * ts) / 2, LegendLabel(c, n), kInk, ts);
      y += row_h;
    }
  }
  const int footer_top = title_h + map_small.height();
  if (options.scale_bar) {
    // A 1 m bar with end ticks and its label above it.
    const int bar_px = static_cast<int>(std::lround(1.0 / options.metres_per_pixel));
    const std::string label = "1 m";
    const int x0 = pad;
    const int label_y = footer_top + 2 * ts;
    const int y0 = label_y + Canvas::TextHeight(label, ts) + 3 * ts;
    view.canvas.DrawText(x0 + bar_px / 2 - Canvas::TextWidth(label, ts) / 2, label_y, label, kInk, ts);
    view.canvas.FillRect(x0, y0, x0 + bar_px, y0 + 2 * ts, kInk);
    view.canvas.FillRect(x0, y0 - 2 * ts, x0 + ts, y0 + 3 * ts, kInk);
    view.canvas.FillRect(x0 + bar_px - ts, y0 - 2 * ts, x0 + bar_px, y0 + 3 * ts, kInk);
  }
  {
    // Axis arrows (+x right, +y up) at the right end of the footer.
    const double len = 12.0 * ts;
    const Eigen::Vector2d o(map_small.width() - pad - len - 8 * ts, footer_top + footer_h - pad - ts);
    view.canvas.DrawArrow(o, o + Eigen::Vector2d(len, 0), kInk, ts, 4.0 * ts);
    view.canvas.DrawArrow(o, o + Eigen::Vector2d(0, -len), kInk, ts, 4.0 * ts);
    view.canvas.DrawText(static_cast<int>(o.x() + len) + 2 * ts, static_cast<int>(o.y()) - 4 * ts, "x", kInk, ts);
    view.canvas.DrawText(static_cast<int>(o.x()) - 8 * ts, static_cast<int>(o.y() - len), "y", kInk, ts);
  }
  return view;
}

}  // namespace objscan::io
