#include "objscan/eval/run_view.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include <Eigen/Core>

#include "objscan/io/category_labels.h"
#include "objscan/io/ply.h"
#include "objscan/world/category.h"

namespace objscan::eval {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

// The page template (src/objscan/eval/run_view_page.html, made a string literal by CMake).
constexpr const char kPageTemplate[] =
#include "run_view_page.inc"
    ;

std::string ReadText(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot read " + what);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

template <class T>
std::string Base64(const std::vector<T>& values) {
  static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* bytes = reinterpret_cast<const unsigned char*>(values.data());
  const std::size_t n = values.size() * sizeof(T);
  std::string out;
  out.reserve((n + 2) / 3 * 4);
  for (std::size_t i = 0; i < n; i += 3) {
    const std::uint32_t b0 = bytes[i], b1 = i + 1 < n ? bytes[i + 1] : 0, b2 = i + 2 < n ? bytes[i + 2] : 0;
    const std::uint32_t triple = (b0 << 16) | (b1 << 8) | b2;
    out += kAlphabet[(triple >> 18) & 63];
    out += kAlphabet[(triple >> 12) & 63];
    out += i + 1 < n ? kAlphabet[(triple >> 6) & 63] : '=';
    out += i + 2 < n ? kAlphabet[triple & 63] : '=';
  }
  return out;
}

const std::vector<std::int32_t>* IntProperty(const io::PlyData& ply, const char* name) {
  for (const auto& [n, values] : ply.int_properties) {
    if (n == name) return &values;
  }
  return nullptr;
}

// A view of trajectory.csv: camera position, yaw and pitch (degrees) and the step it was taken in.
struct View {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double yaw_deg = 0.0, pitch_deg = 0.0;
  int step = 0;
};

struct PathSample {
  double x_m = 0.0, y_m = 0.0;
  int step = 0;
};

void ReadTrajectory(const std::string& path, std::vector<View>* views, std::vector<PathSample>* samples) {
  std::istringstream in(ReadText(path, "trajectory"));
  std::string line;
  if (!std::getline(in, line) || line.rfind("step,time_s,base_x_m,base_y_m", 0) != 0) {
    throw InputError(path + ": not an objscan trajectory.csv (header)");
  }
  int row = 1;
  while (std::getline(in, line)) {
    ++row;
    if (line.empty()) continue;
    std::vector<double> v;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) {
      char* end = nullptr;
      v.push_back(std::strtod(cell.c_str(), &end));
      if (end == cell.c_str()) throw InputError(path + ": line " + std::to_string(row) + ": '" + cell + "' is not a number");
    }
    if (v.size() != 11) throw InputError(path + ": line " + std::to_string(row) + ": expected 11 columns");
    samples->push_back({v[2], v[3], static_cast<int>(v[0])});
    if (v[10] != 0.0) views->push_back({{v[5], v[6], v[7]}, v[8], v[9], static_cast<int>(v[0])});
  }
}

// Camera axes of a view (optical frame, no roll): forward, image right, image down.
void CameraAxes(double yaw_deg, double pitch_deg, Eigen::Vector3d* forward, Eigen::Vector3d* right,
                Eigen::Vector3d* down) {
  const double y = yaw_deg * M_PI / 180.0, p = pitch_deg * M_PI / 180.0;
  *forward = {std::cos(p) * std::cos(y), std::cos(p) * std::sin(y), std::sin(p)};
  *right = {std::sin(y), -std::cos(y), 0.0};
  *down = forward->cross(*right);
}

}  // namespace

std::string RunViewHtml(const std::string& run_dir, const RunViewOptions& options, RunViewSummary* summary) {
  options.Validate();
  const fs::path dir(run_dir);
  const std::string run_path = (dir / "run.json").string();
  if (!fs::exists(run_path)) throw InputError(run_path + ": no run.json: not a finished objscan run folder");
  Json run;
  try {
    run = Json::parse(ReadText(run_path, "run.json"));
  } catch (const Json::parse_error& e) {
    throw InputError(run_path + ": bad JSON: " + e.what());
  }
  const std::string three_js = ReadText(options.three_js_path, "three.js (Debian package libjs-three)");
  const std::string orbit = ReadText(options.orbit_controls_path, "three.js OrbitControls (Debian package libjs-three)");

  // Sensor field of view and range.
  double hfov_deg = 62.0, vfov_deg = 49.0, max_range_m = 4.0, min_range_m = 0.0;
  double width_px = 640, height_px = 480, fx = 525, fy = 525, cx = 319.5, cy = 239.5;
  try {
    const Json& sensor = run.at("config").at("sensor");
    width_px = sensor.at("width_px").get<double>();
    height_px = sensor.at("height_px").get<double>();
    fx = sensor.at("fx_px").get<double>();
    fy = sensor.at("fy_px").get<double>();
    cx = sensor.at("cx_px").get<double>();
    cy = sensor.at("cy_px").get<double>();
    max_range_m = sensor.at("max_range_m").get<double>();
    min_range_m = sensor.at("min_range_m").get<double>();
  } catch (const Json::exception& e) {
    throw InputError(run_path + ": config.sensor: " + e.what());
  }
  hfov_deg = 2.0 * std::atan(0.5 * width_px / fx) * 180.0 / M_PI;
  vfov_deg = 2.0 * std::atan(0.5 * height_px / fy) * 180.0 / M_PI;

  std::vector<View> views;
  std::vector<PathSample> path;
  ReadTrajectory((dir / "trajectory.csv").string(), &views, &path);

  // Points: the ceiling is left out (it would hide the room from above, as in topview.png), every
  // k-th kept beyond max_points, then ordered by the first view that saw them.
  const std::string scene_path = (dir / "scene.ply").string();
  const io::PlyData scene = io::ReadPly(scene_path);
  const std::vector<std::int32_t>* label = IntProperty(scene, "label");
  if (!label) label = IntProperty(scene, "category_id");  // run folders written before `label`
  if (!label) throw InputError(scene_path + ": no label or category_id field");
  const int ceiling = world::CategoryId(world::Category::kCeiling);
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < scene.points.size(); ++i) {
    if ((*label)[i] != ceiling) kept.push_back(i);
  }
  if (kept.size() > static_cast<std::size_t>(options.max_points)) {
    const double stride = static_cast<double>(kept.size()) / options.max_points;
    std::vector<std::size_t> thinned;
    for (int k = 0; k < options.max_points; ++k) thinned.push_back(kept[static_cast<std::size_t>(k * stride)]);
    kept.swap(thinned);
  }
  std::vector<Eigen::Vector3d> forward(views.size()), right(views.size()), down(views.size());
  for (std::size_t v = 0; v < views.size(); ++v) CameraAxes(views[v].yaw_deg, views[v].pitch_deg, &forward[v], &right[v], &down[v]);
  const int last_view = std::max(0, static_cast<int>(views.size()) - 1);
  std::vector<int> first_view(kept.size(), -1);
  // Each view's depth image at a quarter of the sensor's resolution, from the points themselves
  // (splatted, then closed by a 3x3 minimum so a surface has no gaps at close range): a point
  // appears at the first view whose frustum holds it within range and that it is not hidden from.
  const int zw = std::max(1, static_cast<int>(width_px / 4)), zh = std::max(1, static_cast<int>(height_px / 4));
  std::vector<float> depth(static_cast<std::size_t>(zw) * zh), closed(depth.size());
  std::vector<int> pixel(kept.size());
  std::vector<float> point_depth(kept.size());
  for (std::size_t v = 0; v < views.size(); ++v) {
    std::fill(depth.begin(), depth.end(), std::numeric_limits<float>::infinity());
    for (std::size_t k = 0; k < kept.size(); ++k) {
      pixel[k] = -1;
      const Eigen::Vector3d d = scene.points[kept[k]].cast<double>() - views[v].position;
      const double z = d.dot(forward[v]);
      if (z < std::max(1e-3, 0.5 * min_range_m) || d.norm() > 1.05 * max_range_m) continue;
      const double u = (fx * d.dot(right[v]) / z + cx) / 4.0, w = (fy * d.dot(down[v]) / z + cy) / 4.0;
      if (u < 0.0 || w < 0.0 || u >= zw || w >= zh) continue;
      pixel[k] = static_cast<int>(w) * zw + static_cast<int>(u);
      point_depth[k] = static_cast<float>(z);
      depth[pixel[k]] = std::min(depth[pixel[k]], point_depth[k]);
    }
    for (int y = 0; y < zh; ++y) {
      for (int x = 0; x < zw; ++x) {
        float m = std::numeric_limits<float>::infinity();
        for (int yy = std::max(0, y - 1); yy <= std::min(zh - 1, y + 1); ++yy) {
          for (int xx = std::max(0, x - 1); xx <= std::min(zw - 1, x + 1); ++xx) m = std::min(m, depth[yy * zw + xx]);
        }
        closed[y * zw + x] = m;
      }
    }
    for (std::size_t k = 0; k < kept.size(); ++k) {
      if (first_view[k] >= 0 || pixel[k] < 0) continue;
      // Within a few centimetres (more far away, where the sensor is noisier) of the nearest surface.
      if (point_depth[k] <= closed[pixel[k]] + std::max(0.06f, 0.03f * point_depth[k])) first_view[k] = static_cast<int>(v);
    }
  }
  for (int& f : first_view) {
    if (f < 0) f = last_view;  // never found in a view (thinned neighbours, noise): shown at the end
  }
  std::vector<std::size_t> order(kept.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return first_view[a] < first_view[b]; });
  std::vector<float> xyz;
  std::vector<std::int32_t> labels;
  std::vector<int> after_view(views.empty() ? 1 : views.size(), 0);
  xyz.reserve(3 * order.size());
  for (std::size_t k : order) {
    const Eigen::Vector3f& p = scene.points[kept[k]];
    xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
    labels.push_back((*label)[kept[k]]);
    ++after_view[first_view[k]];
  }
  for (std::size_t v = 1; v < after_view.size(); ++v) after_view[v] += after_view[v - 1];

  // Steps and their NBV candidates; the step each object was last the object of interest.
  Json steps = Json::array();
  std::map<int, int> last_ooi_step;
  int last_step = 0, candidates = 0;
  for (const Json& s : run.value("steps", Json::array())) {
    const int index = s.value("index", 0);
    last_step = std::max(last_step, index);
    const int ooi = s.value("ooi", -1);
    if (ooi >= 0) last_ooi_step[ooi] = index;
    Json cands = Json::array();
    for (const Json& c : s.value("nbv_candidates", Json::array())) {
      const Json& pose = c.at("pose");
      const Json& p = pose.at("xyz");
      cands.push_back({p[0], p[1], p[2], pose.at("yaw_deg"), pose.at("pitch_deg"), c.value("gain", 0.0),
                       c.value("validity", std::string()) == "valid" ? 1 : 0});
      ++candidates;
    }
    steps.push_back({{"index", index},
                     {"action", s.value("action", std::string())},
                     {"ooi", ooi},
                     {"candidates", cands}});
  }

  // Models, one mesh per object (the largest kept within max_model_triangles).
  Json models = Json::array();
  const std::string models_path = (dir / "models.ply").string();
  if (fs::exists(models_path)) {
    const io::PlyData ply = io::ReadPly(models_path);
    const std::vector<std::int32_t>* instance = IntProperty(ply, "instance");
    if (!instance) instance = IntProperty(ply, "object_id");
    const std::vector<std::int32_t>* model_label = IntProperty(ply, "label");
    if (!model_label) model_label = IntProperty(ply, "category_id");
    if (!instance || !model_label) throw InputError(models_path + ": no instance/object_id or label/category_id field");
    std::map<int, std::vector<int>> triangles_of;  // object -> triangle indices
    for (std::size_t t = 0; t < ply.triangles.size(); ++t) triangles_of[(*instance)[ply.triangles[t][0]]].push_back(static_cast<int>(t));
    std::vector<std::pair<int, int>> by_size;
    for (const auto& [object, tris] : triangles_of) by_size.emplace_back(static_cast<int>(tris.size()), object);
    std::sort(by_size.begin(), by_size.end(), [](const auto& a, const auto& b) { return a.first > b.first || (a.first == b.first && a.second < b.second); });
    int budget = options.max_model_triangles;
    for (const auto& [count, object] : by_size) {
      if (count > budget) continue;
      budget -= count;
      std::map<int, std::uint32_t> local;
      std::vector<float> vertices;
      std::vector<std::uint32_t> index;
      int category = -1;
      for (int t : triangles_of[object]) {
        for (int k = 0; k < 3; ++k) {
          const int v = ply.triangles[t][k];
          auto [it, inserted] = local.emplace(v, static_cast<std::uint32_t>(local.size()));
          if (inserted) {
            vertices.insert(vertices.end(), {ply.points[v].x(), ply.points[v].y(), ply.points[v].z()});
            category = (*model_label)[v];
          }
          index.push_back(it->second);
        }
      }
      const auto step = last_ooi_step.find(object);
      models.push_back({{"object", object},
                        {"label", category},
                        {"step", step != last_ooi_step.end() ? step->second : last_step},
                        {"xyz", Base64(vertices)},
                        {"index", Base64(index)}});
    }
  }

  Json view_rows = Json::array();
  for (const View& v : views) {
    view_rows.push_back({v.position.x(), v.position.y(), v.position.z(), v.yaw_deg, v.pitch_deg, v.step});
  }
  Json path_rows = Json::array();
  for (const PathSample& p : path) path_rows.push_back({p.x_m, p.y_m, p.step});

  std::ostringstream title;
  title << run.value("scene", std::string("run")) << ", seed " << run.value("seed", 0) << ": "
        << run.value("terminated", std::string()) << ", " << views.size() << " views";
  if (run.contains("metrics")) {
    const Json& m = run["metrics"];
    char buffer[160];
    std::snprintf(buffer, sizeof(buffer), "; recall %.2f, precision %.2f, coverage %.2f", m.value("recall", 0.0),
                  m.value("precision", 0.0), m.value("coverage_rate", 0.0));
    title << buffer;
  }
  Json data;
  data["title"] = title.str();
  data["categories"] = Json::parse(io::CategoriesJson())["categories"];
  data["sensor"] = {{"hfov_deg", hfov_deg}, {"vfov_deg", vfov_deg}, {"max_range_m", max_range_m}};
  data["frustum_depth_m"] = options.frustum_depth_m;
  data["points"] = {{"count", order.size()}, {"xyz", Base64(xyz)}, {"label", Base64(labels)}, {"after_view", after_view}};
  data["models"] = models;
  data["views"] = view_rows;
  data["path"] = path_rows;
  data["steps"] = steps;
  // Inside <script>, "</" would end the element: JSON allows "<\/" for it.
  std::string data_text = data.dump();
  for (std::size_t at = data_text.find("</"); at != std::string::npos; at = data_text.find("</", at + 3)) {
    data_text.replace(at, 2, "<\\/");
  }
  for (const std::string* script : {&three_js, &orbit}) {
    if (script->find("</script") != std::string::npos) throw InputError("three.js: a script holds '</script': cannot inline it");
  }

  std::string page = kPageTemplate;
  const auto put = [&page](const std::string& marker, const std::string& text) {
    const std::size_t at = page.find(marker);
    if (at == std::string::npos) throw InputError("objscan view: page template lacks " + marker);
    page.replace(at, marker.size(), text);
  };
  put("/*OBJSCAN_THREE_JS*/", three_js);
  put("/*OBJSCAN_ORBIT_CONTROLS*/", orbit);
  put("/*OBJSCAN_RUN_DATA*/", data_text);
  if (summary) {
    summary->steps = static_cast<int>(steps.size());
    summary->views = static_cast<int>(views.size());
    summary->points = static_cast<int>(order.size());
    summary->scene_points = static_cast<int>(scene.points.size());
    summary->models = static_cast<int>(models.size());
    summary->candidates = candidates;
  }
  return page;
}

}  // namespace objscan::eval
