// The Python module `objscan` (pybind11): load scenes, build or load model databases, run or step
// the object-aware scanning loop with configuration overrides, and read the run as dicts (the content
// of run.json) and numpy arrays (points, labels, trajectory). The same library calls as `objscan run`
// (apps/objscan/cmd_run.cc), so the same scene, database, seed and --set strings give the same run.
//
// Errors: objscan's InputError becomes objscan.InputError (a ValueError), ConfigError
// objscan.ConfigError (an InputError), a file argument that does not exist FileNotFoundError, any
// other C++ exception RuntimeError; the message is the one line `objscan` prints after "objscan: error: ".
// The GIL is released during every long call (loading, building, scanning, writing).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "objscan/common/error.h"
#include "objscan/eval/benchmark.h"
#include "objscan/eval/run_evaluation.h"
#include "objscan/eval/run_output.h"
#include "objscan/io/scannet.h"
#include "objscan/io/scene_spec.h"
#include "objscan/mapping/surface_map.h"
#include "objscan/recognition/classifier_cache.h"
#include "objscan/recognition/database_builder.h"
#include "objscan/recognition/default_database.h"
#include "objscan/recognition/model_database.h"
#include "objscan/scanning/run_record.h"
#include "objscan/scanning/scanner.h"
#include "objscan/scanning/scene_limits.h"
#include "objscan/scanning/system_config.h"
#include "objscan/sim/simulated_robot.h"
#include "objscan/world/category.h"
#include "objscan/world/scene.h"

namespace py = pybind11;

namespace objscan::python {
namespace {

namespace fs = std::filesystem;

// The module's exception types (set in PYBIND11_MODULE).
PyObject* g_input_error = nullptr;
PyObject* g_config_error = nullptr;

[[noreturn]] void Raise(PyObject* type, const std::string& message) {
  PyErr_SetString(type, message.c_str());
  throw py::error_already_set();
}

// True when `path` names a file argument that is not there (procedural specs are no files).
bool MissingFile(const std::string& path) {
  if (path.empty() || path.rfind("procedural:", 0) == 0 || path == "procedural") return false;
  std::error_code ec;
  return !fs::exists(path, ec);
}

// Runs `f` without the GIL and turns objscan's exceptions into Python ones. `files` are the file
// arguments of the call: an InputError while one of them is missing is a FileNotFoundError.
template <class F>
auto Call(const std::vector<std::string>& files, F&& f) -> decltype(f()) {
  try {
    py::gil_scoped_release release;
    return f();
  } catch (const ConfigError& e) {
    Raise(g_config_error, e.what());
  } catch (const InputError& e) {
    for (const std::string& file : files) {
      if (MissingFile(file)) Raise(PyExc_FileNotFoundError, e.what());
    }
    Raise(g_input_error, e.what());
  }
}

std::vector<std::string> Sets(const std::vector<std::string>& sets, const std::optional<std::string>& model_path,
                              const std::optional<std::string>& category_map) {
  std::vector<std::string> all = sets;
  // As `objscan run --model-path / --category-map` (cmd_run.cc): appended after the --set strings.
  if (model_path && !model_path->empty()) all.push_back("scene.model_path=" + *model_path);
  if (category_map && !category_map->empty()) all.push_back("scene.category_map=" + *category_map);
  return all;
}

py::object JsonToPython(const std::string& json_text) {
  return py::module_::import("json").attr("loads")(json_text);
}

// A loaded scene and the SPEC it came from.
struct PyScene {
  std::string spec;
  std::shared_ptr<const world::Scene> scene;
};

PyScene LoadScene(const std::string& spec, const std::vector<std::string>& sets, const std::string& config_file,
                  const std::optional<std::string>& model_path, const std::optional<std::string>& category_map) {
  return Call({spec, config_file}, [&] {
    const scanning::SystemConfig config =
        scanning::LoadSystemConfig(config_file, Sets(sets, model_path, category_map));
    auto scene = std::make_shared<world::Scene>(io::LoadScene(spec, config.scene));
    return PyScene{spec, std::move(scene)};
  });
}

// A model database and the file it is kept in ("" when it was built and not saved).
struct PyDatabase {
  std::string path;
  std::shared_ptr<const recognition::ModelDatabase> database;
};

PyDatabase LoadDatabase(const std::string& path, double max_memory_mb) {
  return Call({path}, [&] {
    auto db = std::make_shared<recognition::ModelDatabase>(
        recognition::ModelDatabase::Load(path, recognition::DatabaseMemoryLimitBytes(max_memory_mb)));
    if (db->models().empty()) throw InputError(path + ": the model database is empty");
    return PyDatabase{path, std::move(db)};
  });
}

// The built-in database of a scene: procedural scenes (and none given) the procedural one, every other
// scene the real one (the Sweet Home 3D library), as `objscan run`.
PyDatabase DefaultDatabase(const std::optional<std::string>& cache_dir, const std::optional<std::string>& scene) {
  const std::string dir = cache_dir ? *cache_dir : recognition::DefaultDatabaseCacheDir();
  const bool procedural = !scene || recognition::UsesProceduralDatabase(*scene);
  const std::string path = Call({}, [&] {
    return procedural ? recognition::EnsureDefaultDatabase(dir) : recognition::EnsureRealDatabase(dir);
  });
  return LoadDatabase(path, 0.0);
}

// As `objscan db build` (cmd_db.cc): "procedural", a folder of model meshes, or scenes whose
// categorised objects are taken once per model id.
PyDatabase BuildDatabase(const std::vector<std::string>& models, const std::optional<std::string>& out, int variants,
                         const std::string& sampling, const std::vector<std::string>& sets, std::uint64_t seed,
                         int threads, const std::string& model_path, const std::string& category_map) {
  std::vector<std::string> files = models;
  return Call(files, [&] {
    if (models.empty()) throw InputError("models: name 'procedural', a folder of models or scene files");
    recognition::DatabaseBuildOptions options;
    options.threads = threads;
    options.seed = seed;
    config::RawConfig raw;
    for (const auto& s : sets) raw.SetFromAssignment(s);
    config::Apply(raw, &options);
    std::vector<recognition::ModelSource> sources;
    const std::string& first = models.front();
    if (models.size() == 1 && first == "procedural") {
      if (variants < 1) throw InputError("variants must be at least 1");
      sources = recognition::ProceduralModelSources(variants, 0,
                                                    recognition::ParseProceduralSampling(sampling, "sampling"));
    } else if (models.size() == 1 && fs::is_directory(first) && !io::IsScanNetSpec(first)) {
      std::vector<std::string> skipped;
      sources = recognition::ModelSourcesFromFolder(first, &skipped);
    } else {
      io::SceneLoadOptions load;
      load.model_path = model_path;
      if (!category_map.empty()) load.category_map = category_map;
      std::vector<eval::WorldModels> worlds;
      for (const std::string& spec : models) worlds.push_back({spec, io::LoadScene(spec, load)});
      sources = eval::ModelDisjointSources(worlds, worlds.size());
      if (sources.empty()) throw InputError("models " + first + ": no categorised object in the given scenes");
    }
    auto db = std::make_shared<recognition::ModelDatabase>(recognition::BuildDatabase(sources, options));
    if (db->models().empty()) throw InputError("models " + first + ": no model gave any points");
    if (out) db->Save(*out);
    return PyDatabase{out ? *out : std::string(), std::move(db)};
  });
}

// One scanning run: the scanner, its evaluator (metrics when the scene has ground truth, as in
// `objscan run`), and what they keep alive.
class Scan {
 public:
  Scan(PyScene scene, std::optional<PyDatabase> database, std::uint64_t seed, const std::vector<std::string>& sets,
       const std::string& config_file, const std::optional<std::string>& model_path,
       const std::optional<std::string>& category_map)
      : scene_(std::move(scene)), seed_(seed) {
    config_ = Call({config_file}, [&] {
      const scanning::SystemConfig config = scanning::LoadSystemConfig(config_file, Sets(sets, model_path, category_map));
      scanning::CheckSceneLimits(*scene_.scene, config, scene_.spec);
      return config;
    });
    database_ = database ? *database : DefaultDatabase(std::nullopt, scene_.spec);
    Call({}, [&] {
      std::set<world::Category> known;
      for (const auto& m : database_.database->models()) known.insert(m.category);
      robot_ = std::make_unique<sim::SimulatedRobot>(*scene_.scene, config_.sensor, config_.robot, config_.navigation,
                                                     seed_);
      scanner_ = std::make_unique<scanning::Scanner>(config_, robot_.get(), *database_.database, seed_);
      evaluator_ = std::make_unique<eval::RunEvaluator>(*scene_.scene, config_,
                                                        std::vector<world::Category>(known.begin(), known.end()));
      eval::RunEvaluator* evaluator = evaluator_.get();
      scanner_->set_frame_observer([evaluator](const platform::DepthFrame& frame,
                                               const mapping::FrameAssociation& association) {
        evaluator->ObserveFrame(frame, association);
      });
      scanner_->set_analysis_observer([evaluator](const scanning::Scanner& s) { evaluator->ObserveAnalysis(s); });
    });
  }

  // One iteration of the loop; false once the run has terminated.
  bool Step() {
    const bool more = Locked([&] {
      if (finished_) return false;
      return scanner_->Step();
    });
    WarnAboutClassifierCache();
    return more;
  }

  // Steps to the end, then the end-of-run analysis, the report and the metrics (once).
  void Finish() {
    Locked([&] {
      if (finished_) return;
      record_ = scanner_->Run();
      evaluator_->AssignGroundTruthInstances(*scanner_, &record_);
      metrics_ = evaluator_->Evaluate(*scanner_, record_);
      finished_ = true;
    });
    WarnAboutClassifierCache();
  }

  // How the category recognizer came from its cache; None until the scan first asked it.
  py::object ClassifierCacheDict() {
    const recognition::CachedClassifierStatus status = Locked([&] { return scanner_->classifier_cache_status(); });
    if (status.path.empty()) return py::none();
    py::dict d;
    d["path"] = status.path;
    d["loaded"] = status.loaded;
    d["damage"] = status.damage;
    d["write_error"] = status.write_error;
    return d;
  }

  bool finished() const { return finished_; }
  const scanning::RunRecord& record() const { return finished_ ? record_ : scanner_->record(); }

  py::object RecordDict() {
    const std::string text = Locked([&] { return eval::RunJson(Inputs()); });
    return JsonToPython(text);
  }

  py::object MetricsDict() {
    if (!finished_) return py::none();
    py::object record = RecordDict();
    return record.attr("get")("metrics");
  }

  py::object LastStep() {
    py::object record = RecordDict();
    py::list steps = record["steps"];
    if (steps.empty()) return py::none();
    return steps[steps.size() - 1];
  }

  void Save(const std::string& out_dir) {
    if (!finished_) {
      Raise(PyExc_RuntimeError, "Scan.save: the run is not finished (call finish() first)");
    }
    Call({}, [&] {
      std::lock_guard<std::mutex> lock(mutex_);
      eval::WriteRunOutputs(out_dir, Inputs());
    });
  }

  py::array_t<float> Points() {
    std::lock_guard<std::mutex> lock(mutex_);
    const mapping::SurfaceMap& map = scanner_->surface_map();
    py::array_t<float> out(std::vector<py::ssize_t>{static_cast<py::ssize_t>(map.size()), 3});
    auto a = out.mutable_unchecked<2>();
    for (py::ssize_t i = 0; i < static_cast<py::ssize_t>(map.size()); ++i) {
      const Eigen::Vector3f& p = map.position(i);
      for (int k = 0; k < 3; ++k) a(i, k) = p[k];
    }
    return out;
  }

  py::array_t<float> Normals() {
    std::lock_guard<std::mutex> lock(mutex_);
    const mapping::SurfaceMap& map = scanner_->surface_map();
    py::array_t<float> out(std::vector<py::ssize_t>{static_cast<py::ssize_t>(map.size()), 3});
    auto a = out.mutable_unchecked<2>();
    for (py::ssize_t i = 0; i < static_cast<py::ssize_t>(map.size()); ++i) {
      const Eigen::Vector3f n = map.normal(i);
      for (int k = 0; k < 3; ++k) a(i, k) = n[k];
    }
    return out;
  }

  // Per point: (category id, output object id) as in scene.ply's category_id / object_id, or the
  // latest analysis's object ids (during a run, before the report exists).
  std::pair<std::vector<int>, std::vector<int>> ElementObjects() {
    std::vector<int> object_id, category_id;
    std::lock_guard<std::mutex> lock(mutex_);
    scanner_->ElementObjects(&object_id, &category_id);
    return {std::move(category_id), std::move(object_id)};
  }

  py::array_t<std::int32_t> Labels() { return ToArray(ElementObjects().first); }
  py::array_t<std::int32_t> Instances() { return ToArray(ElementObjects().second); }
  py::array_t<std::int32_t> AnalysisInstances() {
    std::vector<int> object_id;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      scanner_->AnalysisElementObjects(&object_id);
    }
    return ToArray(object_id);
  }

  // Every trajectory sample: simulated time, base x/y/theta, the camera pose (4x4), whether a view
  // was taken there and its step.
  py::dict Trajectory() {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto& samples = record().trajectory;
    const auto n = static_cast<py::ssize_t>(samples.size());
    py::array_t<double> time(n);
    py::array_t<double> base(std::vector<py::ssize_t>{n, 3});
    py::array_t<double> poses(std::vector<py::ssize_t>{n, 4, 4});
    py::array_t<bool> view(n);
    py::array_t<std::int32_t> step(n);
    auto t = time.mutable_unchecked<1>();
    auto b = base.mutable_unchecked<2>();
    auto p = poses.mutable_unchecked<3>();
    auto v = view.mutable_unchecked<1>();
    auto s = step.mutable_unchecked<1>();
    for (py::ssize_t i = 0; i < n; ++i) {
      const auto& sample = samples[i];
      t(i) = sample.time_s;
      b(i, 0) = sample.x_m;
      b(i, 1) = sample.y_m;
      b(i, 2) = sample.theta_rad;
      const Eigen::Matrix4d m = sample.T_world_camera.matrix();
      for (int r = 0; r < 4; ++r) {
        for (int c = 0; c < 4; ++c) p(i, r, c) = m(r, c);
      }
      v(i) = sample.view;
      s(i) = sample.step;
    }
    py::dict out;
    out["time_s"] = time;
    out["base_xy_theta"] = base;
    out["T_world_camera"] = poses;
    out["view"] = view;
    out["step"] = step;
    return out;
  }

  // The views as trajectory.tum has them: one row "timestamp tx ty tz qx qy qz qw" per view.
  py::array_t<double> TrajectoryTum() {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<std::array<double, 8>> rows;
    for (const auto& sample : record().trajectory) {
      if (!sample.view) continue;
      Eigen::Quaterniond q(sample.T_world_camera.linear());
      q.normalize();
      if (q.w() < 0.0) q.coeffs() = -q.coeffs();  // as TrajectoryTum (eval/run_output.cc)
      const Eigen::Vector3d x = sample.T_world_camera.translation();
      rows.push_back({sample.time_s, x.x(), x.y(), x.z(), q.x(), q.y(), q.z(), q.w()});
    }
    py::array_t<double> out(std::vector<py::ssize_t>{static_cast<py::ssize_t>(rows.size()), 8});
    auto a = out.mutable_unchecked<2>();
    for (std::size_t i = 0; i < rows.size(); ++i) {
      for (int k = 0; k < 8; ++k) a(i, k) = rows[i][k];
    }
    return out;
  }

  int steps() const { return static_cast<int>(record().steps.size()); }
  int views() const { return record().views; }
  double travel_m() const { return record().travel_m; }
  std::string terminated() const { return scanning::TerminationName(record().terminated); }
  std::uint64_t seed() const { return seed_; }
  const PyScene& scene() const { return scene_; }
  const PyDatabase& database() const { return database_; }
  py::object ConfigDict() const { return JsonToPython(scanning::ToJson(config_)); }

 private:
  eval::RunOutputInputs Inputs() const {
    eval::RunOutputInputs in;
    in.record = &record();
    in.scanner = scanner_.get();
    in.database = database_.database.get();
    in.config = &config_;
    in.metrics = finished_ ? &metrics_ : nullptr;
    in.scene_spec = scene_.spec;
    in.database_path = database_.path;
    in.warn = [](const std::string& m) { std::fprintf(stderr, "objscan: warning: %s\n", m.c_str()); };
    return in;
  }

  // Without the GIL, one call at a time on this run.
  template <class F>
  auto Locked(F&& f) -> decltype(f()) {
    return Call({}, [&] {
      std::lock_guard<std::mutex> lock(mutex_);
      return f();
    });
  }

  // A damaged cache file trained again, or a trained classifier that could not be kept, is said once
  // as a RuntimeWarning with the CLI's words (recognition::ClassifierCacheMessages); the scan's
  // results do not change. Called with the GIL held.
  void WarnAboutClassifierCache() {
    if (classifier_cache_reported_) return;
    const recognition::CachedClassifierStatus status = Locked([&] { return scanner_->classifier_cache_status(); });
    if (status.path.empty()) return;
    classifier_cache_reported_ = true;
    for (const std::string& message : recognition::ClassifierCacheMessages(status)) {
      if (PyErr_WarnEx(PyExc_RuntimeWarning, message.c_str(), 1) != 0) throw py::error_already_set();
    }
  }

  static py::array_t<std::int32_t> ToArray(const std::vector<int>& v) {
    py::array_t<std::int32_t> out(static_cast<py::ssize_t>(v.size()));
    auto a = out.mutable_unchecked<1>();
    for (std::size_t i = 0; i < v.size(); ++i) a(i) = v[i];
    return out;
  }

  PyScene scene_;
  PyDatabase database_;
  bool classifier_cache_reported_ = false;
  std::uint64_t seed_;
  scanning::SystemConfig config_;
  std::unique_ptr<sim::SimulatedRobot> robot_;  // the platform the scanner drives
  std::unique_ptr<scanning::Scanner> scanner_;
  std::unique_ptr<eval::RunEvaluator> evaluator_;
  scanning::RunRecord record_;
  eval::RunMetrics metrics_;
  bool finished_ = false;
  std::mutex mutex_;
};

PyScene SceneOf(const py::object& scene, const std::vector<std::string>& sets, const std::string& config_file,
                const std::optional<std::string>& model_path, const std::optional<std::string>& category_map) {
  if (py::isinstance<PyScene>(scene)) return scene.cast<PyScene>();
  if (py::isinstance<py::str>(scene)) {
    return LoadScene(scene.cast<std::string>(), sets, config_file, model_path, category_map);
  }
  if (py::hasattr(scene, "__fspath__")) {
    return LoadScene(py::str(scene.attr("__fspath__")()).cast<std::string>(), sets, config_file, model_path,
                     category_map);
  }
  throw py::type_error("scene: expected an objscan.Scene or a scene SPEC string");
}

std::optional<PyDatabase> DatabaseOf(const py::object& database) {
  if (database.is_none()) return std::nullopt;
  if (py::isinstance<PyDatabase>(database)) return database.cast<PyDatabase>();
  if (py::isinstance<py::str>(database) || py::hasattr(database, "__fspath__")) {
    const std::string path = py::isinstance<py::str>(database) ? database.cast<std::string>()
                                                                : py::str(database.attr("__fspath__")()).cast<std::string>();
    return LoadDatabase(path, 0.0);
  }
  throw py::type_error("database: expected an objscan.Database, a database file path or None (the built-in one)");
}

py::object ConfigOf(const std::vector<std::string>& sets, const std::string& config_file) {
  const std::string json = Call({config_file}, [&] { return scanning::ToJson(scanning::LoadSystemConfig(config_file, sets)); });
  return JsonToPython(json);
}

}  // namespace
}  // namespace objscan::python

PYBIND11_MODULE(objscan, m) {
  using namespace objscan::python;
  namespace scanning = objscan::scanning;
  m.doc() =
      "objscan: object-aware autonomous scene scanning (next best object, next best view, objectness, "
      "multi-class graph cuts) in a fast headless simulator. See docs/python.md.";
  m.attr("__version__") = "0.1.0";

  static py::exception<objscan::InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<objscan::ConfigError> config_error(m, "ConfigError", input_error.ptr());
  g_input_error = input_error.ptr();
  g_config_error = config_error.ptr();
  // Calls that do not go through Call() (none should) still raise the module's types.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const objscan::ConfigError& e) {
      PyErr_SetString(g_config_error, e.what());
    } catch (const objscan::InputError& e) {
      PyErr_SetString(g_input_error, e.what());
    }
  });

  m.def("config_dir", [] { return scanning::ConfigDir(); },
        "The config/ folder in use ($OBJSCAN_CONFIG_DIR, the source tree's from a build, else the installed one).");
  m.def("config", &ConfigOf, py::arg("sets") = std::vector<std::string>{}, py::arg("config_file") = "",
        "The effective configuration as a dict: defaults, then config_file, then each 'key=value' of sets "
        "(as `objscan run --config F --set ...`). Raises objscan.ConfigError naming an unknown key.");
  m.def("category_names", [] {
    std::vector<std::string> names;
    for (int c = 0; c < objscan::world::kNumCategories; ++c) {
      names.emplace_back(objscan::world::CategoryName(static_cast<objscan::world::Category>(c)));
    }
    return names;
  }, "Category names by id: labels() values index this list (-1: unrecognized).");

  py::class_<PyScene>(m, "Scene", "A loaded scene (load_scene).")
      .def_property_readonly("spec", [](const PyScene& s) { return s.spec; })
      .def_property_readonly("name", [](const PyScene& s) { return s.scene->name(); })
      .def_property_readonly("num_objects", [](const PyScene& s) { return s.scene->objects().size(); })
      .def_property_readonly("num_furniture", [](const PyScene& s) { return s.scene->NumFurniture(); })
      .def_property_readonly("num_triangles", [](const PyScene& s) { return s.scene->NumTriangles(); })
      .def_property_readonly(
          "bounds",
          [](const PyScene& s) {
            const auto box = s.scene->Bounds();
            return py::make_tuple(py::make_tuple(box.min_m.x(), box.min_m.y(), box.min_m.z()),
                                  py::make_tuple(box.max_m.x(), box.max_m.y(), box.max_m.z()));
          },
          "((min x, y, z), (max x, y, z)) in metres.")
      .def(
          "objects",
          [](const PyScene& s) {
            py::list out;
            for (const auto& o : s.scene->objects()) {
              py::dict d;
              d["instance"] = o.instance_id;
              d["category"] = objscan::world::CategoryName(o.category);
              d["name"] = o.name;
              d["model"] = o.model_name;
              d["structural"] = o.IsStructural();
              const auto t = o.T_world_object.translation();
              d["xyz"] = py::make_tuple(t.x(), t.y(), t.z());
              out.append(d);
            }
            return out;
          },
          "The scene's objects (ground truth) as dicts: instance, category, name, model, structural, xyz.")
      .def("__repr__", [](const PyScene& s) {
        return "<objscan.Scene '" + s.spec + "': " + std::to_string(s.scene->objects().size()) + " objects>";
      });

  m.def("load_scene", &LoadScene, py::arg("spec"), py::arg("sets") = std::vector<std::string>{},
        py::arg("config_file") = "", py::arg("model_path") = py::none(), py::arg("category_map") = py::none(),
        "Loads a scene SPEC as `objscan run --scene` does: a Gazebo .world, a .yaml/.json scene file, a "
        "ScanNet scan, a mesh, or procedural:CATEGORY:SEED. model_path / category_map as --model-path / "
        "--category-map; sets (scene.* keys) as --set. Raises FileNotFoundError for a missing file.");

  py::class_<PyDatabase>(m, "Database", "A model database (load_database, default_database, build_database).")
      .def_property_readonly("path", [](const PyDatabase& d) { return d.path; })
      .def_property_readonly("num_models", [](const PyDatabase& d) { return d.database->models().size(); })
      .def_property_readonly("num_entries", [](const PyDatabase& d) { return d.database->entries().size(); })
      .def(
          "categories",
          [](const PyDatabase& d) {
            std::set<std::string> names;
            for (const auto& model : d.database->models()) names.insert(objscan::world::CategoryName(model.category));
            return std::vector<std::string>(names.begin(), names.end());
          },
          "The categories of its models, sorted.")
      .def(
          "models",
          [](const PyDatabase& d) {
            py::list out;
            for (const auto& model : d.database->models()) {
              py::dict x;
              x["name"] = model.name;
              x["category"] = objscan::world::CategoryName(model.category);
              x["source"] = model.source;
              out.append(x);
            }
            return out;
          },
          "The models as dicts: name, category, source.")
      .def("save", [](const PyDatabase& d, const std::string& path) {
        Call({}, [&] { d.database->Save(path); });
      }, py::arg("path"), "Writes the database file (as `objscan db build --out`).")
      .def("__repr__", [](const PyDatabase& d) {
        return "<objscan.Database '" + d.path + "': " + std::to_string(d.database->models().size()) + " models>";
      });

  m.def("load_database", &LoadDatabase, py::arg("path"), py::arg("max_memory_mb") = 0.0,
        "Loads a database file (objscan db build --out F.db). max_memory_mb: refuse one needing more "
        "(0: the memory available).");
  m.def("default_database", &DefaultDatabase, py::arg("cache_dir") = py::none(), py::arg("scene") = py::none(),
        "The built-in database `objscan run` uses for `scene`: the procedural one for procedural scenes "
        "(and when no scene is given), the real one (the Sweet Home 3D library) for every other scene; "
        "built once, minutes, and cached in $OBJSCAN_CACHE_DIR or ~/.cache/objscan (the same files the "
        "program uses).");
  m.def("build_database", &BuildDatabase, py::arg("models") = std::vector<std::string>{"procedural"},
        py::arg("out") = py::none(), py::arg("variants") = 8, py::arg("sampling") = "style-medoids",
        py::arg("sets") = std::vector<std::string>{}, py::arg("seed") = 1, py::arg("threads") = 0,
        py::arg("model_path") = "", py::arg("category_map") = "",
        "Builds a database as `objscan db build` does: models=['procedural'] (variants models of each "
        "category's styles), [FOLDER] of model meshes, or scene files whose categorised objects are taken "
        "once per model id. sets: build options key=value. Saved to out when given.");

  py::class_<Scan>(m, "Scan",
                   "One scanning run. Scan(scene, database=None, seed=1, sets=[], config_file='', "
                   "model_path=None, category_map=None): scene an objscan.Scene or a SPEC string, database an "
                   "objscan.Database, a file path or None for the built-in one; sets the --set strings. step() "
                   "advances one iteration of the loop; finish() runs to the end and scores the run.")
      .def(py::init([](const py::object& scene, const py::object& database, std::uint64_t seed,
                       const std::vector<std::string>& sets, const std::string& config_file,
                       const std::optional<std::string>& model_path, const std::optional<std::string>& category_map) {
             // The configuration is checked before the scene loads, as in `objscan run`.
             ConfigOf(Sets(sets, model_path, category_map), config_file);
             PyScene s = SceneOf(scene, sets, config_file, model_path, category_map);
             return std::make_unique<Scan>(std::move(s), DatabaseOf(database), seed, sets, config_file, model_path,
                                           category_map);
           }),
           py::arg("scene") = "procedural:bedroom:1", py::arg("database") = py::none(), py::arg("seed") = 1,
           py::arg("sets") = std::vector<std::string>{}, py::arg("config_file") = "",
           py::arg("model_path") = py::none(), py::arg("category_map") = py::none())
      .def("step", &Scan::Step,
           "One iteration of the loop (sense, fuse, segment, recognise, choose and move); False once the run "
           "has terminated (then call finish()).")
      .def("finish", &Scan::Finish,
           "Steps to the end, runs the end-of-run analysis and report, and scores the run against the "
           "scene's ground truth (metrics). Idempotent.")
      .def("run", [](Scan& s) {
        s.Finish();
        return s.RecordDict();
      }, "finish() and return record().")
      .def_property_readonly("finished", &Scan::finished)
      .def_property_readonly("terminated", &Scan::terminated, "running, done, max_steps or stuck")
      .def_property_readonly("steps", &Scan::steps, "Steps taken so far.")
      .def_property_readonly("views", &Scan::views, "Views (depth frames) taken so far.")
      .def_property_readonly("travel_m", &Scan::travel_m)
      .def_property_readonly("seed", &Scan::seed)
      .def_property_readonly("scene", &Scan::scene)
      .def_property_readonly("database", &Scan::database)
      .def("config", &Scan::ConfigDict, "The effective configuration (run.json's `config`).")
      .def("classifier_cache", &Scan::ClassifierCacheDict,
           "How the category recognizer came from its cache: a dict of path, loaded (read, not trained), "
           "damage (why a cached file was rejected and trained again) and write_error (why the trained one "
           "could not be kept); None until the scan first asked the recognizer. A damage or a write error "
           "is also said once as a RuntimeWarning.")
      .def("record", &Scan::RecordDict,
           "The run as a dict: the content of run.json (scene, seed, database, config, terminated, steps, "
           "structure, objects, metrics once finished, timing_s), without peak_rss_mb and cpu_s.")
      .def_property_readonly("metrics", &Scan::MetricsDict, "record()['metrics'] once finished, else None.")
      .def("last_step", &Scan::LastStep, "The last step of record()['steps'] (None before the first).")
      .def("points", &Scan::Points, "Reconstructed surface points (N x 3 float32, metres, world frame).")
      .def("normals", &Scan::Normals, "Their unit normals (N x 3 float32).")
      .def("labels", &Scan::Labels,
           "Per point the category id (int32, N; -1 unrecognized; names: category_names()) as scene.ply's "
           "category_id; before finish() only structure (floor, wall, ceiling) is labelled.")
      .def("instances", &Scan::Instances,
           "Per point the output object id (int32, N; -1 none) as scene.ply's object_id (objects of "
           "record()['objects']); all -1 before finish().")
      .def("analysis_instances", &Scan::AnalysisInstances,
           "Per point the object id of the latest analysis (completed and current post-segmented objects; "
           "-1 none): what the method believes mid-run.")
      .def("trajectory", &Scan::Trajectory,
           "Every trajectory sample as arrays: time_s (N), base_xy_theta (N x 3), T_world_camera (N x 4 x 4), "
           "view (N bool), step (N int32).")
      .def("trajectory_tum", &Scan::TrajectoryTum,
           "One row per view: timestamp tx ty tz qx qy qz qw (V x 8 float64), as trajectory.tum.")
      .def("save", &Scan::Save, py::arg("out_dir"),
           "Writes the output folder of `objscan run` (run.json, scene.ply, models.ply, trajectory.csv, "
           "trajectory.tum, categories.json, topview.png, navmap.png, coverage.ply). Only after finish().")
      .def("__repr__", [](const Scan& s) {
        return "<objscan.Scan '" + s.scene().spec + "' seed " + std::to_string(s.seed()) + ": " +
               std::to_string(s.steps()) + " steps, " + std::to_string(s.views()) + " views, " + s.terminated() + ">";
      });

  m.def(
      "run",
      [](const py::object& scene, const py::object& database, std::uint64_t seed, const std::vector<std::string>& sets,
         const std::string& config_file, const std::optional<std::string>& model_path,
         const std::optional<std::string>& category_map, const std::optional<std::string>& out) {
        ConfigOf(Sets(sets, model_path, category_map), config_file);
        PyScene s = SceneOf(scene, sets, config_file, model_path, category_map);
        auto scan = std::make_unique<Scan>(std::move(s), DatabaseOf(database), seed, sets, config_file, model_path,
                                           category_map);
        scan->Finish();
        if (out) scan->Save(*out);
        return scan;
      },
      py::arg("scene") = "procedural:bedroom:1", py::arg("database") = py::none(), py::arg("seed") = 1,
      py::arg("sets") = std::vector<std::string>{}, py::arg("config_file") = "", py::arg("model_path") = py::none(),
      py::arg("category_map") = py::none(), py::arg("out") = py::none(),
      "A whole run, as `objscan run`: returns the finished Scan (record(), metrics, arrays); writes the output "
      "folder when out is given.");
}
