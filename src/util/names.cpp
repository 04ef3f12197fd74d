// The name tables of include/intrinsic/names.h: the one place where each
// user-facing enum value is spelled. The order of each table is the order
// `--help` and messages list the names in.
#include "intrinsic/names.h"

namespace intrinsic {
namespace {

template <class E, size_t N>
ChoiceTable<E> table(const Choice<E> (&rows)[N]) {
  return {rows, N};
}

}  // namespace

template <>
ChoiceTable<Method> choice_table<Method>() {
  static const Choice<Method> rows[] = {{Method::Conformal, "conformal"},
                                        {Method::Authalic, "authalic"},
                                        {Method::Mixed, "mixed"},
                                        {Method::Tutte, "tutte"},
                                        {Method::Floater, "floater"}};
  return table(rows);
}

// Given positions come from a file the command line names by its path.
template <>
ChoiceTable<BoundaryShape> choice_table<BoundaryShape>() {
  static const Choice<BoundaryShape> rows[] = {{BoundaryShape::Circle, "circle"},
                                               {BoundaryShape::Square, "square"},
                                               {BoundaryShape::Natural, "natural"},
                                               {BoundaryShape::Given, "given", false}};
  return table(rows);
}

template <>
ChoiceTable<Spacing> choice_table<Spacing>() {
  static const Choice<Spacing> rows[] = {{Spacing::ArcLength, "arclength"}, {Spacing::Uniform, "uniform"}};
  return table(rows);
}

template <>
ChoiceTable<ScaleMode> choice_table<ScaleMode>() {
  static const Choice<ScaleMode> rows[] = {{ScaleMode::Unit, "unit"}, {ScaleMode::Surface, "surface"}};
  return table(rows);
}

// A result's placement: "given" is where given positions or pins put it.
template <>
ChoiceTable<Placement> choice_table<Placement>() {
  static const Choice<Placement> rows[] = {
      {Placement::Unit, "unit"}, {Placement::Surface, "surface"}, {Placement::Given, "given", false}};
  return table(rows);
}

template <>
ChoiceTable<HoleRule> choice_table<HoleRule>() {
  static const Choice<HoleRule> rows[] = {
      {HoleRule::Fill, "fill"}, {HoleRule::Free, "free"}, {HoleRule::Natural, "natural"}};
  return table(rows);
}

// What a result applied to its holes (reports only, never parsed).
template <>
ChoiceTable<HolesApplied> choice_table<HolesApplied>() {
  static const Choice<HolesApplied> rows[] = {{HolesApplied::None, "none", false},
                                              {HolesApplied::Fill, "fill", false},
                                              {HolesApplied::Free, "free", false},
                                              {HolesApplied::Natural, "natural", false},
                                              {HolesApplied::FreeNoConformalTerm,
                                               "free (method has no conformal term)", false}};
  return table(rows);
}

template <>
ChoiceTable<SolverKind> choice_table<SolverKind>() {
  static const Choice<SolverKind> rows[] = {{SolverKind::Auto, "auto"},         {SolverKind::Cholmod, "cholmod"},
                                            {SolverKind::Umfpack, "umfpack"},   {SolverKind::EigenLLT, "eigen-llt"},
                                            {SolverKind::EigenLU, "eigen-lu"},  {SolverKind::CG, "cg"},
                                            {SolverKind::BiCGSTAB, "bicgstab"},
                                            {SolverKind::SupernodalLU, "supernodal-lu"},
                                            {SolverKind::SupernodalCholesky, "supernodal-cholesky"}};
  return table(rows);
}

template <>
ChoiceTable<LambdaEnergy> choice_table<LambdaEnergy>() {
  static const Choice<LambdaEnergy> rows[] = {{LambdaEnergy::EdgeLength, "edge"}, {LambdaEnergy::Area, "area"}};
  return table(rows);
}

template <>
ChoiceTable<BoundaryEnergy> choice_table<BoundaryEnergy>() {
  static const Choice<BoundaryEnergy> rows[] = {{BoundaryEnergy::EdgeLength, "edge"},
                                                {BoundaryEnergy::Area, "area"},
                                                {BoundaryEnergy::SymmetricDirichlet, "dirichlet"}};
  return table(rows);
}

template <>
ChoiceTable<GradientRoute> choice_table<GradientRoute>() {
  static const Choice<GradientRoute> rows[] = {{GradientRoute::Adjoint, "adjoint"},
                                               {GradientRoute::Responses, "responses"}};
  return table(rows);
}

template <>
ChoiceTable<Descent> choice_table<Descent>() {
  static const Choice<Descent> rows[] = {{Descent::LBFGS, "lbfgs"}, {Descent::GradientDescent, "gradient"}};
  return table(rows);
}

template <>
ChoiceTable<Segmentation> choice_table<Segmentation>() {
  static const Choice<Segmentation> rows[] = {{Segmentation::NormalCones, "normal-cones"},
                                              {Segmentation::Components, "components"}};
  return table(rows);
}

// How a chart was flattened (atlas reports only).
template <>
ChoiceTable<ChartMethod> choice_table<ChartMethod>() {
  static const Choice<ChartMethod> rows[] = {{ChartMethod::Natural, "natural", false},
                                             {ChartMethod::Triangle, "triangle", false},
                                             {ChartMethod::FixedBoundary, "fixed-boundary", false},
                                             {ChartMethod::OptimalLambda, "optimal-lambda", false},
                                             {ChartMethod::OptimizedBoundary, "optimized-boundary", false}};
  return table(rows);
}

template <>
ChoiceTable<ChartOptimizer> choice_table<ChartOptimizer>() {
  static const Choice<ChartOptimizer> rows[] = {{ChartOptimizer::None, "none"},
                                                {ChartOptimizer::OptimalLambda, "optimal-lambda"},
                                                {ChartOptimizer::OptimizeBoundary, "optimize-boundary"}};
  return table(rows);
}

template <>
ChoiceTable<BasisMode> choice_table<BasisMode>() {
  static const Choice<BasisMode> rows[] = {{BasisMode::Full, "full"}, {BasisMode::Lazy, "lazy"}};
  return table(rows);
}

template <>
ChoiceTable<PictureMode> choice_table<PictureMode>() {
  static const Choice<PictureMode> rows[] = {{PictureMode::Checker, "checker"},
                                             {PictureMode::Layout, "layout"},
                                             {PictureMode::Angle, "angle"},
                                             {PictureMode::Area, "area"},
                                             {PictureMode::Stretch, "stretch"}};
  return table(rows);
}

template <>
ChoiceTable<TextureRole> choice_table<TextureRole>() {
  static const Choice<TextureRole> rows[] = {
      {TextureRole::Color, "color"}, {TextureRole::Data, "data"}, {TextureRole::TangentNormal, "normal"}};
  return table(rows);
}

template <>
ChoiceTable<TextureWrap> choice_table<TextureWrap>() {
  static const Choice<TextureWrap> rows[] = {
      {TextureWrap::Repeat, "repeat"}, {TextureWrap::ClampToEdge, "clamp"}, {TextureWrap::MirroredRepeat, "mirror"}};
  return table(rows);
}

template <>
ChoiceTable<AtlasScope> choice_table<AtlasScope>() {
  static const Choice<AtlasScope> rows[] = {{AtlasScope::Whole, "whole"}, {AtlasScope::PerMesh, "per-mesh"}};
  return table(rows);
}

template <>
ChoiceTable<InstanceMode> choice_table<InstanceMode>() {
  static const Choice<InstanceMode> rows[] = {{InstanceMode::Shared, "shared"}, {InstanceMode::Unique, "unique"}};
  return table(rows);
}

}  // namespace intrinsic

namespace intrinsic {

// Declared in atlas.h as a C string, for callers that print it directly.
const char* chart_method_name(ChartMethod m) {
  for (const Choice<ChartMethod>& c : choice_table<ChartMethod>())
    if (c.value == m) return c.name;
  return "?";
}

}  // namespace intrinsic
