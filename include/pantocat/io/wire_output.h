#pragma once

#include <pantocat/space/catenary_discretisation.h>
#include <pantocat/system/semi_discrete_system.h>

#include <string>

namespace pantocat
{
/**
 * Writes the displacement of both wires for the unknowns @p q of @p system:
 * a CSV file (x, w_c, w_w at the grid vertices) and a VTU file sampled with
 * @p subdivisions points per cell (deal.II DataOut, the physical time in the
 * file's metadata).
 */
void write_wire_profiles(const CatenaryDiscretisation& discretisation,
                         const SemiDiscreteSystem& system,
                         const dealii::Vector<double>& q, const std::string& csv_file,
                         const std::string& vtu_file, unsigned int subdivisions,
                         double time = 0.);

/**
 * Writes the heights of the stitch wires for the unknowns @p q of @p system
 * at their nodes (stitch wire number from 1, its support, x, w_s = l_c +
 * u_s) and the carrier's at the same points: a CSV file. Nothing without
 * stitch wires.
 */
void write_stitch_wire_profiles(const CatenaryDiscretisation& discretisation,
                                const SemiDiscreteSystem& system,
                                const dealii::Vector<double>& q,
                                const std::string& csv_file);

/// The unknowns of one block of @p q.
dealii::Vector<double> block_values(const SemiDiscreteSystem& system,
                                    const dealii::Vector<double>& q,
                                    const std::string& block);
} // namespace pantocat
