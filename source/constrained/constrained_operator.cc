#include <pantocat/constrained/constrained_operator.h>
#include <pantocat/constrained/reference_constrained_operator.h>
#include <pantocat/constrained_fast/fast_constrained_operator.h>

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
} // namespace pantocat
