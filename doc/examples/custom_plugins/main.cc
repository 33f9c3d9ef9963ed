// The user's program: lme-mpm's driver, with the plug-ins above linked in.
//   my-lme-mpm FILE.prm [Subsection/Entry=value ...]
#include <deal.II/base/mpi.h>

#include <lme_mpm/base/input.h>
#include <lme_mpm/simulation/run.h>

#include <iostream>

int main(int argc, char **argv)
{
  try
  {
    dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv,
                                                 dealii::numbers::invalid_unsigned_int);
    if (argc < 2)
    {
      std::cerr << "usage: my-lme-mpm FILE.prm [Subsection/Entry=value ...]" << std::endl;
      return 2;
    }
    lme_mpm::run_parameter_file(argv[1], std::vector<std::string>(argv + 2, argv + argc));
  }
  catch (const std::exception &e)
  {
    std::cerr << "my-lme-mpm: error: " << lme_mpm::input::concise_message(e) << std::endl;
    return 1;
  }
  return 0;
}
