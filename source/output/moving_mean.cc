#include <lme_mpm/output/moving_mean.h>

#include <algorithm>

namespace lme_mpm
{
void MovingMean::reset(const unsigned int n, const double window)
{
  n_values = n;
  span     = window;
  lengths.clear();
  values.clear();
  first = 0;
  current.assign(n, 0.0);
}

void MovingMean::book(const double *v, const double dt)
{
  lengths.push_back(dt);
  values.insert(values.end(), v, v + n_values);
  // Drop the oldest steps while the rest still spans the window.
  double covered = 0;
  for (std::size_t s = first; s < lengths.size(); ++s)
    covered += lengths[s];
  while (lengths.size() - first > 1 && covered - lengths[first] >= span)
    covered -= lengths[first++];
  if (2 * first > lengths.size())
  {
    lengths.erase(lengths.begin(), lengths.begin() + first);
    values.erase(values.begin(), values.begin() + first * n_values);
    first = 0;
  }
  // Summed afresh over the window: the same bits whatever came before it.
  covered = 0;
  current.assign(n_values, 0.0);
  for (std::size_t s = first; s < lengths.size(); ++s)
  {
    covered += lengths[s];
    for (unsigned int i = 0; i < n_values; ++i)
      current[i] += lengths[s] * values[s * n_values + i];
  }
  // Over the whole window from the start: before t = 0 nothing acted, so a force that
  // starts with an impact does not read as its first step's alone.
  for (double &c : current)
    c /= std::max(covered, span);
}

void MovingMean::serialize(Archive &ar)
{
  ar(n_values, span, lengths, values, first, current);
}
} // namespace lme_mpm
