#pragma once
// Where the simulator puts the robot down, as an operator would: looking at the room (the scene's
// ground truth), on free floor. The method never reads this; it starts from where the platform is.
#include "objscan/navigation/navigator.h"
#include "objscan/platform/platform.h"
#include "objscan/platform/robot_options.h"
#include "objscan/world/scene.h"

namespace objscan::sim {

// The free spot farthest from obstacles (clearance counted in 10 cm steps up to 1 m), nearest the
// furniture's centre on ties, heading towards that centre. Throws InputError naming the scene when
// no free floor is left for the robot.
platform::BasePose ChooseStartPose(const world::Scene& scene, const platform::RobotOptions& robot_options,
                                   const navigation::NavigatorOptions& navigation_options);

}  // namespace objscan::sim
