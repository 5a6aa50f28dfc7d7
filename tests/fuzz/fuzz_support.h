#pragma once
/// @file fuzz_support.h
/// What the parsers' fuzzers share: a parameter set with every kind and check the scenes use,
/// and the property every accepted input must have, that its scene file (scene.txt) replays it.
///
/// A parser may refuse an input only with gelx::InputError (one line for the user); any other
/// exception, a crash, a sanitizer's report or a scene file that reads back to other values is
/// a bug, and the fuzzer stops on it with the input saved.

#include <cstdio>
#include <cstdlib>
#include <gelx/io/parameters.h>
#include <sstream>
#include <string>

namespace gelx::fuzz
{

/// Stop the fuzzer: libFuzzer saves the input that led here.
[[noreturn]] inline void fail(const std::string& why)
{
  std::fprintf(stderr, "fuzz: %s\n", why.c_str());
  std::abort();
}

/// Parameters of each kind, with and without checks, in two sections, as scenes declare them.
inline void declare(Parameters& prm)
{
  prm.add("geometry", "L", 300.0, "length", Parameters::positive);
  prm.add("geometry", "offset", -1.5, "a real of any sign");
  prm.add("material", "G", 1.0, "modulus", Parameters::positive);
  prm.add("material", "eta", 0.0, "viscosity", Parameters::non_negative);
  prm.add("mesh", "nz", 40, "slabs", Parameters::at_least_one);
  prm.add("mesh", "shift", -3, "an integer of any sign");
  prm.add("loading", "extrapolate", true, "a flag");
  prm.add("loading", "quiet", false, "another flag");
  prm.add("loading", "ends", "clamped", "one word of two", Parameters::one_of({"clamped", "free"}));
  prm.add("output", "label", "", "free text");
  prm.add("output", "n_nu_vm", "0.1,0.01", "a list",
          Parameters::reals([](const std::vector<double>&) { return ""; }));
}

/// The scene file of an accepted `prm` must read back, into a fresh set, to the same values
/// and the same PETSc options (what `--scene scene.txt` relies on to replay a run), and its
/// summary (JSON) and --help table must be writable.
inline void require_replays(const Parameters& prm)
{
  const std::string scene = prm.scene_file({});
  Parameters again;
  declare(again);
  std::istringstream in(scene);
  try
  {
    again.read(in, "scene.txt");
  }
  catch (const InputError& e)
  {
    fail(std::string("its own scene file is refused: ") + e.what() + "\n" + scene);
  }
  if (again.to_json() != prm.to_json())
    fail("the scene file reads back to other values:\n" + scene);
  if (again.petsc_arguments() != prm.petsc_arguments())
    fail("the scene file reads back to other PETSc options:\n" + scene);
  try
  {
    (void)prm.to_json().dump();
    (void)prm.table(true);
  }
  catch (const std::exception& e)
  {
    fail(std::string("the summary or --help cannot be written: ") + e.what());
  }
}

} // namespace gelx::fuzz
