#pragma once
// Options of the scanning loop itself (the stages have their own sections).
#include <string>

#include "objscan/common/config.h"
#include "objscan/scanning/coverage_views.h"
#include "objscan/scanning/map_space_evidence.h"

namespace objscan::scanning {

struct ScannerOptions {
  // "object": the paper's object-aware guidance (NBO + NBV, frontiers when no object is left);
  // "frontier": classic frontier exploration without object guidance (baseline); objects are still
  // recognised from what was seen.
  std::string guidance = "object";
  // The step budget: a run is terminated "max_steps" after min(max_steps, max(step_budget,
  // steps_per_explored_m2 x the area explored so far)) steps. max_steps is the hard cap (set it to
  // cut a run short); step_budget is what one room gets: in the 60 procedural rooms of seeds 1-12
  // the paper's loop ends within 97 steps, and with the coverage views (coverage_views.h) 59 of them
  // end within 156.
  int max_steps = 1000;
  int step_budget = 160;
  // The budget grows with the area explored (navigation grid cells seen free or occupied): the loop's
  // work (frontiers, objects, views) grows with the floor, so a house gets the steps its rooms need
  // and a single room keeps step_budget. 3 per m2 leaves every room up to 53 m2 at 160; the AWS small
  // house (131 m2 explored) ended `done` after 317 steps. 0 = a fixed budget.
  double steps_per_explored_m2 = 3.0;
  double start_camera_height_m = 1.2;  // camera height of look-around views
  double explore_pitch_deg = -25.0;    // pitch of the views taken on arriving at a frontier
  int frontier_views = 4;              // views turning in place at a reached frontier
  // The matcher is asked again about a component only when it grew or shrank by this share since
  // it was last asked (a new frame touches most components a little).
  double rematch_growth_fraction = 0.15;
  int min_object_elements = 300;       // smaller objects (map elements, 1 cm) are not NBO candidates
  // Beyond the paper: an object of interest whose objectness rose by less than stall_min_gain over
  // its last stall_views views is given up early (more views of it are not helping the recognizer).
  // stall_views = 0: the paper's behaviour (only max_views_per_object ends the scanning of an object).
  int stall_views = 2;
  double stall_min_gain = 0.01;
  // Beyond the paper: an object at least this share of whose points lie in components of objects
  // given up before (their objectness stalled or their view budget ran out) is given up too. The
  // post-segmentation regroups components from step to step, so a given-up object comes back under
  // another id (its smallest component's label) with its budget and stall history fresh; on the OASC
  // rooms that made ~65 objects of interest of ~14 objects. 0 = off (objects are given up by id).
  double given_up_surface_share = 0.0;
  bool remove_noise = true;            // paper: objects with O(r) < 0.05 leave T
  double line_of_sight_skip_m = 0.25;  // occupancy this close to the object's centre does not block
  double frontier_max_snap_m = 1.0;    // a frontier goal moves to the nearest free cell within this
  // Where the robot has stood is free floor: its footprint plus this margin counts as known free
  // for navigation even where the camera never looked (the floor right around the base).
  double known_free_margin_m = 0.15;
  // An NBV candidate within this distance and angle of an earlier view of the same object (or of
  // the current camera) is redundant.
  double min_view_separation_m = 0.4;
  double min_view_separation_deg = 25.0;
  // Beyond the paper: a component with at least this share of its points within
  // structure_residue_distance_m of the floor or a detected wall plane is left-over structure (strips
  // at wall edges, floor borders the structure tags missed): it is not post-segmented, so it cannot
  // bridge two objects in the graph cut. 1.0 or more = off (the paper's behaviour).
  double structure_residue_fraction = 0.8;
  double structure_residue_distance_m = 0.04;
  // ... and so do points inside a wall's thickness on faces across it, up to this depth behind the
  // wall plane: the reveals of door and window openings (StructureResult::InWallReveal). 0 = off.
  double structure_reveal_depth_m = 0.3;
  // ... and so is a component of which structure_residue_fraction lies within this band of the floor
  // or of one wall plane, on faces parallel to it, with at least structure_residue_min_side_share of
  // it on each side of the plane: the noise tail of the plane's surface, past the tolerance that
  // tagged the plane (StructureResult::IsPlaneNoise). Anything on the floor or at a wall lies on one
  // side. 0 = off.
  double structure_residue_band_m = 0.08;
  double structure_residue_min_side_share = 0.2;
  // Floor and walls are searched again only when the map grew by this share since the last search;
  // in between, new elements are tagged with the known planes (0 = search every step).
  double structure_redetect_growth = 0.1;
  // What counts as impossible space for a recognition hypothesis (used when
  // recognition.space_weight > 0).
  MapSpaceEvidenceOptions space;
  // Views completing the scan of reported objects when nothing else is left (coverage_views.h).
  CoverageViewOptions coverage_views;
  int threads = 0;                     // 0 = hardware concurrency; results do not depend on it

  template <class V>
  void Visit(V& v) {
    v("guidance", guidance);
    v("max_steps", max_steps);
    v("step_budget", step_budget);
    v("steps_per_explored_m2", steps_per_explored_m2);
    v("start_camera_height_m", start_camera_height_m);
    v("explore_pitch_deg", explore_pitch_deg);
    v("frontier_views", frontier_views);
    v("rematch_growth_fraction", rematch_growth_fraction);
    v("min_object_elements", min_object_elements);
    v("stall_views", stall_views);
    v("stall_min_gain", stall_min_gain);
    v("given_up_surface_share", given_up_surface_share);
    v("remove_noise", remove_noise);
    v("line_of_sight_skip_m", line_of_sight_skip_m);
    v("frontier_max_snap_m", frontier_max_snap_m);
    v("known_free_margin_m", known_free_margin_m);
    v("min_view_separation_m", min_view_separation_m);
    v("min_view_separation_deg", min_view_separation_deg);
    v("structure_residue_fraction", structure_residue_fraction);
    v("structure_residue_distance_m", structure_residue_distance_m);
    v("structure_reveal_depth_m", structure_reveal_depth_m);
    v("structure_residue_band_m", structure_residue_band_m);
    v("structure_residue_min_side_share", structure_residue_min_side_share);
    v("structure_redetect_growth", structure_redetect_growth);
    v("space", space);
    v("coverage_views", coverage_views);
    v("threads", threads);
  }
  void Validate() const {
    config::Require(guidance == "object" || guidance == "frontier", "scanner.guidance", "must be object or frontier");
    config::Require(max_steps >= 1, "scanner.max_steps", "must be >= 1");
    config::Require(step_budget >= 1, "scanner.step_budget", "must be >= 1");
    config::RequireNonNegative("scanner.steps_per_explored_m2", steps_per_explored_m2);
    config::RequireInRange("scanner.start_camera_height_m", start_camera_height_m, 0.3, 1.8);
    config::RequireInRange("scanner.explore_pitch_deg", explore_pitch_deg, -70.0, 30.0);
    config::Require(frontier_views >= 1, "scanner.frontier_views", "must be >= 1");
    config::RequireNonNegative("scanner.rematch_growth_fraction", rematch_growth_fraction);
    config::Require(min_object_elements >= 1, "scanner.min_object_elements", "must be >= 1");
    config::Require(stall_views >= 0, "scanner.stall_views", "must be >= 0");
    config::RequireNonNegative("scanner.stall_min_gain", stall_min_gain);
    config::RequireInRange("scanner.given_up_surface_share", given_up_surface_share, 0.0, 1.0);
    config::RequireNonNegative("scanner.line_of_sight_skip_m", line_of_sight_skip_m);
    config::RequirePositive("scanner.frontier_max_snap_m", frontier_max_snap_m);
    config::RequireNonNegative("scanner.known_free_margin_m", known_free_margin_m);
    config::RequireNonNegative("scanner.min_view_separation_m", min_view_separation_m);
    config::RequireInRange("scanner.min_view_separation_deg", min_view_separation_deg, 0.0, 180.0);
    config::RequireNonNegative("scanner.structure_residue_fraction", structure_residue_fraction);
    config::RequireNonNegative("scanner.structure_residue_distance_m", structure_residue_distance_m);
    config::RequireNonNegative("scanner.structure_reveal_depth_m", structure_reveal_depth_m);
    config::RequireNonNegative("scanner.structure_residue_band_m", structure_residue_band_m);
    config::RequireInRange("scanner.structure_residue_min_side_share", structure_residue_min_side_share, 0.0, 0.5);
    config::RequireNonNegative("scanner.structure_redetect_growth", structure_redetect_growth);
    space.Validate();
    coverage_views.Validate();
    config::Require(threads >= 0, "scanner.threads", "must be >= 0");
  }
};

}  // namespace objscan::scanning
