// Fuzz target: the OMPL.app .cfg reader (readProblemConfig).
#include <cstdint>

#include "fuzz_input_file.h"
#include "mddual/error.h"
#include "mddual/scene/problem_config.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path file = mddual::fuzz::writeInput(data, size, ".cfg");
  try {
    const mddual::scene::ProblemConfig config = mddual::scene::readProblemConfig(file);
    (void)config;
  } catch (const mddual::Error&) {
    // A clear error is an answer.
  }
  return 0;
}
