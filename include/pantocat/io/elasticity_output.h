#pragma once

#include <pantocat/analysis/static_elasticity.h>
#include <pantocat/io/json_writer.h>

#include <string>
#include <vector>

namespace pantocat
{
/**
 * The columns of elasticity.csv: x, elasticity_mm_per_N (the first force),
 * elasticity_mm_per_N_<F>N for each further force, then uplift_mm_<F>N and
 * slackened_droppers_<F>N (how many droppers slacken) for every force.
 */
std::vector<std::string> elasticity_columns(const StaticElasticity& elasticity);

/// elasticity.csv (elasticity_columns(), 12 significant digits), written atomically.
void write_elasticity_csv(const std::string& file, const StaticElasticity& elasticity);

/**
 * elasticity.png: e over x for every force, the span's supports (solid) and
 * droppers (dashed) marked, drawn by gnuplot from elasticity.csv with the
 * script elasticity.gp in @p directory. Returns true if gnuplot wrote it.
 */
bool plot_elasticity(const std::string& directory, const StaticElasticity& elasticity,
                     const std::vector<double>& dropper_positions,
                     const std::string& title);

/**
 * The object "elasticity" of summary.json: span, points and per force
 * force_N, e_min_mm_per_N, e_max_mm_per_N, e_mean_mm_per_N, uniformity.
 */
void write_elasticity_summary(JsonWriter& json, const StaticElasticity& elasticity);
} // namespace pantocat
