#include <pantocat/constrained_fast/iteration_matrix.h>

namespace pantocat
{
void assemble_iteration_matrix(const SemiDiscreteSystem& system,
                               const double damping_factor, const double mass_factor,
                               dealii::SparseMatrix<double>& S)
{
  S.reinit(*system.sparsity);
  S.copy_from(system.stiffness);
  S.add(damping_factor, system.damping);
  S.add(mass_factor, system.mass);
}

IterationMatrix::IterationMatrix(const SemiDiscreteSystem& system,
                                 const double damping_factor, const double mass_factor,
                                 const std::string& what, const LinearSolverType solver)
    : position(system.n_constraints()), moves(system.n_constraints())
{
  dealii::SparseMatrix<double> S;
  assemble_iteration_matrix(system, damping_factor, mass_factor, S);
  inverse.factorize(S, what, solver);
  for (unsigned int i = 0; i < system.n_constraints(); ++i)
  {
    moves[i] = system.constraints[i]->depends_on_time();
    auto& list = moves[i] ? moving : fixed;
    position[i] = list.size();
    list.push_back(i);
  }
  S_columns.resize(moving.size());
  M_columns.resize(moving.size());
  for (auto* batches : {&S_columns, &M_columns})
    for (auto& X : *batches)
      X.reinit(system.n_dofs());
  base.reinit(system.n_dofs());
}
} // namespace pantocat
