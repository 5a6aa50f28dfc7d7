/* A disk that fills up, for tests/full_disk.py: loaded with LD_PRELOAD into a scene, it lets
 * the process write GELX_DISK_BYTES bytes in all to files under GELX_DISK_FOLDER, and fails
 * every write there after that with ENOSPC, as a full disk does (a tmpfs of that size would
 * need mount rights, which a test machine may not give). Writes elsewhere (the terminal, the
 * MPI runtime's files) pass. At exit, each process adds a line with the bytes it wrote there
 * to the file GELX_DISK_REPORT names (the test sizes its disks from a roomy run's). */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/uio.h>
#include <unistd.h>

static long long budget = -1; /* bytes left; -1: not read yet */
static long long written = 0; /* bytes written into the folder */
static char folder[PATH_MAX];

static void read_settings(void)
{
  const char *bytes = getenv("GELX_DISK_BYTES"), *where = getenv("GELX_DISK_FOLDER");
  budget = bytes ? atoll(bytes) : LLONG_MAX;
  if (!where || !realpath(where, folder))
    folder[0] = '\0';
}

/* Whether the file open as `fd` lies under the folder */
static int in_folder(int fd)
{
  char link[64], path[PATH_MAX];
  if (folder[0] == '\0')
    return 0;
  snprintf(link, sizeof(link), "/proc/self/fd/%d", fd);
  const ssize_t n = readlink(link, path, sizeof(path) - 1);
  if (n <= 0)
    return 0;
  path[n] = '\0';
  return strncmp(path, folder, strlen(folder)) == 0;
}

/* How much of `count` bytes to `fd` may be written: all, or what is left of the budget */
static size_t allowed(int fd, size_t count)
{
  if (budget < 0)
    read_settings();
  if (!in_folder(fd))
    return count;
  const size_t granted = (long long)count <= budget ? count : (size_t)budget;
  budget -= (long long)granted;
  written += (long long)granted;
  return granted;
}

/* A write that fails (ENOSPC) may still have been granted part of the budget: the count is
 * of what was granted, a bound the test only scales */
__attribute__((destructor)) static void report(void)
{
  const char* path = getenv("GELX_DISK_REPORT");
  if (!path)
    return;
  folder[0] = '\0'; /* the report itself is not counted, nor refused */
  budget = LLONG_MAX;
  FILE* out = fopen(path, "a");
  if (out)
  {
    fprintf(out, "%lld\n", written);
    fclose(out);
  }
}

#define FORWARD(name, ret, params, args)                                                      \
  ret name params                                                                             \
  {                                                                                           \
    static ret(*real) params = NULL;                                                          \
    if (!real)                                                                                \
      real = (ret(*) params)dlsym(RTLD_NEXT, #name);                                          \
    const size_t want = count, granted = allowed(fd, want);                                   \
    if (granted == 0 && want > 0)                                                             \
    {                                                                                         \
      errno = ENOSPC;                                                                         \
      return -1;                                                                              \
    }                                                                                         \
    count = granted;                                                                          \
    return real args;                                                                         \
  }

FORWARD(write, ssize_t, (int fd, const void* buf, size_t count), (fd, buf, count))
FORWARD(pwrite, ssize_t, (int fd, const void* buf, size_t count, off_t offset),
        (fd, buf, count, offset))
FORWARD(pwrite64, ssize_t, (int fd, const void* buf, size_t count, off_t offset),
        (fd, buf, count, offset))

/* writev and pwritev: the first vector's part of the budget stands for the whole call (their
 * callers retry the rest, as after any short write) */
static ssize_t vector_write(int fd, const struct iovec* iov, int iovcnt, off_t offset, int at)
{
  static ssize_t (*real_write)(int, const void*, size_t) = NULL;
  static ssize_t (*real_pwrite)(int, const void*, size_t, off_t) = NULL;
  if (!real_write)
  {
    real_write = (ssize_t(*)(int, const void*, size_t))dlsym(RTLD_NEXT, "write");
    real_pwrite = (ssize_t(*)(int, const void*, size_t, off_t))dlsym(RTLD_NEXT, "pwrite");
  }
  int k = 0;
  while (k < iovcnt && iov[k].iov_len == 0)
    ++k;
  if (k == iovcnt)
    return 0;
  const size_t granted = allowed(fd, iov[k].iov_len);
  if (granted == 0)
  {
    errno = ENOSPC;
    return -1;
  }
  return at ? real_pwrite(fd, iov[k].iov_base, granted, offset)
            : real_write(fd, iov[k].iov_base, granted);
}

ssize_t writev(int fd, const struct iovec* iov, int iovcnt)
{
  return vector_write(fd, iov, iovcnt, 0, 0);
}

ssize_t pwritev(int fd, const struct iovec* iov, int iovcnt, off_t offset)
{
  return vector_write(fd, iov, iovcnt, offset, 1);
}
