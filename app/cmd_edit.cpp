// `intrinsic edit`: realtime boundary manipulation from the command line
// (paper section 4.2): factor and build the impulse responses once for a base
// boundary, then apply each move file through them, timing each update.
// Every move is applied to the base boundary (not to the previous move), so
// output i equals `intrinsic param --boundary BASE+MOVE_i`.
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "command.h"
#include "intrinsic/boundary_editor.h"
#include "intrinsic/error.h"
#include "intrinsic/io.h"
#include "choice_option.h"
#include "intrinsic/report.h"
#include "intrinsic/param_option_table.h"
#include "table_options.h"

namespace intrinsic::app {
namespace {

struct EditArgs {
  std::string input, output, boundary, report, constraints;
  std::vector<std::string> moves;
  // --method, --lambda, --mu and --solver, as `param` takes them (param_option_table.h).
  std::shared_ptr<GivenOptions> given = std::make_shared<GivenOptions>();
  std::string basis = choice_name(BasisMode::Lazy), holes = choice_name(HoleRule::Fill);
  double memory_budget_gib = 2.0;
  int resolve_above = 64;
  bool binary = false, quiet = false;
  std::int64_t max_vertices = 50'000'000;
};

// OUT for one move; OUT with _1, _2, ... before the extension for several.
std::string numbered(const std::string& path, size_t i, size_t count) {
  if (count == 1) return path;
  const size_t slash = path.rfind('/');
  size_t dot = path.rfind('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) dot = path.size();
  return path.substr(0, dot) + "_" + std::to_string(i + 1) + path.substr(dot);
}

ParamOptions edit_options(const EditArgs& a) {
  if (!(a.memory_budget_gib > 0)) throw_usage("--memory-budget must be positive");
  ParamOptions options = param_request(*a.given, OptionSpelling::Flag).options;
  options.holes = parse_choice<HoleRule>(a.holes, "--holes");
  options.boundary = BoundaryShape::Given;
  return options;
}

EditOptions editor_options(const EditArgs& a) {
  EditOptions eo;
  eo.basis = parse_choice<BasisMode>(a.basis, "--basis");
  eo.memory_budget = static_cast<std::size_t>(a.memory_budget_gib * double(1 << 30));
  eo.resolve_above = a.resolve_above;
  return eo;
}

// The move files as positions to hand the editor: each move starts from the
// base, so vertices moved by the previous file and not by this one go back.
std::vector<std::vector<FixedVertex>> moves_from_base(const EditArgs& a, const std::vector<FixedVertex>& base,
                                                      const std::vector<std::vector<FixedVertex>>& files, int n) {
  std::vector<int> base_index(n, -1);
  for (size_t k = 0; k < base.size(); ++k) base_index[base[k].vertex] = static_cast<int>(k);
  std::vector<std::vector<FixedVertex>> out;
  std::vector<FixedVertex> previous;
  for (size_t i = 0; i < files.size(); ++i) {
    const std::vector<FixedVertex>& move = files[i];
    std::vector<FixedVertex> positions;
    std::vector<char> listed(n, 0);
    for (const FixedVertex& fv : move) {
      if (base_index[fv.vertex] < 0)
        throw_input(a.moves[i] + ": vertex " + std::to_string(fv.vertex) + " is not in the base boundary " + a.boundary +
                    ", so it cannot be moved");
      positions.push_back(fv);
      listed[fv.vertex] = 1;
    }
    for (const FixedVertex& fv : previous)
      if (!listed[fv.vertex]) positions.push_back(base[base_index[fv.vertex]]);
    out.push_back(positions);
    previous = move;
  }
  return out;
}

// Applies move i, writes its mesh, returns its report entry.
nlohmann::json apply_move(const EditArgs& a, const Mesh& mesh, BoundaryEditor& editor,
                          const std::vector<FixedVertex>& positions, size_t i, const std::string& output) {
  const MatrixX2d& uv = editor.move(positions);
  const EditStats stats = editor.last_update();
  const auto t_write = std::chrono::steady_clock::now();
  WriteOptions wo;
  wo.binary = a.binary;
  write_mesh(output, mesh.V, mesh.F, uv, wo);
  const DistortionSummary d = summarize_distortion(mesh.V, mesh.F, uv);
  if (!a.quiet)
    std::cout << output << ": " << stats.moved << " moved, update " << stats.ms << " ms"
              << (stats.resolved ? " (re-solved)" : "")
              << (stats.new_responses ? ", " + std::to_string(stats.new_responses) + " new responses" : "") << ", "
              << d.flipped_triangles << " flipped\n";
  return {{"move", a.moves[i]},          {"output", output},
          {"moved", stats.moved},        {"update_ms", stats.ms},
          {"new_responses", stats.new_responses}, {"resolved", stats.resolved},
          {"flipped_triangles", d.flipped_triangles}, {"write_ms", elapsed_ms(t_write)}};
}

struct EditTimes {
  double read = 0, factor = 0;
};

// The base map as solved (method, boundary, solver, residual, ...) plus the
// editor's figures and one entry per move.
nlohmann::json edit_report(const EditArgs& a, const Mesh& mesh, const ParamResult& base, const Parameterizer& p,
                           const BoundaryEditor& editor, const nlohmann::json& updates, const EditTimes& t) {
  nlohmann::json report = nlohmann::json::parse(mesh_report(mesh));
  report["command"] = "edit";
  report.update(nlohmann::json::parse(solution_report(base, a.boundary)));
  report["boundary"] = a.boundary;
  report["basis"] = a.basis;
  report["responses"] = editor.responses();
  report["basis_bytes"] = editor.basis_bytes();
  report["factorizations"] = p.factorizations();
  if (!a.constraints.empty()) report["constraints"] = nlohmann::json::parse(constraints_report(p.residuals(editor.uv())));
  report["updates"] = updates;
  report["timings_ms"] = {{"read", t.read}, {"factor", t.factor}, {"precompute", editor.precompute_ms()}};
  return report;
}

int run_edit(const EditArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::string> outputs;
  for (size_t i = 0; i < a.moves.size(); ++i) {
    outputs.push_back(numbered(a.output, i, a.moves.size()));
    check_output_mesh_path(outputs.back());
  }
  ParamOptions options = edit_options(a);
  ReadOptions ro;
  ro.max_vertices = a.max_vertices;
  const MeshData data = read_mesh(a.input, ro);
  const Mesh mesh = make_mesh(data);
  const int n = static_cast<int>(mesh.V.rows());
  options.given = read_boundary_file(a.boundary, n);
  std::vector<std::vector<FixedVertex>> move_files;
  for (const std::string& m : a.moves) move_files.push_back(read_boundary_file(m, n));
  EditTimes times;
  times.read = elapsed_ms(t0);

  const auto t1 = std::chrono::steady_clock::now();
  Parameterizer parameterizer(mesh, options);
  if (!a.constraints.empty()) {
    Constraints c = read_constraints_file(a.constraints);
    match_face_corners(c, data.F, mesh);
    parameterizer.set_constraints(c);
  }
  const ParamResult base = parameterizer.solve();
  times.factor = elapsed_ms(t1);
  BoundaryEditor editor(parameterizer, editor_options(a));
  if (!a.quiet)
    std::cout << a.input << ": " << n << " vertices, " << options.given.size() << " fixed, factor " << times.factor
              << " ms, precompute (" << a.basis << " basis, " << editor.responses() << " responses, "
              << editor.basis_bytes() / (1 << 20) << " MiB) " << editor.precompute_ms() << " ms\n";
  const std::vector<std::vector<FixedVertex>> moves = moves_from_base(a, editor.boundary(), move_files, n);
  nlohmann::json updates = nlohmann::json::array();
  size_t written = 0;
  try {
    for (; written < moves.size(); ++written)
      updates.push_back(apply_move(a, mesh, editor, moves[written], written, outputs[written]));
    if (!a.report.empty()) {
      nlohmann::json report = edit_report(a, mesh, base, parameterizer, editor, updates, times);
      report["timings_ms"]["total"] = elapsed_ms(t0);
      write_file_atomically(a.report, report.dump(2) + "\n");
    }
  } catch (...) {
    for (size_t i = 0; i < written; ++i) std::filesystem::remove(outputs[i]);  // no partial set of outputs
    throw;
  }
  return 0;
}

}  // namespace

void register_edit(CLI::App& app, Runner& run) {
  auto a = std::make_shared<EditArgs>();
  CLI::App* cmd = app.add_subcommand(
      "edit", "Move boundary vertices of a fixed-boundary map through precomputed impulse responses");
  cmd->add_option("input", a->input, "Input mesh (.obj, .off, .ply, .stl, optionally .gz)")->required();
  cmd->add_option("--boundary", a->boundary, "Base boundary FILE with lines 'vertex u v'")->required();
  cmd->add_option("-o,--output", a->output, "Output mesh (.obj or .ply); numbered _1, _2, ... for several moves")
      ->required();
  cmd->add_option("--move", a->moves, "Move file(s), lines 'vertex u v' (new positions of base boundary vertices)")
      ->required();
  cmd->add_option("--basis", a->basis, "full: every response precomputed (paper) | lazy: on first move")
      ->check(choice_check<BasisMode>())
      ->capture_default_str();
  cmd->add_option("--memory-budget", a->memory_budget_gib, "GiB the responses may take")->capture_default_str();
  cmd->add_option("--resolve-above", a->resolve_above,
                  "Re-solve with the kept factorization when more vertices than this move at once")
      ->capture_default_str();
  add_table_options(cmd, select_options(param_option_table(), {"method", "lambda", "mu", "solver"}), a->given);
  cmd->add_option("--holes", a->holes, "Holes without given positions: fill | free")
      ->check(CLI::IsMember({choice_name(HoleRule::Fill), choice_name(HoleRule::Free)}))
      ->capture_default_str();
  cmd->add_option("--constraints", a->constraints, "JSON file of point and line constraints, kept during the moves");
  cmd->add_option("--report", a->report, "Write the JSON report (precompute and update times) to this file");
  cmd->add_flag("--binary", a->binary, "Binary PLY output");
  cmd->add_option("--max-vertices", a->max_vertices, "Refuse inputs with more vertices")->capture_default_str();
  cmd->add_flag("-q,--quiet", a->quiet, "Print nothing on success");
  cmd->callback([&run, a] { run = [a] { return run_edit(*a); }; });
}

}  // namespace intrinsic::app
