// objscan as a library: load the installed default configuration, generate a procedural bedroom,
// build a small model database of two of its categories, scan the room for a few steps of the
// object-aware loop, and print what happened as JSON.
//
//   objscan_example [STEPS]      (default 3)
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <set>
#include <string>
#include <vector>

#include "objscan/io/scene_spec.h"
#include "objscan/mapping/surface_map.h"
#include "objscan/recognition/database_builder.h"
#include "objscan/scanning/scanner.h"
#include "objscan/scanning/system_config.h"
#include "objscan/sim/simulated_robot.h"

int main(int argc, char** argv) {
  using namespace objscan;
  const int max_steps = argc > 1 ? std::atoi(argv[1]) : 3;
  try {
    // config/ is found relative to the installed library (share/objscan/config).
    const std::string config_dir = scanning::ConfigDir();
    const scanning::SystemConfig config =
        scanning::LoadSystemConfig(config_dir + "/default.yaml", {"sensor.noise=false"});
    const world::Scene scene = io::LoadScene("procedural:bedroom:1", config.scene);

    // Two categories keep the database build to a few seconds (objscan's own default has eight
    // models of every category).
    const std::set<world::Category> wanted = {world::Category::kBed, world::Category::kNightStand};
    std::vector<recognition::ModelSource> sources;
    for (auto& source : recognition::ProceduralModelSources(1)) {
      if (wanted.count(source.category) != 0) sources.push_back(std::move(source));
    }
    recognition::DatabaseBuildOptions options;
    options.vocabulary.num_words = 48;
    const recognition::ModelDatabase database = recognition::BuildDatabase(sources, options);

    // The simulated robot in the scene (objscan's simulator is one platform; a real robot is another).
    sim::SimulatedRobot robot(scene, config.sensor, config.robot, config.navigation, /*seed=*/1);
    scanning::Scanner scanner(config, &robot, database, /*seed=*/1);
    int steps = 0;
    while (steps < max_steps && scanner.Step()) ++steps;
    const scanning::RunRecord& record = scanner.record();

    std::printf("{\"config_dir\": \"%s\", \"scene_objects\": %zu, \"database_models\": %zu, \"steps\": %zu, "
                "\"views\": %d, \"map_points\": %zu, \"objects\": %zu}\n",
                config_dir.c_str(), scene.objects().size(), database.models().size(), record.steps.size(),
                record.views, scanner.surface_map().size(), record.objects.size());
    return 0;
  } catch (const std::exception& e) {
    // objscan's library throws (InputError, ConfigError) with the file or key named; it never exits.
    std::fprintf(stderr, "objscan_example: %s\n", e.what());
    return 1;
  }
}
