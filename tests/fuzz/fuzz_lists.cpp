/// libFuzzer target: the list parameters, the bistrip's `--section` ("B 9x3, A 9x3") and the
/// lists of reals (`--n_nu_vm 0.1,0.01`). The input's first byte picks the parser, the rest is
/// the text. An accepted list must hold what its parameter promises (layers of positive, finite
/// size; finite reals) and read back from its shortest exact text to the same values.

#include "fuzz_support.h"
#include "layers.h"

#include <charconv>
#include <cmath>
#include <cstdint>

namespace
{
std::string exact(double v)
{
  char digits[32];
  return std::string(digits, std::to_chars(digits, digits + sizeof(digits), v).ptr);
}

void section(const std::string& text)
{
  using gelx::scenes::Layer;
  std::vector<Layer> layers;
  try
  {
    layers = gelx::scenes::parse_section(text, 0.75);
  }
  catch (const gelx::InputError&)
  {
    return;
  }
  if (layers.empty())
    gelx::fuzz::fail("a section without layers was accepted");
  std::string bonded; // the same stack, in bonded sizes (kind S for a prestretched layer)
  for (const Layer& l : layers)
  {
    if (!(l.width > 0) || !(l.thickness > 0) || !std::isfinite(l.width)
        || !std::isfinite(l.thickness))
      gelx::fuzz::fail("a layer of size " + exact(l.width) + " x " + exact(l.thickness));
    bonded += std::string(bonded.empty() ? "" : ", ") + (l.prestretched ? "S " : "B ")
              + exact(l.width) + "x" + exact(l.thickness);
  }
  const auto again = gelx::scenes::parse_section(bonded, 0.75);
  for (std::size_t i = 0; i < layers.size(); ++i)
    if (again.size() != layers.size() || again[i].prestretched != layers[i].prestretched
        || again[i].width != layers[i].width || again[i].thickness != layers[i].thickness)
      gelx::fuzz::fail("section '" + bonded + "' reads back to another stack");
}

void reals(const std::string& text)
{
  std::vector<double> values;
  try
  {
    values = gelx::Parameters::real_list(text);
  }
  catch (const gelx::InputError&)
  {
    return;
  }
  std::string written;
  for (double v : values)
  {
    if (!std::isfinite(v))
      gelx::fuzz::fail("a list with " + exact(v) + " was accepted");
    written += (written.empty() ? "" : ",") + exact(v);
  }
  if (gelx::Parameters::real_list(written) != values)
    gelx::fuzz::fail("list '" + written + "' reads back to other values");
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size == 0)
    return 0;
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  if (data[0] % 2 == 0)
    section(text);
  else
    reals(text);
  return 0;
}
