#include <pantocat/base/input_error.h>
#include <pantocat/time/multiplier_system.h>

#include <cmath>
#include <sstream>

namespace pantocat
{
void solve_multiplier_system(dealii::FullMatrix<double>& A,
                             const dealii::Vector<double>& b, dealii::Vector<double>& x,
                             const double t, const char* what)
{
  if (A.m() == 0)
    return;
  A.gauss_jordan();
  A.vmult(x, b);
  for (const double value : x)
    if (!std::isfinite(value))
    {
      std::ostringstream s;
      s << "the active constraints are linearly dependent at t = " << t << " s (" << what
        << ")";
      throw SimulationError(s.str());
    }
}
} // namespace pantocat
