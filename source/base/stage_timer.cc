#include <lme_mpm/base/stage_timer.h>

#include <cctype>
#include <iomanip>

namespace lme_mpm
{
unsigned int StageTimer::add(const std::string &name)
{
  names.push_back(name);
  elapsed.emplace_back(Clock::duration::zero());
  calls.push_back(0);
  return names.size() - 1;
}

std::map<std::string, double> StageTimer::seconds() const
{
  std::map<std::string, double> s;
  for (unsigned int i = 0; i < names.size(); ++i)
    s[names[i]] = std::chrono::duration<double>(elapsed[i]).count();
  return s;
}

void StageTimer::add_results(std::map<std::string, double> &results) const
{
  for (const auto &[name, seconds] : this->seconds())
    if (seconds > 0)
    {
      std::string key = "stage_seconds_";
      for (const char c : name)
        if (std::isalnum(static_cast<unsigned char>(c)))
          key += std::tolower(static_cast<unsigned char>(c));
        else if (key.back() != '_')
          key += '_';
      while (key.back() == '_')
        key.pop_back();
      results[key] = seconds;
    }
}

void StageTimer::print(std::ostream &out, const double total) const
{
  const std::streamsize precision = out.precision();
  std::size_t width               = 20;
  for (const auto &n : names)
    width = std::max(width, n.size());
  const std::string rule = "+" + std::string(width + 2, '-') + "+" +
                           std::string(11, '-') + "+" + std::string(12, '-') + "+" +
                           std::string(12, '-') + "+";
  out << rule << "\n| " << std::left << std::setw(width) << "Stage of a time step"
      << " | " << std::right << std::setw(9) << "calls"
      << " | " << std::setw(10) << "wall time"
      << " | " << std::setw(10) << "% of total"
      << " |\n"
      << rule << "\n";
  for (unsigned int i = 0; i < names.size(); ++i)
  {
    if (calls[i] == 0)
      continue;
    const double s = std::chrono::duration<double>(elapsed[i]).count();
    out << "| " << std::left << std::setw(width) << names[i] << " | " << std::right
        << std::setw(9) << calls[i] << " | " << std::setw(9) << std::setprecision(3) << s
        << "s | " << std::setw(9) << std::fixed << std::setprecision(1)
        << (total > 0 ? 100 * s / total : 0.0) << "% |\n"
        << std::defaultfloat;
  }
  out << rule << std::endl;
  out.precision(precision);
}
} // namespace lme_mpm
