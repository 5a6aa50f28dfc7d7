/// libFuzzer target: scene files (`--scene FILE`, gelx::Parameters::read). The input is the
/// file's text.

#include "fuzz_support.h"

#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  gelx::Parameters prm;
  gelx::fuzz::declare(prm);
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try
  {
    prm.read(in, "fuzz.scene");
  }
  catch (const gelx::InputError&)
  {
    return 0; // refused in one line: what bad input should get
  }
  gelx::fuzz::require_replays(prm);
  return 0;
}
