#pragma once

#include <deal.II/lac/vector.h>

#include <vector>

namespace pantocat
{
/**
 * A sparse row vector: a constraint gradient such as H_w, H_c or F_w(t) of
 * (31)-(33), with a few non-zeros out of many unknowns. Constraint rows have
 * distinct indices (FemCatenary::full_load_row is the one producer of
 * repeated indices, by design).
 */
struct SparseRow
{
  std::vector<unsigned int> index;
  std::vector<double> value;

  void clear()
  {
    index.clear();
    value.clear();
  }
  void add(const unsigned int i, const double v)
  {
    index.push_back(i);
    value.push_back(v);
  }
  std::size_t size() const { return index.size(); }

  /// row . x
  template <typename VectorType>
  double dot(const VectorType& x) const
  {
    double s = 0.;
    for (std::size_t k = 0; k < index.size(); ++k)
      s += value[k] * x[index[k]];
    return s;
  }
  /// y += factor * row^T
  template <typename VectorType>
  void add_transpose_to(VectorType& y, const double factor) const
  {
    for (std::size_t k = 0; k < index.size(); ++k)
      y[index[k]] += factor * value[k];
  }
  /// Shift all indices by @p offset (to place a block row in a global vector).
  void shift(const unsigned int offset)
  {
    for (auto& i : index)
      i += offset;
  }
  double sum() const
  {
    double s = 0.;
    for (double v : value)
      s += v;
    return s;
  }
};

/**
 * Many constant rows stored flat, for the loops over them every step (no
 * pointer to follow per row): row k is entries [start[k], start[k + 1]) of
 * index and value.
 */
struct CompressedRows
{
  std::vector<unsigned int> start{0}, index;
  std::vector<double> value;

  void clear()
  {
    start.assign(1, 0);
    index.clear();
    value.clear();
  }
  void push_back(const SparseRow& row)
  {
    index.insert(index.end(), row.index.begin(), row.index.end());
    value.insert(value.end(), row.value.begin(), row.value.end());
    start.push_back(index.size());
  }
  unsigned int size() const { return start.size() - 1; }
  /// row k . x, summed in SparseRow::dot()'s order.
  double dot(const unsigned int k, const double* __restrict x) const
  {
    double s = 0.;
    for (unsigned int e = start[k]; e < start[k + 1]; ++e)
      s += value[e] * x[index[e]];
    return s;
  }
  /**
   * out[j] = row k . x[j] for four vectors side by side, each summed as dot()
   * sums it (the same bits): four independent chains, where one dot() waits
   * for each addition before the next.
   */
  void dots(const unsigned int k, const double* const* x, double* out) const
  {
    double s0 = 0., s1 = 0., s2 = 0., s3 = 0.;
    const double *x0 = x[0], *x1 = x[1], *x2 = x[2], *x3 = x[3];
    for (unsigned int e = start[k]; e < start[k + 1]; ++e)
    {
      const double v = value[e];
      const unsigned int i = index[e];
      s0 += v * x0[i];
      s1 += v * x1[i];
      s2 += v * x2[i];
      s3 += v * x3[i];
    }
    out[0] = s0;
    out[1] = s1;
    out[2] = s2;
    out[3] = s3;
  }
};

/**
 * The pattern of a CompressedRows by column: the rows with an entry in
 * column j are row[start[j] .. start[j + 1]), in increasing order (e.g. the
 * fixed constraints on each unknown).
 */
struct RowsByColumn
{
  std::vector<unsigned int> start, row;

  /// From @p rows, whose entries lie in the columns [0, @p n_columns).
  void build(const CompressedRows& rows, const unsigned int n_columns)
  {
    start.assign(n_columns + 1, 0);
    for (const unsigned int j : rows.index)
      ++start[j + 1];
    for (unsigned int j = 0; j < n_columns; ++j)
      start[j + 1] += start[j];
    row.resize(start[n_columns]);
    std::vector<unsigned int> next(start.begin(), start.end() - 1);
    for (unsigned int k = 0; k < rows.size(); ++k)
      for (unsigned int e = rows.start[k]; e < rows.start[k + 1]; ++e)
        row[next[rows.index[e]]++] = k;
  }

  /**
   * The rows with an entry in one of the columns @p ranges (each [first,
   * last), e.g. a moving contact's columns' reach), into @p out, each once, in
   * the order met; @p seen (one flag per row, all 0) is workspace and left all 0.
   */
  template <typename Ranges>
  void rows_in(const Ranges& ranges, std::vector<unsigned int>& out,
               std::vector<char>& seen) const
  {
    out.clear();
    for (const auto& r : ranges)
      for (unsigned int e = start[r.first]; e < start[r.last]; ++e)
        if (!seen[row[e]])
        {
          seen[row[e]] = 1;
          out.push_back(row[e]);
        }
    for (const unsigned int k : out)
      seen[k] = 0;
  }
};
} // namespace pantocat
