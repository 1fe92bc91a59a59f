#include <pantocat/base/number_format.h>
#include <pantocat/base/safe_files.h>
#include <pantocat/io/elasticity_output.h>
#include <pantocat/io/plots.h>

#include <sstream>

namespace pantocat
{
namespace
{
/// "_200N": the suffix of force @p f's columns.
std::string force_suffix(const double f)
{
  return "_" + number_to_string(f) + "N";
}
} // namespace

std::vector<std::string> elasticity_columns(const StaticElasticity& e)
{
  std::vector<std::string> columns{"x", "elasticity_mm_per_N"};
  for (unsigned int f = 1; f < e.forces.size(); ++f)
    columns.push_back("elasticity_mm_per_N" + force_suffix(e.forces[f]));
  for (const double force : e.forces)
    columns.push_back("uplift_mm" + force_suffix(force));
  for (const double force : e.forces)
    columns.push_back("slackened_droppers" + force_suffix(force));
  return columns;
}

void write_elasticity_csv(const std::string& file, const StaticElasticity& e)
{
  std::ostringstream csv;
  csv.precision(12);
  const std::vector<std::string> columns = elasticity_columns(e);
  for (unsigned int c = 0; c < columns.size(); ++c)
    csv << (c > 0 ? "," : "") << columns[c];
  csv << '\n';
  std::vector<std::vector<double>> elasticity;
  for (unsigned int f = 0; f < e.forces.size(); ++f)
    elasticity.push_back(e.elasticity(f));
  for (unsigned int i = 0; i < e.x.size(); ++i)
  {
    csv << e.x[i];
    for (const auto& column : elasticity)
      csv << ',' << column[i];
    for (const auto& uplift : e.uplift)
      csv << ',' << 1000. * uplift[i];
    for (const auto& slack : e.slackened)
      csv << ',' << slack[i].size();
    csv << '\n';
  }
  write_file_atomically(file, csv.str());
}

bool plot_elasticity(const std::string& dir, const StaticElasticity& e,
                     const std::vector<double>& dropper_positions,
                     const std::string& title)
{
  const double a = e.x.front(), b = e.x.back(), margin = 0.02 * (b - a);
  std::ostringstream gp;
  begin_gnuplot_script(gp, "elasticity.gp");
  gp << "set datafile separator ','\n"
     << "set terminal pngcairo size 900,500 noenhanced\n"
     << gnuplot_output("elasticity.png") << '\n'
     << "set grid\nset key outside right\n"
     << "set xrange [" << a - margin << ":" << b + margin << "]\n"
     << "set yrange [0:*]\nset offsets 0, 0, graph 0.05, 0\n"
     << "set xlabel 'x [m]'\nset ylabel 'elasticity [mm/N]'\n"
     << "set title "
     << gnuplot_string(title + ": static elasticity of span " + std::to_string(e.span) +
                       " (supports solid, droppers dashed)")
     << '\n';
  for (const double x : {a, b})
    gp << "set arrow from " << x << ", graph 0 to " << x
       << ", graph 1 nohead lw 2 lc rgb 'black'\n"
       << "set label 'support' at " << x << ", graph 1.03 center\n";
  for (const double x : dropper_positions)
    if (x > a && x < b)
      gp << "set arrow from " << x << ", graph 0 to " << x
         << ", graph 1 nohead dashtype 2 lc rgb '#d09030'\n";
  gp << "plot ";
  for (unsigned int f = 0; f < e.forces.size(); ++f)
    gp << (f > 0 ? ", " : "") << "'elasticity.csv' using 1:" << f + 2
       << " with linespoints pt 7 ps 0.6 title "
       << gnuplot_string("F = " + number_to_string(e.forces[f]) + " N");
  gp << '\n';
  write_file_atomically(dir + "/elasticity.gp", gp.str());
  return !run_gnuplot(dir, "elasticity.gp", {"elasticity.png"}).empty();
}

void write_elasticity_summary(JsonWriter& json, const StaticElasticity& e)
{
  json.begin_object("elasticity")
      .value("span", static_cast<unsigned long>(e.span))
      .value("points", static_cast<unsigned long>(e.x.size()));
  json.begin_array("forces");
  for (unsigned int f = 0; f < e.forces.size(); ++f)
  {
    const ElasticityFigures figures = e.figures(f);
    json.begin_object()
        .value("force_N", figures.force)
        .value("e_min_mm_per_N", figures.minimum)
        .value("e_max_mm_per_N", figures.maximum)
        .value("e_mean_mm_per_N", figures.mean)
        .value("uniformity", figures.uniformity)
        .end_object();
  }
  json.end_array();
  json.end_object();
}
} // namespace pantocat
