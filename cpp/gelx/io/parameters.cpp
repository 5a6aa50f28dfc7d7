#include <gelx/io/parameters.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace gelx
{
namespace
{
std::string trim(const std::string& s)
{
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos)
    return "";
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

/// A PETSc option's name (-name), not a negative number given as its value
bool is_option_name(const std::string& word)
{
  return word.size() > 1 && word[0] == '-' && !std::isdigit(word[1]) && word[1] != '.';
}

std::string to_text(const Parameters::Value& v)
{
  return std::visit(
      [](const auto& x) -> std::string
      {
        using X = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<X, std::string>)
          return x;
        else if constexpr (std::is_same_v<X, bool>)
          return x ? "true" : "false";
        else
        {
          std::ostringstream s;
          s << std::setprecision(12) << x;
          return s.str();
        }
      },
      v);
}

/// The kind of a value as --help names it (the index order of Parameters::Value)
const char* kind_name(const Parameters::Value& v)
{
  static const char* names[] = {"real", "integer", "flag", "text"};
  return names[v.index()];
}

/// Parse `text` as the same type as `like`; throws InputError naming the parameter.
Parameters::Value parse_as(const Parameters::Value& like, const std::string& name,
                           const std::string& text)
{
  const std::string bad = "parameter '" + name + "': '" + text + "' is not ";
  try
  {
    std::size_t used = 0;
    switch (like.index())
    {
    case 0:
    {
      double v = std::stod(text, &used);
      // std::stod also reads "nan" and "inf", which no parameter means
      if (used != text.size() || !std::isfinite(v))
        throw std::invalid_argument("");
      return v;
    }
    case 1:
    {
      int v = std::stoi(text, &used);
      if (used != text.size())
        throw std::invalid_argument("");
      return v;
    }
    case 2:
      if (text == "true" || text == "1" || text == "yes" || text == "on")
        return true;
      if (text == "false" || text == "0" || text == "no" || text == "off")
        return false;
      throw std::invalid_argument("");
    default:
      return text;
    }
  }
  catch (const std::logic_error&)
  {
    static const char* kinds[] = {"a finite number", "an integer", "true or false", "text"};
    throw InputError(bad + kinds[like.index()]);
  }
}

/// `valid` for a Value holding a T (or none).
template <typename T, typename Check>
std::function<std::string(const Parameters::Value&)> check_of(Check valid)
{
  if (!valid)
    return nullptr;
  return [valid](const Parameters::Value& v) { return valid(std::get<T>(v)); };
}
} // namespace


void Parameters::declare(const std::string& section, const std::string& name, Value value,
                         const std::string& help,
                         std::function<std::string(const Value&)> valid)
{
  if (_entries.count(name))
    throw std::logic_error("parameter '" + name + "' declared twice");
  _entries[name] = Entry{section, std::move(value), help, std::move(valid)};
  _order.push_back(name);
}

void Parameters::add(const std::string& section, const std::string& name, double value,
                     const std::string& help, std::function<std::string(double)> valid)
{
  declare(section, name, value, help, check_of<double>(valid));
}

void Parameters::add(const std::string& section, const std::string& name, int value,
                     const std::string& help, std::function<std::string(int)> valid)
{
  declare(section, name, value, help, check_of<int>(valid));
}

void Parameters::add(const std::string& section, const std::string& name, bool value,
                     const std::string& help)
{
  declare(section, name, value, help, nullptr);
}

void Parameters::add(const std::string& section, const std::string& name, const char* value,
                     const std::string& help,
                     std::function<std::string(const std::string&)> valid)
{
  declare(section, name, std::string(value), help, check_of<std::string>(valid));
}

const Parameters::Entry& Parameters::entry(const std::string& name) const
{
  auto it = _entries.find(name);
  if (it == _entries.end())
    throw InputError("unknown parameter '" + name + "' (see --help)");
  return it->second;
}

void Parameters::set(const std::string& name, const std::string& text)
{
  const Entry& e = entry(name);
  Value v = parse_as(e.value, name, trim(text));
  if (e.valid)
  {
    if (std::string why = e.valid(v); !why.empty())
      throw InputError("parameter '" + name + "' = " + to_text(v) + ": " + why);
  }
  _entries[name].value = v;
  if (e.assign)
    e.assign(v);
}

template <typename T, typename Check>
void Parameters::bind_target(const std::string& section, const std::string& name, T& target,
                             const std::string& help, Check valid)
{
  declare(section, name, target, help, check_of<T>(valid));
  _entries[name].assign = [&target](const Value& v) { target = std::get<T>(v); };
}

void Parameters::bind(const std::string& section, const std::string& name, double& target,
                      const std::string& help, std::function<std::string(double)> valid)
{
  bind_target(section, name, target, help, valid);
}

void Parameters::bind(const std::string& section, const std::string& name, int& target,
                      const std::string& help, std::function<std::string(int)> valid)
{
  bind_target(section, name, target, help, valid);
}

void Parameters::bind(const std::string& section, const std::string& name, bool& target,
                      const std::string& help)
{
  bind_target(section, name, target, help, std::function<std::string(bool)>());
}

void Parameters::bind(const std::string& section, const std::string& name, std::string& target,
                      const std::string& help,
                      std::function<std::string(const std::string&)> valid)
{
  bind_target(section, name, target, help, valid);
}

std::vector<std::string> Parameters::parse(int argc, char* argv[], bool* help_requested)
{
  std::vector<std::string> rest = {argv[0]};
  if (help_requested)
    *help_requested = false;
  bool petsc_value_may_follow = false; // right after a PETSc option "-name"
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h")
    {
      if (help_requested)
        *help_requested = true;
      continue;
    }
    if (arg.rfind("--", 0) != 0)
    {
      // A PETSc option or its value; any other word would be silently ignored by PETSc
      if (arg.rfind("-", 0) != 0 && !petsc_value_may_follow)
        throw InputError("unexpected argument '" + arg + "'");
      petsc_value_may_follow = arg.rfind("-", 0) == 0;
      rest.push_back(arg);
      _petsc_arguments.push_back(arg);
      continue;
    }
    petsc_value_may_follow = false;
    std::string name = arg.substr(2), value;
    if (auto eq = name.find('='); eq != std::string::npos)
    {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
    }
    else
    {
      const bool is_flag = _entries.count(name) && _entries.at(name).value.index() == 2;
      const std::string next = i + 1 < argc ? argv[i + 1] : "";
      // A flag alone means true; a value may be negative ("--G -1") but not an option
      if (is_flag && (i + 1 == argc || next.rfind("-", 0) == 0))
        value = "true";
      else if (i + 1 < argc && next.rfind("--", 0) != 0)
        value = argv[++i];
      else
        throw InputError("option --" + name + " needs a value");
    }
    if (name == "scene")
    {
      // The file's PETSc options go where the file is named: later ones override them
      const std::size_t known = _petsc_arguments.size();
      read_file(value);
      rest.insert(rest.end(), _petsc_arguments.begin() + known, _petsc_arguments.end());
    }
    else
    {
      set(name, value);
      _given.insert(name);
    }
  }
  return rest;
}

void Parameters::read_file(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
    throw InputError("cannot read scene file '" + path + "'");
  std::string line;
  for (int number = 1; std::getline(in, line); ++number)
  {
    line = trim(line.substr(0, line.find('#')));
    if (line.empty())
      continue;
    if (line[0] == '-')
    {
      std::istringstream words(line);
      for (std::string word; words >> word;)
        _petsc_arguments.push_back(word);
      continue;
    }
    const auto eq = line.find('=');
    if (eq == std::string::npos)
      throw InputError(path + ":" + std::to_string(number) + ": expected 'name = value'");
    set(trim(line.substr(0, eq)), line.substr(eq + 1));
    _given.insert(trim(line.substr(0, eq)));
  }
}

std::string Parameters::scene_file(const std::set<std::string>& omit) const
{
  std::vector<std::string> sections;
  std::map<std::string, std::vector<std::string>> by_section;
  for (const auto& name : _order)
  {
    if (omit.count(name))
      continue;
    const auto& s = _entries.at(name).section;
    if (by_section[s].empty())
      sections.push_back(s);
    by_section[s].push_back(name);
  }
  std::ostringstream out;
  for (const auto& s : sections)
  {
    out << "# " << s << "\n";
    for (const auto& name : by_section[s])
    {
      const Value& v = _entries.at(name).value;
      std::string text = to_text(v);
      if (const double* x = std::get_if<double>(&v))
      {
        char digits[32];
        text.assign(digits, std::to_chars(digits, digits + sizeof(digits), *x).ptr);
      }
      out << name << " = " << text << "\n";
    }
  }
  if (!_petsc_arguments.empty())
  {
    out << "# PETSc options";
    for (const auto& word : _petsc_arguments)
      out << (is_option_name(word) ? "\n" : " ") << word;
    out << "\n";
  }
  return out.str();
}

double Parameters::real(const std::string& name) const
{
  return std::get<double>(entry(name).value);
}
int Parameters::integer(const std::string& name) const
{
  return std::get<int>(entry(name).value);
}
bool Parameters::flag(const std::string& name) const
{
  return std::get<bool>(entry(name).value);
}
const std::string& Parameters::text(const std::string& name) const
{
  return std::get<std::string>(entry(name).value);
}

std::string Parameters::table(bool with_help) const
{
  std::map<std::string, std::vector<std::string>> by_section;
  std::vector<std::string> sections;
  for (const auto& name : _order)
  {
    const auto& s = _entries.at(name).section;
    if (by_section[s].empty())
      sections.push_back(s);
    by_section[s].push_back(name);
  }
  // An empty text shows as "" (a column of its own for readers of --help)
  auto shown = [](const Value& v) -> std::string
  { return v.index() == 3 && std::get<std::string>(v).empty() ? "\"\"" : to_text(v); };
  std::size_t value_width = 14;
  for (const auto& [name, e] : _entries)
    value_width = std::max(value_width, shown(e.value).size() + 2);
  std::ostringstream out;
  for (const auto& s : sections)
  {
    out << s << ":\n";
    for (const auto& name : by_section[s])
    {
      const Entry& e = _entries.at(name);
      out << "  --" << std::left << std::setw(22) << name << std::setw(value_width) << shown(e.value);
      if (with_help)
        out << std::setw(9) << kind_name(e.value) << e.help;
      out << "\n";
    }
  }
  return out.str();
}

nlohmann::json Parameters::to_json() const
{
  nlohmann::json j = nlohmann::json::object();
  for (const auto& name : _order)
    std::visit([&](const auto& v) { j[name] = v; }, _entries.at(name).value);
  return j;
}

std::string Parameters::positive(double v) { return v > 0 ? "" : "must be positive"; }

std::function<std::string(const std::string&)> Parameters::one_of(std::vector<std::string> words)
{
  std::string list;
  for (std::size_t i = 0; i < words.size(); ++i)
    list += (i == 0 ? "" : i + 1 == words.size() ? " or " : ", ") + words[i];
  return [words = std::move(words), message = "must be " + list](const std::string& w)
  { return std::find(words.begin(), words.end(), w) != words.end() ? "" : message; };
}
std::string Parameters::non_negative(double v)
{
  return v >= 0 ? "" : "must not be negative";
}
std::string Parameters::at_least_one(int v) { return v >= 1 ? "" : "must be at least 1"; }

} // namespace gelx
