#include <gelx/io/files.h>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>

namespace gelx
{

void replace_file(const std::filesystem::path& path,
                  const std::function<void(std::ostream&)>& write, std::ios::openmode mode)
{
  const auto aside = path.string() + ".tmp";
  errno = 0;
  std::ofstream out(aside, mode);
  write(out);
  out.close();
  if (!out)
  {
    const std::string reason = errno != 0 ? std::strerror(errno) : "write failed";
    std::error_code ignored;
    std::filesystem::remove(aside, ignored);
    throw std::runtime_error("cannot write " + path.string() + ": " + reason);
  }
  std::filesystem::rename(aside, path);
}

void append_to_file(const std::filesystem::path& path, const std::string& text)
{
  const auto fail = [&](const std::string& reason)
  { throw std::runtime_error("cannot write " + path.string() + ": " + reason); };
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND);
  struct stat before;
  if (fd < 0 || ::fstat(fd, &before) != 0)
    fail(std::strerror(errno));
  for (std::size_t written = 0; written < text.size();)
  {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR)
      continue;
    if (n <= 0)
    {
      const std::string reason = n < 0 ? std::strerror(errno) : "nothing written";
      const int undone = ::ftruncate(fd, before.st_size);
      ::close(fd);
      fail(reason + (undone == 0 ? "" : " (and its partial row not removed)"));
    }
    written += n;
  }
  if (::close(fd) != 0)
    fail(std::strerror(errno));
}

} // namespace gelx
