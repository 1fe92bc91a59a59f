// What leaving an effect out saves (issue 7): time per step of reduced scenes
// against the paper's full scene, measured in one run (fastest of 5 each,
// no observers), for FDM + half-explicit and FEM + BDF-2.
// Usage: bench_scenes [N+1 = 1000]; prints a Markdown table.
#include "bench_error.h"

#include <pantocat/app/program_parameters.h>
#include <pantocat/simulation/case_runner.h>

#include <deal.II/base/multithread_info.h>

#include <iomanip>
#include <iostream>
#include <string>

using namespace pantocat;

namespace
{
struct ReducedScene
{
  const char* name;
  void (*reduce)(SceneParameters&);
};

const ReducedScene cases[] = {
    {"full scene (the paper's benchmark)", [](SceneParameters&) {}},
    {"without the wires' damping", [](SceneParameters& s) { s.damping = false; }},
    {"rigid carrier (droppers hang from fixed points)",
     [](SceneParameters& s) { s.carrier = WireModel::rigid; }},
    {"contact wire alone (rigid carrier, no droppers)",
     [](SceneParameters& s)
     {
       s.carrier = WireModel::rigid;
       s.droppers = DropperModel::absent;
     }},
    {"moving force on the contact wire alone",
     [](SceneParameters& s)
     {
       s.carrier = WireModel::rigid;
       s.droppers = DropperModel::absent;
       s.pantographs[0].model = "moving force";
     }},
    {"moving force on a string (no bending, gravity, damping)",
     [](SceneParameters& s)
     {
       s.carrier = WireModel::rigid;
       s.droppers = DropperModel::absent;
       s.pantographs[0].model = "moving force";
       s.contact_wire_bending = false;
       s.gravity = false;
       s.damping = false;
     }},
};

/// Seconds per step of the time loop, fastest of 5 runs.
double seconds_per_step(const ProgramParameters& p, unsigned int& unknowns,
                        unsigned int& constraints)
{
  double best = 1e300;
  for (unsigned int run = 0; run < 5; ++run)
  {
    CaseRunner simulation(p.make_case(), {p.output.probe_positions, p.output.energy});
    unknowns = simulation.system().n_dofs();
    constraints = simulation.system().n_constraints();
    const auto r = simulation.run({});
    best = std::min(best, r.time_loop_seconds / r.integrator.steps);
  }
  return best;
}
} // namespace

int main(int argc, char** argv)
try
{
  dealii::MultithreadInfo::set_thread_limit(1); // as pantocat-fem does
  const unsigned int n = argc > 1 ? std::stoul(argv[1]) : 1000;
  for (const SpaceMethod method : {SpaceMethod::fdm, SpaceMethod::fem})
  {
    ProgramParameters p;
    p.discretisation.method = method;
    p.discretisation.n_intervals = n;
    p.pantograph().final_position = 4.;
    const bool fdm = method == SpaceMethod::fdm;
    p.time_integration.integrator = fdm ? "half-explicit" : "bdf2";
    // Below 2/omega_max of the full scene (FDM): the same step for every scene.
    p.time_integration.time_step = fdm ? 2e-6 * (1000. / n) * (1000. / n) : 5e-5;
    std::cout << "\n"
              << (fdm ? "FDM + half-explicit" : "FEM + BDF-2") << ", N+1 = " << n
              << ", dt = " << p.time_integration.time_step << " s\n\n"
              << "| scene | unknowns | constraints | us per step | ratio to full |\n"
              << "|---|---|---|---|---|\n";
    double full = 0.;
    for (const ReducedScene& c : cases)
    {
      ProgramParameters reduced = p;
      c.reduce(reduced.scene);
      unsigned int unknowns = 0, constraints = 0;
      const double s = seconds_per_step(reduced, unknowns, constraints);
      if (full == 0.)
        full = s;
      std::cout << "| " << c.name << " | " << unknowns << " | " << constraints << " | "
                << std::setprecision(3) << 1e6 * s << " | " << s / full << " |\n";
    }
  }
}
catch (const std::exception& e)
{
  return report_bench_error("bench_scenes", e);
}
