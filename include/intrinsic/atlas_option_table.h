// The atlas job's options (`intrinsic atlas`, intrinsic.atlas, the batch
// runner, the Blender add-on), declared once: key, flag, type, range,
// default and help of each (option_table.h), and the request they make.
//
//   GivenOptions given = {{"max_stretch", 1.2}, {"padding", std::int64_t{4}}};
//   AtlasRequest request = atlas_request(given, OptionSpelling::Keyword);
//   AtlasOutcome outcome = atlas_file("scene.glb", request);
//
// Array-valued inputs (Python's face_groups, uv, uv_index, seams as vertex
// pairs) are data rather than options and are set on the request directly.
#pragma once

#include <vector>

#include "intrinsic/option_table.h"
#include "intrinsic/pipeline.h"

namespace intrinsic {

// Every option of the atlas job, in the order --help lists them; each
// default is the one a default-constructed AtlasRequest holds.
const std::vector<OptionSpec>& atlas_option_table();

// The request `given` makes: each value checked against its spec
// (checked_option_value), then the checks that span options (a weight with
// the natural boundary, two chart optimizers, lambda and mu). An unknown
// key, or one given twice (also through an alias), is Error(Usage); every
// message names options as `spelling` spells them, and the request's
// texture and glTF options carry that spelling for the later checks.
AtlasRequest atlas_request(const GivenOptions& given, OptionSpelling spelling);

}  // namespace intrinsic
