#include <gelx/io/sources.h>

#include <gelx/io/parameters.h>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <memory>
#include <openssl/evp.h>
#include <sstream>

namespace
{
gelx::Sources& built_forms()
{
  static gelx::Sources forms; // filled by constructors that may run before main
  return forms;
}
gelx::Sources& read_files()
{
  static gelx::Sources files;
  return files;
}
/// The input files of the record being replayed
gelx::Sources& expected_files()
{
  static gelx::Sources files;
  return files;
}
std::string expected_origin;

std::string abbreviated(const std::string& hash) { return hash.substr(0, 12); }

/// The SHA-256 of the file at `path`, in hex. Throws InputError when it cannot be read.
std::string sha256_of_file(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  const std::string content{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (!in && !in.eof())
    throw gelx::InputError("cannot read '" + path + "'");
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int size = 0;
  if (!EVP_Digest(content.data(), content.size(), digest, &size, EVP_sha256(), nullptr))
    throw std::runtime_error("SHA-256 of '" + path + "' failed");
  std::ostringstream hex;
  for (unsigned int i = 0; i < size; ++i)
    hex << std::hex << std::setw(2) << std::setfill('0') << int(digest[i]);
  return hex.str();
}
} // namespace

/// Called by the constructors that the build compiles in with each form's kernels
/// (cpp/form_sources.cmake), before main.
extern "C" void gelx_record_form_source(const char* path, const char* sha256)
{
  built_forms()[path] = sha256;
}

namespace gelx
{

Sources run_sources()
{
  Sources all = built_forms();
  all.insert(read_files().begin(), read_files().end());
  return all;
}

void record_input_file(const std::string& path, const std::string& name)
{
  const std::string hash = sha256_of_file(path);
  if (const auto expected = expected_files().find(name);
      expected != expected_files().end() && expected->second != hash)
    throw InputError("'" + name + "' is not the file " + expected_origin + " read (its SHA-256 "
                     + abbreviated(hash) + "..., recorded " + abbreviated(expected->second)
                     + "...): the run would not replay");
  read_files()[name] = hash;
}

void expect_sources(const Sources& recorded, const std::string& origin,
                    const std::string& program)
{
  bool has_forms = false;
  for (const auto& [path, hash] : recorded)
    if (path.rfind("forms/", 0) == 0)
    {
      has_forms = true;
      const auto built = built_forms().find(path);
      if (built == built_forms().end())
        throw InputError(origin + " was computed with " + path + ", which this " + program
                         + " was not built from: the run would not replay");
      if (built->second != hash)
        throw InputError(origin + " was computed with another " + path + " (SHA-256 "
                         + abbreviated(hash) + "...; this " + program + " was built from "
                         + abbreviated(built->second)
                         + "...): rebuild from that form, or remove the record's 'source' "
                           "lines to run with this one");
    }
    else
      expected_files()[path] = hash;
  if (has_forms)
    for (const auto& [path, hash] : built_forms())
      if (!recorded.count(path))
        throw InputError("this " + program + " was built from " + path + ", which " + origin
                         + " does not record: the run would not replay");
  expected_origin = origin;
}

} // namespace gelx
