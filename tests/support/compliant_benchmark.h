#pragma once

#include <pantocat/scene/scene_builder.h>
#include <pantocat/simulation/case.h>
#include <pantocat/space/catenary_discretisation.h>
#include <pantocat/time/dynamic_state.h>

#include <memory>

namespace pantocat
{
/// A scene of a Case built without the case runner, and its consistent initial state.
struct BuiltCase
{
  std::unique_ptr<CatenaryDiscretisation> space;
  BuiltScene built;
  DynamicState initial;
};

/**
 * Test-only: the scene of @p c (build_scene()) with every dropper replaced
 * by a compliant one of the same kind, row and offset and @p droppers'
 * stiffness and damping (in the coupled system and in the catenary-only one
 * of the static problem), and the consistent initial state of Sec. 2.2 for
 * it, as the case runner makes it. A rigid @p droppers (k = 0) leaves the
 * scene as it is: the reference run on the same path.
 */
BuiltCase build_case_with_compliant_droppers(const Case& c, const Compliance& droppers);
} // namespace pantocat
