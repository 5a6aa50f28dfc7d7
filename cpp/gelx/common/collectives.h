#pragma once
/// @file collectives.h
/// Small MPI collectives on std::vector that the library and the scenes share.

#include <dolfinx/common/MPI.h>
#include <numeric>
#include <vector>

namespace gelx
{

/// Concatenation of every rank's `local`, in rank order, on every rank. Collective.
template <typename T>
std::vector<T> all_gather(MPI_Comm comm, const std::vector<T>& local)
{
  const int size = dolfinx::MPI::size(comm);
  std::vector<int> counts(size), offsets(size + 1, 0);
  const int n = local.size();
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  std::partial_sum(counts.begin(), counts.end(), offsets.begin() + 1);
  std::vector<T> all(offsets.back());
  MPI_Allgatherv(local.data(), n, dolfinx::MPI::mpi_type<T>(), all.data(), counts.data(),
                 offsets.data(), dolfinx::MPI::mpi_type<T>(), comm);
  return all;
}

} // namespace gelx
