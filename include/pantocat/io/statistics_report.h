#pragma once

#include <pantocat/io/json_writer.h>
#include <pantocat/simulation/contact_statistics.h>

#include <ostream>
#include <string>

namespace pantocat
{
/**
 * The "statistics" object of summary.json: mean, std, mean_minus_3_sigma,
 * mean_plus_3_sigma, max, min [N], percent_without_contact,
 * max_uplift_at_droppers [m], filter_cutoff_hz (0: unfiltered) and window
 * [x0, x1] (x_p of the first and last time point used) [m].
 */
void write_statistics(JsonWriter& json, const ContactForceStatistics& statistics);

/**
 * contact_force.csv: t, x_p, lambda_p and lambda_p_filtered (after the low
 * pass; equal to lambda_p without one) at every time point of the run.
 */
void write_contact_force(const std::string& file, const ContactStatistics& statistics);

/// The same figures as a few lines of text (the end of a run's screen output).
void print_statistics(std::ostream& out, const ContactForceStatistics& statistics);
} // namespace pantocat
