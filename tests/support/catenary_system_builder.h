#pragma once

#include <pantocat/space/catenary_discretisation.h>
#include <pantocat/system/semi_discrete_system.h>

namespace pantocat
{
/**
 * The semi-discrete catenary (29)-(31) of the paper's scene without the
 * pantograph: blocks "carrier" (u_c = w_c - l_c) and "contact wire", the
 * gravity loads of the wires, the point loads of clamps and droppers (b_c,
 * b_w of Sec. 4.2), and one constraint per dropper,
 *
 *   Delta_{d,j} = H_w q_w - H_c q_c + (l_j - l_c) >= 0,   Eq. (5)/(31),
 *
 * unilateral or bilateral as asked (build_scene() with the default scene).
 * Throws InputError if the grid cannot resolve the droppers.
 */
SemiDiscreteSystem build_catenary_system(const CatenaryDiscretisation& discretisation,
                                         Constraint::Kind dropper_kind);

} // namespace pantocat
