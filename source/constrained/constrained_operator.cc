#include <pantocat/constrained/constrained_operator.h>
#include <pantocat/constrained/implicit_step_system.h>
#include <pantocat/constrained/reference_constrained_operator.h>
#include <pantocat/constrained/reference_implicit_step_system.h>
#include <pantocat/constrained_fast/fast_constrained_operator.h>
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

std::unique_ptr<ImplicitStepSystem>
make_implicit_step_system(const SemiDiscreteSystem& system, const double c,
                          const LinearAlgebra algebra, const LinearSolverType solver,
                          const bool forms_next_history)
{
  if (algebra == LinearAlgebra::reference)
    return std::make_unique<ReferenceImplicitStepSystem>(system, c);
  return std::make_unique<FastImplicitStepSystem>(system, c, solver, forms_next_history);
}
} // namespace pantocat
