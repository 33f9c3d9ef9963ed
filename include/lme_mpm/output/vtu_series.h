#ifndef LME_MPM_OUTPUT_VTU_SERIES_H
#define LME_MPM_OUTPUT_VTU_SERIES_H

#include <functional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace lme_mpm
{
/**
 * A time series of VTU files `<stem>_00000.vtu`, `<stem>_00001.vtu`, ... in one
 * directory and the PVD record `<stem>.pvd` that lists them, rewritten after each
 * file so that a run that stops early leaves a readable series. Every file is written
 * under a temporary name and renamed, so a reader never sees half a file.
 */
class VtuSeries
{
public:
  /// (time, file name) of each file written, in order.
  using Records = std::vector<std::pair<double, std::string>>;

  VtuSeries(const std::string &directory, const std::string &stem);

  /// Writes the next file through @p write_vtu and updates the PVD record.
  void add(double time, const std::function<void(std::ostream &)> &write_vtu);

  /**
   * A distributed run's next file: every rank writes its piece
   * `<stem>_<index>.<rank>.vtu` through @p write_piece; rank 0 also writes the
   * `<stem>_<index>.pvtu` that lists the @p n_ranks pieces (@p write_pvtu gets their
   * names) and updates the PVD record. Every rank calls it once per output.
   */
  void add_piece(double time, unsigned int rank, unsigned int n_ranks,
                 const std::function<void(std::ostream &)> &write_piece,
                 const std::function<void(std::ostream &,
                                          const std::vector<std::string> &)> &write_pvtu);

  /// The files written so far (for checkpoints), and their restoration on resume.
  const Records &records() const { return written; }
  void restore(const Records &records) { written = records; }

private:
  std::string directory, stem;
  Records written;
};
} // namespace lme_mpm

#endif
