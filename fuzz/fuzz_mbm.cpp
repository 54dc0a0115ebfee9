// Fuzz target: the arm problem readers on arm7 (configs/arm7). The first
// byte picks the reader: 0 a MotionBenchMaker scene (sceneNNNN.yaml), 1 a
// request (requestNNNN.yaml, then its joint values applied to the robot),
// 2 an SRDF (its collision filter and every group's variables and states),
// 3 a trajectory (trajectoryNNNN.yaml, then each point applied to the robot).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "fuzz_input_file.h"
#include "mddual/error.h"
#include "mddual/scene/mbm_problem.h"
#include "mddual/scene/srdf.h"

namespace {

const mddual::scene::RobotModel& arm7() {
  static const mddual::scene::RobotModel model =
      mddual::scene::loadRobotModel(std::filesystem::path(MDDUAL_CONFIGS_DIR) / "arm7" / "arm7.urdf");
  return model;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const mddual::scene::RobotModel& model = arm7();
  const std::uint8_t which = data[0] % 4;
  try {
    if (which == 0) {
      (void)mddual::scene::loadMbmScene(mddual::fuzz::writeInput(data + 1, size - 1, ".yaml"), model);
    } else if (which == 1) {
      const mddual::scene::MbmRequest r =
          mddual::scene::loadMbmRequest(mddual::fuzz::writeInput(data + 1, size - 1, ".yaml"));
      (void)mddual::scene::applyJointValues(model, model.defaultConfiguration(), r.start, "start_state");
    } else if (which == 3) {
      const mddual::scene::MbmTrajectory t =
          mddual::scene::loadMbmTrajectory(mddual::fuzz::writeInput(data + 1, size - 1, ".yaml"));
      for (const std::vector<double>& point : t.points) {
        std::vector<std::pair<std::string, double>> values;
        for (std::size_t k = 0; k < point.size(); ++k) values.emplace_back(t.joint_names[k], point[k]);
        (void)mddual::scene::applyJointValues(model, model.defaultConfiguration(), values, "points");
      }
    } else {
      const mddual::scene::Srdf srdf =
          mddual::scene::parseSrdf(std::string(reinterpret_cast<const char*>(data + 1), size - 1), "input.srdf");
      const mddual::scene::AllowedCollisions filter(model, srdf);
      for (const mddual::scene::SrdfGroup& g : srdf.groups) {
        (void)mddual::scene::groupVariables(srdf, model, g.name);
      }
      for (const mddual::scene::SrdfGroupState& s : srdf.group_states) {
        (void)mddual::scene::groupStateValues(srdf, model, s.group, s.name);
      }
    }
  } catch (const mddual::Error&) {
  }
  return 0;
}
