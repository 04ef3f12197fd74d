#include "weight_args.h"

#include "intrinsic/error.h"

namespace intrinsic::app {

WeightOptions WeightArgs::options() const {
  WeightOptions w;
  w.method = parse_method(method);
  if ((lambda_set || mu_set) && w.method != Method::Mixed) throw_usage("--lambda and --mu apply to --method mixed only");
  if (w.method == Method::Mixed) {
    if (!lambda_set && !mu_set) throw_usage("--method mixed needs --lambda and/or --mu");
    w.lambda = lambda_set ? lambda : 0.0;
    w.mu = mu_set ? mu : 0.0;
    if (w.lambda == 0 && w.mu == 0) throw_usage("--lambda and --mu cannot both be zero");
  }
  return w;
}

void add_weight_options(CLI::App& cmd, const std::shared_ptr<WeightArgs>& args) {
  cmd.add_option("--method", args->method, "conformal | authalic | mixed | tutte | floater")
      ->check(CLI::IsMember({"conformal", "authalic", "mixed", "tutte", "floater"}))
      ->capture_default_str();
  cmd.add_option_function<double>("--lambda", [args](double v) { args->lambda = v; args->lambda_set = true; },
                                  "Weight of the conformal energy (mixed)");
  cmd.add_option_function<double>("--mu", [args](double v) { args->mu = v; args->mu_set = true; },
                                  "Weight of the authalic energy (mixed)");
}

}  // namespace intrinsic::app
