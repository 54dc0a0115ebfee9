// Fuzz target: the URDF loader, as a robot and as a world (mesh references in
// the fuzzed text resolve next to the temporary file, normally to nothing).
#include <cstdint>

#include "fuzz_input_file.h"
#include "mddual/error.h"
#include "mddual/scene/loaders.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path file = mddual::fuzz::writeInput(data, size, ".urdf");
  try {
    (void)mddual::scene::loadBody(file);
  } catch (const mddual::Error&) {
  }
  try {
    (void)mddual::scene::loadWorld(file);
  } catch (const mddual::Error&) {
  }
  return 0;
}
