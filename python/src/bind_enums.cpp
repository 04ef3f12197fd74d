// The library's choice enums as Python enums: intrinsic.Method.CONFORMAL,
// intrinsic.SolverKind.EIGEN_LLT, ... (pybind11 enums, so a keyword bound to
// the C++ type takes them directly). A member's name is the command line's
// spelling of the choice in capitals, '-' as '_' ("eigen-llt" is EIGEN_LLT,
// "gradient" is Descent.GRADIENT), and `option` gives that spelling back, so
// an enum value and its string mean the same thing (docs/python.md "Enums").
#include <cctype>
#include <string>
#include <utility>
#include <vector>

#include "common.h"
#include "intrinsic/atlas.h"
#include "intrinsic/boundary.h"
#include "intrinsic/boundary_editor.h"
#include "intrinsic/boundary_optimization.h"
#include "intrinsic/solver_kind.h"
#include "intrinsic/optimal_lambda.h"
#include "intrinsic/parameterize.h"
#include "intrinsic/weights.h"

namespace intrinsic::python {
namespace {

// The command line's spelling of a member name: lower case, '_' as '-'.
std::string option_spelling(std::string name) {
  for (char& c : name) c = c == '_' ? '-' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return name;
}

template <typename E>
void bind_enum(py::module_& m, const char* name, const char* doc,
               const std::vector<std::pair<const char*, E>>& members) {
  py::enum_<E> e(m, name, doc);
  for (const auto& [member, value] : members) e.value(member, value);
  e.def_property_readonly(
      "option", [](py::object self) { return option_spelling(py::str(self.attr("name"))); },
      "The command line's spelling of this choice (the string the keyword also takes).");
}

}  // namespace

void register_enums(py::module_& m) {
  bind_enum<Method>(m, "Method", "The weights of the map (method=, --method; paper section 3).",
                    {{"CONFORMAL", Method::Conformal},
                     {"AUTHALIC", Method::Authalic},
                     {"MIXED", Method::Mixed},
                     {"TUTTE", Method::Tutte},
                     {"FLOATER", Method::Floater}});
  bind_enum<BoundaryShape>(
      m, "BoundaryShape",
      "Where the boundary goes (boundary=, --boundary): GIVEN is a boundary file, whose path the keyword takes.",
      {{"CIRCLE", BoundaryShape::Circle},
       {"SQUARE", BoundaryShape::Square},
       {"GIVEN", BoundaryShape::Given},
       {"NATURAL", BoundaryShape::Natural}});
  bind_enum<Spacing>(m, "Spacing", "How boundary vertices are spaced on a circle or square (spacing=, --spacing).",
                     {{"ARCLENGTH", Spacing::ArcLength}, {"UNIFORM", Spacing::Uniform}});
  bind_enum<ScaleMode>(m, "ScaleMode", "The scale of the result (scale=, --scale).",
                       {{"UNIT", ScaleMode::Unit}, {"SURFACE", ScaleMode::Surface}});
  bind_enum<HoleRule>(m, "HoleRule", "What happens to holes, boundary loops other than the outer one (holes=).",
                      {{"FILL", HoleRule::Fill}, {"FREE", HoleRule::Free}, {"NATURAL", HoleRule::Natural}});
  bind_enum<SolverKind>(m, "SolverKind", "The sparse linear solver (solver=, --solver).",
                        {{"AUTO", SolverKind::Auto},
                         {"CHOLMOD", SolverKind::Cholmod},
                         {"UMFPACK", SolverKind::Umfpack},
                         {"EIGEN_LLT", SolverKind::EigenLLT},
                         {"EIGEN_LU", SolverKind::EigenLU},
                         {"CG", SolverKind::CG},
                         {"BICGSTAB", SolverKind::BiCGSTAB},
                         {"SUPERNODAL_LU", SolverKind::SupernodalLU},
                         {"SUPERNODAL_CHOLESKY", SolverKind::SupernodalCholesky}});
  bind_enum<LambdaEnergy>(m, "LambdaEnergy", "The energy the optimal lambda minimises (optimize_lambda=; paper 5.1).",
                          {{"EDGE", LambdaEnergy::EdgeLength}, {"AREA", LambdaEnergy::Area}});
  bind_enum<BoundaryEnergy>(m, "BoundaryEnergy",
                            "The energy boundary optimization minimises (optimize_boundary=; paper 5.2).",
                            {{"EDGE", BoundaryEnergy::EdgeLength},
                             {"AREA", BoundaryEnergy::Area},
                             {"DIRICHLET", BoundaryEnergy::SymmetricDirichlet}});
  bind_enum<GradientRoute>(m, "GradientRoute", "How boundary optimization gets its gradient (gradient=).",
                           {{"ADJOINT", GradientRoute::Adjoint}, {"RESPONSES", GradientRoute::Responses}});
  bind_enum<Descent>(m, "Descent", "The descent of boundary optimization (descent=).",
                     {{"LBFGS", Descent::LBFGS}, {"GRADIENT", Descent::GradientDescent}});
  bind_enum<Segmentation>(m, "Segmentation", "How an atlas groups faces into charts before the validity splits.",
                          {{"NORMAL_CONES", Segmentation::NormalCones}, {"COMPONENTS", Segmentation::Components}});
  bind_enum<AtlasScope>(m, "AtlasScope", "One atlas for the whole file or one per mesh (scope=, --atlas).",
                        {{"WHOLE", AtlasScope::Whole}, {"PER_MESH", AtlasScope::PerMesh}});
  bind_enum<InstanceMode>(m, "InstanceMode",
                          "A mesh several nodes draw: one chart layout shared, or charts per instance (instances=, "
                          "--instances).",
                          {{"SHARED", InstanceMode::Shared}, {"UNIQUE", InstanceMode::Unique}});
  bind_enum<BasisMode>(m, "BasisMode", "The boundary editor's response basis (basis=, intrinsic edit --basis).",
                       {{"FULL", BasisMode::Full}, {"LAZY", BasisMode::Lazy}});
}

}  // namespace intrinsic::python
