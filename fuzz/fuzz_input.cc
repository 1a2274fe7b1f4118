#include "fuzz_input.h"

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <typeinfo>

#include "bag_reader.h"
#include "objscan/common/error.h"
#include "objscan/io/category_map.h"
#include "objscan/io/gazebo_world.h"
#include "objscan/io/ply.h"
#include "objscan/io/scannet.h"
#include "objscan/io/scene_file.h"
#include "objscan/recognition/model_database.h"
#include "objscan/scanning/system_config.h"

namespace objscan::fuzz {
namespace fs = std::filesystem;
namespace {

void WriteFile(const fs::path& path, const char* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(data, static_cast<std::streamsize>(size));
  if (!out) throw std::runtime_error("fuzz harness: cannot write " + path.string());
}
void WriteFile(const fs::path& path, const std::string& text) { WriteFile(path, text.data(), text.size()); }

// Files every input may refer to, made once per workspace.
void MakeFixtures(const fs::path& ws) {
  WriteFile(ws / "triangle.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0.5\nf 1 2 3\n");
  WriteFile(ws / "categories.yaml",
            "rules:\n"
            "  - {name: '^table', category: table}\n"
            "  - {uri: 'mesh_model', category: chair}\n"
            "  - {label: '^(kitchen )?cabinets?$', category: cabinet}\n"
            "  - {label: '^floor$', category: floor}\n");
  fs::create_directories(ws / "box_model");
  WriteFile(ws / "box_model" / "model.config",
            "<?xml version='1.0'?>\n<model><name>box_model</name><sdf version='1.6'>model.sdf</sdf></model>\n");
  WriteFile(ws / "box_model" / "model.sdf",
            "<?xml version='1.0'?>\n<sdf version='1.6'><model name='box_model'><static>true</static>"
            "<link name='link'><visual name='v'><geometry><box><size>0.5 0.4 0.3</size></box></geometry>"
            "</visual></link></model></sdf>\n");
  fs::create_directories(ws / "mesh_model" / "meshes");
  WriteFile(ws / "mesh_model" / "meshes" / "triangle.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0.5\nf 1 2 3\n");
  WriteFile(ws / "mesh_model" / "model.config",
            "<?xml version='1.0'?>\n<model><name>mesh_model</name><sdf version='1.7'>model.sdf</sdf></model>\n");
  WriteFile(ws / "mesh_model" / "model.sdf",
            "<?xml version='1.0'?>\n<sdf version='1.7'><model name='mesh_model'><link name='base'>"
            "<visual name='v'><pose>0 0 0.1 0 0 0</pose><geometry><mesh><uri>model://mesh_model/meshes/"
            "triangle.obj</uri><scale>2 2 2</scale></mesh></geometry></visual></link></model></sdf>\n");
}

// The workspace folder, removed when the process exits (by the destructor of the static holding it:
// an atexit handler registered while that static is being made would run after its destruction).
struct WorkspaceFolder {
  std::string path;
  ~WorkspaceFolder() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t pos = text.find(from); pos != std::string::npos; pos = text.find(from, pos + to.size())) {
    text.replace(pos, from.size(), to);
  }
  return text;
}

// The lines of `text` without their line ends; a text ending in a line end has no empty last line.
std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    lines.push_back(text.substr(pos, end - pos));
    pos = end + 1;
  }
  return lines;
}

// Splits at lines equal to `separator` (dropped with the line end before them).
std::vector<std::string> SplitAtLines(const std::string& text, const std::string& separator) {
  std::vector<std::string> parts(1);
  for (const std::string& line : Lines(text)) {
    if (line == separator) {
      if (!parts.back().empty() && parts.back().back() == '\n') parts.back().pop_back();  // the separator's
      parts.emplace_back();
    } else {
      parts.back() += line + '\n';
    }
  }
  // Every line was given its end back; the text's last line may not have had one.
  if (!text.empty() && text.back() != '\n' && !parts.back().empty()) parts.back().pop_back();
  return parts;
}

const io::CategoryMap& ScanNetCategories() {
  static const io::CategoryMap map = io::CategoryMap::Load((fs::path(Workspace()) / "categories.yaml").string());
  return map;
}

void Load(Target target, const std::string& input) {
  const fs::path ws = Workspace();
  switch (target) {
    case Target::kGazeboWorld: {
      const fs::path path = ws / "input.world";
      WriteFile(path, input);
      io::SceneLoadOptions options;
      options.category_map = (ws / "categories.yaml").string();
      options.allow_missing = true;  // goes on past an unresolved mesh, deeper into the world
      io::LoadGazeboWorld(path.string(), options);
      return;
    }
    case Target::kSceneFile: {
      const fs::path path = ws / "input.yaml";
      WriteFile(path, input);
      io::LoadSceneFile(path.string());
      return;
    }
    case Target::kPly: {
      const fs::path path = ws / "input.ply";
      WriteFile(path, input);
      io::ReadPly(path.string());
      return;
    }
    case Target::kModelDatabase: {
      const fs::path path = ws / "input.db";
      static const char kMagic[8] = {'O', 'B', 'J', 'S', 'C', 'D', 'B', '\n'};
      if (input.size() >= sizeof(kMagic) && std::memcmp(input.data(), kMagic, sizeof(kMagic)) == 0) {
        WriteFile(path, input);
        recognition::ModelDatabase::Load(path.string(), 1ull << 30);
      } else {
        recognition::ModelDatabase::FromPayload(input.data(), input.size(), path.string());
      }
      return;
    }
    case Target::kConfig: {
      const std::vector<std::string> parts = SplitAtLines(input, "#--set");
      std::string config_file;
      if (!parts[0].empty()) {
        config_file = (ws / "config.yaml").string();
        WriteFile(config_file, parts[0]);
      }
      std::vector<std::string> overrides;
      for (std::size_t i = 1; i < parts.size(); ++i) {
        for (const std::string& line : Lines(parts[i])) overrides.push_back(line);
      }
      scanning::LoadSystemConfig(config_file, overrides);
      return;
    }
    case Target::kScanNet: {
      const fs::path dir = ws / "scene0000_00";
      fs::create_directories(dir);
      static const char* kSuffixes[] = {"_vh_clean_2.ply", ".aggregation.json", "_vh_clean_2.0.010000.segs.json",
                                        "_vh_clean_2.labels.ply", ".txt"};
      const std::vector<std::string> parts = SplitAtLines(input, "=====");
      for (std::size_t i = 0; i < 5; ++i) {
        const fs::path file = dir / (std::string("scene0000_00") + kSuffixes[i]);
        std::error_code ec;
        fs::remove(file, ec);
        if (i < parts.size() && !parts[i].empty()) WriteFile(file, parts[i]);
      }
      io::SceneLoadOptions options;
      options.category_map = (ws / "categories.yaml").string();
      if (!io::IsScanNetSpec(dir.string())) return;  // no mesh file: not a scan (nothing to load)
      io::LoadScanNetScan(dir.string(), options, ScanNetCategories());
      return;
    }
    case Target::kBag: {
      const fs::path path = ws / "input.bag";
      WriteFile(path, input);
      // Every field of every message is read (ASan sees a byte outside its buffer, UBSan a bad value);
      // the messages' bytes are parts of the file, so together they cannot be more than the file.
      std::uint64_t sum = 0, data_bytes = 0;
      ros_bridge::ReadBag(path.string(), [&](const ros_bridge::BagMessage& m) {
        data_bytes += m.data.size();
        if (data_bytes > input.size()) {
          throw ContractViolation("bag: " + std::to_string(data_bytes) + " bytes of messages from a file of " +
                                  std::to_string(input.size()));
        }
        for (const char c : m.topic) sum += static_cast<unsigned char>(c);
        for (const char c : m.type) sum += static_cast<unsigned char>(c);
        for (const std::uint8_t b : m.data) sum += b;
        sum += m.time_sec + m.time_nsec;
      });
      [[maybe_unused]] static volatile std::uint64_t sink;
      sink = sum;
      return;
    }
  }
}

}  // namespace

const char* TargetName(Target target) {
  switch (target) {
    case Target::kGazeboWorld: return "gazebo_world";
    case Target::kSceneFile: return "scene_file";
    case Target::kPly: return "ply";
    case Target::kModelDatabase: return "model_database";
    case Target::kConfig: return "config";
    case Target::kScanNet: return "scannet";
    case Target::kBag: return "bag";
  }
  return "?";
}

const std::vector<Target>& AllTargets() {
  static const std::vector<Target> all = {Target::kGazeboWorld,   Target::kSceneFile, Target::kPly,
                                          Target::kModelDatabase, Target::kConfig,    Target::kScanNet,
                                          Target::kBag};
  return all;
}

Target TargetFromName(const std::string& name) {
  for (Target t : AllTargets()) {
    if (name == TargetName(t)) return t;
  }
  throw std::invalid_argument("unknown fuzz target '" + name + "'");
}

const std::string& Workspace() {
  static const WorkspaceFolder ws = [] {
    std::error_code ec;
    const fs::path base = fs::is_directory("/dev/shm", ec) ? fs::path("/dev/shm") : fs::temp_directory_path();
    const fs::path dir = base / ("objscan-fuzz-" + std::to_string(::getpid()));
    fs::remove_all(dir, ec);
    fs::create_directories(dir);
    MakeFixtures(dir);
    return WorkspaceFolder{dir.string()};
  }();
  return ws.path;
}

std::string RunInput(Target target, const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::string& ws = Workspace();
  try {
    Load(target, input);
    return "";
  } catch (const InputError& e) {
    const std::string message = e.what();
    if (message.find('\n') != std::string::npos) {
      throw ContractViolation(std::string(TargetName(target)) + ": error message of several lines: " + message);
    }
    // A config value's error names its key ("config: sensor.width_px must be > 0"), an override's
    // error names --set, every other error the file.
    const bool names_origin =
        message.find(ws) != std::string::npos ||
        (target == Target::kConfig && (message.find("--set") != std::string::npos || message.rfind("config: ", 0) == 0));
    if (!names_origin) {
      throw ContractViolation(std::string(TargetName(target)) + ": error message names no file: " + message);
    }
    return Replace(message, ws, "<ws>");
  } catch (const ContractViolation&) {
    throw;
  } catch (const std::exception& e) {
    throw ContractViolation(std::string(TargetName(target)) + ": " + typeid(e).name() +
                            " escaped the loader instead of InputError: " + e.what());
  }
}

}  // namespace objscan::fuzz
