#include <pantocat/base/input_error.h>
#include <pantocat/simulation/checkpoint_parameters.h>
#include <pantocat/time/integrator_registry.h>

namespace pantocat
{
void CheckpointParameters::declare_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Checkpoint");
  prm.declare_entry("Interval", "0", dealii::Patterns::Integer(0),
                    "Write the state of a dynamic run to checkpoint.bin in the output "
                    "directory every this many time steps (atomically: a temporary "
                    "file renamed); 0: never. Not for Integrator = ida.");
  prm.declare_entry("Resume from checkpoint", "false", dealii::Patterns::Bool(),
                    "Continue the run from checkpoint.bin in the output directory: the "
                    "outputs come out as those of the uninterrupted run. The checkpoint "
                    "must have been made with the same parameters (all but this "
                    "subsection, Output directory, Verbosity, Plots and Force step "
                    "size).");
  prm.declare_entry("Stop after steps", "0", dealii::Patterns::Integer(0),
                    "For tests: stop the run after this many time steps as if it "
                    "were killed (exit 1, summary.json with status failed); 0: never.");
  prm.leave_subsection();
}

void CheckpointParameters::parse_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Checkpoint");
  interval = prm.get_integer("Interval");
  resume = prm.get_bool("Resume from checkpoint");
  stop_after_steps = prm.get_integer("Stop after steps");
  prm.leave_subsection();
}

void CheckpointParameters::check(const std::string& integrator) const
{
  if (integrator_entry(integrator).writes_checkpoints)
    return;
  require(interval == 0, "Checkpoint/Interval", interval,
          "must be 0 with Integrator = " + integrator + " (its history lives inside " +
              "the solver and cannot be saved)");
  require(!resume, "Checkpoint/Resume from checkpoint", "true",
          "not possible with Integrator = " + integrator + " (it writes no checkpoints)");
}
} // namespace pantocat
