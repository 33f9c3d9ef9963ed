#include <lme_mpm/base/input.h>
#include <lme_mpm/base/plugin_libraries.h>
#include <lme_mpm/simulation/run.h>
#include <lme_mpm/simulation/simulation.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace lme_mpm
{
void apply_overrides(ParameterHandler &prm, const std::vector<std::string> &overrides,
                     const bool skip_unknown)
{
  for (const auto &o : overrides)
  {
    const auto eq = o.find('=');
    AssertThrow(eq != std::string::npos,
                ExcBadInput("--set " + o, "expected 'Subsection/Entry=value'"));
    const auto path  = input::split(o.substr(0, eq), '/');
    const auto value = input::trim(o.substr(eq + 1));
    AssertThrow(!path.empty(), ExcBadInput("--set " + o, "no entry named"));
    for (std::size_t i = 0; i + 1 < path.size(); ++i)
      prm.enter_subsection(path[i]);
    try
    {
      prm.set(path.back(), value);
    }
    catch (const ParameterHandler::ExcEntryUndeclared &)
    {
      for (std::size_t i = 0; i + 1 < path.size(); ++i)
        prm.leave_subsection();
      AssertThrow(skip_unknown,
                  ExcBadInput(o.substr(0, eq),
                              "no such entry" +
                                  input::did_you_mean(input::trim(o.substr(0, eq)),
                                                      input::declared_entries(prm))));
      continue;
    }
    catch (const ParameterHandler::ExcValueDoesNotMatchPattern &e)
    {
      for (std::size_t i = 0; i + 1 < path.size(); ++i)
        prm.leave_subsection();
      const std::string message = input::concise_message(e);
      AssertThrow(
          skip_unknown,
          ExcBadInput(o.substr(0, eq), message + input::selection_hint(value, message)));
      continue;
    }
    for (std::size_t i = 0; i + 1 < path.size(); ++i)
      prm.leave_subsection();
  }
}

namespace
{
std::string &command_line()
{
  static std::string line;
  return line;
}

/// The first pass over a file: the plug-in libraries (loaded) and the counts.
ParameterCounts first_pass(const std::string &file,
                           const std::vector<std::string> &overrides,
                           std::vector<std::string> *libraries = nullptr)
{
  AssertThrow(std::filesystem::exists(file),
              ExcBadInput("parameter file", "'" + file + "' does not exist"));
  // The plug-in libraries to load (their names must be known before the selection
  // entries are declared) and how many materials, bodies, ... the file declares.
  ParameterCounts counts;
  ParameterHandler prm;
  ParameterCounts::declare_parameters(prm);
  PluginLibraries::declare_parameters(prm);
  prm.parse_input(file, "", true, false);
  apply_overrides(prm, overrides, true);
  const auto paths = PluginLibraries::parse_parameters(prm);
  PluginLibraries::load(paths);
  if (libraries)
    *libraries = paths;
  counts.parse_parameters(prm);
  return counts;
}

/// The subsection path ("A/B") open at line @p line of @p file.
std::string subsection_at(const std::string &file, const unsigned int line)
{
  std::ifstream in(file);
  std::vector<std::string> path;
  std::string text;
  for (unsigned int n = 1; n < line && std::getline(in, text); ++n)
    input::follow_subsections(text, path);
  return input::path_prefix(path);
}

/**
 * Rethrows deal.II's message on a misspelled entry or subsection, or a value that is
 * not one of a selection's names, in the file @p file, as one line naming the entry
 * with its subsections, the line, and the closest declared name.
 */
template <int dim>
void explain_file_error(const std::exception &e, const std::string &file,
                        const ParameterCounts &counts)
{
  const std::string what = input::concise_message(e);
  // deal.II's form: "Line <N> of file <F>: ..." (the '>' after F is missing in some).
  std::smatch m;
  if (!std::regex_search(what, m, std::regex("Line <([0-9]+)> of file <")))
    return;
  const auto colon = what.find(": ", m.position(0) + m.length(0));
  if (colon == std::string::npos)
    return;
  const unsigned int line = std::stoul(m[1].str());
  const std::string rest  = what.substr(colon + 2),
                    where = " (line " + m[1].str() + " of " + file + ")";
  ParameterHandler declared;
  Simulation<dim>::declare_parameters(declared, counts);
  const auto entries = input::declared_entries(declared);
  std::smatch n;
  if (std::regex_search(rest, n, std::regex("No entry with name <([^>]*)>")))
  {
    const std::string entry = subsection_at(file, line) + input::trim(n[1].str());
    AssertThrow(false, ExcBadInput(entry, "no such entry" + where +
                                              input::did_you_mean(entry, entries)));
  }
  if (std::regex_search(rest, n,
                        std::regex("no such subsection to be entered: ?<?([^>]*)>?")))
  {
    std::string sub = input::trim(n[1].str());
    std::replace(sub.begin(), sub.end(), '.', '/');
    std::vector<std::string> subsections;
    for (const auto &entry : entries)
      for (auto slash = entry.find('/'); slash != std::string::npos;
           slash      = entry.find('/', slash + 1))
        subsections.push_back(entry.substr(0, slash));
    AssertThrow(false, ExcBadInput(sub, "no such subsection" + where +
                                            input::did_you_mean(sub, subsections)));
  }
  if (std::regex_search(
          rest, n,
          std::regex("entry value\\s+<?([^<>]*?)>?\\s+for the entry named\\s+<?"
                     "([^<>]*?)>?\\s+does not match")))
  {
    const std::string entry = subsection_at(file, line) + input::trim(n[2].str());
    AssertThrow(false,
                ExcBadInput(entry, "'" + n[1].str() + "' is not allowed" + where + ": " +
                                       input::trim(rest.substr(std::min(
                                           rest.find("does not match"), rest.size()))) +
                                       input::selection_hint(n[1].str(), rest)));
  }
}

template <int dim>
void read_file(ParameterHandler &prm, const std::string &file,
               const std::vector<std::string> &overrides, const ParameterCounts &counts)
{
  Simulation<dim>::declare_parameters(prm, counts);
  try
  {
    prm.parse_input(file, "", false, false);
  }
  catch (const std::exception &e)
  {
    // A numbered subsection beyond its count ("Body 3" with two bodies): name the
    // count that leaves it out.
    // deal.II wraps its messages; the concise form is on one line.
    const std::string what = input::concise_message(e),
                      tag  = "no such subsection to be entered: ";
    const auto at          = what.find(tag);
    if (at == std::string::npos)
    {
      explain_file_error<dim>(e, file, counts);
      throw;
    }
    const std::string rest = what.substr(at + tag.size());
    const std::string sub  = input::trim(rest.substr(0, rest.find('\n')));
    std::string count;
    for (const auto &[prefix, entry] : std::vector<std::pair<std::string, std::string>>{
             {"Material ", "Problem/Number of materials"},
             {"Body ", "Problem/Number of bodies"},
             {"Boundary conditions.Constraint ",
              "Boundary conditions/Number of constraints"},
             {"Output.Probe ", "Output/Number of probes"}})
      if (sub.rfind(prefix, 0) == 0)
        count = entry;
    if (count.empty())
    {
      explain_file_error<dim>(e, file, counts);
      throw;
    }
    AssertThrow(false, ExcBadInput(count, "the file has a subsection '" + sub +
                                              "', beyond the number this entry gives"));
  }
  apply_overrides(prm, overrides, false);
}

template <int dim>
std::map<std::string, double>
run_dim(const std::string &file, const std::vector<std::string> &overrides,
        const ParameterCounts &counts, std::ostream &console, const std::string &resume,
        RunRecord record)
{
  ParameterHandler prm;
  read_file<dim>(prm, file, overrides, counts);
  Simulation<dim> simulation(prm, counts, console);
  // After the constructor, which wrote the scene's entries into the handler.
  std::ostringstream parameters;
  prm.print_parameters(parameters, ParameterHandler::PRM);
  record.parameters = parameters.str();
  simulation.keep_record(std::move(record));
  if (!resume.empty())
    simulation.resume_from(resume);
  return simulation.run();
}
} // namespace

void set_command_line(const std::string &line)
{
  command_line() = line;
}

void print_parameters(const std::string &file, const std::vector<std::string> &overrides,
                      std::ostream &out)
{
  const ParameterCounts counts = first_pass(file, overrides);
  ParameterHandler prm;
  if (counts.dim == 2)
    read_file<2>(prm, file, overrides, counts);
  else
    read_file<3>(prm, file, overrides, counts);
  prm.print_parameters(out, ParameterHandler::PRM);
}

std::map<std::string, double>
run_parameter_file(const std::string &file, const std::vector<std::string> &overrides,
                   std::ostream &console, const std::string &resume)
{
  RunRecord record;
  record.command_line          = command_line();
  record.parameter_file        = file;
  record.overrides             = overrides;
  record.resumed_from          = resume;
  const ParameterCounts counts = first_pass(file, overrides, &record.libraries);
  if (counts.dim == 2)
    return run_dim<2>(file, overrides, counts, console, resume, std::move(record));
  return run_dim<3>(file, overrides, counts, console, resume, std::move(record));
}

void print_default_parameters(std::ostream &out)
{
  ParameterHandler prm;
  Simulation<2>::declare_parameters(prm, ParameterCounts{2, 1, 1, 1, 1});
  prm.print_parameters(out, ParameterHandler::PRM);
}
} // namespace lme_mpm
