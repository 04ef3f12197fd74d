// The registration and mapping of --method, --lambda and --mu (weight_args.h).
#include "weight_args.h"

#include "choice_option.h"
#include "intrinsic/pipeline.h"

namespace intrinsic::app {

Method WeightArgs::parsed_method() const { return parse_choice<Method>(method, "--method"); }

WeightOptions WeightArgs::options() const {
  return weight_options(parsed_method(), lambda, mu, OptionSpelling::Flag);
}

void add_weight_options(CLI::App& cmd, const std::shared_ptr<WeightArgs>& args) {
  cmd.add_option("--method", args->method, "conformal | authalic | mixed | tutte | floater")
      ->check(choice_check<Method>())
      ->capture_default_str();
  cmd.add_option_function<double>("--lambda", [args](double v) { args->lambda = v; },
                                  "Weight of the conformal energy (mixed)");
  cmd.add_option_function<double>("--mu", [args](double v) { args->mu = v; }, "Weight of the authalic energy (mixed)");
}

}  // namespace intrinsic::app
