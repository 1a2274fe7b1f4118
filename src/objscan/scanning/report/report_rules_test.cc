// Each report rule on a small hand-made case, and the pipeline's order.
#include "objscan/scanning/report/report_rules.h"

#include <gtest/gtest.h>

#include <map>
#include <set>

#include "objscan/common/error.h"
#include "objscan/mapping/planes.h"
#include "objscan/recognition/test_shapes.h"
#include "objscan/scanning/report/report_pipeline.h"
#include "objscan/scanning/testing/size_fixtures.h"
#include "objscan/scanning/testing/wall_shapes.h"

namespace objscan::scanning {
namespace {

using testing::Append;
using testing::OneWallRoom;
using testing::Pane;
using testing::Pleats;
using world::Category;
using Points = std::vector<Eigen::Vector3f>;

Points Box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  Points points, normals;
  recognition::testing::BoxSurface(lo, hi, 0.02, &points, &normals);
  return points;
}

segmentation::ModelMatch Match(Category category, double objectness, int model_id) {
  segmentation::ModelMatch m;
  m.category = category;
  m.objectness = objectness;
  m.model_id = model_id;
  m.entry_id = model_id;
  m.full_model = true;
  return m;
}

// Recognition, map and database of a hand-made room: each component label has its points, and the
// answers of recognition are set per union of labels.
class FakeSources : public ReportSources {
 public:
  std::map<std::int32_t, Points> component_points;
  std::map<std::vector<std::int32_t>, segmentation::MatchResult> full_matches;
  std::map<std::pair<std::vector<std::int32_t>, Category>, segmentation::ModelMatch> best_of_category;
  std::map<int, Points> entries;
  std::map<std::vector<std::int32_t>, std::vector<float>> category_odds;

  std::vector<float> CategoryOdds(const std::vector<std::int32_t>& labels) override {
    auto it = category_odds.find(labels);
    return it == category_odds.end() ? std::vector<float>() : it->second;
  }
  // As the scanner's: the odds stand for the posterior (same argmax), default naming options.
  std::optional<Category> NameCategory(const std::vector<std::int32_t>& labels,
                                       const std::vector<recognition::RetrievedCategory>& votes) override {
    const std::vector<float> odds = CategoryOdds(labels);
    if (odds.empty()) return std::nullopt;
    recognition::CategoryClassifier::Probabilities p{};
    for (std::size_t k = 0; k < odds.size(); ++k) p[k] = odds[k];
    const recognition::CategoryName name = recognition::NameCategory(p, votes, recognition::CategoryNamingOptions());
    return name.named ? std::optional<Category>(name.category) : std::nullopt;
  }
  segmentation::MatchResult MatchFullModels(const std::vector<std::int32_t>& labels) override {
    auto it = full_matches.find(labels);
    return it == full_matches.end() ? segmentation::MatchResult() : it->second;
  }
  std::optional<segmentation::ModelMatch> BestOfCategory(const std::vector<std::int32_t>& labels,
                                                         Category category) override {
    auto it = best_of_category.find({labels, category});
    if (it == best_of_category.end()) return std::nullopt;
    return it->second;
  }
  Points ComponentPoints(const std::vector<std::int32_t>& labels) const override {
    Points out;
    for (auto l : labels) {
      auto it = component_points.find(l);
      if (it != component_points.end()) Append(it->second, &out);
    }
    return out;
  }
  std::size_t ElementCount(const std::vector<std::int32_t>& labels) const override {
    return ComponentPoints(labels).size();
  }
  std::string ModelName(int model_id) const override { return model_id >= 0 ? "m" + std::to_string(model_id) : ""; }
  Points EntryPoints(int entry_id) const override {
    auto it = entries.find(entry_id);
    return it == entries.end() ? Points() : it->second;
  }
};

// One test room: a wall x = 0 facing +x over a floor, the fake sources and the objects.
struct ReportCase {
  FakeSources sources;
  mapping::StructureResult structure = OneWallRoom();
  recognition::CategoryExtents extents;
  ReportedObjects objects;
  std::vector<segmentation::MatchResult> unfinished_matches;  // reserved: pointers stay valid

  ReportCase() { unfinished_matches.reserve(16); }

  ReportContext Context() {
    ReportContext c;
    c.sources = &sources;
    c.structure = &structure;
    c.category_extents = &extents;
    return c;
  }
  // An unfinished object of one component with these points, label and full-model matches.
  int AddUnfinished(std::int32_t label, const Points& points, std::optional<Category> category,
                    std::vector<segmentation::ModelMatch> matches = {}, double objectness = 0.5) {
    sources.component_points[label] = points;
    ReportedObject r;
    r.record.id = label;
    r.record.labels = {label};
    r.record.category = category;
    r.record.objectness = objectness;
    r.points_world = points;
    unfinished_matches.push_back(segmentation::MatchResult{std::move(matches)});
    r.full_matches = &unfinished_matches.back();
    if (!r.full_matches->models.empty()) r.model_entry = r.full_matches->models.front().entry_id;
    return objects.Add(std::move(r));
  }
  // A completed object of one component: its model `match`, placed at the identity.
  int AddCompleted(std::int32_t label, const Points& points, const segmentation::ModelMatch& match) {
    sources.component_points[label] = points;
    ReportedObject r;
    r.record.id = label;
    r.record.labels = {label};
    r.record.category = match.category;
    r.record.objectness = match.objectness;
    r.record.complete = true;
    r.record.model_index = match.model_id;
    r.record.model = sources.ModelName(match.model_id);
    r.model_entry = match.entry_id;
    r.num_elements = points.size();
    return objects.Add(std::move(r));
  }
  void Apply(const ReportRule& rule) { rule.Apply(Context(), &objects); }
  const ObjectRecord& record(int i) const { return objects[static_cast<std::size_t>(i)].record; }
};

const LabelChange& LastChange(const ObjectRecord& o) {
  static const LabelChange kNone;
  return o.label_changes.empty() ? kNone : o.label_changes.back();
}

TEST(ReportRulesTest, ReopenOutgrownReopensCompletedObjectsWhoseSurfaceLeftTheirModel) {
  ReportCase c;
  c.sources.entries[1] = Box({1, 1, 0}, {1.5, 1.5, 0.5});  // a night stand's model
  // One completed object within its model's box, one whose seen surface now runs 1 m beyond it.
  const int inside = c.AddCompleted(1, Box({1, 1, 0}, {1.5, 1.5, 0.5}), Match(Category::kNightStand, 0.97, 1));
  const int outgrown = c.AddCompleted(2, Box({1, 1, 0}, {2.5, 1.5, 0.5}), Match(Category::kNightStand, 0.97, 1));
  c.sources.full_matches[{2}].models = {Match(Category::kDresser, 0.8, 5)};
  // A completed door whose seen surface is 0.6 m deep (a cabinet's front fitted by a door model).
  c.sources.entries[3] = Box({3, 1, 0}, {3.05, 1.6, 2.0});
  const int door = c.AddCompleted(3, Box({3, 1, 0}, {3.6, 1.6, 0.9}), Match(Category::kDoor, 0.97, 3));
  c.Apply(ReopenOutgrownRule(CompletionCheckOptions(), WallOpeningOptions()));
  EXPECT_TRUE(c.record(inside).complete);
  EXPECT_TRUE(c.record(inside).label_changes.empty());
  const ObjectRecord& o = c.record(outgrown);
  EXPECT_FALSE(o.complete);
  EXPECT_EQ(o.model, "m5");  // recognized again as a whole
  EXPECT_DOUBLE_EQ(o.objectness, 0.8);
  EXPECT_EQ(o.category, Category::kNightStand);  // the label stays until a rule changes it
  EXPECT_EQ(LastChange(o).action, "reopen");
  EXPECT_EQ(LastChange(o).rule, "reopen_outgrown");
  EXPECT_EQ(LastChange(o).model, "m1");
  EXPECT_FALSE(c.record(door).complete);
  // A reopened object's grouped points are what was seen of it.
  EXPECT_EQ(c.objects[static_cast<std::size_t>(outgrown)].points_world.size(),
            c.sources.component_points[2].size());
}

TEST(ReportRulesTest, ModelLabelTakesAConfidentBestModelsCategory) {
  ReportCase c;
  const int sure = c.AddUnfinished(1, Box({0, 0, 0}, {0.5, 0.1, 0.4}), Category::kShelves,
                                   {Match(Category::kMonitor, 0.95, 1), Match(Category::kShelves, 0.9, 2)});
  const int unsure = c.AddUnfinished(2, Box({2, 0, 0}, {2.5, 0.1, 0.4}), Category::kShelves,
                                     {Match(Category::kMonitor, 0.9, 1)});
  const int none = c.AddUnfinished(3, Box({4, 0, 0}, {4.5, 0.1, 0.4}), std::nullopt);
  c.Apply(ModelLabelRule(0.93));
  EXPECT_EQ(c.record(sure).category, Category::kMonitor);
  EXPECT_EQ(LastChange(c.record(sure)).from, Category::kShelves);
  EXPECT_EQ(LastChange(c.record(sure)).to, Category::kMonitor);
  EXPECT_EQ(c.record(unsure).category, Category::kShelves);
  EXPECT_TRUE(c.record(unsure).label_changes.empty());
  EXPECT_FALSE(c.record(none).category.has_value());
}

TEST(ReportRulesTest, AbsorbFragmentsJoinsAPieceLyingOnItsNeighboursModel) {
  ReportCase c;
  // A bed recognized with its model; a strip of its frame seen apart lies on that model's surface.
  c.sources.entries[1] = Box({0, 0, 0}, {2, 1.6, 0.5});
  const int bed = c.AddUnfinished(1, Box({0, 0, 0}, {2, 1.6, 0.5}), Category::kBed, {Match(Category::kBed, 0.9, 1)}, 0.9);
  Points strip;
  for (const auto& p : Box({0, 0, 0}, {2, 1.6, 0.5})) {
    if (p.x() > 1.9f) strip.push_back(p);
  }
  const int piece = c.AddUnfinished(2, strip, Category::kChair, {}, 0.6);
  const int apart = c.AddUnfinished(3, Box({4, 0, 0}, {4.4, 0.4, 0.8}), Category::kChair, {}, 0.6);
  c.Apply(AbsorbFragmentsRule(FragmentAbsorptionOptions()));
  EXPECT_FALSE(c.objects[static_cast<std::size_t>(piece)].reported());
  EXPECT_TRUE(c.objects[static_cast<std::size_t>(apart)].reported());
  EXPECT_EQ(c.record(bed).labels, (std::vector<std::int32_t>{1, 2}));
  EXPECT_EQ(LastChange(c.record(bed)).action, "join");
  EXPECT_EQ(LastChange(c.record(bed)).joined_id, 2);
  const std::vector<ObjectRecord> reported = c.objects.TakeReportedRecords();
  EXPECT_EQ(reported.size(), 2u);
}

recognition::SizePlausibilityOptions SizeOptions() { return testing::TightSizeOptions(); }
// Night stands and beds (size_fixtures.h), lamps 1.4-1.7 m tall and radios 0.2-0.3 m.
void AddSizes(recognition::CategoryExtents* extents) {
  *extents = testing::NightStandAndBedSizes();
  extents->Add(Category::kLamp, {1.4, 0.4});
  extents->Add(Category::kLamp, {1.7, 0.5});
  extents->Add(Category::kRadio, {0.2, 0.4});
  extents->Add(Category::kRadio, {0.3, 0.6});
}

TEST(ReportRulesTest, RegroupBySizeJoinsASlabToTheNightStandItCompletes) {
  ReportCase c;
  AddSizes(&c.extents);
  c.structure.walls.clear();  // far from any wall either way
  const int body = c.AddUnfinished(1, Box({1, 1, 0}, {1.4, 1.45, 0.35}), Category::kNightStand);
  const int slab = c.AddUnfinished(2, Box({1, 1, 0.35}, {1.4, 1.45, 0.5}), Category::kBed);
  const int bed = c.AddUnfinished(3, Box({2, 1, 0}, {4, 2.2, 0.6}), Category::kBed);
  c.Apply(RegroupBySizeRule(SizeOptions()));
  EXPECT_FALSE(c.objects[static_cast<std::size_t>(slab)].reported());
  EXPECT_EQ(c.record(body).labels, (std::vector<std::int32_t>{1, 2}));
  EXPECT_EQ(c.record(body).category, Category::kNightStand);
  EXPECT_EQ(LastChange(c.record(body)).rule, "regroup_by_size");
  EXPECT_TRUE(c.objects[static_cast<std::size_t>(bed)].reported());
  EXPECT_EQ(c.objects[static_cast<std::size_t>(body)].points_world.size(),
            c.sources.component_points[1].size() + c.sources.component_points[2].size());
}

TEST(ReportRulesTest, JoinStackedJoinsAShadeToTheLampUnderIt) {
  ReportCase c;
  AddSizes(&c.extents);
  c.structure.walls.clear();
  const int stem = c.AddUnfinished(1, Box({1.05, 1.05, 0}, {1.35, 1.35, 1.2}), Category::kLamp);
  const int shade = c.AddUnfinished(2, Box({1, 1, 1.25}, {1.4, 1.4, 1.5}), Category::kRadio);
  const int radio = c.AddUnfinished(3, Box({3, 1, 0.5}, {3.2, 1.2, 0.7}), Category::kRadio);
  c.Apply(JoinStackedRule(SizeOptions()));
  EXPECT_FALSE(c.objects[static_cast<std::size_t>(shade)].reported());
  EXPECT_EQ(c.record(stem).labels, (std::vector<std::int32_t>{1, 2}));
  EXPECT_EQ(c.record(stem).category, Category::kLamp);
  EXPECT_TRUE(c.objects[static_cast<std::size_t>(radio)].reported());
}

TEST(ReportRulesTest, DoorDepthTakesADoorLabelFromSomethingDeeperThanADoorLeaf) {
  ReportCase c;
  const int leaf = c.AddUnfinished(1, Pane(0.05, 1.0, 1.9, 0.0, 2.0), Category::kDoor);
  const int cabinet = c.AddUnfinished(2, Box({1.0, 2.5, 0}, {1.6, 3.5, 0.9}), Category::kDoor);
  c.Apply(DoorDepthRule(WallOpeningOptions()));
  EXPECT_EQ(c.record(leaf).category, Category::kDoor);
  EXPECT_FALSE(c.record(cabinet).category.has_value());
  EXPECT_EQ(c.objects[static_cast<std::size_t>(cabinet)].taken, Category::kDoor);
  EXPECT_EQ(LastChange(c.record(cabinet)).action, "take");
}

TEST(ReportRulesTest, WallOpeningsMakeAPaneInAnOpeningAWindowAndTakeWindowLabelsElsewhere) {
  ReportCase c;
  // A pane recessed 6 cm in the wall, sill at 0.9 m, labelled dresser; a window label on a thing
  // 1 m out in the room.
  const int pane = c.AddUnfinished(1, Pane(-0.06, 1.0, 2.0, 0.9, 2.0), Category::kDresser);
  c.sources.best_of_category[{{1}, Category::kWindow}] = Match(Category::kWindow, 0.7, 9);
  const int thing = c.AddUnfinished(2, Box({1.0, 1.0, 0.0}, {1.5, 1.5, 0.8}), Category::kWindow);
  c.Apply(WallOpeningsRule(WallOpeningOptions()));
  EXPECT_EQ(c.record(pane).category, Category::kWindow);
  EXPECT_EQ(c.record(pane).model, "m9");
  EXPECT_TRUE(c.objects[static_cast<std::size_t>(pane)].in_wall_opening);
  EXPECT_GT(*c.record(pane).wall_opening_share, 0.9);
  EXPECT_EQ(LastChange(c.record(pane)).action, "adopt");
  EXPECT_FALSE(c.record(thing).category.has_value());
  EXPECT_EQ(c.objects[static_cast<std::size_t>(thing)].taken, Category::kWindow);
}

TEST(ReportRulesTest, SizeCheckTakesALabelNoModelOfThatSizeHas) {
  ReportCase c;
  AddSizes(&c.extents);
  c.structure.walls.clear();
  const int small_bed = c.AddUnfinished(1, Box({1, 1, 0}, {1.4, 1.45, 0.5}), Category::kBed);
  const int stand = c.AddUnfinished(2, Box({3, 1, 0}, {3.4, 1.45, 0.5}), Category::kNightStand);
  const int unknown = c.AddUnfinished(3, Box({5, 1, 0}, {5.1, 1.1, 0.1}), Category::kChair);  // no chair model
  c.Apply(SizeCheckRule(SizeOptions()));
  EXPECT_FALSE(c.record(small_bed).category.has_value());
  EXPECT_EQ(c.objects[static_cast<std::size_t>(small_bed)].taken, Category::kBed);
  EXPECT_EQ(c.record(stand).category, Category::kNightStand);
  EXPECT_EQ(c.record(unknown).category, Category::kChair);
}

TEST(ReportRulesTest, CurtainMustHangTakesCurtainLabelsOffThingsThatHangOnNoWall) {
  ReportCase c;
  const int panel = c.AddUnfinished(1, Pleats(0.1, 0.6, 1.3, 0.02, 2.2), Category::kCurtain);
  Points wardrobe = Pane(0.6, 2.2, 3.6, 0.0, 2.0);
  Append(Pane(0.3, 2.2, 3.6, 2.0, 2.0), &wardrobe);
  const int front = c.AddUnfinished(2, wardrobe, Category::kCurtain);
  c.Apply(CurtainMustHangRule(WallOpeningOptions()));
  EXPECT_EQ(c.record(panel).category, Category::kCurtain);
  EXPECT_FALSE(c.record(front).category.has_value());
  EXPECT_EQ(LastChange(c.record(front)).rule, "curtain_must_hang");
}

TEST(ReportRulesTest, RelabelReplacesATakenLabelByAConfidentMatchThatFits) {
  ReportCase c;
  AddSizes(&c.extents);
  c.structure.walls.clear();
  const Points stand_points = Box({1, 1, 0}, {1.4, 1.45, 0.5});
  const int stand = c.AddUnfinished(1, stand_points, Category::kBed,
                                    {Match(Category::kBed, 0.95, 1), Match(Category::kNightStand, 0.94, 2)});
  const int unsure = c.AddUnfinished(2, Box({3, 1, 0}, {3.4, 1.45, 0.5}), Category::kBed,
                                     {Match(Category::kNightStand, 0.5, 2)});
  const int kept = c.AddUnfinished(3, Box({5, 1, 0}, {5.4, 1.45, 0.5}), Category::kNightStand,
                                   {Match(Category::kBed, 0.99, 1)});
  c.Apply(SizeCheckRule(SizeOptions()));
  c.Apply(RelabelRule(SizeOptions()));
  EXPECT_EQ(c.record(stand).category, Category::kNightStand);
  EXPECT_EQ(c.record(stand).model, "m2");
  EXPECT_EQ(LastChange(c.record(stand)).rule, "relabel");
  EXPECT_FALSE(c.record(unsure).category.has_value());
  EXPECT_EQ(c.record(kept).category, Category::kNightStand);  // no label was taken
}

TEST(ReportRulesTest, JoinWindowPiecesReportsTheSashesOfOneWindowAsOne) {
  ReportCase c;
  const int left = c.AddUnfinished(1, Pane(-0.06, 1.0, 1.48, 0.9, 2.0), Category::kWindow);
  const int right = c.AddUnfinished(2, Pane(-0.06, 1.52, 2.2, 0.9, 2.0), Category::kWindow);
  const int other = c.AddUnfinished(3, Pane(-0.06, 3.0, 3.8, 0.9, 2.0), Category::kWindow);
  c.sources.best_of_category[{{1, 2}, Category::kWindow}] = Match(Category::kWindow, 0.8, 4);
  c.Apply(JoinWindowPiecesRule(WallOpeningOptions()));
  // The larger piece hosts; the grown window takes the model fitting both.
  EXPECT_FALSE(c.objects[static_cast<std::size_t>(left)].reported());
  EXPECT_EQ(c.record(right).labels, (std::vector<std::int32_t>{1, 2}));
  EXPECT_EQ(c.record(right).model, "m4");
  EXPECT_TRUE(c.objects[static_cast<std::size_t>(other)].reported());
}

TEST(ReportRulesTest, CurtainsOverWindowsNameAndJoinThePanelsOverAWindow) {
  ReportCase c;
  c.AddUnfinished(1, Pane(-0.06, 1.0, 2.0, 0.9, 2.0), Category::kWindow);
  const int a = c.AddUnfinished(2, Pleats(0.1, 0.6, 1.3, 0.02, 2.2), Category::kDoor);
  const int b = c.AddUnfinished(3, Pleats(0.1, 1.7, 2.4, 0.02, 2.2), Category::kCurtain);
  const int chair = c.AddUnfinished(4, Box({1.0, 3.0, 0.0}, {1.5, 3.5, 0.9}), Category::kChair);
  c.sources.best_of_category[{{2}, Category::kCurtain}] = Match(Category::kCurtain, 0.6, 7);
  c.Apply(CurtainsOverWindowsRule(WallOpeningOptions()));
  // The door-labelled panel is a curtain; the two panels over the window are one curtain, hosted by
  // the one with more points.
  const std::size_t host = c.objects[static_cast<std::size_t>(a)].reported() ? a : b;
  const std::size_t joined = host == static_cast<std::size_t>(a) ? b : a;
  EXPECT_FALSE(c.objects[joined].reported());
  EXPECT_EQ(c.objects[host].record.category, Category::kCurtain);
  EXPECT_EQ(c.objects[host].record.labels, (std::vector<std::int32_t>{2, 3}));
  EXPECT_EQ(c.record(chair).category, Category::kChair);
}

TEST(ReportRulesTest, DropSmallTakesLabelsFromObjectsUnderTheMinimum) {
  ReportCase c;
  const int tiny = c.AddUnfinished(1, Box({1, 1, 0}, {1.05, 1.05, 0.05}), Category::kLamp);
  const int big = c.AddUnfinished(2, Box({2, 1, 0}, {3, 2, 1}), Category::kBed);
  const int none = c.AddUnfinished(3, Box({5, 1, 0}, {5.05, 1.05, 0.05}), std::nullopt);
  ASSERT_LT(c.sources.component_points[1].size(), 500u);
  ASSERT_GE(c.sources.component_points[2].size(), 500u);
  c.Apply(DropSmallRule(500));
  EXPECT_FALSE(c.record(tiny).category.has_value());
  EXPECT_EQ(LastChange(c.record(tiny)).from, Category::kLamp);
  EXPECT_EQ(c.record(big).category, Category::kBed);
  EXPECT_TRUE(c.record(none).label_changes.empty());
}

TEST(ReportRulesTest, DropUnsureTakesLabelsOfUnfinishedObjectsBelowTheObjectness) {
  ReportCase c;
  const int unsure = c.AddUnfinished(1, Box({1, 1, 0}, {1.5, 1.5, 0.5}), Category::kChair, {}, 0.6);
  const int sure = c.AddUnfinished(2, Box({3, 1, 0}, {3.5, 1.5, 0.5}), Category::kChair, {}, 0.85);
  const int done = c.AddCompleted(3, Box({5, 1, 0}, {5.5, 1.5, 0.5}), Match(Category::kChair, 0.5, 1));
  c.Apply(DropUnsureRule(0.8));
  EXPECT_FALSE(c.record(unsure).category.has_value());
  EXPECT_EQ(LastChange(c.record(unsure)).rule, "drop_unsure");
  EXPECT_EQ(c.record(sure).category, Category::kChair);
  EXPECT_EQ(c.record(done).category, Category::kChair);  // completed objects are their model
}

// The classifier's odds per category for one object: `first` its first choice (odds 1), `other`
// another category at `odds`, every other category 0.1.
std::vector<float> Odds(Category first, Category other, float odds) {
  std::vector<float> v(world::kNumCategories, 0.1f);
  v[world::CategoryId(first)] = 1.f;
  v[world::CategoryId(other)] = odds;
  return v;
}

TEST(ReportRulesTest, ShapeAgreesTakesLabelsTheClassifierFindsUnlikely) {
  ReportCase c;
  const int agrees = c.AddUnfinished(1, Box({1, 1, 0}, {1.5, 1.5, 0.5}), Category::kChair, {}, 0.95);
  const int near_tie = c.AddUnfinished(2, Box({3, 1, 0}, {3.5, 1.5, 0.5}), Category::kChair, {}, 0.95);
  const int at_limit = c.AddUnfinished(3, Box({5, 1, 0}, {5.5, 1.5, 0.5}), Category::kChair, {}, 0.95);
  const int unlikely = c.AddCompleted(4, Box({7, 1, 0}, {7.5, 1.5, 0.5}), Match(Category::kChair, 0.97, 1));
  const int unknown = c.AddUnfinished(5, Box({9, 1, 0}, {9.5, 1.5, 0.5}), Category::kChair, {}, 0.95);
  const int unlabelled = c.AddUnfinished(6, Box({11, 1, 0}, {11.5, 1.5, 0.5}), std::nullopt, {}, 0.95);
  c.sources.category_odds[{1}] = Odds(Category::kChair, Category::kSofa, 0.9f);
  c.sources.category_odds[{2}] = Odds(Category::kSofa, Category::kChair, 0.7f);
  c.sources.category_odds[{3}] = Odds(Category::kSofa, Category::kChair, 0.5f);
  c.sources.category_odds[{4}] = Odds(Category::kTable, Category::kChair, 0.2f);
  c.sources.category_odds[{6}] = Odds(Category::kTable, Category::kChair, 0.2f);
  c.Apply(ShapeAgreesRule(0.5));
  EXPECT_EQ(c.record(agrees).category, Category::kChair);
  EXPECT_EQ(c.record(near_tie).category, Category::kChair);
  EXPECT_EQ(c.record(at_limit).category, Category::kChair);  // at min_odds: kept
  EXPECT_FALSE(c.record(unlikely).category.has_value());    // complete or not
  EXPECT_EQ(LastChange(c.record(unlikely)).rule, "shape_agrees");
  EXPECT_EQ(LastChange(c.record(unlikely)).from, Category::kChair);
  EXPECT_EQ(c.record(unknown).category, Category::kChair);  // no classifier: nothing to disagree
  EXPECT_TRUE(c.record(unlabelled).label_changes.empty());
  // min_odds 1: only the classifier's first choice keeps its label.
  ReportCase strict;
  const int tie = strict.AddUnfinished(2, Box({3, 1, 0}, {3.5, 1.5, 0.5}), Category::kChair, {}, 0.95);
  strict.sources.category_odds[{2}] = Odds(Category::kSofa, Category::kChair, 0.7f);
  strict.Apply(ShapeAgreesRule(1.0));
  EXPECT_FALSE(strict.record(tie).category.has_value());
}

TEST(ReportRulesTest, NameByShapeNamesWhatBothRecognizersSupport) {
  ReportCase c;
  // M(r): sofa 0.9 best, chair 0.8; the classifier finds chair 10 times as likely as sofa: chair.
  const int renamed = c.AddUnfinished(1, Box({1, 1, 0}, {1.5, 1.5, 0.9}), Category::kSofa,
                                      {Match(Category::kSofa, 0.9, 1), Match(Category::kChair, 0.8, 2)}, 0.9);
  c.sources.category_odds[{1}] = Odds(Category::kChair, Category::kSofa, 0.1f);
  c.sources.best_of_category[{{1}, Category::kChair}] = Match(Category::kChair, 0.8, 2);
  // The classifier leans to table, which M(r) lacks: 1 x 0.5 x 0.85 = 0.43 < 0.6 x 0.9 for the bed: kept.
  const int kept = c.AddUnfinished(2, Box({3, 1, 0}, {3.5, 1.5, 0.5}), Category::kBed,
                                   {Match(Category::kBed, 0.9, 3), Match(Category::kSofa, 0.85, 4)}, 0.9);
  std::vector<float> leaning(world::kNumCategories, 0.f);
  leaning[world::CategoryId(Category::kTable)] = 1.f;
  leaning[world::CategoryId(Category::kBed)] = 0.6f;
  c.sources.category_odds[{2}] = leaning;
  // A new name without a model of its category keeps the object's model: only the label changes.
  const int relabelled = c.AddUnfinished(3, Box({5, 1, 0}, {5.5, 1.5, 0.5}), Category::kRadio,
                                         {Match(Category::kRadio, 0.5, 5)}, 0.5);
  c.sources.category_odds[{3}] = Odds(Category::kLamp, Category::kRadio, 0.05f);
  const int no_classifier = c.AddUnfinished(4, Box({7, 1, 0}, {7.5, 1.5, 0.5}), Category::kChair,
                                            {Match(Category::kChair, 0.9, 6)}, 0.9);
  const int unlabelled = c.AddUnfinished(5, Box({9, 1, 0}, {9.5, 1.5, 0.5}), std::nullopt, {}, 0.3);
  c.sources.category_odds[{5}] = Odds(Category::kLamp, Category::kRadio, 0.05f);
  c.Apply(NameByShapeRule());
  EXPECT_EQ(c.record(renamed).category, Category::kChair);
  EXPECT_EQ(c.record(renamed).model, "m2");
  EXPECT_EQ(LastChange(c.record(renamed)).rule, "name_by_shape");
  EXPECT_EQ(c.record(kept).category, Category::kBed);
  EXPECT_TRUE(c.record(kept).label_changes.empty());
  EXPECT_EQ(c.record(relabelled).category, Category::kLamp);
  EXPECT_EQ(c.record(no_classifier).category, Category::kChair);
  EXPECT_FALSE(c.record(unlabelled).category.has_value());  // unrecognized stays so
}

TEST(ReportRulesTest, NameByShapeScopesAndLabelOnlyRenames) {
  const auto run = [](const std::string& scope, bool adopt) {
    auto c = std::make_unique<ReportCase>();
    // A completed sofa, an unfinished chair and an unfinished `other`; the classifier says table for all.
    c->AddCompleted(1, Box({1, 1, 0}, {1.5, 1.5, 0.7}), Match(Category::kSofa, 0.97, 1));
    c->AddUnfinished(2, Box({3, 1, 0}, {3.5, 1.5, 0.7}), Category::kChair, {Match(Category::kChair, 0.6, 2)}, 0.6);
    c->AddUnfinished(3, Box({5, 1, 0}, {5.5, 1.5, 0.7}), Category::kOther, {Match(Category::kOther, 0.6, 3)}, 0.6);
    for (std::int32_t l : {1, 2, 3}) {
      c->sources.category_odds[{l}] = Odds(Category::kTable, Category::kSofa, 0.01f);
      c->sources.best_of_category[{{l}, Category::kTable}] = Match(Category::kTable, 0.5, 10 + l);
    }
    c->Apply(NameByShapeRule(scope, adopt));
    return c;
  };
  auto all = run("all", true);
  EXPECT_EQ(all->record(0).category, Category::kTable);
  EXPECT_EQ(all->record(1).model, "m12");
  auto unfinished = run("unfinished", true);
  EXPECT_EQ(unfinished->record(0).category, Category::kSofa);  // completed: kept
  EXPECT_EQ(unfinished->record(1).category, Category::kTable);
  EXPECT_EQ(unfinished->record(2).category, Category::kTable);
  auto other = run("other", false);
  EXPECT_EQ(other->record(0).category, Category::kSofa);
  EXPECT_EQ(other->record(1).category, Category::kChair);
  EXPECT_EQ(other->record(2).category, Category::kTable);
  EXPECT_EQ(other->record(2).model, "");  // the label alone changed: no model was adopted
  EXPECT_EQ(LastChange(other->record(2)).action, "relabel");
}

TEST(ReportPipelineTest, RulesRunInTheListedOrder) {
  // A door label on a cabinet-deep thing: door_depth takes it and relabel gives it the confident
  // match; in the other order relabel finds nothing taken yet and the label is gone at the end.
  const auto run = [](const std::vector<std::string>& rules) {
    ReportCase c;
    AddSizes(&c.extents);
    c.extents.Add(Category::kDresser, {0.9, 1.1});
    const int o = c.AddUnfinished(1, Box({1.0, 2.5, 0}, {1.6, 3.3, 0.9}), Category::kDoor,
                                  {Match(Category::kDoor, 0.96, 1), Match(Category::kDresser, 0.95, 2)});
    ReportOptions options;
    options.rules = rules;
    const ReportPipeline pipeline(options);
    EXPECT_EQ(pipeline.rule_names(), rules);
    pipeline.Run(c.Context(), &c.objects);
    return c.record(o).category;
  };
  EXPECT_EQ(run({"door_depth", "relabel"}), Category::kDresser);
  EXPECT_EQ(run({"relabel", "door_depth"}), std::nullopt);
  EXPECT_EQ(run({}), Category::kDoor);
}

TEST(ReportPipelineTest, DefaultListNamesEveryRuleOnceAndUnknownNamesAreRejected) {
  const std::vector<std::string> all = AllReportRules();
  EXPECT_EQ(std::set<std::string>(all.begin(), all.end()).size(), all.size());
  // + reopen_outgrown, drop_unsure, shape_agrees
  EXPECT_EQ(DefaultReportRules().size() + 3, all.size());
  ReportOptions options;
  for (const auto& name : all) EXPECT_NE(MakeReportRule(name, options), nullptr) << name;
  EXPECT_TRUE(ReportPipeline(options).needs_category_extents());
  options.rules = {"door_depth", "window_magic"};
  EXPECT_THROW(options.Validate(), ConfigError);
  options.rules = {"door_depth", "door_depth"};
  EXPECT_THROW(options.Validate(), ConfigError);
  options.rules = {"door_depth"};
  EXPECT_FALSE(ReportPipeline(options).needs_category_extents());
}

}  // namespace
}  // namespace objscan::scanning
