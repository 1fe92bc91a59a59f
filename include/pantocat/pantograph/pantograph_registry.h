#pragma once

#include <pantocat/pantograph/pantograph_model.h>
#include <pantocat/pantograph/pantograph_parameters.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace pantocat
{
/**
 * A lumped-mass pantograph model as the scene knows it: its name (a value of
 * Scene/Pantograph and Pantograph k/Model) and how to make it from a
 * pantograph's data. A new model is one file pair (a PantographModel) plus
 * one line in registered_pantograph_models().
 */
struct PantographModelEntry
{
  std::string name;
  std::function<std::unique_ptr<PantographModel>(const PantographParameters&)> create;
};

/// Every lumped-mass model.
const std::vector<PantographModelEntry>& registered_pantograph_models();

/// The model named @p name, or nullptr if no lumped model has that name.
const PantographModelEntry* find_pantograph_model(const std::string& name);

/// "two-mass|three-mass|mass-chain" for Patterns::Selection.
std::string pantograph_model_selection();
} // namespace pantocat
