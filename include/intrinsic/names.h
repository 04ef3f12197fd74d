// Every enum's name table in one include, for the shells (the command line,
// the Python module, the server): each table is declared beside its enum and
// defined in that layer's source (intrinsic/choice.h). Library code includes
// the header of the enum it spells instead, so no layer depends on this one.
#pragma once

#include "intrinsic/atlas.h"
#include "intrinsic/boundary.h"
#include "intrinsic/boundary_editor.h"
#include "intrinsic/boundary_optimization.h"
#include "intrinsic/choice.h"
#include "intrinsic/io.h"
#include "intrinsic/linear_solver.h"
#include "intrinsic/optimal_lambda.h"
#include "intrinsic/parameterize.h"
#include "intrinsic/pictures.h"
#include "intrinsic/texture.h"
#include "intrinsic/weights.h"
