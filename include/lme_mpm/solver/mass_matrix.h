#ifndef LME_MPM_SOLVER_MASS_MATRIX_H
#define LME_MPM_SOLVER_MASS_MATRIX_H

#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>

#include <lme_mpm/base/dealii.h>
#include <lme_mpm/base/rank_reductions.h>
#include <lme_mpm/grid/field_layout.h>
#include <lme_mpm/shape_functions/shape_function.h>

#include <cstddef>
#include <memory>
#include <vector>

class Epetra_Comm;
class Epetra_CrsMatrix;
class Epetra_Import;
class Epetra_Map;
class Epetra_MultiVector;

namespace lme_mpm
{
/**
 * The consistent mass matrix M_C = sum_p m_p N_Ip N_Jp of one step, assembled from
 * the particles' connectivity into a distributed sparse matrix of Trilinos (Epetra)
 * and applied to nodal vectors of Tensor<1,dim> as dim columns of one multivector.
 *
 * Rows are the velocity fields with mass of the grid nodes this rank reports
 * (RankReductions::owns_node()): the halo holds every particle near such a node, so
 * its row is complete here and no entry is sent to another rank. A field's global
 * index is its grid node plus the grid's node count times a slot of its tag (the
 * node's own field, the far side of a crack, a body), the same on every rank
 * whatever order the fields were created in. Epetra stores the rows, builds the
 * column map and fetches the columns other ranks own before each product, which then
 * runs over Epetra's compressed rows on the threads, reading and writing the nodal
 * vectors in place (Epetra's own product is serial and needs copies into its
 * multivectors). Without MPI started (a test, a library user) it runs on Epetra's
 * serial communicator. deal.II's Trilinos wrappers are not used because they apply
 * a matrix to one vector at a time and need MPI started.
 *
 * Each row is summed by one thread over its particles in their store order, so the
 * matrix does not depend on the thread count.
 */
template <int dim>
class ConsistentMassMatrix
{
public:
  ConsistentMassMatrix();
  ~ConsistentMassMatrix();

  /// Distributed runs: the ranks' node ownership and communicator (before assembly).
  void set_ranks(const RankReductions &ranks, MPI_Comm comm);

  /**
   * Assembles the rows of the @p active fields of @p layout that this rank reports,
   * from every particle of @p conn (owned and ghosts) with masses @p particle_mass.
   */
  void assemble(const Connectivity<dim> &conn, const std::vector<double> &particle_mass,
                const FieldLayout &layout, const std::vector<unsigned int> &active);

  /// The fields of this rank's rows, in the order of their global indices.
  const std::vector<unsigned int> &rows() const { return row_fields; }
  /// y = M_C x on this rank's rows (x read on its rows; other ranks send the rest).
  void vmult(const std::vector<Tensor<1, dim>> &x, std::vector<Tensor<1, dim>> &y) const;
  /// Copies the values of the active fields this rank does not report from the rank
  /// that does (the solution a rank's particles read).
  void distribute(std::vector<Tensor<1, dim>> &x) const;
  /// The sum over the ranks.
  double sum(double v) const;
  /// The sums over the ranks, element by element, in place.
  void sum(std::vector<double> &v) const;

  /// The entry (I, J) of fields of this rank's row I (zero where not stored): tests.
  double entry(unsigned int I, unsigned int J) const;
  /// Stored entries of this rank's rows.
  std::size_t n_nonzeros() const;

private:
  /// One block of rows: the entries of each row (field, value), concatenated.
  struct RowBlock
  {
    std::vector<unsigned int> length, field;
    std::vector<double> value;
  };

  /// This rank's rows, the other active fields and the tags' slots.
  void number_rows(const FieldLayout &layout, const std::vector<unsigned int> &active);
  /// The particle-node pairs of each row, in particle order.
  void gather_pairs(const Connectivity<dim> &conn);
  /// The entries of every row, in blocks of rows summed on the threads.
  std::vector<RowBlock> sum_rows(const Connectivity<dim> &conn,
                                 const std::vector<double> &particle_mass,
                                 unsigned int n_fields) const;
  /// The Epetra maps, matrix and imports from the rows' entries.
  void fill(const FieldLayout &layout, const std::vector<RowBlock> &blocks);
  /// The global index of field F (see the class).
  int global_index(const FieldLayout &layout, unsigned int F) const;
  void copy_in(const std::vector<Tensor<1, dim>> &x, Epetra_MultiVector &v,
               const std::vector<unsigned int> &fields) const;
  void copy_out(const Epetra_MultiVector &v, std::vector<Tensor<1, dim>> &x,
                const std::vector<unsigned int> &fields) const;

  const RankReductions *ranks = nullptr;
  MPI_Comm comm               = MPI_COMM_SELF;
  std::unique_ptr<Epetra_Comm> epetra_comm;
  std::unique_ptr<Epetra_Map> row_map, column_map, ghost_map;
  std::unique_ptr<Epetra_CrsMatrix> matrix;
  std::unique_ptr<Epetra_Import> ghost_import, column_import;
  mutable std::unique_ptr<Epetra_MultiVector> x_vector, column_vector, ghost_vector;
  /// The values of the columns, in column order, for one product.
  mutable std::vector<Tensor<1, dim>> column_values;
  std::vector<unsigned int> row_fields, ghost_fields;
  /// Local row of each field (invalid if not a row).
  std::vector<unsigned int> row_of;

  /// The particle-node pairs (connectivity slots) of each row.
  std::vector<std::size_t> pair_offset, pair_index;
  std::vector<int> column_gid;
};
} // namespace lme_mpm

#endif
