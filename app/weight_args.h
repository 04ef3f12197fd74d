// --method, --lambda and --mu, which `param` and `edit` take alike: one
// registration, so their spelling, help and checks cannot drift apart.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "intrinsic/weights.h"

namespace intrinsic::app {

struct WeightArgs {
  std::string method = "conformal";
  double lambda = 1, mu = 0;
  // Whether each was given: mixed needs at least one, other methods none.
  bool lambda_set = false, mu_set = false;

  // Throws Error(Usage) for inconsistent combinations.
  WeightOptions options() const;
};

// `args` stays alive as long as the options refer to it (CLI11 keeps the
// callbacks for the life of the App).
void add_weight_options(CLI::App& cmd, const std::shared_ptr<WeightArgs>& args);

}  // namespace intrinsic::app
