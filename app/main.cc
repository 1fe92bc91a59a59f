// pantocat-fem: the command-line program. All work happens in the core library.
#include <pantocat/app/application.h>

int main(int argc, char** argv)
{
  // MPI is initialised inside when the run needs it (see run_application).
  return pantocat::run_application(argc, argv);
}
