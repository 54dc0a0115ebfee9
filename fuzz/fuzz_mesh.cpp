// Fuzz target: the mesh loader (assimp with OMPL.app's import flags). The
// first byte picks the format, the rest is the file.
#include <cstdint>

#include "fuzz_input_file.h"
#include "mddual/error.h"
#include "mddual/scene/loaders.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const char* const kExtensions[] = {".obj", ".stl", ".dae", ".ply"};
  const std::filesystem::path file = mddual::fuzz::writeInput(data + 1, size - 1, kExtensions[data[0] % 4]);
  try {
    (void)mddual::scene::loadBody(file);
  } catch (const mddual::Error&) {
  }
  return 0;
}
