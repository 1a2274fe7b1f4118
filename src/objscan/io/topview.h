#pragma once
// Orthographic top views of a scene: floor light grey, walls dark, furniture filled in its category
// colour with higher surfaces over lower ones (a height buffer), lighter with height and lit from the
// top-left so stacked objects stay visible, thin outlines, a 1 m scale bar, axis arrows, a title and
// a legend of the categories present. The returned mapping lets callers draw robot paths and view
// directions in world coordinates on the same canvas.
#include <string>

#include "objscan/common/error.h"
#include "objscan/io/canvas.h"
#include "objscan/world/scene.h"

namespace objscan::io {

struct TopViewOptions {
  double metres_per_pixel = 0.01;
  double margin_m = 0.3;  // around the walls (or everything when there are none)
  int supersample = 2;    // anti-aliasing: draw at this factor, then box-filter down
  bool outlines = true;
  bool legend = true;
  bool scale_bar = true;
  bool title = true;
  int text_scale = 2;     // font pixels per 5x7 glyph pixel

  template <class V>
  void Visit(V& v) {
    v("metres_per_pixel", metres_per_pixel);
    v("margin_m", margin_m);
    v("supersample", supersample);
    v("outlines", outlines);
    v("legend", legend);
    v("scale_bar", scale_bar);
    v("title", title);
    v("text_scale", text_scale);
  }
  void Validate() const {
    if (!(metres_per_pixel > 0.0005 && metres_per_pixel < 1.0)) throw ConfigError("metres_per_pixel: must be in (0.0005, 1)");
    if (!(margin_m >= 0.0)) throw ConfigError("margin_m: must be >= 0");
    if (supersample < 1 || supersample > 4) throw ConfigError("supersample: must be 1..4");
    if (text_scale < 1 || text_scale > 8) throw ConfigError("text_scale: must be 1..8");
  }
};

struct TopView {
  Canvas canvas;
  WorldToPixel map;  // world XY -> pixels of `canvas`
};

// Throws InputError when the image would exceed 20000 px on a side (metres_per_pixel too small
// for the scene).
TopView RenderTopView(const world::Scene& scene, const TopViewOptions& options);

}  // namespace objscan::io
