#include "linalg/BlockMatrixCopy.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace indentsim::linalg
{
  namespace
  {
    void check(const PetscErrorCode code, const char *what)
    {
      if (code != 0)
        throw std::runtime_error(std::string("BlockMatrixCopy: PETSc call failed: ") + what +
                                 " (error " + std::to_string(code) + ")");
    }

    constexpr PetscInt block_size = 3;

    // Compressed sparse rows of a sequential matrix: of its entries (AIJ, compressed = false)
    // or of its blocks (BAIJ, compressed = true; for AIJ it would mean its i-node groups).
    struct Csr
    {
      Mat             matrix = nullptr;
      PetscBool       compressed = PETSC_FALSE;
      PetscInt        n_rows = 0;
      const PetscInt *row_start = nullptr, *columns = nullptr;
      Csr(Mat m, const bool blocks)
        : matrix(m)
        , compressed(blocks ? PETSC_TRUE : PETSC_FALSE)
      {
        PetscBool done = PETSC_FALSE;
        check(MatGetRowIJ(matrix, 0, PETSC_FALSE, compressed, &n_rows, &row_start, &columns, &done),
              "MatGetRowIJ");
        if (!done)
          throw std::runtime_error("BlockMatrixCopy: MatGetRowIJ not available");
      }
      ~Csr()
      {
        PetscBool done = PETSC_FALSE;
        MatRestoreRowIJ(matrix, 0, PETSC_FALSE, compressed, &n_rows, &row_start, &columns, &done);
      }
      Csr(const Csr &) = delete;
      Csr &operator=(const Csr &) = delete;
    };
  } // namespace

  BlockMatrixCopy::~BlockMatrixCopy()
  {
    clear();
  }

  void BlockMatrixCopy::clear()
  {
    if (copy_ != nullptr)
      MatDestroy(&copy_);
    copy_ = nullptr;
    source_id_ = 0;
    diagonal_map_.clear();
    off_diagonal_map_.clear();
  }

  void BlockMatrixCopy::build(const Mat source)
  {
    clear();
    MPI_Comm communicator;
    check(PetscObjectGetComm(reinterpret_cast<PetscObject>(source), &communicator),
          "PetscObjectGetComm");
    PetscInt row_begin, row_end, column_begin, column_end, n_rows_global, n_columns_global;
    check(MatGetOwnershipRange(source, &row_begin, &row_end), "MatGetOwnershipRange");
    check(MatGetOwnershipRangeColumn(source, &column_begin, &column_end),
          "MatGetOwnershipRangeColumn");
    check(MatGetSize(source, &n_rows_global, &n_columns_global), "MatGetSize");
    if (row_begin % block_size != 0 || row_end % block_size != 0 ||
        column_begin % block_size != 0 || column_end % block_size != 0)
      throw std::runtime_error("BlockMatrixCopy: the rows of a rank are not whole nodes");

    Mat             diagonal, off_diagonal;
    const PetscInt *off_diagonal_columns; // global column of each off-diagonal block column
    check(MatMPIAIJGetSeqAIJ(source, &diagonal, &off_diagonal, &off_diagonal_columns),
          "MatMPIAIJGetSeqAIJ");
    const PetscInt        n_local_rows = row_end - row_begin;
    const PetscInt        n_block_rows = n_local_rows / block_size;
    std::vector<PetscInt> marker_columns;
    std::vector<double>   markers;
    PetscInt              n_diagonal_values = 0, n_off_diagonal_values = 0;
    {
      const Csr d(diagonal, false), o(off_diagonal, false);
      n_diagonal_values = d.row_start[d.n_rows];
      n_off_diagonal_values = o.row_start[o.n_rows];
      if (std::max(n_diagonal_values, n_off_diagonal_values) >
          std::numeric_limits<std::int32_t>::max() / 2 - 2)
        throw std::runtime_error("BlockMatrixCopy: too many entries on one rank");

      // Preallocation: the distinct block columns of each block row, in the diagonal part
      // (owned columns) and the off-diagonal part.
      std::vector<PetscInt> diagonal_blocks(n_block_rows), off_diagonal_blocks(n_block_rows);
      std::vector<PetscInt> scratch;
      for (PetscInt block_row = 0; block_row < n_block_rows; ++block_row)
        {
          const auto count = [&](const Csr &csr, const bool off) {
            scratch.clear();
            for (PetscInt r = block_row * block_size; r < (block_row + 1) * block_size; ++r)
              for (PetscInt k = csr.row_start[r]; k < csr.row_start[r + 1]; ++k)
                scratch.push_back((off ? off_diagonal_columns[csr.columns[k]] : csr.columns[k]) /
                                  block_size);
            std::sort(scratch.begin(), scratch.end());
            return static_cast<PetscInt>(std::unique(scratch.begin(), scratch.end()) -
                                         scratch.begin());
          };
          diagonal_blocks[block_row] = count(d, false);
          off_diagonal_blocks[block_row] = count(o, true);
        }
      // MPIBAIJ also on one rank (MatCreateBAIJ would make it SeqBAIJ), as the source is
      // MPIAIJ there too.
      check(MatCreate(communicator, &copy_), "MatCreate");
      check(MatSetSizes(copy_, n_local_rows, column_end - column_begin, n_rows_global,
                        n_columns_global),
            "MatSetSizes");
      check(MatSetBlockSize(copy_, block_size), "MatSetBlockSize");
      check(MatSetType(copy_, MATMPIBAIJ), "MatSetType");
      check(MatMPIBAIJSetPreallocation(copy_, block_size, 0, diagonal_blocks.data(), 0,
                                       off_diagonal_blocks.data()),
            "MatMPIBAIJSetPreallocation");
      check(MatSetOption(copy_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "MatSetOption");

      // Every entry of the source gets its position number (1-based; off-diagonal ones after
      // the diagonal ones) as value: exact in a double.
      for (PetscInt r = 0; r < n_local_rows; ++r)
        {
          marker_columns.clear();
          markers.clear();
          for (PetscInt k = d.row_start[r]; k < d.row_start[r + 1]; ++k)
            {
              marker_columns.push_back(column_begin + d.columns[k]);
              markers.push_back(static_cast<double>(k + 1));
            }
          for (PetscInt k = o.row_start[r]; k < o.row_start[r + 1]; ++k)
            {
              marker_columns.push_back(off_diagonal_columns[o.columns[k]]);
              markers.push_back(static_cast<double>(n_diagonal_values + k + 1));
            }
          const PetscInt row = row_begin + r;
          check(MatSetValues(copy_, 1, &row, static_cast<PetscInt>(marker_columns.size()),
                             marker_columns.data(), markers.data(), INSERT_VALUES),
                "MatSetValues");
        }
    }
    check(MatAssemblyBegin(copy_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(copy_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");

    // Read the markers back in the copy's storage order.
    Mat copy_diagonal, copy_off_diagonal;
    check(MatMPIBAIJGetSeqBAIJ(copy_, &copy_diagonal, &copy_off_diagonal, nullptr),
          "MatMPIBAIJGetSeqBAIJ");
    const auto read_map = [&](const Mat block, std::vector<std::int32_t> &map) {
      PetscInt n_blocks = 0;
      {
        const Csr csr(block, true);
        n_blocks = csr.row_start[csr.n_rows];
      }
      PetscScalar *values;
      check(MatSeqBAIJGetArray(block, &values), "MatSeqBAIJGetArray");
      map.resize(static_cast<std::size_t>(n_blocks) * block_size * block_size);
      for (std::size_t q = 0; q < map.size(); ++q)
        {
          const auto marker = static_cast<std::int64_t>(values[q]);
          map[q] = marker == 0 ? -1
                   : marker <= n_diagonal_values
                       ? static_cast<std::int32_t>(marker - 1)
                       : static_cast<std::int32_t>(-2 - (marker - 1 - n_diagonal_values));
        }
      check(MatSeqBAIJRestoreArray(block, &values), "MatSeqBAIJRestoreArray");
    };
    read_map(copy_diagonal, diagonal_map_);
    read_map(copy_off_diagonal, off_diagonal_map_);
    // Every source entry must have found its place exactly once.
    std::vector<unsigned char> seen(n_diagonal_values + n_off_diagonal_values, 0);
    for (const auto *map : {&diagonal_map_, &off_diagonal_map_})
      for (const std::int32_t k : *map)
        if (k != -1)
          ++seen[k >= 0 ? k : n_diagonal_values + (-2 - k)];
    if (std::any_of(seen.begin(), seen.end(), [](unsigned char s) { return s != 1; }))
      throw std::runtime_error("BlockMatrixCopy: the block copy does not hold the pattern");
    check(PetscObjectGetId(reinterpret_cast<PetscObject>(source), &source_id_), "PetscObjectGetId");
    check(MatGetNonzeroState(source, &source_nonzero_state_), "MatGetNonzeroState");
  }

  Mat BlockMatrixCopy::update(const Mat source)
  {
    PetscObjectState nonzero_state;
    PetscObjectId    id;
    check(MatGetNonzeroState(source, &nonzero_state), "MatGetNonzeroState");
    // The object's id, not its address: a new matrix can take the address of a destroyed one.
    check(PetscObjectGetId(reinterpret_cast<PetscObject>(source), &id), "PetscObjectGetId");
    // Collective decision: every rank rebuilds if one must.
    MPI_Comm communicator;
    check(PetscObjectGetComm(reinterpret_cast<PetscObject>(source), &communicator),
          "PetscObjectGetComm");
    int must_build = copy_ == nullptr || id != source_id_ || nonzero_state != source_nonzero_state_;
    MPI_Allreduce(MPI_IN_PLACE, &must_build, 1, MPI_INT, MPI_MAX, communicator);
    if (must_build)
      build(source);

    Mat diagonal, off_diagonal;
    check(MatMPIAIJGetSeqAIJ(source, &diagonal, &off_diagonal, nullptr), "MatMPIAIJGetSeqAIJ");
    const PetscScalar *diagonal_values, *off_diagonal_values;
    check(MatSeqAIJGetArrayRead(diagonal, &diagonal_values), "MatSeqAIJGetArrayRead");
    check(MatSeqAIJGetArrayRead(off_diagonal, &off_diagonal_values), "MatSeqAIJGetArrayRead");
    Mat copy_diagonal, copy_off_diagonal;
    check(MatMPIBAIJGetSeqBAIJ(copy_, &copy_diagonal, &copy_off_diagonal, nullptr),
          "MatMPIBAIJGetSeqBAIJ");
    const auto fill = [&](const Mat block, const std::vector<std::int32_t> &map) {
      PetscScalar *values;
      check(MatSeqBAIJGetArray(block, &values), "MatSeqBAIJGetArray");
      const std::size_t n = map.size();
      for (std::size_t q = 0; q < n; ++q)
        {
          const std::int32_t k = map[q];
          values[q] = k >= 0 ? diagonal_values[k] : k == -1 ? 0.0 : off_diagonal_values[-2 - k];
        }
      check(MatSeqBAIJRestoreArray(block, &values), "MatSeqBAIJRestoreArray");
    };
    fill(copy_diagonal, diagonal_map_);
    fill(copy_off_diagonal, off_diagonal_map_);
    check(MatSeqAIJRestoreArrayRead(diagonal, &diagonal_values), "MatSeqAIJRestoreArrayRead");
    check(MatSeqAIJRestoreArrayRead(off_diagonal, &off_diagonal_values),
          "MatSeqAIJRestoreArrayRead");
    // Marks the parallel matrix as changed (its state), so that a solver sees new values; no
    // entries are stashed, so nothing is communicated but the assembly's reduction.
    check(MatAssemblyBegin(copy_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(copy_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    return copy_;
  }
} // namespace indentsim::linalg
