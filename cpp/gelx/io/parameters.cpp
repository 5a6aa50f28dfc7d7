#include <gelx/io/parameters.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
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

/// Whether text[i...] starts with a well-formed UTF-8 sequence (RFC 3629: no overlong form, no
/// surrogate, nothing past U+10FFFF, as JSON writers require); its length, else 0
std::size_t utf8_length(const std::string& text, std::size_t i)
{
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned c = byte(i);
  if (c < 0x80)
    return 1;
  // the sequence's length and the range of its second byte, from its first
  std::size_t n = 0;
  unsigned lo = 0x80, hi = 0xbf;
  if (c >= 0xc2 && c <= 0xdf)
    n = 2;
  else if (c >= 0xe0 && c <= 0xef)
    n = 3, lo = c == 0xe0 ? 0xa0 : 0x80, hi = c == 0xed ? 0x9f : 0xbf;
  else if (c >= 0xf0 && c <= 0xf4)
    n = 4, lo = c == 0xf0 ? 0x90 : 0x80, hi = c == 0xf4 ? 0x8f : 0xbf;
  if (n == 0 || i + n > text.size() || byte(i + 1) < lo || byte(i + 1) > hi)
    return 0;
  for (std::size_t k = 2; k < n; ++k)
    if (byte(i + k) < 0x80 || byte(i + k) > 0xbf)
      return 0;
  return n;
}

/// Why a scene file could not hold `text` as a value ("" when it can): scene.txt must replay
/// every value exactly, and '#' starts a comment there, a line ends at a newline, and JSON
/// (summary.json) holds only UTF-8
std::string unwritable(const std::string& text)
{
  for (std::size_t i = 0, n; i < text.size(); i += n)
  {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '#')
      return "holds '#', which starts a comment in a scene file";
    if (c < 0x20 || c == 0x7f)
      return "holds a control character";
    if ((n = utf8_length(text, i)) == 0)
      return "is not UTF-8";
  }
  return "";
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
      if (std::string why = unwritable(text); !why.empty())
        throw InputError("parameter '" + name + "': the text " + why);
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
      add_petsc_word(arg, petsc_value_may_follow, "argument");
      petsc_value_may_follow = is_option_name(arg);
      rest.push_back(arg);
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

void Parameters::add_petsc_word(const std::string& word, bool value_may_follow,
                                const std::string& where)
{
  // A PETSc option, or a value right after one; any other word would be silently ignored by
  // PETSc (and a scene file could not place it)
  if (word.empty() || (!is_option_name(word) && !value_may_follow))
    throw InputError("unexpected " + where + " '" + word + "'");
  if (std::string why = unwritable(word); !why.empty() || word.find_first_of(" \t") != word.npos)
    throw InputError("PETSc " + where + " '" + word + "' "
                     + (why.empty() ? "holds a space, which a scene file cannot hold" : why));
  _petsc_arguments.push_back(word);
}

void Parameters::read_file(const std::string& path)
{
  // An ifstream opens a directory, and reads nothing from it
  std::ifstream in(path);
  if (!in || std::filesystem::is_directory(path))
    throw InputError("cannot read scene file '" + path + "'");
  read(in, path);
}

void Parameters::read(std::istream& in, const std::string& origin)
{
  std::string line;
  for (int number = 1; std::getline(in, line); ++number)
  {
    const std::string where = origin + ":" + std::to_string(number);
    line = trim(line.substr(0, line.find('#')));
    if (line.empty())
      continue;
    if (line[0] == '-')
    {
      std::istringstream words(line);
      bool value_may_follow = false; // a line starts with an option's name
      for (std::string word; words >> word; value_may_follow = is_option_name(word))
        add_petsc_word(word, value_may_follow, where + ": PETSc word");
      continue;
    }
    const auto eq = line.find('=');
    if (eq == std::string::npos)
      throw InputError(where + ": expected 'name = value'");
    if (line.rfind("source ", 0) == 0)
    {
      // What the recorded run was computed from (sources.h): `source PATH = SHA256`
      const std::string path = trim(line.substr(7, eq - 7)), hash = trim(line.substr(eq + 1));
      if (path.empty() || hash.size() != 64
          || hash.find_first_not_of("0123456789abcdef") != std::string::npos)
        throw InputError(where + ": expected 'source PATH = SHA-256 in 64 hex digits'");
      _recorded_sources[path] = hash;
      continue;
    }
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

std::vector<double> Parameters::real_list(const std::string& text)
{
  std::vector<double> values;
  std::stringstream items(text);
  for (std::string item; std::getline(items, item, ',');)
  {
    const std::string word = trim(item);
    std::size_t used = 0;
    double v = NAN;
    try
    {
      v = std::stod(word, &used);
    }
    catch (const std::logic_error&) // no number, or one out of a double's range
    {
    }
    if (used == 0 || used != word.size() || !std::isfinite(v))
      throw InputError("'" + word + "' in the list '" + text + "' is not a finite number");
    values.push_back(v);
  }
  // getline drops an empty last item: "1,2," would read as 1, 2
  if (values.empty() || trim(text).back() == ',')
    throw InputError("the list '" + text + "' has an empty item");
  return values;
}

std::string Parameters::positive(double v) { return v > 0 ? "" : "must be positive"; }

std::function<std::string(const std::string&)>
Parameters::reals(std::function<std::string(const std::vector<double>&)> valid)
{
  return [valid = std::move(valid)](const std::string& text)
  {
    std::vector<double> values;
    try
    {
      values = real_list(text);
    }
    catch (const InputError& e)
    {
      return std::string(e.what());
    }
    return valid(values);
  };
}

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
