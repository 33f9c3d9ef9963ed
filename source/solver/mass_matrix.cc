#include <deal.II/base/thread_local_storage.h>

#include <lme_mpm/base/parallel.h>
#include <lme_mpm/solver/mass_matrix.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_Import.h>
#include <Epetra_Map.h>
#include <Epetra_MultiVector.h>
#include <Epetra_SerialComm.h>
#ifdef DEAL_II_WITH_MPI
#include <Epetra_MpiComm.h>
#endif

#include <algorithm>
#include <climits>
#include <numeric>
#include <string>

namespace lme_mpm
{
namespace
{
/// Throws with @p what if an Epetra call returned an error code.
void check(const int code, const char *what)
{
  AssertThrow(code == 0, ExcMessage(std::string("Trilinos (Epetra) failed in ") + what +
                                    " with code " + std::to_string(code)));
}

/// Rows summed by one task: few enough to spread over the threads.
constexpr std::size_t row_block = 256;

/// One thread's dense row: values and a flag per field, and the fields touched.
struct RowScratch
{
  std::vector<double> value;
  std::vector<std::uint8_t> seen;
  std::vector<unsigned int> touched;
};

} // namespace

template <int dim>
ConsistentMassMatrix<dim>::ConsistentMassMatrix()
    : epetra_comm(std::make_unique<Epetra_SerialComm>())
{
}

template <int dim>
ConsistentMassMatrix<dim>::~ConsistentMassMatrix() = default;

template <int dim>
void ConsistentMassMatrix<dim>::set_ranks(const RankReductions &r, MPI_Comm c)
{
  ranks = &r;
  comm  = c;
#ifdef DEAL_II_WITH_MPI
  if (Utilities::MPI::job_supports_mpi())
    epetra_comm = std::make_unique<Epetra_MpiComm>(comm);
#endif
}

template <int dim>
int ConsistentMassMatrix<dim>::global_index(const FieldLayout &layout,
                                            const unsigned int F) const
{
  const unsigned int tag  = layout.tag_of(F);
  const unsigned int slot = tag == FieldLayout::invalid      ? 0
                            : tag == FieldLayout::crack_side ? 1
                                                             : tag + 2;
  return int(layout.node_of(F) + std::size_t(layout.n_grid_nodes()) * slot);
}

template <int dim>
void ConsistentMassMatrix<dim>::assemble(const Connectivity<dim> &conn,
                                         const std::vector<double> &particle_mass,
                                         const FieldLayout &layout,
                                         const std::vector<unsigned int> &active)
{
  number_rows(layout, active);
  gather_pairs(conn);
  fill(layout, sum_rows(conn, particle_mass, layout.n_fields()));
}

template <int dim>
void ConsistentMassMatrix<dim>::number_rows(const FieldLayout &layout,
                                            const std::vector<unsigned int> &active)
{
  // The slots of the tags, agreed over the ranks so that global indices match.
  unsigned int top = 0;
  for (const unsigned int F : active)
  {
    const unsigned int tag = layout.tag_of(F);
    if (tag != FieldLayout::invalid)
      top = std::max(top, tag == FieldLayout::crack_side ? 1u : tag + 2);
  }
  const unsigned int n_slots = 1 + (ranks ? unsigned(ranks->max(double(top))) : top);
  AssertThrow(std::size_t(layout.n_grid_nodes()) * n_slots < std::size_t(INT_MAX),
              ExcMessage("The consistent mass matrix numbers its rows with 32-bit "
                         "indices: " +
                         std::to_string(layout.n_grid_nodes()) + " grid nodes times " +
                         std::to_string(n_slots) + " fields per node is too many"));

  // This rank's rows and the other active fields, each in global order.
  const auto by_index = [&](const unsigned int a, const unsigned int b)
  { return global_index(layout, a) < global_index(layout, b); };
  row_fields.clear();
  ghost_fields.clear();
  for (const unsigned int F : active)
    (!ranks || ranks->owns_node(layout.node_of(F)) ? row_fields : ghost_fields)
        .push_back(F);
  std::sort(row_fields.begin(), row_fields.end(), by_index);
  std::sort(ghost_fields.begin(), ghost_fields.end(), by_index);
  row_of.assign(layout.n_fields(), FieldLayout::invalid);
  for (unsigned int r = 0; r < row_fields.size(); ++r)
    row_of[row_fields[r]] = r;
}

template <int dim>
void ConsistentMassMatrix<dim>::gather_pairs(const Connectivity<dim> &conn)
{
  // The particle-node pairs of each row, in particle order (a counting sort).
  const std::size_t n_rows = row_fields.size(), n_particles = conn.n_nodes.size();
  pair_offset.assign(n_rows + 1, 0);
  for (std::size_t p = 0; p < n_particles; ++p)
    for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
    {
      const unsigned int r = row_of[conn.nodes[p * conn.stride + k]];
      if (r != FieldLayout::invalid)
        ++pair_offset[r + 1];
    }
  std::partial_sum(pair_offset.begin(), pair_offset.end(), pair_offset.begin());
  pair_index.resize(pair_offset.back());
  std::vector<std::size_t> next(pair_offset.begin(), pair_offset.end() - 1);
  for (std::size_t p = 0; p < n_particles; ++p)
    for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
    {
      const std::size_t s  = p * conn.stride + k;
      const unsigned int r = row_of[conn.nodes[s]];
      if (r != FieldLayout::invalid)
        pair_index[next[r]++] = s;
    }
}

template <int dim>
std::vector<typename ConsistentMassMatrix<dim>::RowBlock>
ConsistentMassMatrix<dim>::sum_rows(const Connectivity<dim> &conn,
                                    const std::vector<double> &particle_mass,
                                    const unsigned int n_fields) const
{
  // Each row summed by one thread over its particles in order: m_p N_Ip N_Jp.
  const std::size_t n_rows   = row_fields.size();
  const std::size_t n_blocks = (n_rows + row_block - 1) / row_block;
  std::vector<RowBlock> blocks(n_blocks);
  dealii::Threads::ThreadLocalStorage<RowScratch> scratch;
  parallel::for_range(
      n_blocks,
      [&](const std::size_t b0, const std::size_t b1)
      {
        RowScratch &s = scratch.get();
        if (s.value.size() < n_fields)
          s.value.resize(n_fields), s.seen.resize(n_fields, 0);
        for (std::size_t b = b0; b < b1; ++b)
          for (std::size_t r = b * row_block; r < std::min(n_rows, (b + 1) * row_block);
               ++r)
          {
            s.touched.clear();
            for (std::size_t i = pair_offset[r]; i < pair_offset[r + 1]; ++i)
            {
              const std::size_t slot = pair_index[i];
              const std::size_t p = slot / conn.stride, o = p * conn.stride;
              const double w = particle_mass[p] * conn.N[slot];
              for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
              {
                const unsigned int J = conn.nodes[o + k];
                if (!s.seen[J])
                  s.seen[J] = 1, s.value[J] = 0, s.touched.push_back(J);
                s.value[J] += w * conn.N[o + k];
              }
            }
            blocks[b].length.push_back(s.touched.size());
            for (const unsigned int J : s.touched)
            {
              blocks[b].field.push_back(J);
              blocks[b].value.push_back(s.value[J]);
              s.seen[J] = 0;
            }
          }
      });
  return blocks;
}

template <int dim>
void ConsistentMassMatrix<dim>::fill(const FieldLayout &layout,
                                     const std::vector<RowBlock> &blocks)
{
  // The column map: this rank's rows, then the other ranks' columns in global order.
  const std::size_t n_rows = row_fields.size();
  std::vector<int> row_gid(n_rows);
  for (std::size_t r = 0; r < n_rows; ++r)
    row_gid[r] = global_index(layout, row_fields[r]);
  std::vector<unsigned int> column_of(layout.n_fields(), FieldLayout::invalid);
  column_gid = row_gid;
  for (std::size_t r = 0; r < n_rows; ++r)
    column_of[row_fields[r]] = r;
  std::vector<unsigned int> others;
  for (const RowBlock &block : blocks)
    for (const unsigned int J : block.field)
      if (column_of[J] == FieldLayout::invalid)
        column_of[J] = 0, others.push_back(J);
  std::sort(others.begin(), others.end(),
            [&](const unsigned int a, const unsigned int b)
            { return global_index(layout, a) < global_index(layout, b); });
  for (const unsigned int J : others)
  {
    column_of[J] = column_gid.size();
    column_gid.push_back(global_index(layout, J));
  }
  row_map =
      std::make_unique<Epetra_Map>(-1, int(n_rows), row_gid.data(), 0, *epetra_comm);
  column_map = std::make_unique<Epetra_Map>(-1, int(column_gid.size()), column_gid.data(),
                                            0, *epetra_comm);

  std::vector<int> lengths;
  for (const RowBlock &block : blocks)
    lengths.insert(lengths.end(), block.length.begin(), block.length.end());
  matrix = std::make_unique<Epetra_CrsMatrix>(Copy, *row_map, *column_map, lengths.data(),
                                              true);
  std::vector<int> columns;
  std::size_t r = 0;
  for (const RowBlock &block : blocks)
    for (std::size_t e = 0, k = 0; k < block.length.size(); e += block.length[k++], ++r)
    {
      columns.resize(block.length[k]);
      for (std::size_t c = 0; c < columns.size(); ++c)
        columns[c] = int(column_of[block.field[e + c]]);
      check(matrix->InsertMyValues(int(r), int(columns.size()), block.value.data() + e,
                                   columns.data()),
            "InsertMyValues");
    }
  check(matrix->FillComplete(*row_map, *row_map), "FillComplete");

  x_vector = std::make_unique<Epetra_MultiVector>(*row_map, dim, false);
  // Imports are collective: every rank of several builds and calls them.
  if (epetra_comm->NumProc() > 1)
  {
    column_import = std::make_unique<Epetra_Import>(*column_map, *row_map);
    column_vector = std::make_unique<Epetra_MultiVector>(*column_map, dim, false);
  }
  std::vector<int> ghost_gid(ghost_fields.size());
  for (std::size_t g = 0; g < ghost_fields.size(); ++g)
    ghost_gid[g] = global_index(layout, ghost_fields[g]);
  ghost_map = std::make_unique<Epetra_Map>(-1, int(ghost_gid.size()), ghost_gid.data(), 0,
                                           *epetra_comm);
  ghost_import = std::make_unique<Epetra_Import>(*ghost_map, *row_map);
  ghost_vector = std::make_unique<Epetra_MultiVector>(*ghost_map, dim, false);
}

template <int dim>
void ConsistentMassMatrix<dim>::copy_in(const std::vector<Tensor<1, dim>> &x,
                                        Epetra_MultiVector &v,
                                        const std::vector<unsigned int> &fields) const
{
  for (unsigned int d = 0; d < dim; ++d)
  {
    double *column = v[d];
    for (std::size_t r = 0; r < fields.size(); ++r)
      column[r] = x[fields[r]][d];
  }
}

template <int dim>
void ConsistentMassMatrix<dim>::copy_out(const Epetra_MultiVector &v,
                                         std::vector<Tensor<1, dim>> &x,
                                         const std::vector<unsigned int> &fields) const
{
  for (unsigned int d = 0; d < dim; ++d)
  {
    const double *column = v[d];
    for (std::size_t r = 0; r < fields.size(); ++r)
      x[fields[r]][d] = column[r];
  }
}

template <int dim>
void ConsistentMassMatrix<dim>::vmult(const std::vector<Tensor<1, dim>> &x,
                                      std::vector<Tensor<1, dim>> &y) const
{
  // Epetra brings the other ranks' columns; the product itself reads and writes the
  // nodal vectors in place, its rows spread over the threads (each row summed by one
  // thread in its stored order: the result does not depend on the thread count).
  const std::size_t n_rows = row_fields.size();
  // The columns side by side in column order, so the rows read them directly.
  column_values.resize(column_gid.size());
  for (std::size_t j = 0; j < n_rows; ++j)
    column_values[j] = x[row_fields[j]];
  if (column_import)
  {
    copy_in(x, *x_vector, row_fields);
    check(column_vector->Import(*x_vector, *column_import, Insert), "Import");
    for (unsigned int d = 0; d < dim; ++d)
    {
      const double *column = (*column_vector)[d];
      for (std::size_t j = n_rows; j < column_gid.size(); ++j)
        column_values[j][d] = column[j];
    }
  }
  int *offset = nullptr, *index = nullptr;
  double *value = nullptr;
  check(matrix->ExtractCrsDataPointers(offset, index, value), "ExtractCrsDataPointers");
  const Tensor<1, dim> *const xs = column_values.data();
  parallel::for_range(n_rows,
                      [&](const std::size_t b, const std::size_t e)
                      {
                        for (std::size_t r = b; r < e; ++r)
                        {
                          Tensor<1, dim> sum;
                          for (int k = offset[r]; k < offset[r + 1]; ++k)
                            sum += value[k] * xs[index[k]];
                          y[row_fields[r]] = sum;
                        }
                      });
}

template <int dim>
void ConsistentMassMatrix<dim>::distribute(std::vector<Tensor<1, dim>> &x) const
{
  if (epetra_comm->NumProc() == 1)
    return;
  copy_in(x, *x_vector, row_fields);
  check(ghost_vector->Import(*x_vector, *ghost_import, Insert), "Import");
  copy_out(*ghost_vector, x, ghost_fields);
}

template <int dim>
double ConsistentMassMatrix<dim>::sum(const double v) const
{
  return ranks ? ranks->sum(v) : v;
}

template <int dim>
void ConsistentMassMatrix<dim>::sum(std::vector<double> &v) const
{
  if (ranks)
    ranks->sum(v);
}

template <int dim>
double ConsistentMassMatrix<dim>::entry(const unsigned int I, const unsigned int J) const
{
  if (I >= row_of.size() || row_of[I] == FieldLayout::invalid || J >= row_of.size())
    return 0;
  int n          = 0;
  double *values = nullptr;
  int *columns   = nullptr;
  check(matrix->ExtractMyRowView(int(row_of[I]), n, values, columns), "ExtractMyRowView");
  for (int k = 0; k < n; ++k)
    if (unsigned(columns[k]) < row_fields.size() && row_fields[columns[k]] == J)
      return values[k];
  return 0;
}

template <int dim>
std::size_t ConsistentMassMatrix<dim>::n_nonzeros() const
{
  return matrix ? std::size_t(matrix->NumMyNonzeros()) : 0;
}

template class ConsistentMassMatrix<2>;
template class ConsistentMassMatrix<3>;
} // namespace lme_mpm
