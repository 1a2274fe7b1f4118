#pragma once
// Per-category furniture generators (internal to procedural/). Each draws its variant and jittered
// metric dimensions from `rng`, appends its parts to `parts` in the model frame (x = depth with the
// front at +X, y = width, z = up from the floor) and returns the variant name (e.g.
// "pedestal_solid_arms"). Parts overlap slightly so that each model is one connected shape.
#include <cstdint>
#include <string>

#include "objscan/common/rng.h"
#include "objscan/world/category.h"
#include "objscan/world/procedural/part_builder.h"

namespace objscan::world::procedural::internal {

// Returns false when `category` has no generator.
bool BuildFurniture(Category category, Rng& rng, PartBuilder& parts, std::string* variant);
// The parts of GenerateFurniture(category, model_seed) before normalisation (for tests).
bool BuildFurnitureFromSeed(Category category, std::uint64_t model_seed, PartBuilder* parts, std::string* variant);

std::string BuildChair(Rng& rng, PartBuilder& p);
std::string BuildSofa(Rng& rng, PartBuilder& p);
std::string BuildBed(Rng& rng, PartBuilder& p);
std::string BuildTable(Rng& rng, PartBuilder& p);
std::string BuildDesk(Rng& rng, PartBuilder& p);
std::string BuildTvStand(Rng& rng, PartBuilder& p);
std::string BuildNightStand(Rng& rng, PartBuilder& p);
std::string BuildCabinet(Rng& rng, PartBuilder& p);
std::string BuildDresser(Rng& rng, PartBuilder& p);
std::string BuildShelves(Rng& rng, PartBuilder& p);
std::string BuildRefrigerator(Rng& rng, PartBuilder& p);
std::string BuildBathtub(Rng& rng, PartBuilder& p);
std::string BuildSink(Rng& rng, PartBuilder& p);
std::string BuildToilet(Rng& rng, PartBuilder& p);
std::string BuildLamp(Rng& rng, PartBuilder& p);
std::string BuildMonitor(Rng& rng, PartBuilder& p);
std::string BuildRadio(Rng& rng, PartBuilder& p);
std::string BuildDoor(Rng& rng, PartBuilder& p);
std::string BuildWindow(Rng& rng, PartBuilder& p);
std::string BuildCurtain(Rng& rng, PartBuilder& p);

// Shared parts.
enum class LegStyle { kSquare, kRound, kTapered };
// Four legs whose outer faces span [x0, x1] x [y0, y1], from the floor up to z_top_m.
void FourLegs(PartBuilder& p, double x0, double x1, double y0, double y1, double z_top_m, double thickness_m,
              LegStyle style);
// A small knob on a front face at x = x_front_m.
void Knob(PartBuilder& p, double x_front_m, double y_m, double z_m);
// A bar handle on a front face at x = x_front_m, centred at (y, z), vertical or horizontal.
void BarHandle(PartBuilder& p, double x_front_m, double y_m, double z_m, double length_m, bool vertical);
// A drawer front (slightly proud of the carcass front at x_front_m) with a knob or a bar handle.
void DrawerFront(PartBuilder& p, double x_front_m, double y0, double y1, double z0, double z1, bool bar);
// Index in [0, n).
inline int Pick(Rng& rng, int n) { return rng.UniformInt(0, n - 1); }

}  // namespace objscan::world::procedural::internal
