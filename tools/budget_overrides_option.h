// The `--set KEY.PATH=VALUE` option (repeatable) of every command that loads
// a budget file: run, check, compare, sweep, sensitivity, model.
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "deb/core/error.h"
#include "deb/load/budget_yaml.h"

namespace deb::tools {

// Adds --set (or `name`) to `app`, collecting into `overrides`; a malformed
// KEY.PATH=VALUE is a usage error (exit 2) before anything is read.
inline CLI::Option* AddOverridesOption(CLI::App* app, std::vector<BudgetOverride>* overrides,
                                       const std::string& name = "--set",
                                       const std::string& what = "the budget") {
  return app
      ->add_option_function<std::vector<std::string>>(
          name,
          [overrides, name](const std::vector<std::string>& texts) {
            overrides->clear();
            for (const std::string& t : texts) {
              try {
                overrides->push_back(ParseBudgetOverride(t));
              } catch (const InputError& e) {
                throw CLI::ValidationError(name, e.message());
              }
            }
          },
          "Change " + what + " before loading it: KEY.PATH=VALUE, the key path as in error messages "
          "(e.g. sources[0].spectrum.class=VC-E, 'paths[0].control.gains=[50, 50, 80, 0, 0, 0]'); repeatable")
      ->allow_extra_args(false)
      ->type_name("KEY.PATH=VALUE");
}

}  // namespace deb::tools
