// pantocat-fem: the command-line program. All work happens in the core library.
#include <pantocat/app/application.h>

#include <deal.II/base/mpi.h>

int main(int argc, char** argv)
{
  // First, as Trilinos objects need MPI; serial runs need no mpirun.
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  return pantocat::run_application(argc, argv);
}
