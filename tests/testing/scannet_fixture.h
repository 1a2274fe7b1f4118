#pragma once
// A small ScanNet-format scan written by the tests (the real data is not redistributable): a 4 m x 3 m
// room with walls, an office chair, a coffee table, a trash can and one unannotated box, in the files
// and formats of ScanNet v2 (see src/objscan/io/scannet.h). The scan is tilted and lifted the way a
// real reconstruction is (its floor is not at z = 0), and its .txt axisAlignment undoes that.
#include <string>

namespace objscan::testing {

struct ScanNetFixtureOptions {
  bool aggregation = true;      // ID.aggregation.json + ID_vh_clean_2.0.010000.segs.json
  bool labels_ply = true;       // ID_vh_clean_2.labels.ply (per-vertex NYU40 label)
  bool axis_alignment = true;   // ID.txt with axisAlignment
  double tilt_deg = 4.0;        // rotation of the scan about x (0: only lifted and shifted)
  double lift_m = 0.8;          // height of the scan's floor in its file
  // Each chair as two pieces, as ScanNet meshes have them: its base (z 0 - 0.25) and, 20 cm above,
  // its seat and back (z 0.45 - 0.9), not connected. Its bounds stay kFixtureChair.
  bool split_chairs = false;
  // A second chair beside the first, 20 cm away (kFixtureSecondChair).
  bool second_chair = false;
};

// The levelled boxes the fixture holds (x0 y0 z0 x1 y1 z1), for tests to compare against.
constexpr double kFixtureChair[6] = {0.8, 0.8, 0.0, 1.2, 1.2, 0.9};
constexpr double kFixtureSecondChair[6] = {1.4, 0.8, 0.0, 1.8, 1.2, 0.9};
constexpr double kFixtureTable[6] = {2.2, 1.0, 0.0, 3.2, 1.8, 0.75};
constexpr double kFixtureTrashCan[6] = {3.4, 2.4, 0.0, 3.8, 2.8, 0.4};
constexpr double kFixtureUnannotated[6] = {0.4, 2.3, 0.0, 0.8, 2.7, 0.5};
constexpr double kFixtureRoomX = 4.0, kFixtureRoomY = 3.0, kFixtureWallHeight = 2.4;

// Writes `parent_dir`/`scan_id`/ and returns that folder.
std::string WriteScanNetFixture(const std::string& parent_dir, const std::string& scan_id,
                                const ScanNetFixtureOptions& options = ScanNetFixtureOptions());

}  // namespace objscan::testing
