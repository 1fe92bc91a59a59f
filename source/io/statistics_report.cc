#include <pantocat/io/atomic_file.h>
#include <pantocat/io/statistics_report.h>

#include <pantocat/base/input_error.h>

#include <fstream>
#include <iomanip>
#include <sstream>

namespace pantocat
{
void write_statistics(JsonWriter& json, const ContactForceStatistics& s)
{
  json.begin_object("statistics")
      .value("mean", s.mean)
      .value("std", s.std)
      .value("mean_minus_3_sigma", s.mean_minus_3_sigma)
      .value("mean_plus_3_sigma", s.mean_plus_3_sigma)
      .value("max", s.max)
      .value("min", s.min)
      .value("percent_without_contact", s.percent_without_contact);
  json.begin_array("max_uplift_at_droppers");
  for (const double uplift : s.max_uplift_at_droppers)
    json.value("", uplift);
  json.end_array();
  json.value("filter_cutoff_hz", s.filter_cutoff_hz);
  json.begin_array("window")
      .value("", s.window_start)
      .value("", s.window_end)
      .end_array();
  json.end_object();
}

void write_contact_force(const std::string& file, const ContactStatistics& statistics)
{
  const ContactForceSeries& s = statistics.series();
  const std::vector<double>& filtered = statistics.filtered_force();
  std::ostringstream csv;
  csv << "t,x_p,lambda_p,lambda_p_filtered\n" << std::setprecision(10);
  for (std::size_t n = 0; n < s.t.size(); ++n)
    csv << s.t[n] << ',' << s.x_p[n] << ',' << s.lambda_p[n] << ',' << filtered[n]
        << '\n';
  write_file_atomically(file, csv.str());
}

void print_statistics(std::ostream& out, const ContactForceStatistics& s)
{
  if (s.n_points == 0)
  {
    out << "  contact-force statistics: no time point in the window\n";
    return;
  }
  const auto flags = out.flags();
  const auto precision = out.precision();
  out << "  contact-force statistics ("
      << (s.filter_cutoff_hz > 0. ? "low pass " : "unfiltered");
  if (s.filter_cutoff_hz > 0.)
    out << s.filter_cutoff_hz << " Hz";
  out << ", x_p in [" << std::setprecision(4) << s.window_start << ", " << s.window_end
      << "] m):\n"
      << std::fixed << std::setprecision(2) << "    mean " << s.mean << " N, std "
      << s.std << " N, mean - 3 sigma " << s.mean_minus_3_sigma << " N, mean + 3 sigma "
      << s.mean_plus_3_sigma << " N\n"
      << "    max " << s.max << " N, min " << s.min << " N, without contact "
      << s.percent_without_contact << " % of the time\n";
  if (!s.max_uplift_at_droppers.empty()) // a scene with droppers on an elastic wire
  {
    out << "    max uplift of the contact wire at the droppers:" << std::setprecision(2);
    for (std::size_t j = 0; j < s.max_uplift_at_droppers.size(); ++j)
      out << (j ? "," : "") << " " << 1000. * s.max_uplift_at_droppers[j] << " mm";
    out << '\n';
  }
  out.flags(flags);
  out.precision(precision);
}
} // namespace pantocat
