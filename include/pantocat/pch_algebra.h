// Precompiled header of the layers that never see elements or grids (system,
// time, pantograph, simulation, io, studies, app): the deal.II linear algebra
// and parameter headers only, so that no finite-element header reaches an
// integrator even through the precompiled header.
#pragma once
#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <map>
#include <memory>
#include <string>
#include <vector>
