#include <lme_mpm/base/input.h>
#include <lme_mpm/base/plugin_libraries.h>
#include <lme_mpm/base/registry.h>

#include <dlfcn.h>

namespace lme_mpm
{
void PluginLibraries::declare_parameters(dealii::ParameterHandler &prm)
{
  prm.declare_entry(entry, "", dealii::Patterns::Anything(),
                    "Comma-separated paths of shared libraries with plug-ins "
                    "(materials, shape functions, softening laws, fracture models, "
                    "scenes) to load before the rest of this file is read, so that "
                    "their names can be selected here. A path with a '/' is taken "
                    "as given (relative to the working directory); a bare file "
                    "name is searched for as the system loader does "
                    "(LD_LIBRARY_PATH, the loader cache).");
}

std::vector<std::string> PluginLibraries::parse_parameters(dealii::ParameterHandler &prm)
{
  return input::split(prm.get(entry), ',');
}

RegistrationLog &registration_log()
{
  static RegistrationLog log;
  return log;
}

void PluginLibraries::load(const std::vector<std::string> &paths)
{
  RegistrationLog &log = registration_log();
  for (const auto &path : paths)
  {
    log.current = "the library '" + path + "'";
    log.refused.clear();
    // RTLD_NOW: a plug-in built against another version of the library fails here,
    // with the missing symbol named, not in the middle of a run. RTLD_GLOBAL: a
    // plug-in library may build on another one loaded before it.
    dlerror();
    if (dlopen(path.c_str(), RTLD_NOW | RTLD_GLOBAL) == nullptr)
    {
      const char *why = dlerror();
      log.current     = "the lme-mpm library";
      AssertThrow(false, ExcBadInput(entry, "cannot load '" + path + "': " +
                                                (why ? why : "unknown loader error")));
    }
    log.current = "the lme-mpm library";
    std::string refused;
    for (const auto &r : log.refused)
      refused += (refused.empty() ? "" : "; ") + r;
    AssertThrow(log.refused.empty(),
                ExcBadInput(entry, "a plug-in name clash: " + refused));
  }
}
} // namespace lme_mpm
