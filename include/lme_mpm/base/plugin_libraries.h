#ifndef LME_MPM_BASE_PLUGIN_LIBRARIES_H
#define LME_MPM_BASE_PLUGIN_LIBRARIES_H

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace lme_mpm
{
/**
 * Shared libraries of plug-ins named by the top-level entry `Additional shared
 * libraries` and loaded by the stock program before it declares the other entries:
 * a plug-in registers itself from a static object when its library is loaded, so the
 * selection entries of the same parameter file list it (the mechanism ASPECT uses).
 * Libraries stay loaded until the process ends, since the registries keep pointers
 * into them.
 */
struct PluginLibraries
{
  /// The entry's name, for messages.
  static constexpr const char *entry = "Additional shared libraries";

  /// Declares the top-level entry (a comma-separated list of paths, default empty).
  static void declare_parameters(dealii::ParameterHandler &prm);

  /// The paths the entry lists, in order.
  static std::vector<std::string> parse_parameters(dealii::ParameterHandler &prm);

  /**
   * Loads each library (dlopen, symbols resolved at once). A library that cannot be
   * loaded throws ExcBadInput naming the entry, the path and the loader's message.
   * Loading the same library twice is harmless: the loader keeps one copy and its
   * plug-ins register once. A library that registers a name already taken (by the
   * lme-mpm library or a library loaded before) throws ExcBadInput naming both.
   */
  static void load(const std::vector<std::string> &paths);
};
} // namespace lme_mpm

#endif
