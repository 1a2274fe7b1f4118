// Report rules about where an object is against the walls: door_depth, wall_openings,
// curtain_must_hang, join_window_pieces, curtains_over_windows (wall_openings.h).
#include "objscan/mapping/planes.h"
#include "objscan/scanning/report/report_rules.h"
#include "objscan/scanning/report/wall_openings.h"

namespace objscan::scanning {

void DoorDepthRule::Apply(const ReportContext& context, ReportedObjects* objects) const {
  for (std::size_t i = 0; i < objects->size(); ++i) {
    const ReportedObject& o = (*objects)[i];
    if (!o.reported() || o.record.complete || o.record.category != world::Category::kDoor) continue;
    if (TooDeepForADoor(context.SeenPoints(*objects, i), options_)) objects->TakeLabel(i, name());
  }
}

void WallOpeningsRule::Apply(const ReportContext& context, ReportedObjects* objects) const {
  if (context.structure->walls.empty()) return;
  for (std::size_t i = 0; i < objects->size(); ++i) {
    const ReportedObject& o = (*objects)[i];
    if (!o.reported()) continue;
    const bool window = o.record.category == world::Category::kWindow;
    const WallOpeningResult opening =
        ClassifyWallOpening(context.SeenPoints(*objects, i), *context.structure, window, options_);
    ReportedObject& m = objects->mutable_object(i);
    m.record.wall_opening_share = opening.share;
    m.in_wall_opening = opening.verdict == WallOpeningVerdict::kWindow;
    if (opening.verdict == WallOpeningVerdict::kNotWindow) {
      objects->TakeLabel(i, name());
    } else if (opening.verdict == WallOpeningVerdict::kWindow && !window) {
      const auto best = context.sources->BestOfCategory(o.record.labels, world::Category::kWindow);
      if (best) objects->Adopt(i, *best, context.sources->ModelName(best->model_id), name());
    }
  }
}

void CurtainMustHangRule::Apply(const ReportContext& context, ReportedObjects* objects) const {
  for (std::size_t i = 0; i < objects->size(); ++i) {
    const ReportedObject& o = (*objects)[i];
    if (!o.reported() || o.record.category != world::Category::kCurtain) continue;
    const OpeningExtent hanging = HangingExtent(context.SeenPoints(*objects, i), *context.structure, options_);
    if (CurtainLabelGoes(o.record.category, hanging, options_)) objects->TakeLabel(i, name());
  }
}

void JoinWindowPiecesRule::Apply(const ReportContext& context, ReportedObjects* objects) const {
  std::vector<WindowPiece> pieces(objects->size());
  for (std::size_t i = 0; i < objects->size(); ++i) {
    const ReportedObject& o = (*objects)[i];
    if (!o.reported() || o.record.category != world::Category::kWindow) continue;
    const std::vector<Eigen::Vector3f> seen = context.SeenPoints(*objects, i);
    pieces[i].window = true;
    pieces[i].complete = o.record.complete;
    pieces[i].opening = OpeningBounds(seen, *context.structure, options_);
    pieces[i].num_points = seen.size();
  }
  const std::vector<int> joined = JoinWindowPieces(pieces, options_.join_gap_m);
  std::vector<bool> grew(objects->size(), false);
  for (std::size_t i = 0; i < joined.size(); ++i) {
    const std::size_t into = static_cast<std::size_t>(joined[i]);
    if (into == i) continue;
    objects->Join(i, into, name());
    grew[into] = true;
  }
  // A grown unfinished window takes the window model that fits all its pieces best.
  for (std::size_t i = 0; i < objects->size(); ++i) {
    const ReportedObject& o = (*objects)[i];
    if (!grew[i] || o.record.complete) continue;
    const auto best = context.sources->BestOfCategory(o.record.labels, world::Category::kWindow);
    if (best) objects->Adopt(i, *best, context.sources->ModelName(best->model_id), name());
  }
}

void CurtainsOverWindowsRule::Apply(const ReportContext& context, ReportedObjects* objects) const {
  std::vector<OpeningExtent> windows;
  for (std::size_t i = 0; i < objects->size(); ++i) {
    const ReportedObject& o = (*objects)[i];
    if (!o.reported() || o.record.category != world::Category::kWindow) continue;
    const OpeningExtent w =
        OpeningBounds(context.sources->ComponentPoints(o.record.labels), *context.structure, options_);
    if (w.wall >= 0) windows.push_back(w);
  }
  if (windows.empty()) return;
  // Per object, the window its curtain hangs over (-1: none), and what hosting needs of it.
  std::vector<int> window_of(objects->size(), -1);
  std::vector<WindowPiece> panels(objects->size());
  for (std::size_t i = 0; i < objects->size(); ++i) {
    const ReportedObject& o = (*objects)[i];
    if (!o.reported() || o.in_wall_opening) continue;
    if (!MayBeCurtain(o.record.category, o.record.wall_opening_share.value_or(0.0), options_)) continue;
    const std::vector<Eigen::Vector3f> seen = context.SeenPoints(*objects, i);
    const int window = CurtainWindow(HangingExtent(seen, *context.structure, options_), windows, options_);
    if (window < 0) continue;
    if (o.record.category != world::Category::kCurtain) {
      const auto best = context.sources->BestOfCategory(o.record.labels, world::Category::kCurtain);
      if (!best) continue;
      objects->Adopt(i, *best, context.sources->ModelName(best->model_id), name());
    }
    window_of[i] = window;
    panels[i].complete = o.record.complete;
    panels[i].num_points = seen.size();
  }
  // The panels over one window are one curtain, hosted like the pieces of a window.
  if (!options_.join_curtain_panels) return;
  const std::vector<int> joined = HostsOfGroups(window_of, panels);
  for (std::size_t i = 0; i < joined.size(); ++i) {
    if (joined[i] != static_cast<int>(i)) objects->Join(i, static_cast<std::size_t>(joined[i]), name());
  }
}

}  // namespace objscan::scanning
