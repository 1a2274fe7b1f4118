"""Tests of the Python module objscan (python/objscan_module.cc), run by ctest with the system python3.

ctest (python/CMakeLists.txt) sets PYTHONPATH to the build's module folder and:
  OBJSCAN_BINARY     the objscan program of the same build (the answers the module must match)
  OBJSCAN_TEST_DB    a small procedural database (one model per category style) built by the fixture
  OBJSCAN_BUILD_DIR, OBJSCAN_SOURCE_DIR, CMAKE_COMMAND   for the install test and the example

Known answers: a run through the module gives the run.json of `objscan run` with the same scene,
database, seed and --set strings; stepping then finishing gives the same run as running at once; a
bad key raises the CLI's one-line message.
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import threading
import unittest
import warnings

import numpy as np

import objscan

OBJSCAN = os.environ.get("OBJSCAN_BINARY", "objscan")
DB = os.environ.get("OBJSCAN_TEST_DB", "")
SCENE = "procedural:bathroom:1"
SEED = 3
SETS = ["scanner.max_steps=5"]


def without_timings(record):
    """run.json without what depends on the machine's speed, memory and load."""
    record = json.loads(json.dumps(record))
    for key in ("timing_s", "peak_rss_mb", "cpu_s"):
        record.pop(key, None)
    for step in record.get("steps", []):
        step.pop("timing_ms", None)
    return record


def run_cli(*args):
    return subprocess.run([OBJSCAN, *args], capture_output=True, text=True)


class Scratch(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="objscan_py_")

    def tearDown(self):
        shutil.rmtree(self.dir, ignore_errors=True)


class ErrorsTest(Scratch):
    """Bad input raises a Python exception with the CLI's one line, never aborts."""

    def cli_error(self, *args):
        r = run_cli(*args)
        self.assertNotEqual(r.returncode, 0)
        lines = r.stderr.strip().splitlines()
        self.assertEqual(len(lines), 1, r.stderr)
        self.assertTrue(lines[0].startswith("objscan: error: "), lines[0])
        return lines[0][len("objscan: error: "):]

    def test_unknown_set_key_raises_config_error_with_the_cli_message(self):
        expected = self.cli_error("run", "--set", "sensor.no_such_key=1", "--db", DB, "--out", self.dir)
        self.assertIn("no_such_key", expected)
        for call in (lambda: objscan.config(sets=["sensor.no_such_key=1"]),
                     lambda: objscan.Scan(SCENE, database=DB, sets=["sensor.no_such_key=1"]),
                     lambda: objscan.run(SCENE, database=DB, sets=["sensor.no_such_key=1"])):
            with self.assertRaises(objscan.ConfigError) as ctx:
                call()
            self.assertEqual(str(ctx.exception), expected)
            self.assertIsInstance(ctx.exception, ValueError)
            self.assertIsInstance(ctx.exception, objscan.InputError)

    def test_bad_value_raises_naming_the_key(self):
        expected = self.cli_error("run", "--set", "nbv.num_candidates=-3", "--db", DB, "--out", self.dir)
        with self.assertRaises(objscan.ConfigError) as ctx:
            objscan.config(sets=["nbv.num_candidates=-3"])
        self.assertEqual(str(ctx.exception), expected)

    def test_missing_scene_file_raises_file_not_found_naming_it(self):
        missing = os.path.join(self.dir, "no_such_room.world")
        expected = self.cli_error("run", "--scene", missing, "--db", DB, "--out", os.path.join(self.dir, "out"))
        for call in (lambda: objscan.load_scene(missing), lambda: objscan.Scan(missing, database=DB)):
            with self.assertRaises(FileNotFoundError) as ctx:
                call()
            self.assertIn(missing, str(ctx.exception))
            self.assertEqual(str(ctx.exception), expected)

    def test_missing_database_and_config_files_raise_file_not_found(self):
        with self.assertRaises(FileNotFoundError) as ctx:
            objscan.load_database(os.path.join(self.dir, "none.db"))
        self.assertIn("none.db", str(ctx.exception))
        with self.assertRaises(FileNotFoundError) as ctx:
            objscan.config(config_file=os.path.join(self.dir, "none.yaml"))
        self.assertIn("none.yaml", str(ctx.exception))

    def test_bad_scene_spec_and_corrupt_database_raise_value_error(self):
        with self.assertRaises(objscan.InputError) as ctx:
            objscan.load_scene("procedural:garage:1")
        self.assertIn("garage", str(ctx.exception))
        corrupt = os.path.join(self.dir, "corrupt.db")
        with open(corrupt, "wb") as f:
            f.write(b"not a database")
        with self.assertRaises(ValueError) as ctx:
            objscan.load_database(corrupt)
        self.assertIn(corrupt, str(ctx.exception))

    def test_wrong_argument_types_raise_type_error(self):
        with self.assertRaises(TypeError):
            objscan.Scan(42, database=DB)
        with self.assertRaises(TypeError):
            objscan.Scan(SCENE, database=3.5)


class RunMatchesCliTest(Scratch):
    """Same scene, database, seed and --set: the module's record is the CLI's run.json."""

    def test_record_equals_the_cli_run_json_and_save_writes_the_same_files(self):
        cli_out = os.path.join(self.dir, "cli")
        r = run_cli("run", "--scene", SCENE, "--db", DB, "--seed", str(SEED), "--quiet", "--out", cli_out,
                    *[a for s in SETS for a in ("--set", s)])
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(os.path.join(cli_out, "run.json")) as f:
            cli = json.load(f)

        scan = objscan.run(SCENE, database=DB, seed=SEED, sets=SETS)
        record = scan.record()
        self.assertIn("metrics", record)
        self.assertEqual(without_timings(record), without_timings(cli))
        self.assertEqual(scan.metrics, record["metrics"])
        # The CLI's summary numbers, too.
        summary = json.loads(r.stdout)
        self.assertEqual(summary["views"], scan.views)
        self.assertAlmostEqual(summary["recall"], scan.metrics["recall"], places=4)
        self.assertAlmostEqual(summary["coverage_rate"], scan.metrics["coverage_rate"], places=4)

        py_out = os.path.join(self.dir, "py")
        scan.save(py_out)
        for name in ("run.json", "scene.ply", "models.ply", "trajectory.csv", "trajectory.tum", "categories.json",
                     "topview.png", "navmap.png", "coverage.ply"):
            self.assertTrue(os.path.exists(os.path.join(py_out, name)), name)
        for name in ("scene.ply", "trajectory.csv", "trajectory.tum", "coverage.ply"):
            with open(os.path.join(py_out, name), "rb") as a, open(os.path.join(cli_out, name), "rb") as b:
                self.assertEqual(a.read(), b.read(), name)
        with open(os.path.join(py_out, "run.json")) as f:
            self.assertEqual(without_timings(json.load(f)), without_timings(cli))


class StepTest(Scratch):
    """Stepping one view at a time, inspecting between steps, then finishing is the same run."""

    def test_stepping_then_finishing_equals_running_at_once(self):
        scan = objscan.Scan(SCENE, database=DB, seed=SEED, sets=SETS)
        self.assertEqual(scan.steps, 0)
        self.assertEqual(scan.terminated, "running")
        self.assertIsNone(scan.last_step())
        self.assertEqual(scan.points().shape, (0, 3))
        sizes, views = [], []
        for k in range(1, 4):
            self.assertTrue(scan.step())
            self.assertEqual(scan.steps, k)
            self.assertEqual(scan.last_step()["index"], k - 1)
            self.assertFalse(scan.finished)
            self.assertIsNone(scan.metrics)
            sizes.append(scan.points().shape[0])
            views.append(scan.views)
            self.assertEqual(scan.analysis_instances().shape, (sizes[-1],))
        self.assertGreater(sizes[0], 0)
        self.assertEqual(sizes, sorted(sizes))  # the map only grows
        self.assertEqual(views, sorted(views))
        self.assertEqual(scan.last_step()["action"] in ("nbo", "nbv", "frontier"), True)
        mid = scan.record()
        self.assertNotIn("metrics", mid)
        self.assertEqual(len(mid["steps"]), 3)
        scan.finish()
        self.assertTrue(scan.finished)
        self.assertFalse(scan.step())
        scan.finish()  # idempotent

        at_once = objscan.run(SCENE, database=DB, seed=SEED, sets=SETS)
        self.assertEqual(without_timings(scan.record()), without_timings(at_once.record()))
        np.testing.assert_array_equal(scan.points(), at_once.points())
        np.testing.assert_array_equal(scan.labels(), at_once.labels())

    def test_the_gil_is_released_while_scanning(self):
        scan = objscan.Scan(SCENE, database=DB, seed=SEED, sets=["scanner.max_steps=2"])
        worker = threading.Thread(target=scan.finish)
        ticks = 0
        worker.start()
        while worker.is_alive():
            ticks += 1
        worker.join()
        self.assertTrue(scan.finished)
        # Holding the GIL for the whole scan would leave this thread a handful of ticks at most.
        self.assertGreater(ticks, 1000)

    def test_save_before_finish_raises(self):
        scan = objscan.Scan(SCENE, database=DB, seed=SEED, sets=SETS)
        scan.step()
        with self.assertRaises(RuntimeError):
            scan.save(os.path.join(self.dir, "out"))


class ClassifierCacheTest(Scratch):
    """How the category recognizer came from its cache can be read, and a damaged cache file is trained
    again with one RuntimeWarning naming it (the CLI's line), the scan unchanged."""

    def setUp(self):
        super().setUp()
        self.old_cache = os.environ.get("OBJSCAN_CACHE_DIR")
        os.environ["OBJSCAN_CACHE_DIR"] = os.path.join(self.dir, "cache")

    def tearDown(self):
        if self.old_cache is None:
            os.environ.pop("OBJSCAN_CACHE_DIR", None)
        else:
            os.environ["OBJSCAN_CACHE_DIR"] = self.old_cache
        super().tearDown()

    def scan(self):
        scan = objscan.Scan(SCENE, database=DB, seed=SEED, sets=["scanner.max_steps=2"])
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            scan.finish()
        return scan, [str(w.message) for w in caught if issubclass(w.category, RuntimeWarning)]

    def test_a_damaged_cache_file_is_trained_again_with_one_warning(self):
        self.assertIsNone(objscan.Scan(SCENE, database=DB, seed=SEED).classifier_cache())  # not asked yet
        trained, said = self.scan()
        status = trained.classifier_cache()
        self.assertIsNotNone(status)
        self.assertFalse(status["loaded"])
        self.assertEqual((status["damage"], status["write_error"]), ("", ""))
        self.assertTrue(os.path.isfile(status["path"]))
        self.assertEqual(said, [])

        loaded, said = self.scan()
        self.assertTrue(loaded.classifier_cache()["loaded"])
        self.assertEqual(said, [])

        with open(status["path"], "r+b") as f:
            f.truncate(100)
        repaired, said = self.scan()
        self.assertFalse(repaired.classifier_cache()["loaded"])
        self.assertEqual(len(said), 1, said)
        self.assertIn("the cached category recognizer is damaged, trained it again: " + status["path"], said[0])
        self.assertEqual(without_timings(repaired.record()), without_timings(loaded.record()))

        # Reading it again says nothing more.
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            repaired.finish()
            repaired.step()
        self.assertEqual([w for w in caught if issubclass(w.category, RuntimeWarning)], [])


class ArraysTest(Scratch):
    """Array shapes and dtypes agree with each other and with the record."""

    @classmethod
    def setUpClass(cls):
        cls.scan = objscan.run(SCENE, database=DB, seed=SEED, sets=SETS)
        cls.record = cls.scan.record()

    def test_points_labels_instances(self):
        points, normals = self.scan.points(), self.scan.normals()
        labels, instances = self.scan.labels(), self.scan.instances()
        n = points.shape[0]
        self.assertGreater(n, 1000)
        self.assertEqual(points.shape, (n, 3))
        self.assertEqual(points.dtype, np.float32)
        self.assertEqual(normals.shape, (n, 3))
        self.assertEqual(normals.dtype, np.float32)
        np.testing.assert_allclose(np.linalg.norm(normals, axis=1), 1.0, atol=1e-4)
        self.assertEqual(labels.shape, (n,))
        self.assertEqual(labels.dtype, np.int32)
        self.assertEqual(instances.shape, (n,))
        self.assertEqual(instances.dtype, np.int32)
        names = objscan.category_names()
        self.assertTrue(np.all((labels >= -1) & (labels < len(names))))
        # Every object id on the points is an object of the record, labelled with its category.
        objects = {o["id"]: o for o in self.record["objects"]}
        self.assertTrue(objects)
        for object_id in np.unique(instances):
            if object_id < 0:
                continue
            self.assertIn(int(object_id), objects)
            category = objects[int(object_id)]["category"]
            on_it = labels[instances == object_id]
            expected = names.index(category) if category is not None else -1
            self.assertTrue(np.all(on_it == expected), (object_id, category))
        # The floor is labelled.
        self.assertGreater(np.count_nonzero(labels == names.index("floor")), 0)
        # Points lie in the scene.
        (lo, hi) = self.scan.scene.bounds
        margin = 0.2
        self.assertTrue(np.all(points.min(axis=0) >= np.array(lo) - margin))
        self.assertTrue(np.all(points.max(axis=0) <= np.array(hi) + margin))

    def test_trajectory(self):
        t = self.scan.trajectory()
        n = t["time_s"].shape[0]
        self.assertGreater(n, 0)
        self.assertEqual(t["base_xy_theta"].shape, (n, 3))
        self.assertEqual(t["T_world_camera"].shape, (n, 4, 4))
        self.assertEqual(t["T_world_camera"].dtype, np.float64)
        self.assertEqual(t["view"].dtype, np.bool_)
        self.assertEqual(t["step"].dtype, np.int32)
        self.assertTrue(np.all(np.diff(t["time_s"]) >= 0))
        rotations = t["T_world_camera"][:, :3, :3]
        np.testing.assert_allclose(rotations @ rotations.transpose(0, 2, 1), np.broadcast_to(np.eye(3), rotations.shape),
                                   atol=1e-9)
        np.testing.assert_array_equal(t["T_world_camera"][:, 3, :], np.broadcast_to([0, 0, 0, 1], (n, 4)))
        tum = self.scan.trajectory_tum()
        self.assertEqual(tum.shape, (int(t["view"].sum()), 8))
        self.assertEqual(tum.shape[0], self.record["metrics"]["views"])
        self.assertEqual(tum.shape[0], sum(s["views"] for s in self.record["steps"]))
        np.testing.assert_allclose(tum[:, 1:4], t["T_world_camera"][t["view"], :3, 3])
        np.testing.assert_allclose(np.linalg.norm(tum[:, 4:8], axis=1), 1.0, atol=1e-9)
        # The same numbers as the trajectory.tum the run writes.
        out = os.path.join(self.dir, "out")
        self.scan.save(out)
        written = np.loadtxt(os.path.join(out, "trajectory.tum"), comments="#", ndmin=2)
        np.testing.assert_allclose(written, tum, atol=1e-6)

    def test_scene_ply_has_the_points(self):
        out = os.path.join(self.dir, "out")
        self.scan.save(out)
        with open(os.path.join(out, "scene.ply"), "rb") as f:
            header = f.read(4096).split(b"end_header")[0].decode()
        vertices = [int(line.split()[2]) for line in header.splitlines() if line.startswith("element vertex")]
        self.assertEqual(vertices, [self.scan.points().shape[0]])

    def test_scene_and_database_objects(self):
        scene = objscan.load_scene(SCENE)
        self.assertEqual(scene.spec, SCENE)
        objects = scene.objects()
        self.assertEqual(len(objects), scene.num_objects)
        self.assertGreater(scene.num_furniture, 0)
        self.assertIn("floor", {o["category"] for o in objects})
        db = objscan.load_database(DB)
        self.assertEqual(db.path, DB)
        self.assertEqual(len(db.models()), db.num_models)
        self.assertIn("toilet", db.categories())
        # A loaded Scene and Database give the same run as the SPEC and path.
        again = objscan.run(scene, database=db, seed=SEED, sets=SETS)
        self.assertEqual(without_timings(again.record()), without_timings(self.record))
        config = self.scan.config()
        self.assertEqual(config["scanner"]["max_steps"], 5)
        self.assertEqual(config, self.record["config"])


class BuildDatabaseTest(Scratch):
    def test_built_database_is_saved_and_loads(self):
        out = os.path.join(self.dir, "two.db")
        db = objscan.build_database(["procedural"], out=out, variants=1, sets=["vocabulary.num_words=32"])
        self.assertEqual(db.path, out)
        self.assertGreater(db.num_models, 10)
        loaded = objscan.load_database(out)
        self.assertEqual(loaded.num_models, db.num_models)
        self.assertEqual(loaded.num_entries, db.num_entries)
        with self.assertRaises(objscan.ConfigError):
            objscan.build_database(["procedural"], variants=1, sets=["vocabulary.no_such_key=1"])


class InstalledModuleTest(Scratch):
    """`cmake --install` puts the module beside the library; it imports from there alone."""

    def test_import_from_an_installed_tree(self):
        prefix = os.path.join(self.dir, "prefix")
        r = subprocess.run([os.environ["CMAKE_COMMAND"], "--install", os.environ["OBJSCAN_BUILD_DIR"], "--prefix", prefix],
                           capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        site = os.path.join(prefix, "lib", "python3", "dist-packages")
        modules = [f for f in os.listdir(site) if f.startswith("objscan") and f.endswith(".so")]
        self.assertEqual(len(modules), 1, os.listdir(site))
        env = dict(os.environ, PYTHONPATH=site)
        env.pop("OBJSCAN_CONFIG_DIR", None)
        code = ("import json, objscan; print(json.dumps({'file': objscan.__file__, 'config_dir': objscan.config_dir(), "
                "'sections': sorted(objscan.config())}))")
        r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, cwd=self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        info = json.loads(r.stdout)
        self.assertTrue(os.path.realpath(info["file"]).startswith(os.path.realpath(prefix)), info)
        self.assertEqual(os.path.realpath(info["config_dir"]),
                         os.path.realpath(os.path.join(prefix, "share", "objscan", "config")))
        self.assertIn("scanner", info["sections"])
        # It links the installed library, not the build's.
        ldd = subprocess.run(["ldd", os.path.join(site, modules[0])], capture_output=True, text=True).stdout
        line = [l for l in ldd.splitlines() if "libobjscan.so" in l]
        self.assertEqual(len(line), 1, ldd)
        self.assertIn(os.path.realpath(prefix), os.path.realpath(line[0].split("=>")[1].split()[0]))


class ExampleTest(Scratch):
    def test_scan_room_example_runs_and_saves(self):
        example = os.path.join(os.environ["OBJSCAN_SOURCE_DIR"], "examples", "python", "scan_room.py")
        out = os.path.join(self.dir, "out")
        r = subprocess.run([sys.executable, example, "--scene", SCENE, "--db", DB, "--seed", str(SEED), "--max-steps", "5",
                            "--out", out], capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        summary = json.loads(r.stdout.strip().splitlines()[-1])
        with open(os.path.join(out, "run.json")) as f:
            record = json.load(f)
        self.assertEqual(summary["views"], record["metrics"]["views"])
        self.assertAlmostEqual(summary["recall"], record["metrics"]["recall"])
        points = np.load(os.path.join(out, "points.npz"))
        self.assertEqual(points["xyz"].shape[1], 3)
        self.assertEqual(points["xyz"].shape[0], points["label"].shape[0])


if __name__ == "__main__":
    unittest.main()
