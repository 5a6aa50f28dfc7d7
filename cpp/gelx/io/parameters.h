#pragma once
/// @file parameters.h
/// Typed, validated scene parameters read from the command line and from a scene file.
///
/// Each parameter has a section (geometry, material, ...), a default, a help text and a validity
/// check; everything is echoed at start-up and stored in summary.json. Scene parameters are
/// spelled `--name value` (or `name = value` in a file given with `--scene FILE`); arguments
/// starting with a single dash (`-newton_ksp_type cg`) are left to the PETSc options database.

#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <variant>
#include <vector>

namespace gelx
{

/// Bad user input (unknown option, value out of range, unreadable file): reported in one line.
class InputError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

class Parameters
{
public:
  using Value = std::variant<double, int, bool, std::string>;

  /// Declare a real parameter; `valid` returns an empty string when the value is acceptable,
  /// otherwise the reason ("must be positive").
  void add(const std::string& section, const std::string& name, double value,
           const std::string& help,
           std::function<std::string(double)> valid = nullptr);
  void add(const std::string& section, const std::string& name, int value,
           const std::string& help, std::function<std::string(int)> valid = nullptr);
  void add(const std::string& section, const std::string& name, bool value,
           const std::string& help);
  void add(const std::string& section, const std::string& name, const char* value,
           const std::string& help,
           std::function<std::string(const std::string&)> valid = nullptr);

  /// Declare a parameter whose value lives in `target`, a member of a scene's typed struct:
  /// its default is target's current value, and every change is written there, so that the
  /// struct is filled when the command line is read and each name is spelled once.
  void bind(const std::string& section, const std::string& name, double& target,
            const std::string& help, std::function<std::string(double)> valid = nullptr);
  void bind(const std::string& section, const std::string& name, int& target,
            const std::string& help, std::function<std::string(int)> valid = nullptr);
  void bind(const std::string& section, const std::string& name, bool& target,
            const std::string& help);
  void bind(const std::string& section, const std::string& name, std::string& target,
            const std::string& help,
            std::function<std::string(const std::string&)> valid = nullptr);

  /// Read `--name value` pairs and `--scene FILE`; `--help` sets `help_requested`. Returns the
  /// remaining arguments (PETSc options `-name [value]`), argv[0] first. Throws InputError,
  /// also for a word that is neither (PETSc would ignore it silently).
  std::vector<std::string> parse(int argc, char* argv[], bool* help_requested = nullptr);

  /// Read `name = value` lines (`#` starts a comment), lines of PETSc options
  /// (`-name [value]`, kept in petsc_arguments() for parse() to hand on) and the record of
  /// what a run was computed from, `source PATH = SHA256` (kept in recorded_sources(); see
  /// gelx/io/sources.h). Throws InputError.
  void read_file(const std::string& path);
  /// The same for a scene file's text; `origin` names it in messages.
  void read(std::istream& in, const std::string& origin);

  /// The PETSc options given on the command line and in scene files, word by word in the
  /// order parse() met them.
  const std::vector<std::string>& petsc_arguments() const { return _petsc_arguments; }

  /// A scene file that gives every parameter except those in `omit` its current value, by
  /// section, exactly (reals in their shortest form that reads back to the same double), then
  /// the PETSc options given (petsc_arguments()): `--scene FILE` reads it back.
  std::string scene_file(const std::set<std::string>& omit) const;

  /// Set one parameter from its text form, validating it. Throws InputError.
  void set(const std::string& name, const std::string& text);

  double real(const std::string& name) const;
  int integer(const std::string& name) const;
  bool flag(const std::string& name) const;
  const std::string& text(const std::string& name) const;

  /// Table of all parameters grouped by section, for the start-up echo and (with each kind,
  /// real, integer, flag or text, and help text) for --help.
  std::string table(bool with_help) const;
  nlohmann::json to_json() const;
  /// The `source PATH = SHA256` lines of the scene files read: path -> SHA-256.
  const std::map<std::string, std::string>& recorded_sources() const
  {
    return _recorded_sources;
  }

  /// The names of the parameters that the command line or a scene file set (parse()).
  const std::set<std::string>& given() const { return _given; }

  /// A comma-separated list of reals ("0.1, 0.01"), every one finite. Throws InputError
  /// saying what is wrong (an empty item, a word that is not a number).
  static std::vector<double> real_list(const std::string& text);

  /// Common validity checks.
  static std::string positive(double v);
  static std::string non_negative(double v);
  static std::string at_least_one(int v);
  /// A word among `words`: "must be a, b or c" otherwise.
  static std::function<std::string(const std::string&)> one_of(std::vector<std::string> words);
  /// A text check for a list of reals (real_list): what is wrong with the list, else what
  /// `valid` says of its values ("" when they are fine).
  static std::function<std::string(const std::string&)>
  reals(std::function<std::string(const std::vector<double>&)> valid);

private:
  struct Entry
  {
    std::string section;
    Value value;
    std::string help;
    std::function<std::string(const Value&)> valid;
    std::function<void(const Value&)> assign; ///< writes a bound parameter's target
  };
  const Entry& entry(const std::string& name) const;
  template <typename T, typename Check>
  void bind_target(const std::string& section, const std::string& name, T& target,
                   const std::string& help, Check valid);
  void declare(const std::string& section, const std::string& name, Value value,
               const std::string& help, std::function<std::string(const Value&)> valid);
  void add_petsc_word(const std::string& word, bool value_may_follow, const std::string& where);
  std::map<std::string, Entry> _entries;
  std::vector<std::string> _order;
  std::set<std::string> _given;
  std::map<std::string, std::string> _recorded_sources;
  std::vector<std::string> _petsc_arguments;
};

} // namespace gelx
