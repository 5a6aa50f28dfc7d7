#include "layers.h"

#include <cmath>
#include <gelx/io/parameters.h>
#include <sstream>

namespace gelx::scenes
{

std::vector<Layer> parse_section(const std::string& section, double lateral_stretch)
{
  std::vector<Layer> layers;
  std::istringstream list(section);
  std::string item;
  while (std::getline(list, item, ','))
  {
    std::istringstream words(item);
    std::string kind, size, rest;
    words >> kind >> size >> rest;
    double width = NAN, thickness = NAN;
    char times = 0, end = 0;
    std::istringstream dims(size);
    dims >> width >> times >> thickness;
    const bool read = !dims.fail() && times == 'x' && !(dims >> end);
    if (!read || !rest.empty() || !(width > 0) || !(thickness > 0) || !std::isfinite(width)
        || !std::isfinite(thickness))
      throw InputError("section layer '" + item
                       + "': write KIND WIDTHxTHICKNESS with positive sizes in mm, e.g. B 9x3");
    if (kind == "A")
      layers.push_back({true, lateral_stretch * width, lateral_stretch * thickness});
    else if (kind == "S")
      layers.push_back({true, width, thickness});
    else if (kind == "B")
      layers.push_back({false, width, thickness});
    else
      throw InputError("section layer '" + item + "': unknown kind '" + kind
                       + "' (A: prestretched, natural size; S: prestretched, bonded size; "
                         "B: stress-free)");
  }
  if (layers.empty())
    throw InputError("the section has no layer");
  return layers;
}

} // namespace gelx::scenes
