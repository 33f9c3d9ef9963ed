#ifndef LME_MPM_SIMULATION_RUN_H
#define LME_MPM_SIMULATION_RUN_H

#include <deal.II/base/parameter_handler.h>

#include <iostream>
#include <map>
#include <string>
#include <vector>

namespace lme_mpm
{
/**
 * Reads a parameter file, applies "Subsection/Entry=value" overrides, builds the
 * simulation of the declared dimension and runs it (continuing the checkpoint in
 * @p resume if given). Throws on bad input before anything is written.
 */
std::map<std::string, double>
run_parameter_file(const std::string &file, const std::vector<std::string> &overrides,
                   std::ostream &console = std::cout, const std::string &resume = "");

/// Applies "A/B/Entry=value" overrides; with @p skip_unknown, unknown entries are
/// ignored.
void apply_overrides(dealii::ParameterHandler &prm,
                     const std::vector<std::string> &overrides, bool skip_unknown);

/// Writes the documented default parameter file of a 2D run.
void print_default_parameters(std::ostream &out);

/**
 * Writes the parameter handler of @p file with @p overrides applied: every entry the
 * file's run declares (its counts, dimension and plug-in libraries) with the values
 * the run would read.
 */
void print_parameters(const std::string &file, const std::vector<std::string> &overrides,
                      std::ostream &out);

/// The command line of this process, for the runs' records (the program sets it).
void set_command_line(const std::string &command_line);
} // namespace lme_mpm

#endif
