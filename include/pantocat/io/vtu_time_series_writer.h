#pragma once

#include <pantocat/base/safe_files.h>
#include <pantocat/simulation/time_point.h>
#include <pantocat/space/catenary_discretisation.h>
#include <pantocat/system/semi_discrete_system.h>
#include <pantocat/lac/sparse_row.h>

#include <deal.II/base/timer.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/grid/tria.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pantocat
{
/**
 * ParaView output of a dynamic run: a frame every @p interval simulated
 * seconds (at the time point nearest to k interval), listed with its physical
 * time in solution.pvd (rewritten after every frame, so that it is valid while
 * the run goes on). Each frame has two parts in vtu/:
 *  - wires-NNNNN.vtu: both wires on [0, L], sampled with @p subdivisions
 *    points per cell for FEM, at the nodes for FDM (the layout of
 *    static_profile.vtu): carrier_displacement
 *    (w_c, with l_c), contact_wire_displacement (w_w), carrier_velocity,
 *    contact_wire_velocity;
 *  - pantograph-droppers-NNNNN.vtu: points in the (x, w) plane: the pantograph
 *    head at (x_p, w_p1) and each dropper clamp at (x_d, w_w(x_d)), with their
 *    constraint force [N], active flag and id (0: pantograph, j: dropper j).
 * Both VTU files carry the physical time (VTK field TIME). start() removes
 * the frames of an earlier run from vtu/ (a symbolic link vtu is replaced by
 * a directory, with a warning: nothing outside the output directory is
 * removed or written); resume() refuses to go on when a frame written before
 * the checkpoint is missing. An interval below @p time_step is
 * taken as @p time_step (a frame every time point; OutputParameters::check
 * refuses such an input): the frame counter then advances at most once per
 * time step, where a tiny interval made it count for ever.
 */
class VtuTimeSeriesWriter : public SimulationObserver
{
public:
  VtuTimeSeriesWriter(const std::string& directory, double interval, double time_step,
                      unsigned int subdivisions,
                      const CatenaryDiscretisation& discretisation,
                      const SemiDiscreteSystem& system,
                      dealii::TimerOutput* timer = nullptr);

  void start(const SimulationLayout& layout) override;
  void observe(const TimePoint&) override {}
  void observe_state(const TimePoint& point, const DynamicState& state) override;
  /// The frames written; resume() keeps them (frames after the checkpoint are
  /// written again under the same names).
  void save(CheckpointOut& archive) const override;
  void resume(const SimulationLayout& layout, CheckpointIn& archive) override;

  /// (time, wires file relative to the directory) of each frame written.
  const std::vector<std::pair<double, std::string>>& frames() const { return written; }

private:
  void write_wires(const DynamicState& state, const std::string& file) const;
  void write_points(const TimePoint& point, const DynamicState& state,
                    const std::string& file) const;
  void write_pvd() const;

  std::string directory;
  /// vtu/ inside it, opened without following a link (start(), resume()).
  std::optional<Directory> frames_directory;
  double interval, tolerance;
  unsigned long next_frame = 0;
  dealii::TimerOutput* timer;
  SimulationLayout layout;
  std::vector<double> dropper_x;
  double support_height;

  dealii::Triangulation<1> sample_mesh;
  dealii::FE_Q<1> sample_fe;
  dealii::DoFHandler<1> sample_dofs;
  /// Per sample dof: rows r with r . q = u_c(x) and w_w(x) (global indices).
  std::vector<SparseRow> carrier_rows, wire_rows;
  std::vector<SparseRow> dropper_rows; ///< w_w(x_d) = row . q
  std::vector<std::pair<double, std::string>> written;
};
} // namespace pantocat
