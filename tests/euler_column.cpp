// Verification: Euler buckling of a slender 3-D column by the linear pre-buckling eigenproblem
// (thesis Eq. 1.13) with SLEPc, on the column of the buckling scene (demos/buckling).
//
// A column of cross-section tx x ty (tx < ty, so it buckles in x) and length L = 30 tx,
// compressible neo-Hookean with G = 1, nu = 0.3, clamped at z = 0; the other end free under a
// dead axial load (effective length 2L) or clamped and shortened (effective length L/2).
// Slenderness K L / r = K L sqrt(12) / tx >= 52 for both. The critical loads are compared with
// pi^2 E I / (K L)^2 on two meshes, the clamped-clamped mode shapes' symmetry about mid-length
// is checked, and mode 1 is seeded as an imperfection. The post-buckling paths (bifurcation,
// branch switching, the imperfect column) are checked on the scene's output
// (tests/post_buckling.py).

#include "euler_column.h"
#include "support.h"

#include <cmath>
#include <slepcsys.h>

int main(int argc, char* argv[])
{
  SlepcInitialize(&argc, &argv, nullptr, nullptr);
  int status;
  {
    MPI_Comm comm = PETSC_COMM_WORLD;
    gelx::test::Checks checks(comm);
    const double imperfection = 0.01;
    for (bool clamped_clamped : {false, true})
    {
      const std::string name = clamped_clamped ? "clamped-clamped" : "clamped-free";
      std::vector<double> errors;
      for (std::array<int, 3> cells : {std::array<int, 3>{2, 3, 40}, {3, 4, 80}})
      {
        gelx::scenes::ColumnParameters p;
        p.cells = cells;
        p.ends = name;
        gelx::scenes::EulerColumn column(comm, p);
        const auto modes = column.buckling_modes(2);
        const std::string level = name + ", mesh " + std::to_string(cells[0]) + "x"
                                  + std::to_string(cells[1]) + "x" + std::to_string(cells[2]);
        // Euler's load pi^2 E I / (K L)^2, computed here from the column's data; the modes'
        // load factors are in units of the scene's own Euler load (euler_load())
        const double E = 2 * p.G * (1 + p.nu), I = p.ty * std::pow(p.tx, 3) / 12;
        const double length = (clamped_clamped ? 0.5 : 2.0) * p.L;
        const double P_euler = M_PI * M_PI * E * I / (length * length);
        const double P_cr = modes[0].load_factor * column.euler_load();
        errors.push_back(std::abs(P_cr / P_euler - 1));
        // 2% (the bound at slenderness >= 50): what separates the 3-D continuum from
        // Euler's beam at this slenderness is shear deformation and the cross-section's
        // Poisson effect, both O((r/L)^2) ~ 1e-3, plus the discretisation error.
        checks.require(level + ": slenderness K L sqrt(12) / tx "
                           + std::to_string(length * std::sqrt(12.0) / p.tx) + " >= 50",
                       length * std::sqrt(12.0) / p.tx >= 50);
        checks.relative(level + ": critical load against Euler's", P_cr, P_euler, 0.02);
        if (clamped_clamped)
        {
          // Mode 1 symmetric, mode 2 antisymmetric about mid-length. The box mesh is mirror
          // symmetric about z = L/2, so the symmetry is limited by the eigensolver's accuracy
          // (residual 1e-10; measured asymmetries 1e-9 to 1e-6), not by discretisation: 1e-4.
          checks.absolute(level + ": mode 1 odd part (relative)",
                          column.mode_odd_even_parts(modes[0].shape)[0], 0, 1e-4);
          checks.absolute(level + ": mode 2 even part (relative)",
                          column.mode_odd_even_parts(modes[1].shape)[1], 0, 1e-4);
          // The second mode in x: 8.18 pi^2 EI / L^2 = 2.046 Euler loads of the clamped-clamped
          // column (beam theory). Its half-waves are shorter, so shear and discretisation
          // errors are larger: 5%.
          checks.relative(level + ": second critical load against 8.183 pi^2 EI/L^2",
                          modes[1].load_factor * column.euler_load(),
                          8.183 * M_PI * M_PI * E * I / (p.L * p.L), 0.05);
        }

        // Seed mode 1 as a geometric imperfection: the nodes move by at most its amplitude
        std::span<const double> x = column.mesh().mesh->geometry().x();
        const std::vector<double> x0(x.begin(), x.end());
        gelx::seed_imperfection(*column.mesh().mesh, {modes[0]}, {imperfection * p.tx});
        double shift = 0;
        for (std::size_t k = 0; k < x0.size(); ++k)
          shift = std::max(shift, std::abs(x[k] - x0[k]));
        MPI_Allreduce(MPI_IN_PLACE, &shift, 1, MPI_DOUBLE, MPI_MAX, comm);
        // The mode's largest component is 1; the mesh nodes are its vertices, where it is at
        // most 1 and, on these meshes, within 1e-3 of it (the peak may sit on an edge node)
        checks.relative(level + ": largest node shift vs imperfection amplitude", shift,
                        imperfection * p.tx, 1e-3);
        checks.require(level + ": no node moves by more than the amplitude",
                       shift <= imperfection * p.tx * (1 + 1e-12));
      }
      checks.require(name + ": error shrinks under refinement (" + std::to_string(errors[0])
                         + " -> " + std::to_string(errors[1]) + ")",
                     errors[1] < errors[0]);
    }
    status = checks.finish();
  }
  SlepcFinalize();
  return status;
}
