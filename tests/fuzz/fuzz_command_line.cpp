/// libFuzzer target: the `--name value` command line (gelx::Parameters::parse). The input's
/// bytes, split at NUL bytes, are the words after the program's name.

#include "fuzz_support.h"

#include <cstdint>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  std::vector<std::string> words = {"gelx-fuzz"};
  const char* text = reinterpret_cast<const char*>(data);
  for (std::size_t begin = 0, end; begin <= size; begin = end + 1)
  {
    for (end = begin; end < size && text[end] != '\0'; ++end)
      ;
    words.emplace_back(text + begin, end - begin);
  }
  // --scene reads a file: the scene-file parser is fuzz_scene_file's, and a fuzzer must not
  // read this machine's files
  for (const auto& w : words)
    if (w.rfind("--scene", 0) == 0)
      return 0;
  std::vector<char*> argv;
  for (auto& w : words)
    argv.push_back(w.data());

  gelx::Parameters prm;
  gelx::fuzz::declare(prm);
  try
  {
    bool help = false;
    const auto rest = prm.parse(static_cast<int>(argv.size()), argv.data(), &help);
    if (rest.size() != prm.petsc_arguments().size() + 1)
      gelx::fuzz::fail("the words handed to PETSc are not the PETSc options recorded");
  }
  catch (const gelx::InputError&)
  {
    return 0; // refused in one line: what bad input should get
  }
  gelx::fuzz::require_replays(prm);
  return 0;
}
