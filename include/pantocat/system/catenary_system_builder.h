#pragma once

#include <pantocat/space/catenary_discretisation.h>
#include <pantocat/system/semi_discrete_system.h>

namespace pantocat
{
/**
 * Assembles the semi-discrete catenary (29)-(31) into a SemiDiscreteSystem:
 * blocks "carrier" (u_c = w_c - l_c) and "contact wire", the gravity loads of
 * the wires, the point loads of clamps and droppers (b_c, b_w of Sec. 4.2),
 * and one constraint per dropper,
 *
 *   Delta_{d,j} = H_w q_w - H_c q_c + (l_j - l_c) >= 0,   Eq. (5)/(31),
 *
 * unilateral or bilateral as asked. Throws InputError if the grid cannot
 * resolve the droppers (a dropper on an eliminated boundary node, or two
 * droppers on one node).
 */
SemiDiscreteSystem
build_catenary_system(const CatenaryDiscretisation& discretisation,
                      Constraint::Kind dropper_kind,
                      const std::vector<const BlockOperator*>& extra_bodies = {});

/// The dropper constraint row of dropper @p j in the numbering of @p system.
SparseRow dropper_row(const CatenaryDiscretisation& discretisation,
                      const SemiDiscreteSystem& system, unsigned int j);
} // namespace pantocat
