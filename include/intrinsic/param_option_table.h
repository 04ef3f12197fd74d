// The param job's options (`intrinsic param`, intrinsic.parameterize, the
// batch runner, the editor's weights), declared once: key, flag, type,
// range, default and help of each (option_table.h), and the request they
// make.
//
//   GivenOptions given = {{"boundary", std::string("natural")},
//                         {"pins", std::string("0:0,0")}, {"pins", std::string("9:1,0")}};
//   ParamRequest request = param_request(given, OptionSpelling::Keyword);
//   ParamOutcome outcome = parameterize_file("patch.obj", request);
//
// In-memory constraints (Python's dict) and the progress callback are data
// rather than options and are set on the request directly.
#pragma once

#include <vector>

#include "intrinsic/option_table.h"
#include "intrinsic/pipeline.h"

namespace intrinsic {

// Every option of the param job, in the order --help lists them; each
// default is the one a default-constructed ParamRequest holds. The group
// "Optimizers" holds the options of the two section 5 optimizers, which a
// kept Parameterizer (one fixed map) does not take.
const std::vector<OptionSpec>& param_option_table();

// The request `given` makes: each value checked against its spec
// (checked_option_value), pins parsed ("V:U,V"), the solver checked against
// this build, then the checks that span options (check_param_request). An
// unknown key, or one given twice (also through an alias) other than a
// repeated one (pins), is Error(Usage); every message names options as
// `spelling` spells them.
ParamRequest param_request(const GivenOptions& given, OptionSpelling spelling);

}  // namespace intrinsic
