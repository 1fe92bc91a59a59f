#pragma once

#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

namespace pantocat
{
/**
 * Columns @p wanted (1-based, in the order given) of the CSV file @p path
 * whose first line is a header, one vector per column. Only the wanted
 * fields are converted. Throws SimulationError if the file cannot be read or a
 * row is shorter than the largest wanted column.
 */
std::vector<std::vector<double>> read_csv_columns(const std::string& path,
                                                  const std::vector<std::size_t>& wanted);

/// A curve to draw: its points in the order they are joined.
struct PlotCurve
{
  std::vector<double> x, y;
};

/**
 * The curve (x_i, y_i) for drawing with lines at a width of @p bins / 2
 * pixels over [x_0, x_1] = [min x, max x]: per bin of width (x_1 - x_0) / bins
 * its lowest and its highest point, in the order they come, plus the first
 * and the last point. A line through these covers, in every pixel column,
 * the same range of y as the line through all points, so the picture is the
 * same with at most 2 bins + 2 points where x does not decrease (time, x_p).
 * Where x turns back, each visit of a bin keeps its two points. Points with a
 * coordinate that is not finite are left out; a curve of at most 2 bins + 2
 * points is returned as it is.
 */
PlotCurve envelope(const std::vector<double>& x, const std::vector<double>& y,
                   unsigned int bins);

/// The points of @p curve as the gnuplot datablock $@p name (two columns,
/// each number as printf's "%.10g" writes it: write_csv_number()).
void write_datablock(std::ostream& gp, const std::string& name, const PlotCurve& curve);
} // namespace pantocat
