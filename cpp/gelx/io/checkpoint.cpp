#include <gelx/io/checkpoint.h>
#include <gelx/io/files.h>
#include <gelx/io/parameters.h>
#include <gelx/common/petsc_utils.h>
#include <gelx/systems/problem.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/common/MPI.h>
#include <dolfinx/fem/DofMap.h>
#include <dolfinx/fem/FiniteElement.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/io/HDF5Interface.h>
#include <fstream>
#include <map>
#include <regex>

namespace gelx
{

OwnedVec copy_of(Vec v)
{
  Vec c;
  GELX_PETSC(VecDuplicate(v, &c));
  GELX_PETSC(VecCopy(v, c));
  return OwnedVec(c);
}
namespace
{
namespace fs = std::filesystem;
using HDF5 = dolfinx::io::HDF5Interface;

constexpr int key_width = 5; ///< (sub-space, component, X, Y, Z)
constexpr const char* format = "gelx checkpoint 1";

std::string folder_name(int step)
{
  char name[32];
  std::snprintf(name, sizeof name, "step_%06d", step);
  return name;
}

/// The step of a checkpoint folder (from its name), or -1.
int step_of(const fs::path& folder)
{
  static const std::regex pattern(R"(step_(\d{6}))");
  std::smatch m;
  const std::string name = folder.filename().string();
  return std::regex_match(name, m, pattern) ? std::stoi(m[1]) : -1;
}

/// The key of each owned unknown of `system` (Checkpoints' class comment), key_width each.
/// Collective.
std::vector<double> unknown_keys(MPI_Comm comm, NonlinearSystem& system)
{
  PetscInt n;
  GELX_PETSC(VecGetLocalSize(system.unknowns(), &n));
  std::vector<double> keys(key_width * n, 0.0);
  std::vector<char> keyed(n, 0);
  const auto W = system.problem().u()->function_space();
  const std::int32_t num_owned
      = W->dofmap()->index_map->size_local() * W->dofmap()->index_map_bs();
  const std::vector<PetscInt>& unknown_of = system.unknown_of_problem_dof();
  const bool mixed = W->element()->is_mixed();
  for (int s = 0; s < (mixed ? W->element()->num_sub_elements() : 1); ++s)
  {
    // The sub-space as a plain (possibly blocked) space, and where its dofs sit in W's vector
    std::shared_ptr<const dolfinx::fem::FunctionSpace> V = W;
    std::vector<std::int32_t> to_W;
    if (mixed)
    {
      auto [collapsed, map] = W->sub({s})->collapse();
      if (collapsed.element()->is_mixed())
        throw std::logic_error("checkpoint: nested mixed spaces are not supported");
      V = std::make_shared<dolfinx::fem::FunctionSpace>(std::move(collapsed));
      to_W = std::move(map);
    }
    const int bs = V->dofmap()->index_map_bs();
    const std::vector<double> X = V->tabulate_dof_coordinates(false);
    const std::size_t num_dofs = mixed ? to_W.size() : X.size() / 3 * bs;
    for (std::size_t j = 0; j < num_dofs; ++j)
    {
      const std::int32_t dof = mixed ? to_W[j] : std::int32_t(j);
      if (dof >= num_owned || unknown_of[dof] < 0)
        continue;
      const PetscInt u = unknown_of[dof];
      const std::size_t node = j / bs;
      const std::array<double, key_width> key
          = {double(s), double(j % bs), X[3 * node], X[3 * node + 1], X[3 * node + 2]};
      std::copy(key.begin(), key.end(), keys.begin() + key_width * u);
      keyed[u] = 1;
    }
  }
  // The unknowns of no dof, in global order
  std::int64_t extra = std::count(keyed.begin(), keyed.end(), 0), first = 0;
  MPI_Exscan(&extra, &first, 1, MPI_INT64_T, MPI_SUM, comm);
  for (PetscInt u = 0; u < n; ++u)
    if (!keyed[u])
    {
      keys[key_width * u] = -1;
      keys[key_width * u + 1] = double(first++);
    }
  return keys;
}

/// For each key of `keys`, the row of `stored` with the same sub-space and component and a
/// position within 1e-9 of the stored positions' extent; -1 where there is none or more than
/// one.
std::vector<std::int64_t> match(const std::vector<double>& keys, const std::vector<double>& stored)
{
  double extent = 0;
  for (std::size_t r = 0; r < stored.size(); r += key_width)
    for (int c = 2; c < key_width; ++c)
      extent = std::max(extent, std::abs(stored[r + c]));
  const double tol = 1e-9 * (extent > 0 ? extent : 1.0);
  // Rows binned in cells of size tol: a position within tol of a row lies in the row's cell
  // or a neighbouring one
  using Cell = std::array<std::int64_t, key_width>;
  auto cell_of = [tol](const double* key, const std::array<int, 3>& shift)
  {
    Cell c = {std::llround(key[0]), std::llround(key[1]), 0, 0, 0};
    for (int k = 0; k < 3; ++k)
      c[2 + k] = std::int64_t(std::floor(key[2 + k] / tol)) + shift[k];
    return c;
  };
  std::map<Cell, std::vector<std::int64_t>> bins;
  for (std::size_t r = 0; r < stored.size() / key_width; ++r)
    bins[cell_of(&stored[key_width * r], {0, 0, 0})].push_back(r);
  std::vector<std::int64_t> rows(keys.size() / key_width, -1);
  for (std::size_t i = 0; i < rows.size(); ++i)
  {
    const double* key = &keys[key_width * i];
    int found = 0;
    for (int a = -1; a <= 1; ++a)
      for (int b = -1; b <= 1; ++b)
        for (int c = -1; c <= 1; ++c)
        {
          const auto bin = bins.find(cell_of(key, {a, b, c}));
          if (bin == bins.end())
            continue;
          for (std::int64_t r : bin->second)
          {
            const double* other = &stored[key_width * r];
            if (std::abs(other[2] - key[2]) <= tol && std::abs(other[3] - key[3]) <= tol
                && std::abs(other[4] - key[4]) <= tol)
            {
              rows[i] = r;
              ++found;
            }
          }
        }
    if (found != 1)
      rows[i] = -1;
  }
  return rows;
}

nlohmann::json vector_names(const PathState& s)
{
  nlohmann::json names = nlohmann::json::array();
  for (const auto& [name, v] : s.vectors)
    names.push_back(name);
  return names;
}

nlohmann::json path_to_json(const PathState& s)
{
  return {{"step", s.step},
          {"load", s.load},
          {"step_size", s.step_size},
          {"arc_length", s.arc_length},
          {"cutbacks", s.cutbacks},
          {"direction", bool(s.direction)},
          {"load_direction", s.load_direction},
          {"stability", std::isnan(s.stability) ? nlohmann::json(nullptr)
                                                : nlohmann::json(s.stability)},
          {"negative_eigenvalues", s.negative_eigenvalues},
          {"scene", s.scene},
          {"vectors", vector_names(s)},
          {"driver", s.driver}};
}

/// The path's scalars and scene from path_to_json (not the direction vector).
PathState path_from_json(const nlohmann::json& j)
{
  PathState s;
  s.step = j.at("step");
  s.load = j.at("load");
  s.step_size = j.at("step_size");
  s.arc_length = j.at("arc_length");
  s.cutbacks = j.at("cutbacks");
  s.load_direction = j.at("load_direction");
  s.stability = j.at("stability").is_null() ? NAN : j.at("stability").get<double>();
  s.negative_eigenvalues = j.at("negative_eigenvalues");
  s.scene = j.at("scene");
  s.driver = j.value("driver", nlohmann::json::object());
  return s;
}

/// The owned entries of v as rows [first, first + n) of the column `name` of `total` rows.
void write_column(hid_t h5, const std::string& name, Vec v, std::int64_t first,
                  std::int64_t total, bool parallel)
{
  PetscInt n;
  const PetscScalar* values;
  GELX_PETSC(VecGetLocalSize(v, &n));
  GELX_PETSC(VecGetArrayRead(v, &values));
  HDF5::write_dataset(h5, name, values, {first, first + n}, {total, 1}, parallel, false);
  GELX_PETSC(VecRestoreArrayRead(v, &values));
}

/// The owned entries of v from the rows `rows` of the column `name`.
void read_column(hid_t h5, const std::string& name, const std::vector<std::int64_t>& rows, Vec v)
{
  const std::vector<double> column = HDF5::read_dataset<double>(h5, name, {-1, -1});
  PetscScalar* values;
  GELX_PETSC(VecGetArray(v, &values));
  for (std::size_t i = 0; i < rows.size(); ++i)
    values[i] = column.at(rows[i]);
  GELX_PETSC(VecRestoreArray(v, &values));
}
} // namespace

Checkpoints::Checkpoints(MPI_Comm comm, std::filesystem::path folder)
    : _comm(comm), _folder(std::move(folder))
{
}

void Checkpoints::write(NonlinearSystem& system, const PathState& state,
                        const nlohmann::json& record)
{
  if (_system != &system)
  {
    _keys = unknown_keys(_comm, system);
    _system = &system;
  }
  const bool root = dolfinx::MPI::rank(_comm) == 0;
  const bool parallel = dolfinx::MPI::size(_comm) > 1;
  const fs::path folder = _folder / folder_name(state.step);
  if (root)
  {
    fs::remove_all(folder); // an incomplete one of a run killed after this step
    fs::create_directories(folder);
  }
  MPI_Barrier(_comm); // every rank opens the file in it

  // 1. The vectors, each rank its owned rows
  const std::int64_t n = _keys.size() / key_width;
  std::int64_t first = 0, total = 0;
  MPI_Exscan(&n, &first, 1, MPI_INT64_T, MPI_SUM, _comm);
  MPI_Allreduce(&n, &total, 1, MPI_INT64_T, MPI_SUM, _comm);
  const hid_t h5 = HDF5::open_file(_comm, folder / "vectors.h5", "w", parallel);
  HDF5::write_dataset(h5, "/key", _keys.data(), {first, first + n}, {total, key_width}, parallel,
                      false);
  write_column(h5, "/unknowns", system.unknowns(), first, total, parallel);
  OwnedVec history(system.create_vector());
  GELX_PETSC(VecSet(history.get(), 0.0));
  system.save_history(history.get());
  write_column(h5, "/history", history.get(), first, total, parallel);
  if (state.direction)
    write_column(h5, "/direction", state.direction.get(), first, total, parallel);
  for (const auto& [name, v] : state.vectors)
    write_column(h5, "/vector_" + name, v.get(), first, total, parallel);
  HDF5::close_file(h5); // collective: every rank's rows are written

  // 2. state.json last: the checkpoint is complete once it exists
  if (!root)
    return;
  const nlohmann::json contents = {{"format", format},
                                   {"ranks", dolfinx::MPI::size(_comm)},
                                   {"unknowns", total},
                                   {"path", path_to_json(state)},
                                   {"run", record}};
  replace_file(folder / "state.json",
               [&](std::ostream& out) { out << contents.dump(1) << "\n"; });

  // 3. Keep this one and the newest complete one before it
  const int previous = step_of(newest(_folder, state.step));
  std::vector<fs::path> others;
  for (const auto& entry : fs::directory_iterator(_folder))
  {
    const int step = step_of(entry.path());
    if (step >= 0 && step != state.step && step != previous)
      others.push_back(entry.path());
  }
  for (const auto& folder : others)
    fs::remove_all(folder);
}

void Checkpoints::clear()
{
  if (dolfinx::MPI::rank(_comm) == 0)
    fs::remove_all(_folder);
}

fs::path Checkpoints::newest(const fs::path& folder, int before)
{
  fs::path found;
  int found_step = -1;
  if (!fs::is_directory(folder))
    return found;
  for (const auto& entry : fs::directory_iterator(folder))
  {
    const int step = step_of(entry.path());
    if (step > found_step && step < before && fs::exists(entry.path() / "state.json"))
    {
      found = entry.path();
      found_step = step;
    }
  }
  return found;
}

nlohmann::json Checkpoints::read_record(const fs::path& checkpoint)
{
  std::ifstream in(checkpoint / "state.json");
  nlohmann::json contents = nlohmann::json::parse(in, nullptr, false);
  if (!in || contents.is_discarded() || contents.value("format", "") != format)
    throw InputError("cannot read the checkpoint " + (checkpoint / "state.json").string());
  return contents;
}

PathState Checkpoints::read(MPI_Comm comm, const fs::path& checkpoint, NonlinearSystem& system)
{
  const nlohmann::json contents = read_record(checkpoint);
  const std::vector<double> keys = unknown_keys(comm, system);
  const hid_t h5 = HDF5::open_file(comm, checkpoint / "vectors.h5", "r",
                                   dolfinx::MPI::size(comm) > 1);
  const std::vector<std::int64_t> rows
      = match(keys, HDF5::read_dataset<double>(h5, "/key", {-1, -1}));
  std::int64_t unmatched = std::count(rows.begin(), rows.end(), -1), total = rows.size();
  MPI_Allreduce(MPI_IN_PLACE, &unmatched, 1, MPI_INT64_T, MPI_SUM, comm);
  MPI_Allreduce(MPI_IN_PLACE, &total, 1, MPI_INT64_T, MPI_SUM, comm);
  if (unmatched > 0 || total != contents.at("unknowns").get<std::int64_t>())
  {
    HDF5::close_file(h5);
    throw InputError("the checkpoint " + checkpoint.string() + " holds "
                     + contents.at("unknowns").dump() + " unknowns, this run has "
                     + std::to_string(total) + " (" + std::to_string(unmatched)
                     + " not found in it): another mesh or discretisation");
  }
  read_column(h5, "/unknowns", rows, system.unknowns());
  system.unknowns_changed();
  OwnedVec history(system.create_vector());
  read_column(h5, "/history", rows, history.get());
  system.load_history(history.get());
  PathState state = path_from_json(contents.at("path"));
  if (contents.at("path").at("direction").get<bool>())
  {
    state.direction.reset(system.create_vector());
    read_column(h5, "/direction", rows, state.direction.get());
  }
  for (const std::string name : contents.at("path").value("vectors", nlohmann::json::array()))
  {
    OwnedVec v(system.create_vector());
    read_column(h5, "/vector_" + name, rows, v.get());
    state.vectors[name] = std::move(v);
  }
  HDF5::close_file(h5);
  return state;
}

} // namespace gelx
