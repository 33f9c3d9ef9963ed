// lme-mpm: runs a scene described by a deal.II parameter file.
#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>

#include <boost/program_options.hpp>

#include <lme_mpm/base/input.h>
#include <lme_mpm/base/interrupt.h>
#include <lme_mpm/base/run_record.h>
#include <lme_mpm/simulation/run.h>
#include <lme_mpm/simulation/run_guard.h>

#include <chrono>
#include <iostream>
#include <memory>
#include <thread>

#ifdef __SANITIZE_ADDRESS__
#include <sanitizer/lsan_interface.h>
#endif

namespace po = boost::program_options;

namespace
{
/**
 * MPI (and deal.II's thread pool) for the run. Open MPI never frees some of what it
 * allocates while starting and stopping; in sanitizer builds the leak checker ignores
 * those allocations so that it reports the project's own.
 */
class MpiSession
{
public:
  MpiSession(int &argc, char **&argv)
  {
#ifdef __SANITIZE_ADDRESS__
    __lsan::ScopedDisabler not_ours;
#endif
    mpi = std::make_unique<dealii::Utilities::MPI::MPI_InitFinalize>(
        argc, argv, dealii::numbers::invalid_unsigned_int);
    MPI_Comm_dup(MPI_COMM_WORLD, &errors);
  }
  ~MpiSession()
  {
#ifdef __SANITIZE_ADDRESS__
    __lsan::ScopedDisabler not_ours;
#endif
    MPI_Comm_free(&errors);
    mpi.reset();
  }

  /**
   * Whether every rank reports an error within @p seconds. Bad input fails alike on
   * every rank, which then end cleanly with one message; an error on some ranks only
   * (the others wait in a collective call of the run) needs MPI_Abort. The handshake
   * runs on a communicator of its own, so it cannot meet the run's collective calls.
   */
  bool all_ranks_failed(const double seconds) const
  {
    MPI_Request request;
    MPI_Ibarrier(errors, &request);
    const auto end =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    int done = 0;
    while (!done && std::chrono::steady_clock::now() < end)
    {
      MPI_Test(&request, &done, MPI_STATUS_IGNORE);
      if (!done)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return done != 0;
  }

private:
  std::unique_ptr<dealii::Utilities::MPI::MPI_InitFinalize> mpi;
  MPI_Comm errors = MPI_COMM_NULL;
};
/// The program's options (shown by --help) and the hidden positional FILE.
struct CommandLine
{
  po::options_description options{"Usage: lme-mpm FILE.prm [options]\n       lme-mpm "
                                  "--resume DIR [options]\nOptions"};
  po::variables_map vm;

  CommandLine()
  {
    options.add_options()("help,h", "print this help")(
        "set,s", po::value<std::vector<std::string>>()->composing(),
        "override an entry: --set \"Subsection/Entry=value\" (repeatable)")(
        "threads,t", po::value<unsigned int>(), "worker threads (default: all cores)")(
        "resume", po::value<std::string>(),
        "continue the run whose checkpoint.bin is in this directory, with the "
        "parameters it recorded (DIR/parameters.prm) unless FILE is given; --set "
        "\"Time/End time=...\" extends a run that has finished")(
        "print-parameters",
        "write the documented parameter file to standard output: the defaults, or with "
        "FILE (and --set) every entry of that run with the values it would read")(
        "version", "print the version and the git revision of the build");
  }

  /// Reads argv; false (after a message) on a malformed command line.
  bool parse(int argc, char **argv)
  {
    po::options_description hidden, all;
    hidden.add_options()("file", po::value<std::string>(), "parameter file");
    all.add(options).add(hidden);
    po::positional_options_description positional;
    positional.add("file", 1);
    try
    {
      po::store(
          po::command_line_parser(argc, argv).options(all).positional(positional).run(),
          vm);
      po::notify(vm);
    }
    catch (const po::error &e)
    {
      std::cerr << "lme-mpm: " << e.what() << "\n" << options << std::endl;
      return false;
    }
    return true;
  }

  /// The parameter file: FILE, or with --resume DIR alone the parameters the run
  /// recorded there.
  std::string file() const
  {
    if (vm.count("file"))
      return vm["file"].as<std::string>();
    return vm.count("resume") ? vm["resume"].as<std::string>() + "/parameters.prm" : "";
  }
  std::vector<std::string> overrides() const
  {
    return vm.count("set") ? vm["set"].as<std::vector<std::string>>()
                           : std::vector<std::string>();
  }
};

/**
 * The requests answered without a run (--help, --version, --print-parameters): their
 * exit code, or -1 when the command line asks for a run.
 */
int answer_without_run(const CommandLine &cl)
{
  if (cl.vm.count("help"))
  {
    std::cout << cl.options << std::endl;
    return 0;
  }
  if (cl.vm.count("version"))
  {
    std::cout << lme_mpm::version_line() << std::endl;
    return 0;
  }
  if (cl.vm.count("print-parameters"))
  {
    if (cl.vm.count("file"))
      lme_mpm::print_parameters(cl.file(), cl.overrides(), std::cout);
    else
      lme_mpm::print_default_parameters(std::cout);
    return 0;
  }
  if (cl.file().empty())
  {
    std::cerr << "lme-mpm: no parameter file given\n" << cl.options << std::endl;
    return 2;
  }
  return -1;
}

bool is_rank_zero()
{
  return dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
}

bool several_ranks()
{
  return dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1;
}

/**
 * Runs the parameter file on this rank and turns how it ended into the exit code:
 * interrupted 128 + the signal, failed or bad input 1 with one message. An error that
 * reached some ranks only (the others wait in a collective call) stops them all.
 */
int run(const CommandLine &cl, const MpiSession &mpi, const std::string &command_line)
{
  lme_mpm::set_command_line(command_line);
  lme_mpm::interrupt::install();
  try
  {
    lme_mpm::run_parameter_file(cl.file(), cl.overrides(), std::cout,
                                cl.vm.count("resume") ? cl.vm["resume"].as<std::string>()
                                                      : "");
    return 0;
  }
  catch (const lme_mpm::ExcRunInterrupted &e)
  {
    // The shell's convention for a process ended by a signal: 128 + its number.
    if (is_rank_zero())
      std::cerr << "lme-mpm: " << lme_mpm::input::concise_message(e) << std::endl;
    return 128 + lme_mpm::interrupt::received();
  }
  catch (const lme_mpm::ExcRunFailed &e)
  {
    // Every rank ended the run together, output written: one report, no abort.
    if (is_rank_zero())
      std::cerr << "lme-mpm: error: " << lme_mpm::input::concise_message(e) << std::endl;
    return 1;
  }
  catch (const std::exception &e)
  {
    if (several_ranks() && !mpi.all_ranks_failed(5.0))
    {
      // The output written so far stays.
      std::cerr << "lme-mpm: error on rank "
                << dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) << ": "
                << lme_mpm::input::concise_message(e) << std::endl;
      MPI_Abort(MPI_COMM_WORLD, 1);
    }
    if (is_rank_zero())
      std::cerr << "lme-mpm: error: " << lme_mpm::input::concise_message(e) << std::endl;
    return 1;
  }
}
} // namespace

int main(int argc, char **argv)
{
  try
  {
    CommandLine cl;
    if (!cl.parse(argc, argv))
      return 2;
    if (const int code = answer_without_run(cl); code >= 0)
      return code;
    // MPI ranks split the grid (mpirun -np N); TBB threads work inside each rank and
    // keep all cores unless --threads caps them.
    const MpiSession mpi(argc, argv);
    if (cl.vm.count("threads"))
    {
      const unsigned int n = cl.vm["threads"].as<unsigned int>();
      if (n == 0)
      {
        std::cerr << "lme-mpm: --threads must be at least 1" << std::endl;
        return 2;
      }
      dealii::MultithreadInfo::set_thread_limit(n);
    }
    std::string command_line;
    for (int i = 0; i < argc; ++i)
      command_line += (i ? " " : "") + std::string(argv[i]);
    return run(cl, mpi, command_line);
  }
  catch (const std::exception &e)
  {
    std::cerr << "lme-mpm: error: " << lme_mpm::input::concise_message(e) << std::endl;
    return 1;
  }
  catch (...)
  {
    std::cerr << "lme-mpm: unknown error" << std::endl;
    return 1;
  }
}
