#pragma once

#include <pantocat/catenary/catenary_parameters.h>
#include <pantocat/scene/scene_parameters.h>
#include <pantocat/simulation/guard_parameters.h>
#include <pantocat/space/discretisation_parameters.h>
#include <pantocat/time/time_integration_parameters.h>

namespace pantocat
{
/**
 * A case: the physics and the numerics of one simulation, and nothing of how
 * it was asked for (no command line, no output settings). The scene says
 * which bodies and effects exist (any number of pantographs), the catenary
 * the wires' domain and the geometry along it, the discretisation and time
 * integration how it is solved, the guards when a run is stopped. Built once
 * from the parameters; every mode and every study runs a case through the
 * CaseRunner.
 */
struct Case
{
  SceneParameters scene;
  CatenaryParameters catenary;
  DiscretisationParameters discretisation;
  TimeIntegrationParameters time_integration;
  GuardParameters guards;

  /**
   * The end time t_e of a dynamic run: the first pantograph (moving force or
   * body) to reach its final position ends it; without any, pantograph 1's.
   */
  double end_time() const;

  /**
   * Cross-checks between the parts (bending of the carrier and its element,
   * every pantograph inside the domain for the whole run, ...); throws
   * InputError naming the parameter, the value and what is allowed.
   */
  void check() const;

  /**
   * What a dynamic run needs beyond check(): unknowns to integrate, and a
   * number of steps up to end_time() that is finite and fits into memory.
   */
  void check_dynamics() const;
};
} // namespace pantocat
