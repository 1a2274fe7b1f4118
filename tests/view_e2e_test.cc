// `objscan view OUT/` on a short run: view.html is one file with everything inlined (no script, style
// or image loaded from elsewhere), the numbers it reports are the run's, and headless Chromium
// renders it: screenshots at the first and the last step differ and both show the reported objects'
// category colours.
// Needs Debian's chromium and libjs-three (scripts/install_deps.sh); skips, saying so, without them.
#include <gtest/gtest.h>

#include "run_command.h"

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>

#include "objscan/eval/run_view.h"
#include "objscan/io/png.h"
#include "objscan/world/category.h"

namespace {

namespace fs = std::filesystem;
using objscan::testing::ReadFile;
using objscan::testing::RunCommand;

const char* const kChromium = "/usr/bin/chromium";

// Pixels of `image` within 8 levels of one of `colors`.
long PixelsOfColors(const objscan::io::ImageRgb& image, const std::vector<std::array<unsigned char, 3>>& colors) {
  long count = 0;
  for (std::size_t i = 0; i + 2 < image.rgb.size(); i += 3) {
    for (const auto& c : colors) {
      if (std::abs(image.rgb[i] - c[0]) <= 8 && std::abs(image.rgb[i + 1] - c[1]) <= 8 && std::abs(image.rgb[i + 2] - c[2]) <= 8) {
        ++count;
        break;
      }
    }
  }
  return count;
}

// A screenshot of `page` at `fragment` (e.g. "step=1") in headless Chromium; empty on failure.
std::string Screenshot(const fs::path& page, const std::string& fragment, const fs::path& png, const fs::path& profile) {
  const std::string args =
      "--headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking "
      "--disable-component-update --disable-sync --enable-unsafe-swiftshader --hide-scrollbars "
      "--user-data-dir=" + profile.string() + " --window-size=1000,700 --virtual-time-budget=20000 --screenshot=" +
      png.string() + " 'file://" + page.string() + "#" + fragment + "'";
  const auto r = RunCommand("timeout 180 " + std::string(kChromium), args);
  return r.exit_code == 0 && fs::exists(png) ? png.string() : std::string();
}

TEST(ViewE2eTest, PageIsSelfContainedAndChromiumShowsTheRunStepByStep) {
  const objscan::eval::RunViewOptions defaults;
  if (!fs::exists(kChromium) || !fs::exists(defaults.three_js_path)) {
    GTEST_SKIP() << "SKIPPED LOUDLY: needs " << kChromium << " and " << defaults.three_js_path
                 << " (Debian chromium, libjs-three: scripts/install_deps.sh)";
  }
  const fs::path dir = objscan::testing::ScratchPath("objscan_view_e2e");
  fs::create_directories(dir);
  const std::string db = (dir / "small.db").string();
  const auto build = RunCommand(OBJSCAN_BINARY, "db build --models procedural --variants 1 --out " + db);
  ASSERT_EQ(build.exit_code, 0) << build.err;
  const fs::path out = dir / "run";
  const auto run = RunCommand(OBJSCAN_BINARY, "run --scene procedural:bathroom:1 --db " + db +
                                                  " --seed 3 --set scanner.max_steps=8 --out " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json record = nlohmann::json::parse(ReadFile(out / "run.json"));

  const auto view = RunCommand(OBJSCAN_BINARY, "view " + out.string());
  ASSERT_EQ(view.exit_code, 0) << view.err;
  const nlohmann::json summary = nlohmann::json::parse(view.out);
  EXPECT_EQ(summary["steps"].get<std::size_t>(), record["steps"].size());
  EXPECT_EQ(summary["views"], record["metrics"]["views"]);
  int complete = 0;
  std::size_t candidates = 0;
  for (const auto& o : record["objects"]) complete += o["complete"].get<bool>() ? 1 : 0;
  for (const auto& s : record["steps"]) candidates += s.value("nbv_candidates", nlohmann::json::array()).size();
  EXPECT_EQ(summary["models"].get<int>(), complete);
  EXPECT_EQ(summary["nbv_candidates"].get<std::size_t>(), candidates);
  EXPECT_GT(summary["points"].get<int>(), 10000);

  // Self-contained: no element loads anything from a URL or another file.
  const fs::path page = out / "view.html";
  const std::string html = ReadFile(page);
  EXPECT_FALSE(std::regex_search(html, std::regex(R"(<(script|img|link|iframe)[^>]*\s(src|href)\s*=)", std::regex::icase)));
  EXPECT_NE(html.find("THREE"), std::string::npos);

  // A bad folder: one line naming run.json, non-zero exit.
  const auto bad = RunCommand(OBJSCAN_BINARY, "view " + (dir / "nothing").string());
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("run.json"), std::string::npos) << bad.err;

  const std::string first = Screenshot(page, "step=1", dir / "first.png", dir / "profile");
  const std::string last = Screenshot(page, "step=last", dir / "last.png", dir / "profile");
  ASSERT_FALSE(first.empty()) << "chromium made no screenshot";
  ASSERT_FALSE(last.empty()) << "chromium made no screenshot";
  const objscan::io::ImageRgb a = objscan::io::ReadPngRgb(first), b = objscan::io::ReadPngRgb(last);
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  long differing = 0;
  for (std::size_t i = 0; i < a.rgb.size(); i += 3) {
    differing += a.rgb[i] != b.rgb[i] || a.rgb[i + 1] != b.rgb[i + 1] || a.rgb[i + 2] != b.rgb[i + 2];
  }
  EXPECT_GT(differing, static_cast<long>(a.rgb.size() / 3 / 100)) << "the two steps look the same";
  // The colours of the categories reported (objects, not floor and walls).
  std::vector<std::array<unsigned char, 3>> colors;
  std::set<std::string> names;
  for (const auto& o : record["objects"]) {
    if (o["category"].is_null() || !names.insert(o["category"].get<std::string>()).second) continue;
    colors.push_back(objscan::world::CategoryColor(*objscan::world::ParseCategory(o["category"].get<std::string>())));
  }
  ASSERT_FALSE(colors.empty());
  const long coloured_first = PixelsOfColors(a, colors), coloured_last = PixelsOfColors(b, colors);
  EXPECT_GT(coloured_first, 2000) << "the first step shows few object colours";
  EXPECT_GT(coloured_last, 2000) << "the last step shows few object colours";
  // Kept for people to look at (OBJSCAN_VIEW_SHOTS=folder).
  if (const char* keep = std::getenv("OBJSCAN_VIEW_SHOTS")) {
    fs::create_directories(keep);
    fs::copy_file(first, fs::path(keep) / "view-first.png", fs::copy_options::overwrite_existing);
    fs::copy_file(last, fs::path(keep) / "view-last.png", fs::copy_options::overwrite_existing);
  }
  fs::remove_all(dir);
}

}  // namespace
