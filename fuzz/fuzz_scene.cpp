// libFuzzer: the scene loader (docs/scene-format.md) on JSON text. Bad input
// is refused with SceneError; anything else escaping, a crash or a hang is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    // Beside the standard scenes, so that their mesh files resolve.
    mc1::scene::parse_scene(text, MC1_FUZZ_SCENE_DIR "/fuzz.json", MC1_FUZZ_SCENE_DIR);
  } catch (const mc1::scene::SceneError&) {
  }
  return 0;
}
