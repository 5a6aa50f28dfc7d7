#pragma once
/// @file buckling.h
/// Linear (eigenvalue) buckling about a base state, and imperfections seeded from its modes.

#include <gelx/systems/system.h>

#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/mesh/Mesh.h>
#include <memory>
#include <mpi.h>
#include <petscksp.h>
#include <petscmat.h>
#include <string>
#include <vector>

namespace gelx
{

/// One buckling mode: the load factor lambda at which it appears (or, for a tangent's
/// eigenpair, the eigenvalue) and its shape (largest displacement component 1).
struct BucklingMode
{
  double load_factor;
  std::shared_ptr<dolfinx::fem::Function<double>> shape;
};

/// The linear pre-buckling eigenproblem of thesis Eq. 1.13, (K + lambda K_D) v = 0.
///
/// K is the tangent at the base state (load P_n) and K_D the differential stiffness of the
/// perturbation load Q: the tangent at the state under P_n + Q minus K. The critical load is
/// P_n + lambda Q. SLEPc solves the equivalent symmetric-definite problem
///   -K_D v = theta K v,   lambda = 1/theta,
/// for the largest theta, which needs K positive definite: a base state below the first
/// critical load. Needs SLEPc initialised (run_program does it). Options prefix `buckling_` (e.g. `-buckling_eps_type krylovschur`); the inner
/// solves with K default to MUMPS LU.
class LinearBuckling
{
public:
  explicit LinearBuckling(MPI_Comm comm, const std::string& prefix = "buckling_");

  /// The `num_modes` lowest positive load factors and their modes, in increasing order.
  /// `space` is the space of the tangents' unknowns.
  std::vector<BucklingMode> solve(Mat K, Mat K_perturbed, int num_modes,
                                  std::shared_ptr<const dolfinx::fem::FunctionSpace> space);

private:
  MPI_Comm _comm;
  std::string _prefix;
};

/// The eigenvalue of a tangent K nearest zero and its eigenvector (largest component 1): the
/// stability of an equilibrium. A negative value means the state is unstable; a sign change
/// along a path marks a limit or bifurcation point. Shift-and-invert about 0 with MUMPS;
/// options prefix `stability_`. Dirichlet rows (eigenvalue 1) do not interfere as long as the
/// physical eigenvalue sought is nearer zero than 1, which holds near instabilities.
BucklingMode lowest_tangent_eigenpair(MPI_Comm comm, Mat K,
                                      std::shared_ptr<const dolfinx::fem::FunctionSpace> space);

/// The `num_modes` lowest free vibrations of `system` about its current state, K phi =
/// omega^2 M phi with K its tangent and M the mass form assembled on its unknowns (prescribed
/// rows and columns left out): load_factor holds omega^2, in increasing order. SLEPc, through
/// LinearBuckling with K_D = -M (options prefix `vibration_`). Collective.
std::vector<BucklingMode> vibration_modes(MPI_Comm comm, NonlinearSystem& system,
                                          const dolfinx::fem::Form<double>& mass_form,
                                          int num_modes);

/// Make the linear solver with options `prefix` factorise by MUMPS's LDL^T (Cholesky of a
/// symmetric, possibly indefinite matrix) unless the user chose otherwise, with ICNTL(13) = 1:
/// MUMPS's ScaLAPACK root front does not report the signs of its pivots, so without it the
/// parallel inertia is wrong (PETSc refuses MatGetInertia then).
void default_to_symmetric_factorisation(const std::string& prefix);

/// The number of negative eigenvalues of the symmetric matrix that `ksp` factorised at its
/// last set-up, read from the signs of its LDL^T factors (Sylvester's law of inertia,
/// MatGetInertia): no extra factorisation. Throws unless the factorisation is a Cholesky
/// (LDL^T) one by MUMPS, the only parallel one in PETSc 3.18 that reports an inertia.
///
/// For a tangent it counts the directions in which the equilibrium is unstable: along a path
/// it changes by the number of eigenvalues that cross zero, also when several cross together
/// (a double bifurcation), which the eigenvalue nearest zero cannot tell. For a mixed u-p
/// tangent, a saddle point, it also counts one per pressure unknown.
int factored_negative_eigenvalues(KSP ksp);

/// Factorise the symmetric K by LDL^T (default_to_symmetric_factorisation, options prefix
/// `inertia_`) and return its number of negative eigenvalues. Collective.
int negative_eigenvalues(MPI_Comm comm, Mat K);

/// The number of negative eigenvalues of `system`'s tangent at its current state (assembled
/// into a matrix of its own, then negative_eigenvalues): the directions in which that state,
/// if an equilibrium, is unstable. Collective.
int tangent_negative_eigenvalues(MPI_Comm comm, NonlinearSystem& system);

/// Add the imperfection sum_i amplitude_i * mode_i to the mesh coordinates (as ABAQUS
/// *IMPERFECTION does): each mode (largest component 1) is evaluated at the mesh nodes.
/// For meshes with linear geometry and modes in a vector Lagrange space on that mesh.
void seed_imperfection(dolfinx::mesh::Mesh& mesh, const std::vector<BucklingMode>& modes,
                       const std::vector<double>& amplitudes);

} // namespace gelx
