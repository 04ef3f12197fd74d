// Which sparse solver a map is solved with (ParamOptions::solver): the
// public choice; the solvers themselves are internal (src/solve).
#pragma once

#include <string>
#include <string_view>

#include "intrinsic/choice.h"

namespace intrinsic {

// SupernodalLU: LU without pivoting on the Cholesky pattern; every solve's
// residual is checked and the solver switches to UMFPACK (kind() then says
// so) when the factorization needs pivoting. Auto uses it for
// non-symmetric systems when SuiteSparse and OpenBLAS are built in.
// SupernodalCholesky: the library's own supernodal Cholesky on CHOLMOD's
// analysis, subtrees of the elimination tree on separate cores; Auto uses it
// for symmetric systems (CHOLMOD when it finds the matrix not positive
// definite), the natural map's complex form included (L L^H of the n x n
// Hermitian matrix; CHOLMOD's complex factor when that fails, or with
// --solver cholmod).
enum class SolverKind { Auto, Cholmod, Umfpack, EigenLLT, EigenLU, CG, BiCGSTAB, SupernodalLU, SupernodalCholesky };
template <>
ChoiceTable<SolverKind> choice_table<SolverKind>();

std::string solver_name(SolverKind k);
SolverKind parse_solver(const std::string& name);  // throws Error(Usage)
// The solver named `name` that this build has: Error(Usage) "<label>: ..."
// for a name not in the table and for one it lacks (SuiteSparse not found).
SolverKind parse_solver(const std::string& name, std::string_view label);
bool solver_available(SolverKind k);                // false e.g. for CHOLMOD without SuiteSparse

}  // namespace intrinsic
