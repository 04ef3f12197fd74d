// --method, --lambda and --mu, which `param`, `atlas` and `edit` take alike:
// one registration, so their spelling, help and checks cannot drift apart.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <optional>
#include <string>

#include "intrinsic/intrinsic.h"
#include "intrinsic/weights.h"

namespace intrinsic::app {

struct WeightArgs {
  std::string method = choice_name(Method::Conformal);
  std::optional<double> lambda, mu;  // as given: mixed needs at least one, other methods none

  Method parsed_method() const;
  // The library's checks (pipeline.h weight_options), messages naming the flags.
  WeightOptions options() const;
  // Whether anything but the default conformal map was asked for.
  bool given() const { return parsed_method() != Method::Conformal || lambda || mu; }
};

// `args` stays alive as long as the options refer to it (CLI11 keeps the
// callbacks for the life of the App).
void add_weight_options(CLI::App& cmd, const std::shared_ptr<WeightArgs>& args);

}  // namespace intrinsic::app
