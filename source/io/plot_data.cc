#include <pantocat/base/input_error.h>
#include <pantocat/io/csv_number.h>
#include <pantocat/io/plot_data.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>

namespace pantocat
{
std::vector<std::vector<double>> read_csv_columns(const std::string& path,
                                                  const std::vector<std::size_t>& wanted)
{
  std::ifstream in(path);
  if (!in)
    throw SimulationError("cannot read " + path);
  const std::size_t last =
      wanted.empty() ? 0 : *std::max_element(wanted.begin(), wanted.end());
  // slot[c]: where field c (1-based) goes, or wanted.size() if nowhere.
  std::vector<std::size_t> slot(last + 1, wanted.size());
  for (std::size_t k = 0; k < wanted.size(); ++k)
    slot[wanted[k]] = k;
  std::vector<std::vector<double>> columns(wanted.size());
  std::string line;
  std::getline(in, line); // the header
  for (std::size_t row = 2; std::getline(in, line); ++row)
  {
    if (line.empty())
      continue;
    const char* p = line.data();
    const char* const end = p + line.size();
    std::size_t c = 1;
    for (; c <= last; ++c)
    {
      const char* comma = std::find(p, end, ',');
      if (slot[c] < wanted.size())
      {
        double value = std::numeric_limits<double>::quiet_NaN();
        std::from_chars(p, comma, value);
        columns[slot[c]].push_back(value);
      }
      if (comma == end)
        break;
      p = comma + 1;
    }
    if (c < last)
      throw SimulationError(path + ", line " + std::to_string(row) + ": " +
                            std::to_string(c) + " fields, expected at least " +
                            std::to_string(last));
  }
  return columns;
}

PlotCurve envelope(const std::vector<double>& x, const std::vector<double>& y,
                   const unsigned int bins)
{
  PlotCurve curve;
  std::vector<std::size_t> points;
  for (std::size_t i = 0; i < x.size() && i < y.size(); ++i)
    if (std::isfinite(x[i]) && std::isfinite(y[i]))
      points.push_back(i);
  if (points.size() > 2 * static_cast<std::size_t>(bins) + 2)
  {
    double x0 = x[points.front()], x1 = x0;
    for (const std::size_t i : points)
    {
      x0 = std::min(x0, x[i]);
      x1 = std::max(x1, x[i]);
    }
    const double scale = x1 > x0 ? bins / (x1 - x0) : 0.;
    const auto bin_of = [&](const std::size_t i)
    { return std::min<long>(bins - 1, static_cast<long>((x[i] - x0) * scale)); };
    std::vector<std::size_t> kept{points.front()};
    // A bin is a run of consecutive points in one bin: x need not be monotone.
    for (std::size_t k = 0; k < points.size();)
    {
      const long bin = bin_of(points[k]);
      std::size_t low = points[k], high = points[k];
      for (; k < points.size() && bin_of(points[k]) == bin; ++k)
      {
        if (y[points[k]] < y[low])
          low = points[k];
        if (y[points[k]] > y[high])
          high = points[k];
      }
      kept.push_back(std::min(low, high));
      kept.push_back(std::max(low, high));
    }
    kept.push_back(points.back());
    kept.erase(std::unique(kept.begin(), kept.end()), kept.end());
    points = std::move(kept);
  }
  for (const std::size_t i : points)
  {
    curve.x.push_back(x[i]);
    curve.y.push_back(y[i]);
  }
  return curve;
}

void write_datablock(std::ostream& gp, const std::string& name, const PlotCurve& curve)
{
  // The numbers as a stream with precision 10 writes them (append_csv_number()).
  std::string block = '$' + name + " << EOD\n";
  block.reserve(block.size() + 36 * curve.x.size() + 4);
  for (std::size_t i = 0; i < curve.x.size(); ++i)
  {
    append_csv_number(block, curve.x[i]);
    block += ' ';
    append_csv_number(block, curve.y[i]);
    block += '\n';
  }
  block += "EOD\n";
  gp.write(block.data(), static_cast<std::streamsize>(block.size()));
}
} // namespace pantocat
