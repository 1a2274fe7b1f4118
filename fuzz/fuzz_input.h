#pragma once
// One fuzz input through one of objscan's file loaders, shared by the libFuzzer targets (fuzz_*.cc,
// built with -DOBJSCAN_FUZZ=ON) and the regression test of the normal suite (regressions_test.cc),
// so that an input the fuzzer found replays exactly in both.
//
// The contract checked on every input: the loader returns, or throws objscan::InputError (ConfigError
// is one) whose what() is one line naming the file (or `--set` for an override). Anything else — a
// crash, a sanitizer report, another exception type escaping, a message of several lines or naming no
// file — is a finding: RunInput throws ContractViolation, which the fuzz targets turn into a crash.
//
// Every target writes its input to files in a workspace folder of its own process
// (<tmp>/objscan-fuzz-<pid>/, /dev/shm when there is one) and loads them from there:
//   gazebo_world   the input is a .world file; model://box_model and model://mesh_model resolve to
//                  small models of the workspace, and a category map of the workspace is used.
//   scene_file     the input is a scene file (.yaml; JSON is YAML); `mesh: triangle.obj` resolves.
//   ply            the input is a PLY file (io::ReadPly).
//   model_database the input is a database payload: the harness writes the header (magic, version,
//                  size, checksum) in front so the parser behind the checksum is what gets fuzzed;
//                  an input that starts with the magic is written as it is (the header checks).
//   config         YAML of a --config file, then optionally a line "#--set" and one `key=value`
//                  override per line (scanning::LoadSystemConfig).
//   scannet        the files of a ScanNet scan folder, in this order, separated by a line "=====":
//                  _vh_clean_2.ply, .aggregation.json, _vh_clean_2.0.010000.segs.json,
//                  _vh_clean_2.labels.ply, .txt; an empty or absent part is a missing file.
//   bag            the input is a ROS bag file (ros_bridge::ReadBag); every message's topic, type, time
//                  and bytes are read.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace objscan::fuzz {

enum class Target { kGazeboWorld, kSceneFile, kPly, kModelDatabase, kConfig, kScanNet, kBag };

// Name as used by scripts/fuzz.sh, fuzz/corpus/<name>/ and fuzz/regressions/<name>/.
const char* TargetName(Target target);
const std::vector<Target>& AllTargets();
// Throws std::invalid_argument for an unknown name.
Target TargetFromName(const std::string& name);

class ContractViolation : public std::logic_error {
 public:
  explicit ContractViolation(const std::string& what) : std::logic_error(what) {}
};

// Loads the input. Returns "" when it loaded, else the one-line InputError message (the workspace
// folder in it replaced by "<ws>", so messages compare across processes). Throws ContractViolation.
std::string RunInput(Target target, const std::uint8_t* data, std::size_t size);

// The workspace folder of this process (made on first use, removed at exit).
const std::string& Workspace();

}  // namespace objscan::fuzz
