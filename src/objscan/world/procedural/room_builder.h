#pragma once
// RoomBuilder: the placement machinery behind GenerateRoom. It holds the room outline (a rectangle
// or an L), the openings of its walls, the scene under construction and the footprints placed so
// far, and only accepts a placement that keeps the room valid: inside the walls, no overlap with
// other floor-standing footprints or reserved zones (door entry, the area in front of windows for
// tall furniture), and a free floor that still passes CheckFreeFloor.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "objscan/common/rng.h"
#include "objscan/world/procedural/procedural.h"
#include "objscan/world/procedural/room_options.h"
#include "objscan/world/scene.h"

namespace objscan::world::procedural {

// Axis-aligned rectangle in the floor plane.
struct Rect {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool Overlaps(const Rect& o, double gap_m = 0.0) const {
    return x0 < o.x1 + gap_m && o.x0 < x1 + gap_m && y0 < o.y1 + gap_m && o.y0 < y1 + gap_m;
  }
  double Width() const { return x1 - x0; }
  double Height() const { return y1 - y0; }
};

// One straight wall of the outline: interior to the left of a -> b (counter-clockwise outline).
struct RoomEdge {
  Eigen::Vector2d a, b, dir, inward;
  double length = 0.0;
  struct Opening {
    double s0, s1;  // along the edge from a
    double z0, z1;
  };
  std::vector<Opening> openings;
  // A point at `s` along the edge and `inward_m` into the room.
  Eigen::Vector2d At(double s, double inward_m) const { return a + s * dir + inward_m * inward; }
  // Yaw that turns a model's +X (its front) into the room.
  double InwardYaw() const;
};

// Where a placed object stands.
struct Placement {
  int index = -1;  // into scene().objects()
  Rect footprint;
  double height_m = 0.0;     // top of the object (world z)
  Eigen::Vector2d center;    // world XY of the model origin
  double yaw_rad = 0.0;
  int edge = -1;             // wall it stands against, or -1
  double s_center = 0.0;     // position along that wall
  Eigen::Vector3d size_m;    // model bounding box size in its own frame
  bool Valid() const { return index >= 0; }
  Eigen::Vector2d Front() const { return Eigen::Vector2d(std::cos(yaw_rad), std::sin(yaw_rad)); }
};

class RoomBuilder {
 public:
  // Model seeds are SceneModelSeed(room_category, scene_seed, k) for k = first_model_slot, ...
  RoomBuilder(std::string room_category, std::uint64_t scene_seed, std::uint64_t layout_seed,
              std::uint64_t first_model_slot, const RoomOptions& options);

  Rng& rng() { return rng_; }
  const RoomOptions& options() const { return options_; }

  // Outline: [0, width] x [0, depth], minus a notch of notch_w x notch_d at corner `notch_corner`
  // (0: (0,0), 1: (width,0), 2: (width,depth), 3: (0,depth); -1 for a plain rectangle).
  void SetOutline(double width_m, double depth_m, double wall_height_m, int notch_corner, double notch_w_m,
                  double notch_d_m);
  const std::vector<RoomEdge>& edges() const { return edges_; }
  double width() const { return width_; }
  double depth() const { return depth_; }
  double wall_height() const { return wall_height_; }
  bool Inside(const Rect& r) const;

  // A furniture model from the scene's model stream; redraws (next seeds) until `accept` holds,
  // returns nullopt after `max_draws`.
  std::optional<FurnitureModel> DrawModel(Category category,
                                          const std::function<bool(const FurnitureModel&)>& accept = {},
                                          int max_draws = 60);

  // Structure. Call ChooseDoor and ChooseWindow before BuildStructure (they cut openings), then
  // BuildStructure adds floor, walls, the door and the windows to the scene.
  bool ChooseDoor(const FurnitureModel& door);
  bool ChooseWindow(const FurnitureModel& window, double sill_z_m);
  void BuildStructure();
  // A curtain in front of the window placed as window number `window` (0-based).
  Placement PlaceCurtain(const FurnitureModel& curtain, int window);
  int NumWindows() const { return static_cast<int>(windows_.size()); }
  double WindowWidth(int window) const { return windows_.at(window).width_m; }

  // Floor-standing furniture. Against a wall (back to the wall, front into the room), at a given
  // or random position; `corner_bias` is the probability of snapping a random position to a corner.
  Placement PlaceAgainstWall(const FurnitureModel& model, int edge, double s_center, double gap_m = 0.02);
  Placement PlaceAgainstAnyWall(const FurnitureModel& model, int tries, double corner_bias = 0.0,
                                double gap_m = 0.02);
  // Free-standing at a world position with a yaw.
  Placement PlaceFree(const FurnitureModel& model, const Eigen::Vector2d& center, double yaw_rad);
  // On the top surface of a placed object (random spot; `back_bias` puts it near the support's back).
  Placement PlaceOnTop(const FurnitureModel& model, const Placement& support, int tries, bool back_bias = false);

  int NumFurniture() const { return num_furniture_; }
  bool Full() const { return num_furniture_ >= options_.max_objects; }
  Scene TakeScene() { return std::move(scene_); }
  const Scene& scene() const { return scene_; }

 private:
  struct Footprint {
    Rect rect;
    int support = -1;  // index of the supporting object for on-top placements
  };
  struct WindowZone {
    Rect rect;
    double max_height_m;
  };
  struct PendingObject {
    FurnitureModel model;
    geometry::Pose3 pose;
  };
  struct WindowInfo {
    int edge;
    double s_center;
    double width_m, z0_m, z1_m;
    double protrusion_m;  // how far the window (its sill) stands into the room
  };

  bool FloorFits(const Rect& r, double height_m) const;
  // Adds the object, runs the free-floor check when `check_floor`, and undoes the addition when it fails.
  Placement Commit(const FurnitureModel& model, const Eigen::Vector2d& center, double z_m, double yaw_rad,
                   bool check_floor, int support);
  geometry::Pose3 PoseOf(const Eigen::Vector2d& center, double z_m, double yaw_rad) const;
  static Rect FootprintOf(const FurnitureModel& model, const geometry::Pose3& pose);

  std::string room_category_;
  std::uint64_t scene_seed_;
  RoomOptions options_;
  Rng rng_;
  std::uint64_t next_model_ = 0;
  double width_ = 0, depth_ = 0, wall_height_ = 2.6;
  std::optional<Rect> notch_;
  std::vector<Eigen::Vector2d> outline_;
  std::vector<RoomEdge> edges_;
  std::vector<Rect> reserved_;
  std::vector<WindowZone> window_zones_;
  std::vector<PendingObject> pending_;
  std::vector<WindowInfo> windows_;
  std::vector<Footprint> footprints_;  // parallel to scene_.objects()
  Scene scene_;
  int num_furniture_ = 0;
};

// "procedural/<category>/<model seed>": the SceneObject::model_name of procedural furniture.
std::string ProceduralModelName(Category category, std::uint64_t model_seed);
// Inverse of ProceduralModelName; false when `model_name` is not of that form.
bool ParseProceduralModelName(const std::string& model_name, Category* category, std::uint64_t* model_seed);

}  // namespace objscan::world::procedural
