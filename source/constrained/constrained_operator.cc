#include <pantocat/constrained/constrained_operator.h>
#include <pantocat/constrained/half_explicit_step_system.h>
#include <pantocat/constrained/implicit_step_system.h>
#include <pantocat/constrained/reference_constrained_operator.h>
#include <pantocat/constrained/reference_half_explicit_step_system.h>
#include <pantocat/constrained/reference_implicit_step_system.h>
#include <pantocat/constrained_fast/fast_constrained_operator.h>
#include <pantocat/constrained_fast/fast_half_explicit_step_system.h>
#include <pantocat/constrained_fast/fast_implicit_step_system.h>

namespace pantocat
{
const char* to_string(const LinearAlgebra algebra)
{
  return algebra == LinearAlgebra::fast ? "fast" : "reference";
}

std::unique_ptr<ConstrainedOperator>
make_constrained_operator(const SemiDiscreteSystem& system,
                          const ConstrainedOperator::Definition& definition,
                          const LinearAlgebra algebra)
{
  if (algebra == LinearAlgebra::reference)
    return std::make_unique<ReferenceConstrainedOperator>(system, definition);
  return std::make_unique<FastConstrainedOperator>(system, definition);
}

std::unique_ptr<ConstrainedOperator> make_mass_operator(const SemiDiscreteSystem& system,
                                                        const LinearAlgebra algebra,
                                                        const LinearSolverType solver)
{
  ConstrainedOperator::Definition M;
  M.what = "mass matrix M";
  M.solver = solver;
  return make_constrained_operator(system, M, algebra);
}

std::unique_ptr<ImplicitStepSystem>
make_implicit_step_system(const SemiDiscreteSystem& system, const double c,
                          const LinearAlgebra algebra, const LinearSolverType solver,
                          const bool forms_next_history)
{
  if (algebra == LinearAlgebra::reference)
    return std::make_unique<ReferenceImplicitStepSystem>(system, c);
  return std::make_unique<FastImplicitStepSystem>(system, c, solver, forms_next_history);
}

std::unique_ptr<HalfExplicitStepSystem>
make_half_explicit_step_system(const SemiDiscreteSystem& system, const double h,
                               const LinearAlgebra algebra)
{
  if (algebra == LinearAlgebra::reference)
    return std::make_unique<ReferenceHalfExplicitStepSystem>(system, h);
  return std::make_unique<FastHalfExplicitStepSystem>(system, h);
}
} // namespace pantocat
