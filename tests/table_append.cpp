// A results table grows by appending, and a row that cannot be written leaves whole rows.
//
// ResultsWriter::append_step writes steps.csv whole with its first row and appends every later
// row (gelx::append_to_file). A disk that fills in the middle of an append is simulated by the
// process's file size limit (RLIMIT_FSIZE, SIGXFSZ ignored): the write stops at the limit, as
// on a full disk, and the next fails (EFBIG). Asserted: the append throws, naming the file;
// steps.csv is byte for byte what it was (the partial row removed); the writer's progress
// counts only the rows written; with the limit lifted the same row is appended after them.
// Seen to fail with the partial row left in place (the truncation removed), 2026-12-07.
//
// usage: test_table_append OUTPUT_DIR (rank 0 writes the tables: 1 rank)

#include "support.h"

#include <csignal>
#include <fstream>
#include <gelx/io/output.h>
#include <petscsys.h>
#include <sstream>
#include <sys/resource.h>

namespace
{
std::string contents(const std::filesystem::path& path)
{
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}
} // namespace

int main(int argc, char* argv[])
{
  PetscInitialize(&argc, &argv, nullptr, nullptr);
  int status;
  {
    MPI_Comm comm = PETSC_COMM_WORLD;
    gelx::test::Checks checks(comm);
    const std::filesystem::path folder = argc > 1 ? argv[1] : "table_append";
    const auto box = gelx::test::tagged_box(comm, {1, 1, 1}, {1, 1, 1});
    gelx::ResultsWriter results(comm, folder, box.mesh);
    const auto row = [](int step)
    {
      return nlohmann::json{{"step", step},
                            {"t", 0.125 * step},
                            {"axial_force", 1.0 / 3 * step},
                            {"strain_energy", 2.0 / 3 * step}};
    };
    const auto steps_csv = folder / "steps.csv";
    results.append_step(row(1));
    results.append_step(row(2));
    const std::string two_rows = contents(steps_csv);
    checks.require("two rows written: " + std::to_string(results.progress().rows),
                   results.progress().rows == 2);

    // The third row crosses the file size limit 10 bytes past the two rows
    std::signal(SIGXFSZ, SIG_IGN);
    rlimit roomy;
    getrlimit(RLIMIT_FSIZE, &roomy);
    rlimit tight = roomy;
    tight.rlim_cur = two_rows.size() + 10;
    setrlimit(RLIMIT_FSIZE, &tight);
    std::string error;
    try
    {
      results.append_step(row(3));
    }
    catch (const std::runtime_error& e)
    {
      error = e.what();
    }
    setrlimit(RLIMIT_FSIZE, &roomy);
    checks.require("the append past the limit throws, naming the file: '" + error + "'",
                   error.find(steps_csv.string()) != std::string::npos);
    const std::string after_failure = contents(steps_csv);
    checks.require("steps.csv after the failed append: " + std::to_string(after_failure.size())
                       + " bytes, the two rows' " + std::to_string(two_rows.size())
                       + ", byte for byte",
                   after_failure == two_rows);
    checks.require("rows counted after the failed append: "
                       + std::to_string(results.progress().rows) + " (written: 2)",
                   results.progress().rows == 2);

    // Room again: the row follows the two
    results.append_step(row(3));
    const std::string three_rows = contents(steps_csv);
    const std::string third = three_rows.substr(std::min(two_rows.size(), three_rows.size()));
    checks.require("the third row appended after the two: '" + third.substr(0, 40) + "...'",
                   three_rows.compare(0, two_rows.size(), two_rows) == 0
                       && third.rfind("3,0.375,", 0) == 0 && third.back() == '\n'
                       && std::count(third.begin(), third.end(), '\n') == 1
                       && results.progress().rows == 3);
    status = checks.finish();
  }
  PetscFinalize();
  return status;
}
