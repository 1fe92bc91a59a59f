// Checkpoints (issue 6): the parameter fingerprint, and each integrator's
// saved state continuing bit for bit in a fresh integrator.
#include <pantocat/app/program_parameters.h>
#include <pantocat/base/input_error.h>
#include <pantocat/base/serialization.h>
#include <pantocat/simulation/case_runner.h>
#include <pantocat/simulation/checkpoint.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

using namespace pantocat;

namespace
{
const std::string* find(const ParameterFingerprint& f, const std::string& name)
{
  const auto it =
      std::find_if(f.begin(), f.end(), [&](const auto& e) { return e.first == name; });
  return it == f.end() ? nullptr : &it->second;
}
} // namespace

TEST(Checkpoint, FingerprintHoldsTheCriticalParametersOnly)
{
  dealii::ParameterHandler prm;
  ProgramParameters::declare_parameters(prm);
  prm.parse_input_from_string(
      "subsection Discretisation\n set Number of intervals = 250\n"
      "end\nsubsection Output\n set Verbosity = quiet\nend\n");
  const ParameterFingerprint f = critical_parameters(prm);
  // Grid, integrator, step, nested subsections (Catenary/Droppers/...) are in it.
  ASSERT_NE(find(f, "Discretisation/Number of intervals"), nullptr);
  EXPECT_EQ(*find(f, "Discretisation/Number of intervals"), "250");
  EXPECT_NE(find(f, "Time integration/Integrator"), nullptr);
  EXPECT_NE(find(f, "Time integration/Time step"), nullptr);
  EXPECT_NE(find(f, "Catenary/Droppers/Positions"), nullptr);
  EXPECT_NE(find(f, "Pantograph/Speed"), nullptr);
  EXPECT_NE(find(f, "Output/Time series interval"), nullptr);
  // What does not change the results is not.
  for (const auto& [name, value] : f)
  {
    EXPECT_NE(name.rfind("Checkpoint/", 0), 0u) << name;
    EXPECT_NE(name.rfind("Study/", 0), 0u) << name;
    EXPECT_NE(name, "Output/Verbosity");
    EXPECT_NE(name, "Output/Output directory");
    EXPECT_NE(name, "Output/Plots");
    EXPECT_NE(name, "Time integration/Force step size");
  }
}

namespace
{
/// The state after n1 + n2 steps, uninterrupted and through a checkpoint
/// after n1 steps loaded into a fresh integrator: must be equal bit for bit.
void expect_resume_bit_for_bit(const ProgramParameters& p, const unsigned int n1,
                               const unsigned int n2)
{
  const CaseRunner simulation(p.make_case(), {p.output.probe_positions, p.output.energy});
  auto whole = create_time_integrator(simulation.system(), p.time_integration);
  auto first = create_time_integrator(simulation.system(), p.time_integration);
  auto second = create_time_integrator(simulation.system(), p.time_integration);
  whole->initialize(simulation.initial_state());
  first->initialize(simulation.initial_state());
  for (unsigned int n = 0; n < n1 + n2; ++n)
    whole->advance();
  for (unsigned int n = 0; n < n1; ++n)
    first->advance();
  std::stringstream buffer;
  {
    CheckpointOut out(buffer);
    first->save(out);
  }
  second->initialize(simulation.initial_state());
  {
    CheckpointIn in(buffer);
    second->load(in);
  }
  for (unsigned int n = 0; n < n2; ++n)
    second->advance();
  const DynamicState &a = whole->latest(), &b = second->latest();
  EXPECT_EQ(whole->time(), second->time());
  EXPECT_EQ(a.t, b.t);
  EXPECT_EQ(a.active, b.active);
  EXPECT_EQ(a.lambda, b.lambda);
  for (unsigned int i = 0; i < a.q.size(); ++i)
  {
    ASSERT_EQ(a.q[i], b.q[i]) << i;
    ASSERT_EQ(a.v[i], b.v[i]) << i;
  }
  EXPECT_EQ(whole->statistics().steps, second->statistics().steps);
  EXPECT_EQ(whole->statistics().active_set_changes,
            second->statistics().active_set_changes);
}

ProgramParameters case_48(const SpaceMethod method, const std::string& integrator)
{
  ProgramParameters p;
  p.mode = RunMode::dynamics;
  p.scene.start = Start::paper; // the paper's case and start (13)
  p.pantograph().speed = 48.;
  p.pantograph().initial_offset = 0.002;
  p.discretisation.method = method;
  p.discretisation.n_intervals = 250;
  p.time_integration.integrator = integrator;
  return p;
}
} // namespace

// 48 m/s, N+1 = 250: the checkpoint after 5150 steps (t = 0.2575 s) lies in
// the slack interval of dropper 2; 200 steps on, across its re-tension.
TEST(Checkpoint, HalfExplicitResumesBitForBit)
{
  expect_resume_bit_for_bit(case_48(SpaceMethod::fdm, "half-explicit"), 5150, 200);
}

// The BDF-2 steps form the next step's history (rho_q, rho_v, h) in their
// last pass over q, v, a; a loaded run forms it from x_n, x_{n-1} in a pass
// of its own. Both must give the same bits.
TEST(Checkpoint, Bdf2ResumesBitForBitFem)
{
  expect_resume_bit_for_bit(case_48(SpaceMethod::fem, "bdf2"), 5150, 200);
}

TEST(Checkpoint, Bdf2ResumesBitForBitRightAfterItsRichardsonStart)
{
  expect_resume_bit_for_bit(case_48(SpaceMethod::fem, "bdf2"), 1, 20);
}

TEST(Checkpoint, GeneralizedAlphaResumesBitForBitFem)
{
  expect_resume_bit_for_bit(case_48(SpaceMethod::fem, "generalized-alpha"), 5150, 200);
}

TEST(Checkpoint, IdaRefusesToWriteOne)
{
  ProgramParameters p = case_48(SpaceMethod::fdm, "ida");
  p.pantograph().final_position = 2.1;
  const CaseRunner simulation(p.make_case(), {p.output.probe_positions, p.output.energy});
  auto ida = create_time_integrator(simulation.system(), p.time_integration);
  ida->initialize(simulation.initial_state());
  std::stringstream buffer;
  CheckpointOut out(buffer);
  EXPECT_THROW(ida->save(out), SimulationError);
}
